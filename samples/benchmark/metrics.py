"""Scores of one estimate: the paper's failure metric (Sec. V-C.1), errors against ground truth,
and inlier precision / recall against labels."""
import numpy as np
import cv2

from datasets import sampson_distance

CHI2_2_95 = 5.991464547107979  # chi2_2^-1(0.95), the paper's tau^2 = sigma^2 * this
PAPER_KAPPA = 0.5              # failure when n_I* / n_I <= kappa
ROTATION_FAILURE_DEG = 5.0     # failure against ground truth: rotation error above this ...
TRANSLATION_FAILURE_DEG = 15.0  # ... or translation direction error above this
F_FAILURE_PX = 5.0             # F-only pairs: RMS Sampson error of the true matches above this


def skew(v):
    """[v]x."""
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


class _MotionModel:
    """F = K^-T [t]x R K^-1 over 5 parameters: a rotation increment and a tangent step of t."""

    def __init__(self, R, t, K):
        self.R, self.t = R, t.ravel() / np.linalg.norm(t)
        self.Kinv = np.linalg.inv(K)
        basis = np.linalg.svd(self.t.reshape(1, 3))[2]
        self.tangent = basis[1:].T  # 3x2, orthogonal to t
        self.size = 5

    def F(self, x):
        R = rotation_exp(x[:3]) @ self.R
        t = self.t + self.tangent @ x[3:]
        return self.Kinv.T @ skew(t / np.linalg.norm(t)) @ R @ self.Kinv

    def update(self, x):
        self.R = rotation_exp(x[:3]) @ self.R
        t = self.t + self.tangent @ x[3:]
        self.__init__(self.R, t, np.linalg.inv(self.Kinv))


class _FundamentalModel:
    """F = U diag(1, s, 0) V^T (rank 2) over 7 parameters: rotations of U and V, and s."""

    def __init__(self, F):
        U, S, Vt = np.linalg.svd(F)
        self.U, self.V, self.s = U, Vt.T, S[1] / S[0]
        self.size = 7

    def F(self, x):
        U = self.U @ rotation_exp(x[:3])
        V = self.V @ rotation_exp(x[3:6])
        return U @ np.diag([1.0, self.s + x[6], 0.0]) @ V.T

    def update(self, x):
        self.__init__(self.F(x))


def _huber_mle(model, p1, p2, huber_threshold, iterations=10):
    """Gold Standard refinement on the Sampson error with Huber weights (iteratively reweighted
    Gauss-Newton with a numeric Jacobian, steps accepted only when the robust cost drops)."""
    def cost(x):
        e = sampson_distance(model.F(x), p1, p2)
        return e, np.where(e <= huber_threshold, e * e,
                           2 * huber_threshold * e - huber_threshold ** 2).sum()

    zero = np.zeros(model.size)
    for _ in range(iterations):
        e, current = cost(zero)
        weights = np.where(e <= huber_threshold, 1.0, huber_threshold / np.maximum(e, 1e-12))
        J = np.empty((len(e), model.size))
        for k in range(model.size):
            step = np.zeros(model.size)
            step[k] = 1e-6
            J[:, k] = (sampson_distance(model.F(step), p1, p2) - e) / 1e-6
        A = J.T @ (J * weights[:, None])
        g = J.T @ (weights * e)
        damping, accepted = 1e-3 * np.trace(A) / model.size + 1e-12, False
        for _ in range(8):
            x = -np.linalg.solve(A + damping * np.eye(model.size), g)
            if cost(x)[1] < current:
                model.update(x)
                accepted = True
                break
            damping *= 10
        if not accepted:
            break
    return model.F(np.zeros(model.size))


def paper_failure(estimate, p1, p2, K, sigma):
    """(n_I, n_I*, failed): consistent inliers of the estimate's inlier set before and after a
    Huber-robust MLE, consistent meaning Huber(error) < tau^2 = sigma^2 chi2_2^-1(0.95), i.e.
    a Sampson error below tau. Before: under the method's output F; after: under the MLE from it
    (over the motion when K is known, else over F)."""
    tau = sigma * np.sqrt(CHI2_2_95)
    inliers = estimate.mask
    a, b = p1[inliers], p2[inliers]
    before = int(np.sum(sampson_distance(estimate.F, a, b) < tau))
    if before < 8:
        return before, 0, True
    if K is not None and estimate.R is not None:
        model = _MotionModel(estimate.R, estimate.t, K)
    else:
        model = _FundamentalModel(estimate.F)
    refined = _huber_mle(model, a, b, tau)
    after = int(np.sum(sampson_distance(refined, a, b) < tau))
    return before, after, after <= PAPER_KAPPA * before


def pose_failure(rotation_deg, translation_deg):
    return rotation_deg > ROTATION_FAILURE_DEG or translation_deg > TRANSLATION_FAILURE_DEG


def f_error(F, gt_points):
    """RMS Sampson distance (px) of the true correspondences under an estimated F."""
    d = sampson_distance(F, gt_points[:, :2], gt_points[:, 2:])
    return float(np.sqrt(np.mean(d * d)))


# The judge's blindness test (epipole_blind): a homography through the true matches, and
# epipoles far apart: four at infinity 45 deg apart, four at this distance (px) around them.
BLIND_HOMOGRAPHY_PX = 3.0
BLIND_EPIPOLE_DISTANCE_PX = 2000.0


def epipole_blind(gt_points):
    """True when the F-only judge (f_error <= F_FAILURE_PX) cannot tell one epipole from another
    on these true matches: they fit one homography H so closely that F = [e]x H passes the judge
    for epipoles e in all of eight spread directions. A scene's F is then not determined by its
    labelled matches (one plane, or planes too close to tell), and no estimate can be called right
    or wrong there."""
    gt_points = np.asarray(gt_points, np.float64)
    if len(gt_points) < 4:
        return False
    H, _ = cv2.findHomography(gt_points[:, :2], gt_points[:, 2:], cv2.RANSAC,
                              BLIND_HOMOGRAPHY_PX, maxIters=5000, confidence=0.9999)
    if H is None:
        return False
    cx, cy = np.mean(gt_points[:, 2], axis=0), np.mean(gt_points[:, 3], axis=0)
    d = BLIND_EPIPOLE_DISTANCE_PX
    epipoles = [(1, 0, 0), (1, 1, 0), (0, 1, 0), (-1, 1, 0),
                (cx + d, cy, 1), (cx, cy + d, 1), (cx - d, cy, 1), (cx, cy - d, 1)]
    for e in epipoles:
        F = skew(np.asarray(e, np.float64)) @ H
        if f_error(F / np.linalg.norm(F), gt_points) > F_FAILURE_PX:
            return False
    return True


def precision_recall(mask, truth):
    found = int(np.sum(mask & truth))
    precision = found / max(int(mask.sum()), 1)
    recall = found / max(int(truth.sum()), 1)
    return precision, recall


def rotation_exp(omega):
    """R = exp([omega]x)."""
    return cv2.Rodrigues(np.asarray(omega, np.float64).reshape(3, 1))[0]


def tangent_basis(t):
    """B of Report::covariance: b1 = normalize(t x e_k), e_k the axis of t's smallest absolute
    component, b2 = t x b1."""
    e = np.zeros(3)
    e[np.argmin(np.abs(t))] = 1.0
    b1 = np.cross(t, e)
    b1 /= np.linalg.norm(b1)
    return np.c_[b1, np.cross(t, b1)]
