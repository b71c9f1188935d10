#!/usr/bin/python3
"""A sequence's ground-truth cameras against a bundle adjustment of all its images: how accurate
the ground truth's relative motions are, measured from the images without the benchmark's
two-view estimates (fountain-P11's 11 images, templeSR's 16).

    PYTHONPATH=build/python /usr/bin/python3 samples/benchmark/bundle_adjustment.py \
        [--sequence fountain-P11|templeSR] [--bootstrap 30] [--out FILE]
    PYTHONPATH=build/python build/poselib-venv/bin/python samples/benchmark/bundle_adjustment.py \
        --judge "rcme default" "PoseLib relpose" [--sequence ...]

--judge scores methods of the benchmark (methods.METHODS; PoseLib needs with_poselib.sh's venv)
on the sequence's benchmark pairs twice: against the ground truth and against the relative
motions of the adjustment with K fixed (AUC@10 and the mean of max(rotation, translation
direction error)), exactly N = 1000 with seeds 0-2 for rcme's methods and once for the peers, and
adaptive once; it prints a Markdown table (to --out when given) instead of the report.

The default --out is doc/benchmark/fountain_bundle_adjustment.md or
doc/benchmark/templeSR_bundle_adjustment.md. SIFT as the benchmark makes it (matching.Matcher, the
same cache, at the benchmark's image size for the sequence), matched between all pairs of images;
matches further than GATE_PX (Sampson, px) from the ground truth's epipolar lines are dropped (far
beyond any error the ground truth could have), and the matches are joined into tracks (a track
that meets one image twice is dropped). Each track is triangulated with the ground-truth cameras
(K fixed, as given), observations further than GATE_PX from their reprojection are dropped, and
then a sparse Levenberg-Marquardt over all cameras (rotation and centre) and all points, with a
Huber loss, finds the optimum of the image evidence. Gauge: camera 0 fixed and one coordinate of
the last camera's centre (the scale); relative rotations do not depend on it. Pure NumPy (the
Schur complement over the points).

Reported: tracks, points, observations; reprojection RMS under the ground-truth cameras (points
re-optimised with the cameras fixed) and under the adjusted ones, on the same observations, and
the drop of the weighted squared residuals (chi-square with the free parameters' degrees of
freedom in noise units if the ground truth were exact); the adjustment's precision of each
relative motion (from its covariance, and by a bootstrap over tracks); and the differences
between the adjusted and the ground truth's relative motions for the benchmark's pairs, in the
tangent of Report::covariance. Where the adjustment's precision is far below the differences, the
differences estimate the ground truth's error."""
import argparse
import os
import sys

import numpy as np

import datasets
import matching
import pairs as pair_selection
from metrics import rotation_exp, skew, tangent_basis

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

GATE_PX = 4.0  # matches and observations further than this from the ground truth are outliers
HUBER_PX = 1.0  # the Huber loss's corner (px); about 2-3 times the SIFT observations' noise
MIN_RAY_ANGLE_DEG = 1.0  # tracks whose rays are all closer than this are left out (depth-blind)


# ---- tracks ----------------------------------------------------------------------------------

def build_tracks(sequence, matcher, max_side):
    """obs_cam, obs_uv (m, 2), obs_track: every keypoint of every track, by matching all pairs
    (SIFT on the images downscaled to max_side, 0: full size)."""
    n = len(sequence.images)
    nodes, coords = {}, []

    def node(image, xy):
        key = (image, float(xy[0]), float(xy[1]))
        if key not in nodes:
            nodes[key] = len(coords)
            coords.append(key)
        return nodes[key]

    edges = []
    for i in range(n):
        for j in range(i + 1, n):
            p1, p2, _ = matcher.match(sequence.images[i], sequence.images[j], max_side)
            if len(p1) < 8:
                continue
            R, t, _ = sequence.relative_motion(i, j)
            F = np.linalg.inv(sequence.K).T @ skew(t) @ R @ np.linalg.inv(sequence.K)
            keep = datasets.sampson_distance(F, p1, p2) < GATE_PX
            edges += [(node(i, a), node(j, b)) for a, b in zip(p1[keep], p2[keep])]
    parent = list(range(len(coords)))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in edges:
        ra, rb = find(a), find(b)
        if ra != rb:
            parent[ra] = rb
    members = {}
    for k in range(len(coords)):
        members.setdefault(find(k), []).append(k)
    obs_cam, obs_uv, obs_track = [], [], []
    for k, group in enumerate(g for g in members.values() if len(g) >= 2):
        images = [coords[m][0] for m in group]
        if len(set(images)) != len(images):
            continue  # two keypoints of one image: an inconsistent track
        for m in group:
            obs_cam.append(coords[m][0])
            obs_uv.append(coords[m][1:])
            obs_track.append(k)
    _, obs_track = np.unique(obs_track, return_inverse=True)
    return np.array(obs_cam), np.array(obs_uv, np.float64), obs_track


