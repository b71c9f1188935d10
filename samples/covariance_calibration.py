#!/usr/bin/python3
"""Calibration of rcme's motion covariance: the normalized estimation error squared (NEES) of the
estimated motion against ground truth, in the covariance's own tangent space.

For a calibrated covariance the 5-DoF NEES theta^T Sigma^-1 theta is chi-square with 5 degrees
of freedom (mean 5, 95 % of the scenes below 11.07); the rotation block alone is chi-square(3)
(mean 3, 95 % below 7.815). theta = (omega, beta) is the error of the estimate in the tangent of
Report::covariance: R_true = R exp([omega]x), t_true ~ t + B beta (see Report::covariance).

    PYTHONPATH=build/python /usr/bin/python3 samples/covariance_calibration.py --synthetic
    PYTHONPATH=build/python /usr/bin/python3 samples/covariance_calibration.py --real

--real runs on the image sequences of ../shared/data with the benchmark's pair selection and
cached SIFT matches (samples/benchmark); their ground truth has errors of its own.
"""
import argparse
import os
import sys

import numpy as np

try:
    import rcme
except ImportError:  # built inside OpenCV
    import cv2
    rcme = cv2.rcme

CHI2_95 = {3: 7.814727903251178, 5: 11.070497693516351, 2: 5.991464547107979}


def log_rotation(R):
    """Rotation vector of R (inverse of Rodrigues' formula), also near pi."""
    cos_angle = np.clip((np.trace(R) - 1) / 2, -1.0, 1.0)
    angle = np.arccos(cos_angle)
    w = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    if angle < 1e-9:
        return 0.5 * w
    if np.pi - angle < 1e-6:
        axis = np.sqrt(np.maximum((np.diag(R) + 1) / 2, 0))
        axis *= np.sign(w + (w == 0))
        return angle * axis / np.linalg.norm(axis)
    return angle / (2 * np.sin(angle)) * w


def motion_error(R, t, R_true, t_true):
    """The 6-vector (omega, delta) with R_true = R exp([omega]x) and delta = R^T (t_true / (t .
    t_true) - t): the 5-DoF tangent error written in the 6-D tangent of rcme.poseCovariance
    (delta is orthogonal to R^T t, the unknown scale direction). None when t_true is not in t's
    hemisphere (the error is then beyond any linearization)."""
    t, t_true = t.ravel() / np.linalg.norm(t), t_true.ravel() / np.linalg.norm(t_true)
    along = float(t @ t_true)
    if along <= 0:
        return None
    return np.r_[log_rotation(R.T @ R_true), R.T @ (t_true / along - t)]


# A motion this far from the truth is a wrong answer (a status question), not noise that a
# covariance could describe; the tables count such runs and also give the figures without them.
GROSS_ROTATION_DEG, GROSS_TRANSLATION_DEG = 5.0, 15.0


def nees(report, R_true, t_true):
    """(5-DoF NEES, rotation-only 3-DoF NEES, gross error?) of a successful calibrated report,
    or None."""
    if report.status != rcme.STATUS_SUCCESS or report.covariance is None:
        return None
    error = rcme.compareMotion(report.R, report.t, R_true, t_true)
    gross = (error.rotationDeg > GROSS_ROTATION_DEG or
             error.translationDeg > GROSS_TRANSLATION_DEG)
    xi = motion_error(report.R, report.t, R_true, t_true)
    if xi is None:
        return (np.inf, np.inf, True)
    cov6 = rcme.poseCovariance(report.R, report.t, report.covariance)
    full = float(xi @ np.linalg.pinv(cov6, rcond=1e-12, hermitian=True) @ xi)
    rot = float(xi[:3] @ np.linalg.solve(cov6[:3, :3], xi[:3]))
    return full, rot, gross


def summary(values, dof):
    v = np.asarray(values, float)
    if len(v) == 0:
        return "- | - | -"
    return "%.2f | %.2f | %.1f %%" % (np.mean(v), np.median(v), 100.0 * np.mean(v < CHI2_95[dof]))


def params_for(sigma, noise_from_data):
    p = rcme.Params()
    p.sigma = sigma
    p.useEstimatedNoise = noise_from_data
    return p


def synthetic_configs(scenes_per_config):
    """Generic scene and corridor over several n, sigma, baselines and outlier ratios."""
    configs = []
    for kind in (rcme.SCENE_GENERIC, rcme.SCENE_CORRIDOR):
        for n in (100, 300, 1000):
            for sigma in (0.5, 1.0, 2.0):
                for baseline in ((0.5, 1.0, 2.0) if kind == rcme.SCENE_GENERIC else (1.0,)):
                    for inlier_ratio in (1.0, 0.7):
                        configs.append(dict(kind=kind, n=n, sigma=sigma, baseline=baseline,
                                            inlier_ratio=inlier_ratio))
    return [(c, seed) for c in configs for seed in range(scenes_per_config)]


