#!/usr/bin/python3
"""Calibration of rcme's motion covariance (Report::covariance): the normalized estimation error
squared (NEES) of the returned motion, on the benchmark's real pairs and on synthetic scenes.

For a calibrated covariance the 5-DoF NEES theta^T Sigma^-1 theta is chi-square(5) (mean 5,
median 4.35, 95 % below 11.07) and its rotation block chi-square(3) (mean 3, median 2.37, 95 %
below 7.815); theta = (omega, beta) is the error in the covariance's own tangent:
R_true = R exp([omega]x), t_true ~ t + B beta (see Report::covariance).

    samples/benchmark/with_poselib.sh --covariance [--quick] [--synthetic]
    PYTHONPATH=build/python /usr/bin/python3 samples/benchmark/covariance_calibration.py

Real pairs: the benchmark's selection (run_benchmark.real_pairs: SIFT ratio-test matches,
threshold 1.96 px at sigma 1 px), default Params, only the right answers (the benchmark's
judge, metrics.pose_failure; a wrong motion is a status question, not an error a covariance
describes). Per dataset: the NEES against the ground truth with the estimated noise (the
default) and with the stated sigma, a reliability table (predicted standard deviation against
the actual error, binned) and plot, and the candidate covariances computed from the same fit
(sandwich, spatially clustered sandwich). Datasets are split into a tuning half and a reported
half (TUNE / REPORT below).

Ground truth has errors of its own, so the same covariance is also judged without it: triplets
of frames (i, j, k) of one sequence, each image's keypoints split between its two pairs (so no
keypoint error enters two pairs of a loop: shared keypoints cancel in a loop and would make any
covariance look conservative), and the loop's rotation R_ik^T R_jk R_ij, which is the identity
for exact estimates, judged against the three pairs' covariances (chi-square(3)); and the
translation directions' coplanarity: t_ik, R_jk t_ij and t_jk lie in one plane, and t_ik's angle
out of it, over its variance propagated from the three 5x5 covariances, is chi-square(1). Both
are checked on synthetic triplets. Where the 5-DoF NEES against the ground truth comes from is
split up (translation block alone, the covariance's narrowest direction, the exact likelihood
ratio, the ground truth's epipolar shift in px), and judged with a stated calibration error.
fountain-P11 and templeSR are also judged with their ground truth's error as a bundle adjustment of
all their images measures it (bundle_adjustment.py, no two-view estimate in it; not with --quick).

Writes a markdown report (default doc/benchmark/covariance_calibration.md) and a reliability plot
next to it."""
import argparse
import math
import os
import sys

import numpy as np
import cv2

import datasets
import matching
import metrics
import plots
import run_benchmark

try:
    import rcme
except ImportError:  # built inside OpenCV
    rcme = cv2.rcme

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CHI2_95 = {1: 3.841458820694124, 2: 5.991464547107979, 3: 7.814727903251178,
           5: 11.070497693516351}
CHI2_MEDIAN = {1: 0.454936423119573, 2: 1.386294361119891, 3: 2.365973884375338,
               5: 4.351460191095527}
# Tuned on (candidates compared, choices made) against reported on (judged once, as is).
TUNE = ("templeSR", "KITTI-06")
REPORT = ("fountain-P11", "KITTI-01")
# KITTI's poses come from an OXTS RT3003 GPS/INS: roll and pitch 0.03 deg, heading 0.1 deg
# (1 sigma, the unit's specification; Geiger et al., IJRR 2013, for the setup).
KITTI_GT_ROTATION_SPEC_DEG = (0.03, 0.03, 0.1)
# Triplet gaps (frames) per sequence for the loop test: enough parallax on each of the 3 pairs.
LOOP_GAPS = {"KITTI-01": (2, 3, 4), "KITTI-06": (3, 4, 5), "fountain-P11": (1, 2),
             "templeSR": (1, 2)}
# The spatially clustered sandwich: cells of a grid over the inliers in image 1.
CLUSTER_GRID = 8
# The spatial (kernel) sandwich: scores of inliers closer than a few of this (px, image 1) are
# taken as correlated, with Gaussian weights (a positive semi-definite kernel); the scale was
# picked among 10, 30 and 100 px on templeSR and KITTI 06.
SPATIAL_KERNEL_PX = 30.0
SPATIAL = "spatial sandwich (kernel %g px), beyond 2 standard errors" % SPATIAL_KERNEL_PX
# The error floor: an epipolar error of this RMS (px) that the inliers share, so that it does not
# shrink with their number; added to the reported covariance as floor^2 (J^T J / n)^-1. Picked
# among 0.01-0.05 px on templeSR's ground truth and KITTI 06's loops (those with the estimated
# noise in all three pairs). A candidate, not the library's.
EPIPOLAR_FLOOR_PX = 0.02
FLOOR = "reported + a %g px epipolar floor, floor^2 (J^T J / n)^-1" % EPIPOLAR_FLOOR_PX


# ---- the covariance's tangent --------------------------------------------------------------

def _log(R):
    return cv2.Rodrigues(np.asarray(R, np.float64))[0].ravel()


def tangent_error(R, t, R_true, t_true):
    """theta = (omega, beta) with R_true = R exp([omega]x), t_true ~ t + B beta; None when t_true
    is not in t's hemisphere (beyond any linearization)."""
    t, t_true = np.ravel(t) / np.linalg.norm(t), np.ravel(t_true) / np.linalg.norm(t_true)
    along = float(t @ t_true)
    if along <= 0:
        return None
    return np.r_[_log(np.asarray(R).T @ R_true), metrics.tangent_basis(t).T @ (t_true / along - t)]


def nees(theta, covariance):
    """(5-DoF NEES, rotation-only 3-DoF NEES)."""
    C = np.asarray(covariance, np.float64)
    return (float(theta @ np.linalg.solve(C, theta)),
            float(theta[:3] @ np.linalg.solve(C[:3, :3], theta[:3])))


def residuals_and_jacobian(R, t, K, p1, p2, step=1e-7):
    """Signed Sampson residuals of (p1, p2) under the motion and their derivatives with respect
    to the tangent (central differences)."""
    Kinv = np.linalg.inv(K)
    t = np.ravel(t) / np.linalg.norm(t)
    B = metrics.tangent_basis(t)

    def residual(theta):
        t_theta = t + B @ theta[3:]
        F = Kinv.T @ metrics.skew(t_theta / np.linalg.norm(t_theta)) @ R @ metrics.rotation_exp(theta[:3]) @ Kinv
        return datasets.sampson_residual(F, p1, p2)

    J = np.empty((len(p1), 5))
    for k in range(5):
        delta = np.zeros(5)
        delta[k] = step
        J[:, k] = (residual(delta) - residual(-delta)) / (2 * step)
    return residual(np.zeros(5)), J


def truncated_normal_variance(k):
    """E[z^2 | |z| < k] of a standard normal z (the library's truncatedNormalVariance)."""
    density = np.exp(-0.5 * k * k) / np.sqrt(2 * np.pi)
    return 1.0 - 2.0 * k * density / math.erf(k / np.sqrt(2))


def psd_max(A, B, margin=0.0):
    """The smallest covariance at least as large as A and B along every direction, B's
    eigenvalues in A's whitened coordinates lowered by margin first:
    A^1/2 max(I, A^-1/2 B A^-1/2 - margin) A^1/2 (with margin 2 sqrt(2 / n), the library's
    sandwichBeyondItsNoise as it raises the covariance, without lowering it)."""
    w, V = np.linalg.eigh(A)
    half = V @ np.diag(np.sqrt(np.maximum(w, 1e-300))) @ V.T
    inv_half = V @ np.diag(1 / np.sqrt(np.maximum(w, 1e-300))) @ V.T
    m, U = np.linalg.eigh(inv_half @ B @ inv_half)
    return half @ U @ np.diag(np.maximum(m - margin, 1.0)) @ U.T @ half


# The stated sigma's weight as a prior on the noise, in residual degrees of freedom (the library's
# kStatedNoiseDof, components/residual_covariance.cpp; picked among 0-30 on the tune sets).
STATED_NOISE_DOF = 4.0
# Residual degrees of freedom from which the final fit uses the estimated noise, and the reported
# covariance is raised to the sandwich (model_fit.cpp's kMinNoiseDof).
MIN_NOISE_DOF = 30


def _threshold(params):
    return params.threshold if params.threshold > 0 else 1.959963984540054 * params.sigma