def triangulate(R, C, K, obs_cam, obs_uv, obs_pt, count):
    """Linear (DLT) points from the observations, one per track."""
    P = np.einsum("ij,cjk->cik", K, np.concatenate([R, -np.einsum("cij,cj->ci", R, C)[:, :, None]],
                                                   axis=2))
    rows = np.concatenate([obs_uv[:, :1] * P[obs_cam, 2] - P[obs_cam, 0],
                           obs_uv[:, 1:] * P[obs_cam, 2] - P[obs_cam, 1]])
    A = np.zeros((count, 4, 4))
    np.add.at(A, np.r_[obs_pt, obs_pt], rows[:, :, None] * rows[:, None, :])
    X = np.linalg.eigh(A)[1][:, :, 0]
    return X[:, :3] / X[:, 3:]


def ray_angle_ok(R, C, X, obs_cam, obs_pt, count):
    """Per track: the largest angle between two of its rays is at least MIN_RAY_ANGLE_DEG."""
    rays = X[obs_pt] - C[obs_cam]
    rays /= np.linalg.norm(rays, axis=1, keepdims=True)
    mean = np.zeros((count, 3))
    np.add.at(mean, obs_pt, rays)
    mean /= np.linalg.norm(mean, axis=1, keepdims=True)
    spread = np.zeros(count)
    np.maximum.at(spread, obs_pt, np.degrees(np.arccos(np.clip(
        np.sum(rays * mean[obs_pt], axis=1), -1, 1))))
    return spread >= MIN_RAY_ANGLE_DEG / 2


# ---- the adjustment --------------------------------------------------------------------------

class Problem:
    """Observations (camera, point, pixel) of cameras x = R (X - C), u = (fx x / z + cx,
    fy y / z + cy). The parameters are blocks of 6: one per camera (rotation increment omega,
    R <- exp([omega]x) R, and centre) and a last one for the intrinsics (fx, fy, cx, cy and two
    unused), which every observation shares."""

    def __init__(self, obs_cam, obs_pt, obs_uv, n_cameras, n_points):
        self.cam, self.pt, self.uv = obs_cam, obs_pt, obs_uv
        self.n_cameras, self.n_points = n_cameras, n_points
        order = np.argsort(obs_pt, kind="stable")
        starts = np.r_[0, np.cumsum(np.bincount(obs_pt, minlength=n_points))]
        first, second = [], []
        for p in range(n_points):
            o = order[starts[p]:starts[p + 1]]
            first.append(np.repeat(o, len(o)))
            second.append(np.tile(o, len(o)))
        self.pair_a, self.pair_b = np.concatenate(first), np.concatenate(second)

    def residuals(self, state):
        R, C, X, k = state
        x = np.einsum("oij,oj->oi", R[self.cam], X[self.pt] - C[self.cam])
        u = np.c_[k[0] * x[:, 0] / x[:, 2] + k[2], k[1] * x[:, 1] / x[:, 2] + k[3]]
        return u - self.uv, x

    def jacobians(self, state, x):
        """d residual / d (omega, C, intrinsics) (2 x 12 per observation) and / d X."""
        R, k = state[0], state[3]
        z = x[:, 2]
        D = np.zeros((len(x), 2, 3))
        D[:, 0, 0], D[:, 0, 2] = k[0] / z, -k[0] * x[:, 0] / z ** 2
        D[:, 1, 1], D[:, 1, 2] = k[1] / z, -k[1] * x[:, 1] / z ** 2
        skew = np.zeros((len(x), 3, 3))
        skew[:, 0, 1], skew[:, 0, 2], skew[:, 1, 2] = -x[:, 2], x[:, 1], -x[:, 0]
        skew -= skew.transpose(0, 2, 1)
        J_point = D @ R[self.cam]
        J_intrinsics = np.zeros((len(x), 2, 6))
        J_intrinsics[:, 0, 0], J_intrinsics[:, 0, 2] = x[:, 0] / z, 1.0
        J_intrinsics[:, 1, 1], J_intrinsics[:, 1, 3] = x[:, 1] / z, 1.0
        J_camera = np.concatenate([-D @ skew, -J_point, J_intrinsics], axis=2)
        return J_camera, J_point

    def blocks(self, obs):
        """The parameter indices (12) of observations obs: their camera's 6, the intrinsics' 6."""
        return np.c_[6 * self.cam[obs][:, None] + np.arange(6),
                     np.repeat(6 * self.n_cameras + np.arange(6)[None], len(obs), axis=0)]

    @property
    def n_parameters(self):
        return 6 * (self.n_cameras + 1)


