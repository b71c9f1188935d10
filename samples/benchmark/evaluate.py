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
           "seconds": estimate.seconds, "points": len(p1)}
    if not estimate.ok:
        return row
    before, after, failed = metrics.paper_failure(estimate, p1, p2, pair.K, budget.sigma)
    row.update(n_I=before, n_I_star=after, paper_fail=bool(failed),
               inliers=int(estimate.mask.sum()))
    if pair.R_gt is not None and estimate.R is not None:
        error = rcme.compareMotion(estimate.R, estimate.t.reshape(3, 1), pair.R_gt,
                                   pair.t_gt.reshape(3, 1))
        row.update(rot=error.rotationDeg, trans=error.translationDeg, dq=error.dq, dt=error.dt,
                   gt_fail=metrics.pose_failure(error.rotationDeg, error.translationDeg))
    elif pair.gt_points is not None:
        row["f_err"] = metrics.f_error(estimate.F, pair.gt_points)
        row["gt_fail"] = row["f_err"] > metrics.F_FAILURE_PX
    if pair.labels is not None:
        row["precision"], row["recall"] = metrics.precision_recall(estimate.mask, pair.labels)
    return row