def posterior_noise_variance(stated, estimated, dof, prior_dof=STATED_NOISE_DOF):
    """The library's posteriorNoiseVariance: the mean of sigma^2's scaled-inverse-chi-square
    posterior with the stated sigma as a prior worth prior_dof degrees of freedom."""
    if dof < 1 or not np.isfinite(estimated):
        return stated * stated
    return (prior_dof * stated * stated + dof * estimated * estimated) / (prior_dof + dof - 2)


def _noise_and_truncation(report, params, inliers):
    """The reported covariance's sigma (with the estimated noise: the posterior of the estimate
    and the stated sigma, as the library computes it; else the stated one) and its band's
    truncation factor h: sigma^2 / h(c / sigma)."""
    sigma = params.sigma
    if params.useEstimatedNoise:
        sigma = math.sqrt(posterior_noise_variance(params.sigma, report.noiseSigma, inliers - 5))
    return sigma, truncated_normal_variance(_threshold(params) / sigma)


def _fit_noise(report, params, inliers):
    """The final fit's own sigma (main before the posterior noise): the estimate from
    MIN_NOISE_DOF residual degrees of freedom on, the stated sigma below."""
    estimated = (params.useEstimatedNoise and inliers - 5 >= MIN_NOISE_DOF and
                 np.isfinite(report.noiseSigma))
    return report.noiseSigma if estimated else params.sigma


REPORTED = "reported (Report::covariance)"
MODEL_BASED = "model-based sigma^2 / h (J^T J)^-1"
PREVIOUS = "before: 83c2b8b (plain sandwich, no outliers in the band)"
LEVERAGE_ONLY = "leverage-corrected sandwich alone, no outliers in the band"
BAND_ONLY = "outliers in the band alone, plain sandwich"
WHOLE_BAND = "leverage-corrected sandwich + outliers in the whole band (w = c)"
# The library's band-outlier count: the points outside the band with Sampson distances between
# NEAR_BAND[0] and NEAR_BAND[1] band widths, 1 / (NEAR_BAND[1] - NEAR_BAND[0]) of them
# (components/residual_covariance.cpp's kNearFrom, kNearTo).
NEAR_BAND = (2.0, 6.0)
# Leverages above 1 - this are taken as it (the library's kMinLeverageComplement).
MIN_LEVERAGE_COMPLEMENT = 0.01


def band_outlier_term(pair, report, params, inliers, A_inv, sigma, whole_band=False):
    """The library's term for the outliers inside the band that the residuals cannot show: their
    number read off the points just outside the band, the share w / c of them within the noise's
    own band w = min(c, 1.96 sigma), their excess residual variance w^2 / 3 - h(w / sigma)
    sigma^2, their gradients those of the points near the band:
    A^-1 (sum g^T g over them) A^-1 excess / (NEAR_BAND width) / h(c / sigma)^2, sigma the
    reported covariance's noise (the posterior). whole_band: w = c (the candidate compared on the
    tune sets)."""
    c = _threshold(params)
    d, J = residuals_and_jacobian(np.asarray(report.R), np.asarray(report.t), pair.K,
                                  pair.points1[~inliers], pair.points2[~inliers])
    near = (np.abs(d) > NEAR_BAND[0] * c) & (np.abs(d) <= NEAR_BAND[1] * c)
    w = c if whole_band else min(c, 1.959963984540054 * sigma)
    excess = w / c * max(0.0, w * w / 3 - truncated_normal_variance(w / sigma) * sigma ** 2)
    h = truncated_normal_variance(c / sigma)
    return A_inv @ (J[near].T @ J[near]) @ A_inv * excess / (NEAR_BAND[1] - NEAR_BAND[0]) / h ** 2


def candidates(report, pair, params):
    """The candidate covariances of one successful estimate, all from its own final inliers: the
    reported one (Report::covariance), the model-based one (one noise for every point: the
    library's covariance before components/residual_covariance.cpp), the residual-based sandwich,
    the same with the scores summed over spatial cells (errors correlated within a cell), the
    larger of the model-based one and the sandwich without the library's margin, and the larger
    of the model-based one and a spatial-kernel sandwich (scores of nearby inliers correlated)
    with the library's margin; 83c2b8b's reported one (the plain sandwich, no term for the
    outliers in the band) and each of the two terms issue 36d added alone; and the reported one
    with an error floor that does not shrink with the number of inliers."""
    inliers = np.asarray(report.mask).ravel().astype(bool)
    p1, p2 = pair.points1[inliers], pair.points2[inliers]
    d, J = residuals_and_jacobian(np.asarray(report.R), np.asarray(report.t), pair.K, p1, p2)
    n = len(d)
    A_inv = np.linalg.inv(J.T @ J)
    sigma, h = _noise_and_truncation(report, params, n)
    model_based = sigma * sigma / h * A_inv
    fitted = _fit_noise(report, params, n)
    h_fitted = truncated_normal_variance(_threshold(params) / fitted)
    estimated = (params.useEstimatedNoise and n - 5 >= MIN_NOISE_DOF and
                 np.isfinite(report.noiseSigma))
    scores = J * d[:, None]
    # the sandwich's truncation factor is the estimated noise's (the library's, where it is used)
    h = h_fitted if np.isfinite(report.noiseSigma) and fitted == report.noiseSigma else h
    sandwich = A_inv @ (scores.T @ scores) @ A_inv * n / (n - 5) / h ** 2
    leverage = np.einsum("ij,jk,ik->i", J, A_inv, J)
    shrunk = scores / np.maximum(1 - leverage, MIN_LEVERAGE_COMPLEMENT)[:, None]
    leverage_sandwich = A_inv @ (shrunk.T @ shrunk) @ A_inv * n / (n - 5) / h ** 2
    margin = 2 * math.sqrt(2 / n)
    previous = psd_max(model_based, sandwich, margin) if estimated else model_based
    leverage_only = psd_max(model_based, leverage_sandwich, margin) if estimated else model_based
    band, whole = (band_outlier_term(pair, report, params, inliers, A_inv, sigma, whole_band)
                   if params.useEstimatedNoise else 0 * A_inv for whole_band in (False, True))
    lo, hi = p1.min(0), p1.max(0) + 1e-9
    cells = np.floor((p1 - lo) / (hi - lo) * CLUSTER_GRID).astype(int) @ [CLUSTER_GRID, 1]
    sums = np.array([scores[cells == c].sum(0) for c in np.unique(cells)])
    G = len(sums)
    clustered = A_inv @ (sums.T @ sums) @ A_inv * G / max(G - 1, 1) / h ** 2
    squared_distances = np.sum((p1[:, None, :] - p1[None, :, :]) ** 2, axis=-1)
    weights = np.exp(-squared_distances / (2 * SPATIAL_KERNEL_PX ** 2))
    spatial = A_inv @ (scores.T @ weights @ scores) @ A_inv * n / (n - 5) / h ** 2
    return {REPORTED: np.asarray(report.covariance, np.float64), MODEL_BASED: model_based,
            "sandwich": sandwich,
            "clustered sandwich (%dx%d cells)" % (CLUSTER_GRID, CLUSTER_GRID): clustered,
            "max(model-based, sandwich), no margin": psd_max(model_based, sandwich),
            SPATIAL: psd_max(model_based, spatial, margin), PREVIOUS: previous,
            LEVERAGE_ONLY: leverage_only, BAND_ONLY: previous + band,
            WHOLE_BAND: leverage_only + whole,
            FLOOR: np.asarray(report.covariance, np.float64) +
            EPIPOLAR_FLOOR_PX ** 2 * n * A_inv}