def huber_weights(r, k):
    norm = np.linalg.norm(r, axis=1)
    return np.where(norm <= k, 1.0, k / np.maximum(norm, 1e-12))


def huber_cost(r, k, weight):
    norm = np.linalg.norm(r, axis=1)
    return float(np.sum(weight * np.where(norm <= k, norm ** 2, 2 * k * norm - k * k)))


def _scatter(n, rows, cols, values):
    """A dense n x n matrix with values (..., a, b) summed at (rows[..., a], cols[..., b])."""
    index = rows[:, :, None] * n + cols[:, None, :]
    return np.bincount(index.ravel(), weights=values.ravel(), minlength=n * n).reshape(n, n)


def normal_equations(problem, state, k, weight):
    r, x = problem.residuals(state)
    w = huber_weights(r, k) * weight
    Jc, Jp = problem.jacobians(state, x)
    every = np.arange(len(r))
    cols = problem.blocks(every)
    m = problem.n_parameters
    U = _scatter(m, cols, cols, w[:, None, None] * np.einsum("oki,okj->oij", Jc, Jc))
    V = np.zeros((problem.n_points, 3, 3))
    np.add.at(V, problem.pt, w[:, None, None] * np.einsum("oki,okj->oij", Jp, Jp))
    W = w[:, None, None] * np.einsum("oki,okj->oij", Jc, Jp)
    gc = np.bincount(cols.ravel(), weights=(w[:, None] * np.einsum("oki,ok->oi", Jc, r)).ravel(),
                     minlength=m)
    gp = np.zeros((problem.n_points, 3))
    np.add.at(gp, problem.pt, w[:, None] * np.einsum("oki,ok->oi", Jp, r))
    return U, V, W, gc, gp, cols


def schur(problem, U, V_inv, W, cols):
    """The cameras' and intrinsics' reduced normal matrix U - W V^-1 W^T; and W V^-1."""
    Y = np.einsum("oij,ojk->oik", W, V_inv[problem.pt])
    a, b = problem.pair_a, problem.pair_b
    S = U - _scatter(problem.n_parameters, cols[a], cols[b], np.einsum("oij,okj->oik", Y[a], W[b]))
    return S, Y


def apply_step(state, dc, dp):
    R, C, X, k = state
    dc = dc.reshape(-1, 6)
    R = np.array([rotation_exp(d[:3]) @ Ri for d, Ri in zip(dc, R)])
    return R, C + dc[:len(C), 3:], X + dp, k + dc[-1, :4]


def adjust(problem, state, free, k=HUBER_PX, weight=None, iterations=50):
    """Levenberg-Marquardt on the Huber cost; free: mask of the n_parameters camera and
    intrinsics parameters that move (the gauge and the fixed ones stay); free None re-optimises
    the points alone."""
    weight = np.ones(len(problem.cam)) if weight is None else weight
    lam = 1e-4
    cost = huber_cost(problem.residuals(state)[0], k, weight)
    for _ in range(iterations):
        U, V, W, gc, gp, cols = normal_equations(problem, state, k, weight)
        improved = False
        for _ in range(10):
            Vd = V + lam * (np.einsum("pii->pi", V)[:, :, None] * np.eye(3) + 1e-12 * np.eye(3))
            V_inv = np.linalg.inv(Vd)
            step = np.zeros(problem.n_parameters)
            if free is not None:
                S, Y = schur(problem, U, V_inv, W, cols)
                b = -gc + np.bincount(cols.ravel(), weights=np.einsum(
                    "oij,oj->oi", Y, gp[problem.pt]).ravel(), minlength=problem.n_parameters)
                Sf = S[np.ix_(free, free)]
                Sf = Sf + lam * np.diag(np.diag(Sf))
                step[free] = np.linalg.solve(Sf, b[free])
            back = np.zeros((problem.n_points, 3))
            np.add.at(back, problem.pt, np.einsum("oji,oj->oi", W, step[cols]))
            dp = -np.einsum("pij,pj->pi", V_inv, gp + back)
            candidate = apply_step(state, step, dp)
            cost2 = huber_cost(problem.residuals(candidate)[0], k, weight)
            if cost2 < cost:
                relative = (cost - cost2) / cost
                state, cost = candidate, cost2
                lam = max(lam / 10, 1e-9)
                improved = True
                break
            lam *= 10
        if not improved or relative < 1e-10:
            break
    return state


