"""Two-view pairs from an image sequence, chosen as a monocular SLAM initialiser (ORB-SLAM)
chooses them: from each reference frame, the first later frame whose matches are numerous, show
enough parallax, and are not explained about as well by a homography as by F."""
from dataclasses import dataclass

import numpy as np
import cv2

from datasets import sampson_distance
from metrics import epipole_blind

ORB_SLAM_CHI2_F, ORB_SLAM_CHI2_H = 3.841, 5.991  # ORB-SLAM's per-image chi2 cut-offs (sigma 1)
MAX_HOMOGRAPHY_RATIO = 0.40  # ORB-SLAM picks H above this R_H = S_H / (S_H + S_F): reject then
MIN_PARALLAX_DEG = 1.0
MIN_TRIANGULATED = 50
MIN_MATCHES = 100


@dataclass
class Pair:
    dataset: str
    name: str
    points1: np.ndarray
    points2: np.ndarray
    K: object = None
    R_gt: object = None
    t_gt: object = None
    labels: object = None      # true-inlier mask (bool) when labels exist
    gt_points: object = None   # true correspondences [x1 y1 x2 y2] to score F-only pairs
    note: str = ""
    sigma: object = None       # noise of the pair when known (corridor), else the run's sigma
    iterations: object = None  # the case's own N when it fixes one (a hard case), else the run's
    # F-only pairs whose true matches cannot tell F's epipole (metrics.epipole_blind): their
    # runs are neither right nor wrong in the confusion table
    unjudgeable: bool = False


def _line_distances_squared(F, p1, p2):
    x1 = np.hstack([p1, np.ones((len(p1), 1))])
    x2 = np.hstack([p2, np.ones((len(p2), 1))])
    l2, l1 = x1 @ F.T, x2 @ F
    num = np.sum(x2 * l2, axis=1) ** 2
    return num / (l2[:, 0] ** 2 + l2[:, 1] ** 2 + 1e-300), num / (l1[:, 0] ** 2 + l1[:, 1] ** 2
                                                                    + 1e-300)


def _transfer_squared(H, a, b):
    x = np.hstack([a, np.ones((len(a), 1))]) @ H.T
    return np.sum((x[:, :2] / x[:, 2:3] - b) ** 2, axis=1)


def homography_ratio(p1, p2):
    """ORB-SLAM's R_H = S_H / (S_H + S_F) with F and H from OpenCV's RANSAC (sigma 1 px)."""
    cv2.setRNGSeed(0)
    F, _ = cv2.findFundamentalMat(p1, p2, cv2.FM_RANSAC, 1.96, 0.999, 2000)
    H, _ = cv2.findHomography(p1, p2, cv2.RANSAC, 2.45, maxIters=2000, confidence=0.999)
    if F is None or F.shape != (3, 3) or H is None:
        return 1.0

    def score(d2, cutoff):
        return np.where(d2 < cutoff, ORB_SLAM_CHI2_H - d2, 0.0).sum()

    d1, d2 = _line_distances_squared(F[:3], p1, p2)
    s_f = score(d1, ORB_SLAM_CHI2_F) + score(d2, ORB_SLAM_CHI2_F)
    s_h = (score(_transfer_squared(H, p1, p2), ORB_SLAM_CHI2_H)
           + score(_transfer_squared(np.linalg.inv(H), p2, p1), ORB_SLAM_CHI2_H))
    return float(s_h / max(s_h + s_f, 1e-12))


def agrees_with_truth(p1, p2, K, R, t):
    """The matches that agree with the true motion: Sampson distance below 2 px."""
    Kinv = np.linalg.inv(K)
    F = Kinv.T @ np.array([[0, -t[2], t[1]], [t[2], 0, -t[0]], [-t[1], t[0], 0]]) @ R @ Kinv
    return sampson_distance(F, p1, p2) < 2.0


def parallax(p1, p2, K, R, t):
    """(count, median parallax in degrees) of the matches that agree with the true motion
    (Sampson < 2 px) and triangulate in front of both cameras. Measured with the ground truth
    so that the selection favours none of the compared estimators."""
    good = agrees_with_truth(p1, p2, K, R, t)
    if good.sum() < MIN_TRIANGULATED:
        return int(good.sum()), 0.0
    P1 = K @ np.hstack([np.eye(3), np.zeros((3, 1))])
    P2 = K @ np.hstack([R, t.reshape(3, 1)])
    X = cv2.triangulatePoints(P1, P2, p1[good].T, p2[good].T)
    X = (X[:3] / X[3]).T
    depth2 = X @ R.T + t.ravel()
    front = (X[:, 2] > 0) & (depth2[:, 2] > 0)
    ray1 = X[front]
    ray2 = X[front] + (R.T @ t.ravel())  # from camera 2's centre C2 = -R^T t
    cos = np.sum(ray1 * ray2, axis=1) / (np.linalg.norm(ray1, axis=1)
                                         * np.linalg.norm(ray2, axis=1))
    if len(cos) < MIN_TRIANGULATED:
        return int(len(cos)), 0.0
    return int(len(cos)), float(np.degrees(np.median(np.arccos(np.clip(cos, -1, 1)))))


def select_sequence_pairs(sequence, matcher, max_gap, references):
    """For each reference frame, the first of the next max_gap frames that passes."""
    pairs, rejected = [], {"matches": 0, "parallax": 0, "homography": 0}
    for i in references:
        for j in range(i + 1, min(i + max_gap, len(sequence.images) - 1) + 1):
            p1, p2, _ = matcher.match(sequence.images[i], sequence.images[j],
                                      sequence.max_side or None)
            if len(p1) < MIN_MATCHES:
                rejected["matches"] += 1
                continue
            R, t, _ = sequence.relative_motion(i, j)
            count, median_parallax = parallax(p1, p2, sequence.K, R, t)
            if count < MIN_TRIANGULATED or median_parallax < MIN_PARALLAX_DEG:
                rejected["parallax"] += 1
                continue
            ratio = homography_ratio(p1, p2)
            if ratio > MAX_HOMOGRAPHY_RATIO:
                rejected["homography"] += 1
                continue
            pairs.append(Pair(sequence.name, "%s %d-%d" % (sequence.name, i, j), p1, p2,
                              sequence.K, R, t,
                              note="R_H %.2f, parallax %.1f deg" % (ratio, median_parallax)))
            break
    return pairs, rejected


def labelled_pairs(raw_pairs, matcher):
    """Pairs of datasets.magsac_pairs (or magsac_given_pairs) as Pair: no K, no pose; labels or
    annotated points."""
    pairs = []
    for raw in raw_pairs:
        if raw.images:
            p1, p2, _ = matcher.match(*raw.images)
            if len(p1) < 8:
                continue
            pairs.append(Pair("MAGSAC vpts", raw.name, p1, p2, gt_points=raw.gt_points,
                              unjudgeable=epipole_blind(raw.gt_points)))
        else:
            truth = raw.labels > 0
            gt = np.hstack([raw.points1[truth], raw.points2[truth]])
            # vpts rows as given: the unlabelled rows may be true too, no precision / recall
            given_vpts = raw.gt_points is not None
            pairs.append(Pair("MAGSAC vpts, given rows" if given_vpts else "AdelaideRMF",
                              raw.name, raw.points1, raw.points2,
                              labels=None if given_vpts else truth, gt_points=gt,
                              unjudgeable=epipole_blind(gt)))
    return pairs