def ground_truth_fit(report, pair, params):
    """How far the ground truth's motion is from the matches, from the final inliers alone: the
    likelihood ratio (SSR_gt - SSR) h / sigma^2 (the exact counterpart of the model-based
    covariance's NEES5: equal to it where the first order holds), the RMS shift of the inliers'
    Sampson residuals sqrt((SSR_gt - SSR) / n) in px that the ground truth's epipolar geometry
    asks for, and the motion's derivative with respect to K's fx, fy, cx, cy (5x4, per px: the
    final fit's implicit function, -A^-1 J^T dd/dK)."""
    inliers = np.asarray(report.mask).ravel().astype(bool)
    p1, p2 = pair.points1[inliers], pair.points2[inliers]
    R, t = np.asarray(report.R, np.float64), np.asarray(report.t, np.float64)
    d, J = residuals_and_jacobian(R, t, pair.K, p1, p2)
    Kinv = np.linalg.inv(pair.K)
    F_gt = Kinv.T @ metrics.skew(np.ravel(pair.t_gt) / np.linalg.norm(pair.t_gt)) @ pair.R_gt @ Kinv
    excess = float(np.sum(datasets.sampson_residual(F_gt, p1, p2) ** 2) - np.sum(d * d))
    sigma, h = _noise_and_truncation(report, params, len(d))
    D = np.empty((len(d), 4))
    for k, (row, col) in enumerate(((0, 0), (1, 1), (0, 2), (1, 2))):
        K_plus, K_minus = pair.K.copy(), pair.K.copy()
        K_plus[row, col] += 0.5
        K_minus[row, col] -= 0.5
        D[:, k] = residuals_and_jacobian(R, t, K_plus, p1, p2)[0] - \
            residuals_and_jacobian(R, t, K_minus, p1, p2)[0]
    motion_by_K = -np.linalg.solve(J.T @ J, J.T @ D)
    # what a change of K does to the residuals once the motion has followed it: the pairs' part of
    # a K correction fitted to all of a set's pairs (self_calibration)
    visible = (D + J @ motion_by_K) * math.sqrt(h) / sigma
    return dict(likelihood_ratio=excess * h / sigma ** 2,
                epipolar_shift=math.sqrt(max(excess, 0.0) / len(d)),
                motion_by_K=motion_by_K, focal_length=float(pair.K[0, 0]),
                K_information=visible.T @ visible, K_score=visible.T @ d * math.sqrt(h) / sigma)


def params_for(sigma, estimated_noise):
    p = rcme.Params()
    p.sigma = sigma
    p.useEstimatedNoise = estimated_noise
    return p


NOISE_MODES = ((True, "estimated noise (default)"), (False, "stated sigma"))


# ---- tables --------------------------------------------------------------------------------

def median_interval(values, level=0.9):
    """A distribution-free interval for the median (order statistics x_(l), x_(n+1-l), l the
    largest with P(Binomial(n, 1/2) <= l - 1) <= (1 - level) / 2): covers it with probability at
    least `level`. None below 5 values (no such l)."""
    v = np.sort(np.asarray(values, np.float64))
    n = len(v)
    log_half_n = n * math.log(0.5)
    tail, l = 0.0, 0
    while l < n // 2:
        tail += math.exp(math.lgamma(n + 1) - math.lgamma(l + 1) - math.lgamma(n - l + 1) +
                         log_half_n)
        if tail > (1 - level) / 2:
            break
        l += 1
    return (v[l - 1], v[n - l]) if l >= 1 else None


def _stats(values, dof):
    """Mean, median with its 90 % interval (median_interval), share below chi-square's 95 %."""
    v = np.asarray(values, np.float64)
    if len(v) == 0:
        return ["-"] * 3
    interval = median_interval(v)
    return ["%.2f" % np.mean(v), "%.2f" % np.median(v) + (
        " (%.2f-%.2f)" % interval if interval is not None else ""),
        "%.0f %%" % (100 * np.mean(v < CHI2_95[dof]))]


def nees_table(rows, groups):
    """rows: dicts with nees5, nees3; groups: (label cells, predicate)."""
    out = []
    for labels, keep in groups:
        subset = [r for r in rows if keep(r)]
        if subset:
            out.append(labels + [str(len(subset))] + _stats([r["nees3"] for r in subset], 3)
                       + _stats([r["nees5"] for r in subset], 5))
    return out


NEES_HEADER = ["pairs", "NEES3 mean", "NEES3 median", "NEES3 < 7.815", "NEES5 mean",
               "NEES5 median", "NEES5 < 11.07"]


LOOP_HEADER = ["NEES3 mean", "NEES3 median", "NEES3 < 7.815", "NEES1 mean", "NEES1 median",
               "NEES1 < 3.841", "conditioning, median"]


def loop_stats(rows):
    """The loop table's cells: rotation (chi-square(3)) and coplanarity (chi-square(1))."""
    return (_stats([r["nees3"] for r in rows], 3) + _stats([r["nees1"] for r in rows], 1)
            + ["%.1f" % np.median([r["conditioning"] for r in rows])])


def split_of(dataset):
    return "tune" if dataset in TUNE else "report" if dataset in REPORT else "report (other)"


# ---- real pairs against the ground truth ---------------------------------------------------

def run_pairs(task_pairs, sigma):
    """One row per right answer, noise mode and candidate covariance; and the count of wrong
    answers and failures per dataset and mode."""
    rows, others = [], {}
    for pair in task_pairs:
        for estimated, mode in NOISE_MODES:
            params = params_for(sigma, estimated)
            report = rcme.estimateRelativeMotion(pair.points1, pair.points2, pair.K, params)
            key = (pair.dataset, mode)
            if report.status != rcme.STATUS_SUCCESS:
                others.setdefault(key, [0, 0])[1] += 1
                continue
            error = rcme.compareMotion(report.R, report.t, pair.R_gt, pair.t_gt)
            theta = tangent_error(report.R, report.t, pair.R_gt, pair.t_gt)
            if theta is None or metrics.pose_failure(error.rotationDeg, error.translationDeg):
                others.setdefault(key, [0, 0])[0] += 1
                continue
            fit = ground_truth_fit(report, pair, params) if estimated else {}
            for name, C in candidates(report, pair, params).items():
                n5, n3 = nees(theta, C)
                rows.append(dict(dataset=pair.dataset, mode=mode, candidate=name, theta=theta,
                                 covariance=C, nees5=n5, nees3=n3, pair=pair.name, **fit))
    return rows, others


RELIABILITY_BLOCKS = (("rotation", slice(0, 3)), ("translation direction", slice(3, 5)))


def reliability_rows(rows, block, bins=3):
    """Per dataset: pairs binned by the predicted standard deviation of the block (per axis, RMS
    over its axes), with the RMS actual error per axis in each bin; and the per-pair points."""
    out, points = [], {}
    name, axes = block
    for dataset in sorted({r["dataset"] for r in rows}):
        subset = [r for r in rows if r["dataset"] == dataset]
        k = axes.stop - axes.start
        std = np.degrees(np.sqrt([np.trace(r["covariance"][axes, axes]) / k for r in subset]))
        err = np.degrees([np.linalg.norm(r["theta"][axes]) / np.sqrt(k) for r in subset])
        points[dataset] = (std, err)
        edges = np.quantile(std, np.linspace(0, 1, bins + 1))
        for b in range(bins):
            inside = (std >= edges[b]) & (std <= edges[b + 1])
            if inside.any():
                predicted = np.sqrt(np.mean(std[inside] ** 2))
                actual = np.sqrt(np.mean(err[inside] ** 2))
                out.append([dataset, name, "%.4f-%.4f" % (edges[b], edges[b + 1]),
                            str(int(inside.sum())), "%.4f" % predicted, "%.4f" % actual,
                            "%.1f" % (actual / predicted)])
    return out, points


# ---- loops of three frames, without ground truth -------------------------------------------

def _keypoint_half(points, salt):
    """0 or 1 per keypoint, a hash of its coordinates and the loop: the same keypoint of an image
    gets the same half in both pairs of the loop it belongs to."""
    q = np.round(np.asarray(points) * 64).astype(np.int64)
    mixed = (q[:, 0] * 73856093) ^ (q[:, 1] * 19349663) ^ (salt * 83492791)
    return (mixed >> 7) & 1