def camera_covariance(problem, state, free, k=HUBER_PX):
    """sigma^2 (J^T W J)^-1 of the free parameters (n_parameters square, zeros where fixed),
    sigma^2 from the weighted residuals; and sigma."""
    U, V, W, _, _, cols = normal_equations(problem, state, k, np.ones(len(problem.cam)))
    S, _ = schur(problem, U, np.linalg.inv(V), W, cols)
    r = problem.residuals(state)[0]
    w = huber_weights(r, k)
    dof = 2 * len(r) - 3 * problem.n_points - int(free.sum())
    sigma2 = float(np.sum(w * np.sum(r * r, axis=1)) / dof)
    cov = np.zeros_like(S)
    cov[np.ix_(free, free)] = sigma2 * np.linalg.inv(S[np.ix_(free, free)])
    return cov, np.sqrt(sigma2)


def log_rotation(R):
    """The rotation vector of R, accurate near the identity (cv2.Rodrigues returns 0 below about
    1e-5 rad, the size of the differences measured here)."""
    v = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    s, c = np.linalg.norm(v), 0.5 * (np.trace(R) - 1)
    angle = np.arctan2(s, c)
    return v * (angle / s if s > 1e-15 else 1.0)


def tangent_error(R, t, R_true, t_true):
    """covariance_calibration.tangent_error with log_rotation: theta = (omega, beta),
    R_true = R exp([omega]x), t_true ~ t + B beta."""
    t, t_true = np.ravel(t) / np.linalg.norm(t), np.ravel(t_true) / np.linalg.norm(t_true)
    return np.r_[log_rotation(R.T @ R_true), tangent_basis(t).T @ (t_true / (t @ t_true) - t)]


def relative_theta(R, C, i, j, reference):
    """The tangent error (omega, beta) of camera pair (i, j) of (R, C) against reference (R, t)."""
    Rij = R[j] @ R[i].T
    tij = R[j] @ (C[i] - C[j])
    return tangent_error(reference[0], reference[1], Rij, tij)


def relative_covariance(state, cov, i, j, step=1e-7):
    """The 5x5 covariance of pair (i, j)'s relative motion in its tangent, from the cameras'."""
    R, C = state[:2]
    reference = (R[j] @ R[i].T, R[j] @ (C[i] - C[j]))
    G = np.zeros((5, len(cov)))
    for c in (i, j):
        for a in range(6):
            d = np.zeros(len(cov))
            d[6 * c + a] = step
            R2, C2 = apply_step(state, d, 0.0)[:2]
            G[:, 6 * c + a] = relative_theta(R2, C2, i, j, reference) / step
    return G @ cov @ G.T


# ---- the measurement -------------------------------------------------------------------------

def _rms(r):
    return float(np.sqrt(np.mean(np.sum(r * r, axis=1))))


# The adjustments: which intrinsics move besides the cameras (the gauge fixes camera 0 and one
# coordinate of the last camera's centre).
VARIANTS = (("K fixed (as given)", ()), ("K free (fx, fy, cx, cy shared)", (0, 1, 2, 3)))


def tracks_under_ground_truth(sequence, matcher, max_side, log):
    """The tracks, gated and triangulated with the ground-truth cameras: Problem, GT state."""
    n = len(sequence.images)
    R_gt = np.array(sequence.rotations)
    C_gt = np.array([-R.T @ t for R, t in zip(sequence.rotations, sequence.translations)])
    K = sequence.K
    k_gt = np.array([K[0, 0], K[1, 1], K[0, 2], K[1, 2]])
    obs_cam, obs_uv, obs_track = build_tracks(sequence, matcher, max_side)
    count = int(obs_track.max()) + 1
    log("tracks before the gate: %d, observations %d" % (count, len(obs_cam)))
    X = triangulate(R_gt, C_gt, K, obs_cam, obs_uv, obs_track, count)
    for _ in range(2):  # re-optimise the points, gate, drop what is left with one view
        p = Problem(obs_cam, obs_track, obs_uv, n, count)
        X = adjust(p, (R_gt, C_gt, X, k_gt), None, iterations=10)[2]
        r, x = p.residuals((R_gt, C_gt, X, k_gt))
        keep = (np.linalg.norm(r, axis=1) < GATE_PX) & (x[:, 2] > 0)
        per_track = np.bincount(obs_track[keep], minlength=count)
        keep &= per_track[obs_track] >= 2
        keep &= ray_angle_ok(R_gt, C_gt, X, obs_cam, obs_track, count)[obs_track]
        tracks, obs_track = np.unique(obs_track[keep], return_inverse=True)
        obs_cam, obs_uv, X, count = obs_cam[keep], obs_uv[keep], X[tracks], len(tracks)
    problem = Problem(obs_cam, obs_track, obs_uv, n, count)
    X = adjust(problem, (R_gt, C_gt, X, k_gt), None, iterations=20)[2]
    return problem, (R_gt, C_gt, X, k_gt)


