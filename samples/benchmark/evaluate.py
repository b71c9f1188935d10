"""One method on one pair: run it and score it. The row it returns is what the report reads."""
import numpy as np

import methods
import metrics
from methods import rcme


def evaluate(method, pair, budget):
    """A dict of scores, or None when the method does not apply to the pair (no K)."""
    p1 = np.ascontiguousarray(pair.points1, np.float64)
    p2 = np.ascontiguousarray(pair.points2, np.float64)
    estimate = methods.run(method, p1, p2, pair.K, budget)
    if estimate is None:
        return None
    row = {"dataset": pair.dataset, "pair": pair.name, "N": budget.iterations,
           "seed": budget.seed, "method": method, "ok": estimate.ok, "status": estimate.status,
           "seconds": estimate.seconds, "points": len(p1), "flagged": estimate.flagged,
           "unjudgeable": pair.unjudgeable}
    if not estimate.ok:
        # A flag is judged through the rejected model: wrong means caught, right a false alarm.
        judged = _against_truth(estimate.rejected_F, estimate.rejected_R, estimate.rejected_t,
                                pair)
        row["rejected_wrong"] = judged.get("gt_fail")
        if "f_err" in judged:
            row["rejected_f_err"] = judged["f_err"]
        return row
    before, after, failed = metrics.paper_failure(estimate, p1, p2, pair.K, budget.sigma)
    row.update(n_I=before, n_I_star=after, paper_fail=bool(failed),
               inliers=int(estimate.mask.sum()))
    row.update(_against_truth(estimate.F, estimate.R, estimate.t, pair))
    if pair.labels is not None:
        row["precision"], row["recall"] = metrics.precision_recall(estimate.mask, pair.labels)
    return row


def _against_truth(F, R, t, pair):
    """Errors of a model against the pair's ground truth and whether it is wrong (gt_fail):
    pose errors with a true pose, else the true matches' RMS Sampson error; {} when there is
    nothing to judge (no model, or no ground truth for it). Where the truth has no translation
    every motion is wrong, and a flag is a caught failure whatever it turned down."""
    if pair.t_gt is not None and not np.any(pair.t_gt):
        return dict(gt_fail=True)  # no translation (pure rotation, all outliers): no motion is right
    if pair.R_gt is not None and R is not None:
        error = rcme.compareMotion(R, t.reshape(3, 1), pair.R_gt, pair.t_gt.reshape(3, 1))
        return dict(rot=error.rotationDeg, trans=error.translationDeg, dq=error.dq, dt=error.dt,
                    gt_fail=metrics.pose_failure(error.rotationDeg, error.translationDeg))
    if pair.R_gt is None and pair.gt_points is not None and F is not None:
        f_err = metrics.f_error(F, pair.gt_points)
        return dict(f_err=f_err, gt_fail=f_err > metrics.F_FAILURE_PX)
    return {}