def loop_rows(sequences, matcher, sigma, max_loops):
    """Per triplet (i, j, k), the rotation NEES of R_ik^T R_jk R_ij against the three pairs'
    covariances: pair ij uses half 0 of image i and of image j, jk half 1 of j and half 0 of k,
    ik half 1 of i and of k. First-order: the loop's rotation vector is
    omega_ik - omega_ij - R_ij^T omega_jk, its covariance C_ik + C_ij + R_ij^T C_jk R_ij."""
    rows = []
    for sequence in sequences:
        gaps = LOOP_GAPS.get(sequence.name, (1, 2))
        triplets = [(i, i + g, i + 2 * g) for g in gaps
                    for i in range(0, len(sequence.images) - 2 * g, g)]
        if max_loops:
            triplets = triplets[:max_loops]
        for salt, (i, j, k) in enumerate(triplets):
            fits = []
            for (a, b), (half_a, half_b) in (((i, j), (0, 0)), ((j, k), (1, 0)), ((i, k), (1, 1))):
                p1, p2, _ = matcher.match(sequence.images[a], sequence.images[b],
                                          sequence.max_side or None)
                keep = ((_keypoint_half(p1, 3 * salt + (a - i) // max(j - i, 1)) == half_a) &
                        (_keypoint_half(p2, 3 * salt + (b - i) // max(j - i, 1)) == half_b))
                fits.append((p1[keep], p2[keep]))
            for estimated, mode in NOISE_MODES:
                params = params_for(sigma, estimated)
                reports = [rcme.estimateRelativeMotion(p1, p2, sequence.K, params)
                           for p1, p2 in fits]
                if any(r.status != rcme.STATUS_SUCCESS for r in reports):
                    continue
                if any(metrics.pose_failure(e.rotationDeg, e.translationDeg) for e in (
                        rcme.compareMotion(r.R, r.t, *sequence.relative_motion(a, b)[:2])
                        for r, (a, b) in zip(reports, ((i, j), (j, k), (i, k))))):
                    continue  # a wrong answer in the loop: not noise
                pair_candidates = [
                    candidates(r, _Fit(p1, p2, sequence.K), params)
                    for r, (p1, p2) in zip(reports, fits)]
                for name in pair_candidates[0]:
                    covariances = [c[name] for c in pair_candidates]
                    nees1, conditioning = loop_translation_nees(reports, covariances)
                    rows.append(dict(dataset=sequence.name, mode=mode, candidate=name,
                                     nees3=loop_nees(reports, covariances), nees1=nees1,
                                     conditioning=conditioning, few_inliers=any(
                                         int(np.sum(r.mask)) - 5 < MIN_NOISE_DOF
                                         for r in reports)))
    return rows


class _SubsampledMatcher:
    """A matcher that keeps half of another's matches (a hash of the point in image 1, independent
    of the loops' split): the loop tests at a smaller share of the matches."""

    def __init__(self, matcher):
        self.matcher = matcher

    def match(self, *args):
        p1, p2, *rest = self.matcher.match(*args)
        q = np.round(np.asarray(p1) * 64).astype(np.int64)
        keep = (((q[:, 0] * 2654435761) ^ (q[:, 1] * 40503)) >> 11) & 1 == 0
        return (p1[keep], p2[keep], *rest)


def loop_nees(reports, covariances):
    """Rotation NEES of the loop of the reports of (i, j), (j, k), (i, k) with these covariances:
    omega = log(R_ik^T R_jk R_ij) ~ omega_ik - omega_ij - R_ij^T omega_jk to first order, with
    covariance C_ik + C_ij + R_ij^T C_jk R_ij."""
    Rij, Rjk, Rik = (np.asarray(r.R) for r in reports)
    Cij, Cjk, Cik = (np.asarray(c)[:3, :3] for c in covariances)
    omega = _log(Rik.T @ Rjk @ Rij)
    C = Cik + Cij + Rij.T @ Cjk @ Rij
    return float(omega @ np.linalg.solve(C, omega))


def _perturbed(report, delta):
    """The motion of a report moved by delta in its covariance's tangent: R exp([omega]x),
    t + B beta normalized."""
    R, t = np.asarray(report.R, np.float64), np.ravel(report.t) / np.linalg.norm(report.t)
    t = t + metrics.tangent_basis(t) @ delta[3:]
    return R @ metrics.rotation_exp(delta[:3]), t / np.linalg.norm(t)


def _coplanarity(motions):
    """Signed angle of t_ik out of the plane of R_jk t_ij and t_jk (all in frame k): 0 for exact
    estimates, since t_ik = R_jk t_ij + t_jk up to the two unknown scales; and the angle between
    R_jk t_ij and t_jk, which says how well that plane is defined."""
    (_, tij), (Rjk, tjk), (_, tik) = motions
    b, c = Rjk @ tij, tjk
    normal = np.cross(b, c)
    return (math.asin(float(np.clip(tik @ normal / np.linalg.norm(normal), -1, 1))),
            math.atan2(np.linalg.norm(normal), float(b @ c)))


def loop_translation_nees(reports, covariances, step=1e-6):
    """The translation directions' loop test: the coplanarity angle e of the loop of the reports
    of (i, j), (j, k), (i, k) and its variance propagated to first order from the three 5x5
    covariances (e depends on all three translation directions and on R_jk); e^2 / var is
    chi-square(1) for a calibrated covariance. Also the angle between the plane's two spanning
    directions over its own standard deviation: the first order holds only when it is large
    (three nearly collinear baselines leave the plane undefined)."""
    base = [_perturbed(r, np.zeros(5)) for r in reports]
    e, spread = _coplanarity(base)
    variance, spread_variance = 0.0, 0.0
    for p, (report, C) in enumerate(zip(reports, covariances)):
        g, h = np.empty(5), np.empty(5)
        for k in range(5):
            delta = np.zeros(5)
            delta[k] = step
            plus, minus = list(base), list(base)
            plus[p], minus[p] = _perturbed(report, delta), _perturbed(report, -delta)
            (e_plus, s_plus), (e_minus, s_minus) = _coplanarity(plus), _coplanarity(minus)
            g[k], h[k] = (e_plus - e_minus) / (2 * step), (s_plus - s_minus) / (2 * step)
        C = np.asarray(C, np.float64)
        variance += float(g @ C @ g)
        spread_variance += float(h @ C @ h)
    return e * e / variance, (spread / math.sqrt(spread_variance) if spread_variance > 0
                              else math.inf)


# Synthetic triplets of the loop tests: camera centres 0, c1, c2 (units) with N(0, scatter) added,
# 800 points 6-20 units deep, small rotations. Sideways: baselines about 17 deg apart; triangle:
# about 80 deg; forward: three nearly collinear baselines along the optical axis, as a car's.
SYNTHETIC_LOOP_GEOMETRIES = (("sideways", (1.0, 0.1, 0.3), (2.0, -0.1, 0.5), 0.1),
                             ("triangle", (1.0, 0.0, 0.3), (1.0, 1.0, 0.0), 0.1),
                             ("forward, nearly collinear", (0.0, 0.0, 1.0), (0.0, 0.0, 2.0), 0.01))


FLOOR_KIND = "keypoints split, the %g px floor candidate" % EPIPOLAR_FLOOR_PX


def synthetic_loop_values(count, seed=1, geometries=SYNTHETIC_LOOP_GEOMETRIES, points=800):
    """The loop tests on synthetic triplets with independent Gaussian noise (exact covariances):
    keypoints shared by the two pairs of an image, as SIFT's are (sideways only), against split
    between them as the real loops split them; f = 700 px, sigma 0.5 px, this many scene points
    (each pair of a split loop gets about a quarter). Per (geometry, kind), an array of (NEES3,
    NEES1, conditioning) rows, one per loop of three successes; the split loops also with the floor
    candidate's covariance (FLOOR_KIND)."""
    rng = np.random.default_rng(seed)
    K = np.array([[700.0, 0, 500], [0, 700, 350], [0, 0, 1]])
    sigma = 0.5
    values = {}
    for geometry, c1, c2, scatter in geometries:
        kinds = (("shared keypoints", "keypoints split between the pairs")
                 if geometry == "sideways" else ("keypoints split between the pairs",))
        found = {kind: [] for kind in kinds + (FLOOR_KIND,)}
        for _ in range(count):
            X = np.c_[rng.uniform(-6, 6, points), rng.uniform(-4, 4, points),
                      rng.uniform(6, 20, points)]
            rotations = [np.eye(3)] + [metrics.rotation_exp(rng.normal(0, 0.05, 3)) for _ in range(2)]
            centres = [np.zeros(3), np.r_[c1] + rng.normal(0, scatter, 3),
                       np.r_[c2] + rng.normal(0, scatter, 3)]
            images = []
            for R, C in zip(rotations, centres):
                x = (X @ R.T - R @ C) @ K.T
                images.append(x[:, :2] / x[:, 2:] + rng.normal(0, sigma, (len(X), 2)))
            half = [rng.integers(0, 2, len(X)) for _ in range(3)]
            for kind in kinds:
                reports, fits = [], []
                for (a, b), (half_a, half_b) in (((0, 1), (0, 0)), ((1, 2), (1, 0)),
                                                 ((0, 2), (1, 1))):
                    keep = (np.ones(len(X), bool) if kind == "shared keypoints"
                            else (half[a] == half_a) & (half[b] == half_b))
                    fits.append(_Fit(images[a][keep], images[b][keep], K))
                    reports.append(rcme.estimateRelativeMotion(
                        images[a][keep], images[b][keep], K, params_for(sigma, True)))
                if all(r.status == rcme.STATUS_SUCCESS for r in reports):
                    covariances = [r.covariance for r in reports]
                    found[kind].append((loop_nees(reports, covariances),
                                        *loop_translation_nees(reports, covariances)))
                    if kind != "shared keypoints":  # the floor candidate on the same loops
                        covariances = [candidates(r, f, params_for(sigma, True))[FLOOR]
                                       for r, f in zip(reports, fits)]
                        found[FLOOR_KIND].append((loop_nees(reports, covariances),
                                                  *loop_translation_nees(reports, covariances)))
        for kind, loops in found.items():
            values[geometry, kind] = np.asarray(loops).reshape(-1, 3)
    return values


def synthetic_loops(count, seed=1):
    """The synthetic loop tests' table."""
    table = []
    values = synthetic_loop_values(count, seed)
    for points in (400, 1600):  # how the loop test reads at fewer and more matches per pair
        more = synthetic_loop_values(count, seed, SYNTHETIC_LOOP_GEOMETRIES[:1], points)
        values.update({("%s, %d points" % (geometry, points), kind): v
                       for (geometry, kind), v in more.items() if kind != "shared keypoints"})
    for (geometry, kind), v in values.items():
        table.append([geometry, kind, str(len(v))] + _stats(v[:, 0], 3) + _stats(v[:, 1], 1)
                     + ["%.1f" % np.median(v[:, 2]) if len(v) else "-"])
    lines = ["\n### The loop tests on synthetic triplets\n",
             "%d triplets per geometry with independent noise (sigma 0.5 px, the default "
             "covariance): a calibrated covariance gives chi-square(3) (rotation) and "
             "chi-square(1) (translation directions' coplanarity: mean 1, median 0.455, 95 %% "
             "below 3.841) when no keypoint enters two pairs of a loop; shared keypoints cancel "
             "in the loop and make it look conservative. Geometries (800 scene points unless "
             "said): %s.\n" % (count, "; ".join(
                 "%s: centres 0, %s, %s + N(0, %g) per axis" % (g, c1, c2, s)
                 for g, c1, c2, s in SYNTHETIC_LOOP_GEOMETRIES))]
    lines.append(_markdown(["geometry", "keypoints", "loops"] + LOOP_HEADER, table))
    return lines


class _Fit:
    """The parts of a benchmark Pair that candidates() reads."""

    def __init__(self, points1, points2, K):
        self.points1, self.points2, self.K = points1, points2, K


# The translation directions' loop test judges a sequence only where its loops' baselines span a
# plane: median conditioning at least this (synthetic triplets are chi-square(1) from about 2 up).
MIN_LOOP_CONDITIONING = 5.0


def gt_error(rows, loops, axes, loop_key, loop_dof):
    """Per dataset: the ground truth's error per axis (deg) of a block of the tangent (rotation:
    axes 0-2, judged by the loops' NEES3; translation direction: axes 3-4, by their NEES1) that
    the pairs' errors imply beyond the estimate's own, the latter being the library covariance
    scaled by the loop test's mean NEES / its dof, kappa (no ground truth in it):
    sigma_gt^2 = max(0, (sum |theta_block|^2 - kappa sum tr C_block) / (k n)), k the block's
    axes."""
    out = {}
    k = axes.stop - axes.start
    for dataset in sorted({r["dataset"] for r in rows}):
        subset = [r for r in rows if r["dataset"] == dataset]
        loop = [r for r in loops if r["dataset"] == dataset]
        if not loop or (loop_key == "nees1" and np.median(
                [r["conditioning"] for r in loop]) < MIN_LOOP_CONDITIONING):
            continue
        kappa = np.mean([r[loop_key] for r in loop]) / loop_dof
        total = sum(float(r["theta"][axes] @ r["theta"][axes]) for r in subset)
        own = kappa * sum(np.trace(r["covariance"][axes, axes]) for r in subset)
        out[dataset] = (np.degrees(np.sqrt(max(0.0, (total - own) / (k * len(subset))))), kappa)
    return out


def _baseline(sequences, pair_name):
    """The ground truth's baseline length of a pair named '<dataset> i-j' (the sequence's units)."""
    dataset, frames = pair_name.rsplit(" ", 1)
    i, j = (int(f) for f in frames.split("-"))
    return sequences[dataset].relative_motion(i, j)[2]


# ---- synthetic -----------------------------------------------------------------------------

GROSS_ROTATION_DEG, GROSS_TRANSLATION_DEG = metrics.ROTATION_FAILURE_DEG, \
    metrics.TRANSLATION_FAILURE_DEG


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


# The synthetic NEES3 mean's spread is shown per block of this many seeds per configuration (the
# suite's size before issue 36c: its 1080 scenes gave a mean of 2.62, the lowest of four blocks).
SEED_BLOCK = 15


def run_synthetic(scenes_per_config, stated_sigma_factor):
    rows, noise_ratio = [], []
    for config, seed in synthetic_configs(scenes_per_config):
        sp = rcme.SceneParams()
        sp.kind, sp.numPoints, sp.sigma = config["kind"], config["n"], config["sigma"]
        sp.baseline, sp.inlierRatio, sp.seed = config["baseline"], config["inlier_ratio"], seed
        scene = rcme.generateScene(sp)
        for estimated, mode in NOISE_MODES:
            params = params_for(config["sigma"] * stated_sigma_factor, estimated)
            report = rcme.estimateRelativeMotion(scene.points1, scene.points2,
                                                 scene.cameraMatrix, params)
            if report.status != rcme.STATUS_SUCCESS:
                continue
            error = rcme.compareMotion(report.R, report.t, scene.R, scene.t)
            theta = tangent_error(report.R, report.t, scene.R, scene.t)
            gross = theta is None or error.rotationDeg > GROSS_ROTATION_DEG or \
                error.translationDeg > GROSS_TRANSLATION_DEG
            if estimated:
                noise_ratio.append(report.noiseSigma / config["sigma"])
            covariances = candidates(report, _Fit(scene.points1, scene.points2,
                                                  scene.cameraMatrix), params)
            for name, C in covariances.items():
                n5, n3 = (np.inf, np.inf) if theta is None else nees(theta, C)
                rows.append(dict(mode=mode, candidate=name, gross=gross, nees5=n5, nees3=n3,
                                 seed=seed, scene="generic" if config["kind"] == rcme.SCENE_GENERIC
                                 else "corridor",
                                 outliers="no outliers" if config["inlier_ratio"] == 1.0
                                 else "30 % outliers"))
    lines = ["## Synthetic scenes\n",
             "%d scenes (generic: n 100/300/1000, sigma 0.5/1/2 px, baseline 0.5/1/2 m; corridor: "
             "same n and sigma, baseline 1 m; inlier ratio 1.0 and 0.7), stated sigma = %g x the "
             "true one, default Params otherwise; runs more than %g deg / %g deg off (gross) "
             "left out.\n" % (len(synthetic_configs(scenes_per_config)), stated_sigma_factor,
                              GROSS_ROTATION_DEG, GROSS_TRANSLATION_DEG)]
    groups = []
    for estimated, mode in NOISE_MODES:
        for name in ((REPORTED, PREVIOUS, LEVERAGE_ONLY, BAND_ONLY, WHOLE_BAND, MODEL_BASED,
                      "sandwich", SPATIAL, FLOOR) if estimated else
                     (REPORTED,)):
            for scene, outliers in (("all", "all"), ("generic", "no outliers"),
                                    ("generic", "30 % outliers"), ("corridor", "no outliers"),
                                    ("corridor", "30 % outliers")):
                groups.append(([mode, name, scene, outliers],
                               lambda r, m=mode, c=name, s=scene, o=outliers:
                               (r["mode"], r["candidate"]) == (m, c) and not r["gross"] and
                               (s == "all" or (r["scene"], r["outliers"]) == (s, o))))
    lines.append(_markdown(["noise", "covariance", "scene", "outliers"] + NEES_HEADER,
                           nees_table(rows, groups)))
    r = np.asarray(noise_ratio)
    reported = [x for x in rows if x["candidate"] == REPORTED and x["mode"] == NOISE_MODES[0][1]]
    blocks = [[x["nees3"] for x in reported if not x["gross"] and b <= x["seed"] < b + SEED_BLOCK]
              for b in range(0, scenes_per_config, SEED_BLOCK)]
    if len(blocks) > 1:
        lines.append("\nThe NEES3 mean is heavy-tailed: the default's, per block of %d seeds "
                     "(%d scenes each), mean / median / below 7.815: %s.\n" % (
                         SEED_BLOCK, SEED_BLOCK * len(synthetic_configs(1)),
                         "; ".join("%.2f / %.2f / %.0f %%" % (np.mean(v), np.median(v),
                                                               100 * np.mean(np.less(v, 7.815)))
                                   for v in blocks if v)))
    # noiseSigma is NaN where the residuals fill the band as uniformly as no Gaussian would
    # (Report::noiseSigma): counted apart, not averaged.
    estimated = r[np.isfinite(r)]
    if len(estimated):
        lines.append("\nnoiseSigma / true sigma over %d successful runs with an estimate (%d "
                     "without: residuals as uniform as no Gaussian's): mean %.3f, median %.3f, "
                     "5-95 %% range %.3f-%.3f; gross runs: %d of %d.\n" % (
                         len(estimated), len(r) - len(estimated), estimated.mean(),
                         np.median(estimated), *np.percentile(estimated, [5, 95]),
                         sum(x["gross"] for x in reported), len(reported)))
    return lines


# ---- report --------------------------------------------------------------------------------

def _markdown(header, lines):
    return "\n".join(["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
                     + ["| " + " | ".join(line) + " |" for line in lines]) + "\n"


def real_report(args, out_dir):
    matcher = matching.Matcher(args.cache)
    selection = argparse.Namespace(data=args.data, max_references=args.max_references,
                                   quick=False)
    with_pose = [p for p in run_benchmark.real_pairs(selection, matcher)[0]
                 if p.K is not None and p.R_gt is not None]
    rows, others = run_pairs(with_pose, args.sigma)
    sequences = datasets.load_all(args.data)[0]
    loops = loop_rows(sequences, matcher, args.sigma, args.max_loops)
    datasets_seen = sorted({r["dataset"] for r in rows}, key=lambda d: (split_of(d), d))
    candidate_names = list(dict.fromkeys(r["candidate"] for r in rows))
    lines = ["## Real pairs against the ground truth\n",
             "The benchmark's calibrated pairs (SIFT, ratio test 0.8), sigma %g px (threshold "
             "%.2f px), default Params; right answers only (rotation <= %g deg, translation "
             "direction <= %g deg). Tuned on: %s; reported on: %s.\n" % (
                 args.sigma, 1.959963984540054 * args.sigma, metrics.ROTATION_FAILURE_DEG,
                 metrics.TRANSLATION_FAILURE_DEG, ", ".join(TUNE), ", ".join(REPORT)),
             "Wrong answers / failures left out (estimated noise): %s.\n" % ", ".join(
                 "%s %d / %d" % (d, *others.get((d, NOISE_MODES[0][1]), (0, 0)))
                 for d in datasets_seen)]
    groups = [([d, split_of(d), mode, name],
               lambda r, d=d, m=mode, c=name: (r["dataset"], r["mode"], r["candidate"]) ==
               (d, m, c))
              for d in datasets_seen for _, mode in NOISE_MODES for name in candidate_names
              if name == REPORTED or mode == NOISE_MODES[0][1]]
    lines.append(_markdown(["dataset", "split", "noise", "covariance"] + NEES_HEADER,
                           nees_table(rows, groups)))
    default = [r for r in rows if r["mode"] == NOISE_MODES[0][1] and r["candidate"] == REPORTED]
    for _, mode in NOISE_MODES:
        reported = [r for r in rows if r["mode"] == mode and r["candidate"] == REPORTED]
        table = sum((reliability_rows(reported, block)[0] for block in RELIABILITY_BLOCKS), [])
        lines += ["\n### Reliability, %s\n" % mode,
                  "Pairs binned by their predicted standard deviation (per axis, RMS over the "
                  "block's axes), against the RMS actual error per axis; a calibrated covariance "
                  "has a ratio near 1.\n",
                  _markdown(["dataset", "block", "predicted std bin, deg", "pairs",
                             "predicted std, deg", "actual error, deg", "ratio"], table)]
    points = reliability_rows(default, RELIABILITY_BLOCKS[0])[1]
    plot = os.path.join(out_dir, "covariance_reliability.png")
    plots.reliability_scatter(plot, "rotation: predicted std against actual error, per axis "
                              "(default covariance)", points)
    lines.append("![reliability](%s)\n" % os.path.basename(plot))
    lines += ["## Loops of three frames, without the ground truth\n",
              "Triplets (i, i+g, i+2g) of each sequence (gaps %s), each image's keypoints "
              "split between its two pairs of the loop; rotation NEES of the loop against the "
              "three pairs' covariances (chi-square(3); checked on synthetic triplets below: "
              "with shared keypoints a calibrated covariance looks conservative, hence the "
              "split). The translation directions: t_ik, R_jk t_ij and t_jk lie in one plane "
              "for exact estimates (t_ik = R_jk t_ij + t_jk up to the scales); NEES1 is the "
              "square of t_ik's angle out of the plane of the other two over its variance "
              "propagated from the three 5x5 covariances (chi-square(1)). Conditioning: the "
              "angle between R_jk t_ij and t_jk over its standard deviation; below about 2 the "
              "plane is ill-defined and the test is weak (synthetic: mean 0.82 there). Loops "
              "with a failure or a wrong answer are left out.\n" % ", ".join(
                  "%s %s" % (k, "/".join(map(str, v))) for k, v in LOOP_GAPS.items())]
    loop_groups = [([d, split_of(d), mode, name],
                    lambda r, d=d, m=mode, c=name: (r["dataset"], r["mode"], r["candidate"]) ==
                    (d, m, c))
                   for d in sorted({r["dataset"] for r in loops}, key=lambda d: (split_of(d), d))
                   for _, mode in NOISE_MODES for name in candidate_names
                   if name == REPORTED or mode == NOISE_MODES[0][1]]
    loop_table = []
    for labels, keep in loop_groups:
        subset = [r for r in loops if keep(r)]
        if subset:
            loop_table.append(labels + [str(len(subset))] + loop_stats(subset))
    lines.append(_markdown(["sequence", "split", "noise", "covariance", "loops"] + LOOP_HEADER,
                           loop_table))
    default_loops = [r for r in loops if r["mode"] == NOISE_MODES[0][1] and
                     r["candidate"] == REPORTED]
    estimated_loops = [r for r in loops if r["mode"] == NOISE_MODES[0][1]]
    smaller = [r for r in loop_rows(sequences, _SubsampledMatcher(matcher), args.sigma,
                                    args.max_loops)
               if r["mode"] == NOISE_MODES[0][1] and r["candidate"] in (REPORTED, PREVIOUS, FLOOR)]
    share_table = [[d, split_of(d), share, name, which, str(len(subset))] + loop_stats(subset)
                   for d in sorted({r["dataset"] for r in default_loops},
                                   key=lambda d: (split_of(d), d))
                   for name in (REPORTED, PREVIOUS, FLOOR)
                   for share, rows_of in (("1/4", estimated_loops), ("1/8", smaller))
                   for which, keep in (("all", lambda r: True),
                                       ("35 inliers or more in all three pairs",
                                        lambda r: not r["few_inliers"]))
                   for subset in [[r for r in rows_of if r["dataset"] == d and
                                   r["candidate"] == name and keep(r)]] if subset]
    lines += ["\nThe same loops with half of each pair's matches left out first (each pair keeps "
              "about 1/8 of its matches instead of 1/4). A covariance that leaves out an error "
              "which does not shrink with the number of matches looks more over-confident the "
              "more matches it is computed from. The reported covariance's noise is the posterior "
              "of the estimate and the stated sigma (a prior worth %g residual degrees of "
              "freedom). From 35 inliers on the covariance is also raised to the "
              "(leverage-corrected) sandwich, so the loops whose three pairs all have them are "
              "shown apart. Before: %s. The floor candidate: %s.\n" % (STATED_NOISE_DOF,
                                                                      PREVIOUS, FLOOR),
              _markdown(["sequence", "split", "share of the matches", "covariance", "loops kept",
                         "loops"] + LOOP_HEADER, share_table)]
    gt = gt_error(default, default_loops, slice(0, 3), "nees3", 3)
    gt_t = gt_error(default, default_loops, slice(3, 5), "nees1", 1)
    by_name = {s.name: s for s in sequences}
    translation_points = reliability_rows(default, RELIABILITY_BLOCKS[1])[1]
    lines += ["\n## The ground truth's own error\n",
              "Per axis, what the pairs' rotation errors against the ground truth imply beyond "
              "the estimate's own error (the default covariance scaled by the loop test's mean "
              "NEES3 / 3, kappa). KITTI's poses come from an OXTS RT3003 GPS/INS whose "
              "specification is %s deg (roll, pitch, heading; 1 sigma, absolute).\n" %
              "/".join("%g" % v for v in KITTI_GT_ROTATION_SPEC_DEG),
              _markdown(["dataset", "kappa (loops)", "ground truth rotation error per axis, deg",
                         "median predicted rotation std per axis, deg"],
                        [[d, "%.2f" % k, "%.4f" % s,
                          "%.4f" % np.median(points[d][0])] for d, (s, k) in gt.items()])]
    lines += ["\nThe same for the translation direction, where the loops' coplanarity judges "
              "it (median conditioning at least %g; kappa the loops' mean NEES1). Times the "
              "pair's baseline, the error per axis is a relative position error across the "
              "baseline (the sequence's units: metres for KITTI).\n" % MIN_LOOP_CONDITIONING,
              _markdown(["dataset", "kappa (loops)",
                         "ground truth translation direction error per axis, deg",
                         "median predicted translation direction std per axis, deg",
                         "median baseline", "times the median baseline"],
                        [[d, "%.2f" % k, "%.4f" % s, "%.4f" % np.median(translation_points[d][0]),
                          "%.3f" % b, "%.4f" % (np.radians(s) * b)]
                         for d, (s, k) in gt_t.items()
                         for b in [np.median([_baseline(by_name, r["pair"]) for r in default
                                              if r["dataset"] == d])]])]
    with_gt = []
    for r in default:
        if r["dataset"] in gt:
            C = r["covariance"].copy()
            C[:3, :3] += np.radians(gt[r["dataset"]][0]) ** 2 * np.eye(3)
            if r["dataset"] in gt_t:
                C[3:, 3:] += np.radians(gt_t[r["dataset"]][0]) ** 2 * np.eye(2)
            n5, n3 = nees(r["theta"], C)
            with_gt.append(dict(r, nees5=n5, nees3=n3))
    lines += ["\nThe default covariance with those errors added (the translation direction's "
              "only where its loops judge it: %s; the added errors are estimated from these "
              "same pairs, so this table checks the distribution's shape, not its scale):\n" %
              (", ".join(gt_t) or "none"),
              _markdown(["dataset", "split"] + NEES_HEADER, nees_table(
                  with_gt, [([d, split_of(d)], lambda r, d=d: r["dataset"] == d)
                            for d in datasets_seen]))]
    if not args.quick:
        lines += bundle_adjusted_ground_truth(args, rows)
    lines += five_dof_sections(rows, datasets_seen, with_pose, args.sigma)
    return lines


# Bootstrap replicates over the tracks for the adjustment's own precision: fountain-P11's agree
# with its covariance (doc/covariance.md) and take 13 minutes, templeSR's (2.5 views per track)
# are up to twice its covariance's standard deviations and take under a minute. A sequence not
# listed takes none.
ADJUSTMENT_BOOTSTRAP = {"fountain-P11": 0, "templeSR": 30}


def bundle_adjusted_ground_truth(args, rows):
    """fountain-P11 and templeSR judged with their ground truth's error as a bundle adjustment of
    all their images measures it (bundle_adjustment.py: the ground truth's relative motions
    against the adjusted ones, beyond the adjustment's own precision, over the benchmark's pairs;
    no two-view estimate in it), added to the reported covariance per axis."""
    import bundle_adjustment as bundle
    table, notes = [], []
    for name in bundle.SEQUENCES:
        judged_rows = [r for r in rows if r["dataset"] == name and r["candidate"] == REPORTED]
        if not judged_rows:
            continue
        result = bundle.measure(args.data, args.cache, ADJUSTMENT_BOOTSTRAP.get(name, 0),
                                log=lambda s: sys.stderr.write(s + "\n"), name=name)
        variant = result["variants"][bundle.VARIANTS[0][0]]
        difference, own, gt = bundle.ground_truth_error(variant["pairs"],
                                                        result["benchmark_pairs"])

        def adjusted(r, variant=variant):
            row = variant["pairs"][tuple(int(f) for f in r["pair"].rsplit(" ", 1)[1].split("-"))]
            if row["bootstrap_cov"] is None:
                return row
            return dict(row, cov=psd_max(row["cov"], row["bootstrap_cov"]))

        def zero(r):
            return 0.0

        # (label, the reference's motion in the pair's tangent less the ground truth's, the
        # covariance added); the adjusted motions as the reference: theta against them is, to
        # first order, theta against the ground truth less the ground truth's in the adjusted
        # tangent
        judged = (("ground truth as exact", zero, zero),
                  ("+ its rotation error", zero,
                   lambda r, gt=gt: np.diag(np.radians(np.r_[gt[:3], 0, 0])) ** 2),
                  ("+ its rotation and translation direction errors", zero,
                   lambda r, gt=gt: np.diag(np.radians(gt)) ** 2),
                  ("the adjusted motions instead (+ their covariance; the pair's matches are "
                   "among the adjustment's)", lambda r: adjusted(r)["theta"],
                   lambda r: adjusted(r)["cov"]))
        for _, mode in NOISE_MODES:
            for label, shift, extra in judged:
                subset = []
                for r in (r for r in judged_rows if r["mode"] == mode):
                    n5, n3 = nees(r["theta"] - shift(r), r["covariance"] + extra(r))
                    subset.append(dict(r, nees5=n5, nees3=n3))
                table.append([name, split_of(name), mode, label] +
                             nees_table(subset, [([], lambda r: True)])[0])
        notes.append(
            "%s: all %d images, %d tracks, %d observations; reprojection RMS %.4f px under the "
            "ground truth (points re-optimised), %.4f px adjusted, a cost drop of %.0f sigma^2 "
            "for %d free parameters (chi-square(%d) if the ground truth were exact). Over the "
            "benchmark's %d pairs, the ground truth's relative motion in the adjusted one's "
            "tangent differs by %s deg RMS per axis (rotation x / y / z, translation direction "
            "b1 / b2) where the adjustment's own standard deviation is %s deg: the ground "
            "truth's error, sqrt(difference^2 - own variance), is %s deg per axis.\n" % (
                name, len(result["per_image"]), result["tracks"], result["observations"],
                variant["rms_gt"], variant["rms_ba"],
                (variant["cost_gt"] - variant["cost_ba"]) / variant["sigma"] ** 2,
                variant["free"], variant["free"], len(result["benchmark_pairs"]),
                " / ".join("%.4f" % v for v in difference), " / ".join("%.4f" % v for v in own),
                " / ".join("%.4f" % v for v in gt)))
    if not table:
        return []
    return (["\n## The ground truth, measured by a bundle adjustment\n",
             "A bundle adjustment of all the images of a sequence (`bundle_adjustment.py`: the "
             "benchmark's SIFT matched between all pairs of images, K fixed as given, Huber loss) "
             "against the ground-truth cameras. No two-view estimate enters it. The ground "
             "truth's error it implies is added to the reported covariance (diagonal, per "
             "axis). The adjustment's own precision is its covariance's, or, with bootstrap "
             "replicates over the tracks (%s), the larger of the two.\n" % ", ".join(
                 "%s %d" % item for item in ADJUSTMENT_BOOTSTRAP.items())] + notes +
            [_markdown(["dataset", "split", "noise", "ground truth"] + NEES_HEADER, table)])


# Stated calibration errors propagated to the motion (standard deviation of the principal point,
# px, and of the focal length, as a share of it): a term a user with that calibration would add.
CALIBRATION_ERRORS = ((1.0, 0.0), (2.0, 0.0), (5.0, 0.0), (0.0, 0.01), (2.0, 0.01))


def _translation_nees(r, C):
    return float(r["theta"][3:] @ np.linalg.solve(C[3:, 3:], r["theta"][3:]))


def self_calibration(rows):
    """The K correction (fx, fy, cx, cy, px) that best fits all these pairs' inliers with each
    pair's motion free, its standard deviation, and the drop of the squared residuals it brings
    (sigma^2 units, first order)."""
    information = sum(r["K_information"] for r in rows)
    score = sum(r["K_score"] for r in rows)
    correction = -np.linalg.solve(information, score)
    return (correction, np.sqrt(np.diag(np.linalg.inv(information))),
            float(score @ np.linalg.solve(information, score)))


def _median_nees5_with_K(task_pairs, correction, sigma):
    """The default's NEES5 median against the ground truth over its right answers when it is given
    K corrected by (fx, fy, cx, cy)."""
    values = []
    for pair in task_pairs:
        K = pair.K.copy()
        K[0, 0], K[1, 1] = K[0, 0] + correction[0], K[1, 1] + correction[1]
        K[0, 2], K[1, 2] = K[0, 2] + correction[2], K[1, 2] + correction[3]
        if K[0, 0] <= 0 or K[1, 1] <= 0:
            return "- (no camera: focal length <= 0)"
        report = rcme.estimateRelativeMotion(pair.points1, pair.points2, K,
                                             params_for(sigma, True))
        if report.status != rcme.STATUS_SUCCESS:
            continue
        error = rcme.compareMotion(report.R, report.t, pair.R_gt, pair.t_gt)
        theta = tangent_error(report.R, report.t, pair.R_gt, pair.t_gt)
        if theta is not None and not metrics.pose_failure(error.rotationDeg, error.translationDeg):
            values.append(nees(theta, report.covariance)[0])
    return "%.1f (%d)" % (np.median(values), len(values)) if values else "-"


def five_dof_sections(rows, datasets_seen, pairs, sigma):
    """Where the 5-DoF NEES against the ground truth comes from, per dataset: the translation
    block alone, the share along the covariance's narrowest direction, the exact likelihood ratio
    against the first order, the ground truth's epipolar shift in px; and the NEES with a stated
    calibration error added. pairs: the benchmark pairs the rows come from, at Params.sigma
    sigma."""
    default = {d: [r for r in rows if (r["dataset"], r["mode"], r["candidate"]) ==
                   (d, NOISE_MODES[0][1], REPORTED)] for d in datasets_seen}
    model = {d: [r for r in rows if (r["dataset"], r["mode"], r["candidate"]) ==
                 (d, NOISE_MODES[0][1], MODEL_BASED)] for d in datasets_seen}
    table = []
    for d in datasets_seen:
        subset = default[d]
        if not subset:
            continue
        narrowest = []
        for r in subset:
            w, V = np.linalg.eigh(r["covariance"])
            narrowest.append(float(V[:, 0] @ r["theta"]) ** 2 / w[0] / r["nees5"])
        n2 = _stats([_translation_nees(r, r["covariance"]) for r in subset], 2)
        table.append([d, split_of(d), str(len(subset)),
                      "%.2f" % np.median([r["nees5"] for r in subset]),
                      "%.2f" % np.median([r["nees3"] for r in subset])] + n2[1:] + [
                      "%.0f %%" % (100 * np.median(narrowest)),
                      "%.1f / %.1f" % (np.median([r["nees5"] for r in model[d]]),
                                       np.median([r["likelihood_ratio"] for r in model[d]])),
                      "%.3f" % np.median([r["epipolar_shift"] for r in subset])])
    lines = ["\n## Where the 5-DoF NEES comes from\n",
             "Default covariance (estimated noise, reported). NEES2: the translation direction's "
             "block alone (chi-square(2): median 1.39, 95 % below 5.99). Narrowest direction: "
             "the share of NEES5 along the covariance's smallest eigenvector (a combination of "
             "rotation and translation direction; a calibrated covariance: median 12 %, mean "
             "20 %). "
             "Likelihood ratio: (SSR of the inliers under the ground truth's motion - SSR under "
             "the estimate) h / sigma^2, the exact form of the model-based covariance's NEES5; "
             "equal to it where the first order holds. Epipolar shift: sqrt of that SSR "
             "difference over the inliers, in px: how far the ground truth's epipolar geometry "
             "is from what the matches fit.\n",
             _markdown(["dataset", "split", "pairs", "NEES5 median", "NEES3 median",
                        "NEES2 median", "NEES2 < 5.991", "narrowest direction's share, median",
                        "model-based NEES5 / likelihood ratio, medians",
                        "epipolar shift, median px"], table)]
    table = []
    for pp, focal in CALIBRATION_ERRORS:
        for d in datasets_seen:
            n5, n3, n2 = [], [], []
            for r in default[d]:
                G, sf = r["motion_by_K"], focal * r["focal_length"]
                C = r["covariance"] + G @ np.diag([sf * sf, sf * sf, pp * pp, pp * pp]) @ G.T
                a, b = nees(r["theta"], C)
                n5.append(a)
                n3.append(b)
                n2.append(_translation_nees(r, C))
            if n5:
                table.append(["%g px" % pp, "%g %%" % (100 * focal), d, split_of(d),
                              str(len(n5))] + _stats(n3, 3)[1:] + _stats(n5, 5)[1:] +
                             _stats(n2, 2)[1:])
    fitted_K = []
    for d in datasets_seen:
        if default[d]:
            correction, std, drop = self_calibration(default[d])
            fitted_K.append([d, split_of(d), str(len(default[d]))] +
                            ["%.1f +- %.1f" % (c, e) for c, e in zip(correction, std)] +
                            ["%.1f" % drop, "%.1f -> %s" % (
                                np.median([r["nees5"] for r in default[d]]),
                                _median_nees5_with_K([p for p in pairs if p.dataset == d],
                                                     correction, sigma))])
    lines += ["\n### Can the pairs see an error of the camera matrix?\n",
              "One correction of K's fx, fy, cx, cy (px) fitted to the inliers of all of a set's "
              "pairs, each pair's motion free (to first order, in the model-based noise's "
              "units), with its standard deviation, and how much it lowers the sum of squared "
              "residuals (chi-square(4) if K is right and the pairs independent: 95 % below 9.49; "
              "the pairs share images and keypoints, which overstates it). No ground truth in "
              "it. A principal point the pairs leave undetermined to several px cannot be told "
              "from a motion error by any two-view covariance.\n",
              _markdown(["dataset", "split", "pairs", "fx", "fy", "cx", "cy",
                         "chi-square drop", "NEES5 median, given K -> fitted K"],
                        fitted_K)]
    lines += ["\n### With a stated calibration error\n",
              "The default covariance plus G diag(sf^2, sf^2, spp^2, spp^2) G^T, G the motion's "
              "derivative with respect to K's fx, fy, cx, cy (the final fit's implicit "
              "function), spp the principal point's and sf the focal length's standard "
              "deviation. Not in the library: what a user who knows their calibration's "
              "accuracy would add. Tuned on %s, reported on %s.\n" % (", ".join(TUNE),
                                                                     ", ".join(REPORT)),
              _markdown(["principal point std", "focal length std", "dataset", "split", "pairs",
                         "NEES3 median", "NEES3 < 7.815", "NEES5 median", "NEES5 < 11.07",
                         "NEES2 median", "NEES2 < 5.991"], table)]
    return lines


def main():
    ap = matching.benchmark_arguments(__doc__, REPO_ROOT, os.path.join(
        REPO_ROOT, "doc", "benchmark", "covariance_calibration.md"))
    ap.add_argument("--sigma", type=float, default=1.0, help="Params.sigma on real pairs (px)")
    ap.add_argument("--synthetic", action="store_true", help="also the synthetic scenes")
    ap.add_argument("--synthetic-only", action="store_true", help="only the synthetic scenes")
    ap.add_argument("--scenes-per-config", type=int, default=60,
                    help="synthetic scenes per configuration (48 configurations)")
    ap.add_argument("--stated-sigma-factor", type=float, default=1.0,
                    help="synthetic: Params.sigma as a multiple of the true noise")
    ap.add_argument("--max-references", type=int, default=0, metavar="K",
                    help="at most K reference frames per sequence (0: all), as the benchmark's")
    ap.add_argument("--max-loops", type=int, default=0,
                    help="at most this many triplets per sequence (0: all)")
    ap.add_argument("--synthetic-loops", type=int, default=200,
                    help="synthetic triplets per geometry of the loop tests' check")
    ap.add_argument("--quick", action="store_true",
                    help="2 reference frames and 2 loops per sequence, 1 synthetic scene per "
                         "configuration: checks that it runs, not its figures")
    args = ap.parse_args()
    if args.quick:
        args.max_references, args.max_loops, args.scenes_per_config = 2, 2, 1
        args.synthetic_loops = 3
    if not any(datasets.load_all(args.data)):
        print("skipped: no data under %s" % args.data)
        return run_benchmark.EXIT_SKIPPED
    out_dir = os.path.dirname(os.path.abspath(args.out))
    os.makedirs(out_dir, exist_ok=True)
    lines = ["# Motion covariance calibration\n",
             "Generated by `samples/benchmark/covariance_calibration.py%s`; see "
             "doc/covariance.md for what it means.\n" % (" --quick" if args.quick else "")]
    if not args.synthetic_only:
        lines += real_report(args, out_dir)
    if args.synthetic_only:
        lines = lines[:2]
    if args.synthetic or args.synthetic_only or args.quick:
        lines += run_synthetic(args.scenes_per_config, args.stated_sigma_factor)
        lines += synthetic_loops(args.synthetic_loops)
    with open(args.out, "w") as f:
        f.write("\n".join(lines))
    print("\n".join(lines))
    written = [p for p in (args.out, os.path.join(out_dir, "covariance_reliability.png"))
               if os.path.isfile(p) and os.path.getsize(p) > 0]
    if len(written) < (1 if args.synthetic_only else 2):
        print("FAILED: the report or the reliability plot was not written")
        return 1
    print("wrote %s" % ", ".join(written))
    return 0


if __name__ == "__main__":
    sys.exit(main())