def free_parameters(problem, C, intrinsics=()):
    """The gauge: camera 0 fixed and the scale, one coordinate of the last camera's centre (the
    one that changes most from camera 0's); the intrinsics fixed but those listed."""
    n = problem.n_cameras
    free = np.zeros(problem.n_parameters, bool)
    free[6:6 * n] = True
    free[6 * (n - 1) + 3 + int(np.argmax(np.abs(C[n - 1] - C[0])))] = False
    free[6 * n + np.array(intrinsics, int)] = True
    return free


def adjusted(problem, gt, intrinsics, bootstrap, rng, log):
    """One adjustment from the ground truth: its state, covariance, and per pair of cameras the
    ground truth's relative motion in the adjusted one's tangent, with both covariances."""
    n = problem.n_cameras
    free = free_parameters(problem, gt[1], intrinsics)
    state = adjust(problem, gt, free, iterations=100)
    cov, sigma = camera_covariance(problem, state, free)
    r_gt, r_ba = problem.residuals(gt)[0], problem.residuals(state)[0]
    R, C = state[:2]
    R_gt, C_gt = gt[:2]
    pairs = {}
    for i in range(n):
        for j in range(i + 1, n):
            reference = (R[j] @ R[i].T, R[j] @ (C[i] - C[j]))
            pairs[(i, j)] = dict(theta=relative_theta(R_gt, C_gt, i, j, reference),
                                 cov=relative_covariance(state, cov, i, j), samples=[])
    for b in range(bootstrap):  # over tracks, from the optimum
        weight = np.bincount(rng.integers(0, problem.n_points, problem.n_points),
                             minlength=problem.n_points)[problem.pt].astype(float)
        Rb, Cb = adjust(problem, state, free, weight=weight, iterations=8)[:2]
        for (i, j), row in pairs.items():
            row["samples"].append(relative_theta(Rb, Cb, i, j, (R[j] @ R[i].T,
                                                                R[j] @ (C[i] - C[j]))))
        log("bootstrap %d / %d" % (b + 1, bootstrap))
    for row in pairs.values():
        row["bootstrap_cov"] = np.cov(np.array(row["samples"]).T) if bootstrap > 1 else None
    k_std = np.sqrt(np.diag(cov)[6 * n:6 * n + 4])
    return dict(rms_gt=_rms(r_gt), rms_ba=_rms(r_ba), sigma=sigma, free=int(free.sum()),
                inside_gt=float(np.mean(np.linalg.norm(r_gt, axis=1) < HUBER_PX)),
                inside_ba=float(np.mean(np.linalg.norm(r_ba, axis=1) < HUBER_PX)),
                cost_gt=huber_cost(r_gt, HUBER_PX, 1.0), cost_ba=huber_cost(r_ba, HUBER_PX, 1.0),
                intrinsics=state[3] - gt[3], intrinsics_std=k_std, pairs=pairs,
                camera_error_deg=[np.degrees(np.linalg.norm(log_rotation(R[c] @ R_gt[c].T)))
                                  for c in range(n)])


def adjusted_relative_motions(problem, gt, camera_pairs):
    """{(i, j): (R, t)} of the adjustment with K fixed started from the ground truth (the
    report's gauge), x_j = R x_i + t."""
    state = adjust(problem, gt, free_parameters(problem, gt[1], ()), iterations=100)
    R, C = state[:2]
    return {(i, j): (R[j] @ R[i].T, R[j] @ (C[i] - C[j])) for i, j in camera_pairs}


def motion_error_deg(R, t, R_ref, t_ref):
    """max(rotation, translation direction error) of (R, t) against the reference, deg, as the
    benchmark judges it (rcme.compareMotion)."""
    from methods import rcme
    error = rcme.compareMotion(np.asarray(R, float), np.asarray(t, float).reshape(3, 1),
                               np.asarray(R_ref, float), np.asarray(t_ref, float).reshape(3, 1))
    return float(max(error.rotationDeg, error.translationDeg))