def run_synthetic(args):
    rows = {}
    noise_ratio, noise_ratio_f = [], []
    for config, seed in synthetic_configs(args.scenes_per_config):
        sp = rcme.SceneParams()
        sp.kind, sp.numPoints, sp.sigma = config["kind"], config["n"], config["sigma"]
        sp.baseline, sp.inlierRatio, sp.seed = config["baseline"], config["inlier_ratio"], seed
        scene = rcme.generateScene(sp)
        stated = config["sigma"] * args.stated_sigma_factor
        for noise_from_data in (False, True):
            rep = rcme.estimateRelativeMotion(scene.points1, scene.points2, scene.cameraMatrix,
                                              params_for(stated, noise_from_data))
            result = nees(rep, scene.R, scene.t)
            if noise_from_data and rep.status == rcme.STATUS_SUCCESS:
                noise_ratio.append(rep.noiseSigma / config["sigma"])
                # F only: the 7-DoF covariance is not reported; its noise estimate is
                f_only = rcme.estimateRelativeMotion(scene.points1, scene.points2, None,
                                                     params_for(stated, True))
                if f_only.status == rcme.STATUS_SUCCESS:
                    noise_ratio_f.append(f_only.noiseSigma / config["sigma"])
            if result is None:
                continue
            scene_name = "generic" if config["kind"] == rcme.SCENE_GENERIC else "corridor"
            outliers = "no outliers" if config["inlier_ratio"] == 1.0 else "30 % outliers"
            for key in ((scene_name, outliers), ("all", "all")):
                rows.setdefault((noise_from_data,) + key, []).append(result)
    n_scenes = len(synthetic_configs(args.scenes_per_config))
    print("synthetic: %d scenes (generic: n 100/300/1000, sigma 0.5/1/2 px, baseline 0.5/1/2 m; "
          "corridor: same n and sigma, baseline 1 m; inlier ratio 1.0 and 0.7), stated sigma = "
          "%g x true, default Params otherwise" % (n_scenes, args.stated_sigma_factor))
    print_table(rows)
    for name, ratios in (("with K", noise_ratio), ("F only", noise_ratio_f)):
        r = np.asarray(ratios)
        print("\nnoiseSigma / true sigma, %s, over %d successful runs: mean %.3f, median %.3f, "
              "5-95 %% range %.3f-%.3f" % (name, len(r), r.mean(), np.median(r),
                                           *np.percentile(r, [5, 95])))


def print_table(rows):
    print("| covariance noise | scenes | subset | runs | gross | mean NEES5 | median NEES5 | "
          "NEES5 < 11.07 | mean NEES3 (rotation) | median NEES3 | NEES3 < 7.815 | "
          "without gross: mean NEES5 | NEES5 < 11.07 | NEES3 < 7.815 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for key in sorted(rows, key=lambda k: (k[0], k[1] != "all", k[1], k[2])):
        values = np.asarray(rows[key], float)
        gross = values[:, 2] > 0
        local = values[~gross]
        local_summary = ("%.2f | %.1f %% | %.1f %%" % (
            np.mean(local[:, 0]), 100 * np.mean(local[:, 0] < CHI2_95[5]),
            100 * np.mean(local[:, 1] < CHI2_95[3])) if len(local) else "- | - | -")
        print("| %s | %s | %s | %d | %d | %s | %s | %s |" % (
            "estimated" if key[0] else "stated sigma", key[1], key[2], len(values),
            int(gross.sum()), summary(values[:, 0], 5), summary(values[:, 1], 3),
            local_summary))


def run_real(args):
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path.insert(0, os.path.join(here, "benchmark"))
    import matching
    import run_benchmark
    repo_root = os.path.dirname(here)
    data = os.path.normpath(os.path.join(repo_root, "..", "shared", "data"))
    matcher = matching.Matcher(args.cache or matching.default_cache_dir(repo_root))
    selection = argparse.Namespace(data=data, max_references=args.max_references, quick=False)
    with_pose = [p for p in run_benchmark.real_pairs(selection, matcher)[0]
                 if p.K is not None and p.R_gt is not None]
    rows = {}
    noise = {}
    for pair in with_pose:
        for noise_from_data in (False, True):
            rep = rcme.estimateRelativeMotion(pair.points1, pair.points2, pair.K,
                                              params_for(args.real_sigma, noise_from_data))
            result = nees(rep, pair.R_gt, pair.t_gt)
            if result is None:
                continue
            if noise_from_data:
                error = rcme.compareMotion(rep.R, rep.t, pair.R_gt, pair.t_gt)
                noise.setdefault(pair.dataset, []).append(
                    (rep.noiseSigma, error.rotationDeg, np.linalg.norm(rep.rotationStdDeg),
                     error.translationDeg, rep.translationStdDeg))
            for key in ((pair.dataset, "all pairs"), ("all", "all")):
                rows.setdefault((noise_from_data,) + key, []).append(result)
    print("real pairs (benchmark selection, SIFT matches), stated sigma %g px, default Params"
          % args.real_sigma)
    print_table(rows)
    print("\n| sequence | noiseSigma median (range), px | median rotation error, deg | "
          "median predicted rotation std (norm), deg | median translation error, deg | "
          "median predicted translation std, deg |")
    print("|---|---|---|---|---|---|")
    for name, values in sorted(noise.items()):
        v = np.asarray(values)
        print("| %s | %.2f (%.2f-%.2f) | %.3f | %.4f | %.2f | %.3f |" % (
            name, np.median(v[:, 0]), v[:, 0].min(), v[:, 0].max(), *np.median(v[:, 1:], 0)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--synthetic", action="store_true")
    ap.add_argument("--real", action="store_true")
    ap.add_argument("--scenes-per-config", type=int, default=20,
                    help="synthetic scenes per configuration (48 configurations)")
    ap.add_argument("--stated-sigma-factor", type=float, default=1.0,
                    help="Params.sigma as a multiple of the true noise (synthetic)")
    ap.add_argument("--real-sigma", type=float, default=1.0, help="Params.sigma on real pairs")
    ap.add_argument("--cache", default=None, help="match cache folder (default: the benchmark's)")
    ap.add_argument("--max-references", type=int, default=0, metavar="K",
                    help="real: at most K reference frames per sequence (0: all), as the "
                         "benchmark's option")
    args = ap.parse_args()
    if not (args.synthetic or args.real):
        args.synthetic = True
    if args.synthetic:
        run_synthetic(args)
    if args.real:
        run_real(args)


if __name__ == "__main__":
    main()