def judge_against_adjustment(data, cache, method_names, name="fountain-P11", log=print):
    """Rows (method, mode, runs, AUC@10 and mean error against the ground truth, the same against
    the adjustment) and the ground truth's own distance from the adjustment (median, mean, deg)
    over the sequence's benchmark pairs."""
    import methods
    import report
    import run_benchmark
    folder, load, _ = SEQUENCES[name]
    sequence = load(os.path.join(data, folder), name)
    matcher = matching.Matcher(cache)
    problem, gt = tracks_under_ground_truth(sequence, matcher, sequence.max_side, log)
    found, _ = run_benchmark.real_pairs(run_benchmark.parse_args(["--data", data, "--cache", cache]),
                                        matcher)
    chosen = [p for p in found if p.dataset == name]
    keys = [tuple(int(f) for f in p.name.rsplit(" ", 1)[1].split("-")) for p in chosen]
    adjusted = adjusted_relative_motions(problem, gt, keys)
    gt_distance = [motion_error_deg(*adjusted[k], p.R_gt, p.t_gt) for k, p in zip(keys, chosen)]
    rows = []
    for method in method_names:
        for adaptive in (False, True):
            seeds = [0] if adaptive or method in methods.PEER_METHODS else [0, 1, 2]
            errors = {"gt": [], "ba": []}
            for key, pair in zip(keys, chosen):
                for seed in seeds:
                    e = methods.run(method, pair.points1, pair.points2, pair.K,
                                    methods.Budget(1000, 1.0, seed, adaptive))
                    ok = e is not None and e.ok and e.R is not None
                    errors["gt"].append(motion_error_deg(e.R, e.t, pair.R_gt, pair.t_gt)
                                        if ok else np.inf)
                    errors["ba"].append(motion_error_deg(e.R, e.t, *adjusted[key])
                                        if ok else np.inf)
            score = {k: (report.auc([{"ok": np.isfinite(x), "rot": x, "trans": x} for x in v]),
                         float(np.mean(v))) for k, v in errors.items()}
            rows.append((method, "adaptive" if adaptive else "exactly N = 1000", len(errors["gt"]),
                         score["gt"], score["ba"]))
    return rows, (float(np.median(gt_distance)), float(np.mean(gt_distance)))


def judge_table(name, rows, gt_distance):
    lines = ["%s's benchmark pairs judged against the ground truth and against the relative "
             "motions of a bundle adjustment of all its images (K fixed); the ground truth is "
             "%.3f deg from the adjustment at the median, %.3f deg on average (max(rotation, "
             "translation direction)).\n" % (name, gt_distance[0], gt_distance[1])]
    lines.append(_table(["method", "runs", "n", "AUC@10 vs ground truth (mean error, deg)",
                         "AUC@10 vs adjustment (mean error, deg)"],
                        [[m, mode, str(n), "%.4f (%.4f)" % gt, "%.4f (%.4f)" % ba]
                         for m, mode, n, gt, ba in rows]))
    return lines


# The sequences whose cameras it adjusts: name -> (folder under the data, loader, the default
# report's file name under doc/benchmark).
SEQUENCES = {
    "fountain-P11": ("epfl_strecha_fountain-P11", datasets.fountain_sequence,
                     "fountain_bundle_adjustment.md"),
    "templeSR": ("middlebury_templeSparseRing", datasets.temple_sequence,
                 "templeSR_bundle_adjustment.md"),
}


def measure(data, cache, bootstrap, seed=0, log=print, max_side=None, name="fountain-P11"):
    """The adjustments' figures for the sequence `name` (SEQUENCES); max_side: SIFT's image size
    for the tracks (None: the benchmark's, 1536 px for fountain-P11, templeSR's as they are; 0:
    full size), the benchmark's pairs stay the benchmark's."""
    folder, load, _ = SEQUENCES[name]
    sequence = load(os.path.join(data, folder), name)
    matcher = matching.Matcher(cache)
    n = len(sequence.images)
    benchmark_pairs = pair_selection.select_sequence_pairs(sequence, matcher, 3, range(n - 1))[0]
    problem, gt = tracks_under_ground_truth(
        sequence, matcher, sequence.max_side if max_side is None else max_side, log)
    lengths = np.bincount(problem.pt)
    result = dict(name=name, tracks=problem.n_points, observations=len(problem.cam),
                  mean_length=float(lengths.mean()), length_hist=np.bincount(lengths),
                  per_image=np.bincount(problem.cam, minlength=n), variants={}, max_side=max_side,
                  benchmark_pairs=[tuple(int(f) for f in p.name.rsplit(" ", 1)[1].split("-"))
                                   for p in benchmark_pairs])
    rng = np.random.default_rng(seed)
    for name, intrinsics in VARIANTS:
        v = adjusted(problem, gt, intrinsics, bootstrap, rng, log)
        result["variants"][name] = v
        log("%s: RMS under GT %.4f px, adjusted %.4f px, sigma %.4f px" % (
            name, v["rms_gt"], v["rms_ba"], v["sigma"]))
    return result


def per_axis(values):
    return np.degrees(np.sqrt(np.mean(np.square(values), axis=0)))


def _table(header, lines):
    return ("| " + " | ".join(header) + " |\n|" + "---|" * len(header) + "\n" +
            "\n".join("| " + " | ".join(line) + " |" for line in lines) + "\n")


def ground_truth_error(pairs, keys):
    """Per axis (deg): the RMS difference of the rotation (x, y, z) and translation direction
    (b1, b2), the adjustment's own standard deviation (RMS over the pairs; the larger of its
    covariance's and the bootstrap's), and the ground truth's error that the difference implies,
    sqrt(max(0, difference^2 - own variance))."""
    theta = np.array([pairs[k]["theta"] for k in keys])
    own = np.array([np.maximum(np.diag(pairs[k]["cov"]), np.diag(pairs[k]["bootstrap_cov"]))
                    if pairs[k]["bootstrap_cov"] is not None else np.diag(pairs[k]["cov"])
                    for k in keys])
    difference2, own2 = np.mean(theta ** 2, axis=0), np.mean(own, axis=0)
    return (np.degrees(np.sqrt(difference2)), np.degrees(np.sqrt(own2)),
            np.degrees(np.sqrt(np.maximum(0.0, difference2 - own2))))


def report(result, bootstrap):
    r = result
    n = len(r["per_image"])
    lines = ["# %s: a bundle adjustment against the ground truth\n" % r["name"],
             "Generated by `samples/benchmark/bundle_adjustment.py --sequence %s --bootstrap "
             "%d%s`; see doc/covariance.md (\"The ground truth, measured by a bundle "
             "adjustment\").\n" % (r["name"], bootstrap, "" if r["max_side"] is None else
                                   " --max-side %d" % r["max_side"]),
             "Tracks %d (observations %d, %.2f per track; tracks by length 2, 3, ..., %d: %s); "
             "observations per image %s. Huber loss at %g px; gauge: camera 0 and one coordinate "
             "of camera %d's centre fixed.\n" % (
                 r["tracks"], r["observations"], r["mean_length"], len(r["length_hist"]) - 1,
                 ", ".join(str(v) for v in r["length_hist"][2:]),
                 ", ".join(str(v) for v in r["per_image"]), HUBER_PX, n - 1)]
    fit = []
    for name, v in r["variants"].items():
        fit.append([name, "%d" % v["free"], "%.4f" % v["rms_gt"], "%.4f" % v["rms_ba"],
                    "%.1f / %.1f %%" % (100 * v["inside_gt"], 100 * v["inside_ba"]),
                    "%.4f" % v["sigma"], "%.0f" % ((v["cost_gt"] - v["cost_ba"]) / v["sigma"] ** 2),
                    ", ".join("%+.2f +- %.2f" % (d, e) for d, e in
                              zip(v["intrinsics"], v["intrinsics_std"]) if e > 0) or "-"])
    lines += ["Does the ground truth fit the images? Reprojection RMS of the same observations "
              "under the ground-truth cameras (each point re-optimised with the cameras fixed) "
              "and under the adjusted ones; the drop of the Huber cost over sigma^2 is "
              "chi-square(free parameters) if the ground truth were exact.\n",
              _table(["adjustment", "free parameters", "RMS under the ground truth, px",
                      "RMS adjusted, px", "within %g px, GT / adjusted" % HUBER_PX,
                      "sigma, px", "cost drop / sigma^2",
                      "intrinsics moved (fx, fy, cx, cy), px"], fit)]
    table = []
    for name, v in r["variants"].items():
        subsets = (("the benchmark's pairs", r["benchmark_pairs"]),
                   ("gap 1-3", [k for k in v["pairs"] if k[1] - k[0] <= 3]),
                   ("all %d" % len(v["pairs"]), list(v["pairs"])))
        for label, keys in subsets:
            theta = np.array([v["pairs"][k]["theta"] for k in keys])
            std = np.degrees(np.sqrt(np.mean([np.diag(v["pairs"][k]["cov"]) for k in keys],
                                             axis=0)))
            boot = np.degrees(np.sqrt(np.mean([np.diag(v["pairs"][k]["bootstrap_cov"])
                                               for k in keys], axis=0))) if bootstrap > 1 \
                else np.full(5, np.nan)
            difference, _, gt = ground_truth_error(v["pairs"], keys)
            table.append([name, label, str(len(keys)),
                          "%.4f / %.4f / %.4f" % tuple(difference[:3]),
                          "%.4f / %.4f / %.4f" % tuple(std[:3]),
                          "%.4f / %.4f / %.4f" % tuple(boot[:3]),
                          "%.4f / %.4f / %.4f (RMS %.4f)" % (*gt[:3],
                                                             np.sqrt(np.mean(gt[:3] ** 2))),
                          "%.4f / %.4f" % tuple(difference[3:]),
                          "%.4f / %.4f" % tuple(np.maximum(std, np.nan_to_num(boot))[3:]),
                          "%.4f / %.4f" % tuple(gt[3:])])
    lines += ["Relative motions, the ground truth's in the adjusted one's tangent (that of "
              "Report::covariance: rotation x / y / z in the first camera's frame, translation "
              "direction b1 / b2), deg: RMS difference per axis over the pairs; the adjustment's "
              "own standard deviation (RMS over the pairs) from its covariance and from %d "
              "bootstrap replicates over the tracks; the ground truth's error per axis, "
              "sqrt(difference^2 - the larger own variance).\n" % bootstrap,
              _table(["adjustment", "pairs", "n", "rotation difference", "BA std (covariance)",
                      "BA std (bootstrap)", "ground truth rotation error",
                      "translation direction difference", "BA std (larger)",
                      "ground truth translation direction error"], table)]
    for name, v in r["variants"].items():
        lines.append("%s, per camera: the adjusted rotation's angle from the ground truth's "
                     "(camera 0 fixed, so relative to camera 0), deg: %s.\n" % (name, ", ".join(
                         "%.4f" % a for a in v["camera_error_deg"])))
    per_pair = []
    v = next(iter(r["variants"].values()))
    for k in r["benchmark_pairs"]:
        theta, C = v["pairs"][k]["theta"], v["pairs"][k]["cov"]
        per_pair.append(["%d-%d" % k] + ["%+.4f" % a for a in np.degrees(theta)] +
                        ["%.4f" % a for a in np.degrees(np.sqrt(np.diag(C)))] +
                        ["%.0f" % float(theta[:3] @ np.linalg.solve(C[:3, :3], theta[:3]))])
    lines += ["The benchmark's pairs one by one (%s; deg):\n" % next(iter(r["variants"])),
              _table(["pair", "omega x", "omega y", "omega z", "beta 1", "beta 2", "std x",
                      "std y", "std z", "std b1", "std b2",
                      "rotation difference^T C_BA^-1 difference"], per_pair)]
    return lines


def main(argv=None):
    ap = matching.benchmark_arguments(__doc__, REPO_ROOT, None)
    ap.add_argument("--sequence", choices=sorted(SEQUENCES), default="fountain-P11",
                    help="the sequence whose cameras are adjusted")
    ap.add_argument("--bootstrap", type=int, default=30, help="bootstrap replicates over tracks")
    ap.add_argument("--max-side", type=int, default=None,
                    help="SIFT on images downscaled to this size for the tracks (default the "
                         "benchmark's: 1536 px for fountain-P11; 0: full size)")
    ap.add_argument("--judge", nargs="+", metavar="METHOD", default=None,
                    help="score these methods (methods.METHODS names) against the ground truth "
                         "and the adjustment instead of writing the report")
    args = ap.parse_args(argv)
    # Refused before any data is read: a negative count or size was taken as none before.
    if args.bootstrap < 0:
        ap.error("--bootstrap must be >= 0 (replicates), not %d" % args.bootstrap)
    if args.max_side is not None and args.max_side < 0:
        ap.error("--max-side must be >= 0 (pixels; 0: full size), not %d" % args.max_side)
    if args.judge:
        import methods
        unknown = [m for m in args.judge if m not in methods.METHODS]
        if unknown:
            ap.error("--judge: no method %s (known: %s)" % (", ".join(unknown),
                                                            ", ".join(methods.METHODS)))
    folder, _, report_name = SEQUENCES[args.sequence]
    out = args.out or os.path.join(REPO_ROOT, "doc", "benchmark", report_name)
    if not os.path.isdir(os.path.join(args.data, folder)):
        print("skipped: no %s under %s" % (args.sequence, args.data))
        return 0
    if args.judge:
        rows, gt_distance = judge_against_adjustment(
            args.data, args.cache, args.judge, args.sequence,
            log=lambda s: sys.stderr.write(s + "\n"))
        lines = judge_table(args.sequence, rows, gt_distance)
        if args.out:
            with open(args.out, "w") as f:
                f.write("\n".join(lines))
        print("\n".join(lines))
        return 0
    result = measure(args.data, args.cache, args.bootstrap, max_side=args.max_side,
                     log=lambda s: sys.stderr.write(s + "\n"), name=args.sequence)
    lines = report(result, args.bootstrap)
    with open(out, "w") as f:
        f.write("\n".join(lines))
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
