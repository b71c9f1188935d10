"""Loaders for the real data in ../shared/data: image sequences with ground-truth cameras (KITTI,
EPFL fountain-P11, Middlebury temple) and the MAGSAC/AdelaideRMF two-view pairs with given
correspondences. Conventions as in doc/synthetic.md: x2 = R x1 + t between camera frames."""
import os
from dataclasses import dataclass

import numpy as np
import cv2


@dataclass
class Sequence:
    """Images of one moving camera with world-to-camera poses (x_cam = R X + t)."""
    name: str
    images: list
    K: np.ndarray
    rotations: list
    translations: list
    max_side: int = 0  # images are downscaled to this longest side before matching (0: as is)

    def relative_motion(self, i, j):
        """Ground truth from frame i to frame j: x_j = R x_i + t, t of unit length."""
        R = self.rotations[j] @ self.rotations[i].T
        t = self.translations[j] - R @ self.translations[i]
        return R, t / np.linalg.norm(t), float(np.linalg.norm(t))


@dataclass
class LabelledPair:
    """Two views with given correspondences; no camera matrix, no pose.

    labels: per correspondence, 0 = outlier, k >= 1 = k-th structure (AdelaideRMF), or None when
    the input carries no labels (the vpts pairs, scored by their annotated points instead).
    gt_points: (M, 4) annotated true correspondences [xA yA xB yB] (vpts pairs), else None.
    images: the two image paths when the correspondences are to be matched (points1 is None)."""
    name: str
    points1: object
    points2: object
    labels: object = None
    gt_points: object = None
    gt_F: object = None
    images: tuple = ()


def kitti_sequence(folder, name):
    P0 = np.loadtxt(os.path.join(folder, "calib.txt"))[0].reshape(3, 4)
    poses = np.loadtxt(os.path.join(folder, "poses.txt")).reshape(-1, 3, 4)
    images = sorted(os.path.join(folder, "image_l", f)
                    for f in os.listdir(os.path.join(folder, "image_l")) if f.endswith(".png"))
    # poses are camera-to-world; invert to world-to-camera
    rotations = [T[:, :3].T for T in poses]
    translations = [-T[:, :3].T @ T[:, 3] for T in poses]
    return Sequence(name, images[:len(poses)], P0[:, :3].copy(), rotations, translations)


def fountain_sequence(folder, name, max_side=1536):
    image_dir = os.path.join(folder, "images")
    images = sorted(os.path.join(image_dir, f) for f in os.listdir(image_dir)
                    if f.endswith(".jpg"))
    rotations, translations, K = [], [], None
    for path in images:
        rows = open(os.path.join(folder, "gt_dense_cameras", os.path.basename(path) + ".camera")
                    ).read().split("\n")
        numbers = [list(map(float, r.split())) for r in rows if r.strip()]
        K = np.array(numbers[0:3])
        R_cw, C = np.array(numbers[4:7]), np.array(numbers[7])
        rotations.append(R_cw.T)
        translations.append(-R_cw.T @ C)
    return Sequence(name, images, K, rotations, translations, max_side)


def temple_sequence(folder, name):
    rows = open(os.path.join(folder, "templeSR_par.txt")).read().split("\n")[1:]
    images, rotations, translations, K = [], [], [], None
    for row in rows:
        parts = row.split()
        if len(parts) != 22:
            continue
        values = np.array(list(map(float, parts[1:])))
        K = values[0:9].reshape(3, 3)
        images.append(os.path.join(folder, parts[0]))
        rotations.append(values[9:18].reshape(3, 3))
        translations.append(values[18:21])
    return Sequence(name, images, K, rotations, translations)


def _fit_fundamental(a, b):
    F, _ = cv2.findFundamentalMat(a, b, cv2.FM_8POINT)
    return F[:3] if F is not None else None


def sampson_residual(F, p1, p2):
    """Signed Sampson distance (pixels) of x2^T F x1 = 0 for (N, 2) point arrays: the algebraic
    residual over the norm of its gradient in (x1, x2)."""
    x1 = np.hstack([p1, np.ones((len(p1), 1))])
    x2 = np.hstack([p2, np.ones((len(p2), 1))])
    Fx1, Ftx2 = x1 @ F.T, x2 @ F
    algebraic = np.sum(x2 * Fx1, axis=1)
    norm = Fx1[:, 0] ** 2 + Fx1[:, 1] ** 2 + Ftx2[:, 0] ** 2 + Ftx2[:, 1] ** 2
    return algebraic / np.sqrt(np.maximum(norm, 1e-300))


def sampson_distance(F, p1, p2):
    """Sampson distance (pixels) of x2^T F x1 = 0 for (N, 2) point arrays."""
    return np.abs(sampson_residual(F, p1, p2))


def magsac_pairs(folder):
    """Every *_pts.txt pair. AdelaideRMF pairs (no *_vpts.mat) use all rows and their labels.
    vpts pairs are matched with SIFT (points1 None, images set): their label-0 rows are not
    usable input (on 9 of the 24 pairs under 10 % agree with the annotated geometry); the label-1
    rows (the hand-annotated matches) only score, so they never help an estimator."""
    pairs = []
    for fname in sorted(os.listdir(folder)):
        if not fname.endswith("_pts.txt"):
            continue
        name = fname[:-len("_pts.txt")]
        rows = np.loadtxt(os.path.join(folder, fname), ndmin=2)
        a, b, labels = rows[:, 0:2], rows[:, 3:5], rows[:, 6].astype(int)
        if os.path.exists(os.path.join(folder, name + "_vpts.mat")):
            gt = np.hstack([a[labels == 1], b[labels == 1]])
            model = os.path.join(folder, name + "_model.txt")
            M = np.loadtxt(model) if os.path.exists(model) else np.zeros((3, 3))
            gt_F = M.T if np.abs(M).sum() > 0 else _fit_fundamental(gt[:, :2], gt[:, 2:])
            images = tuple(os.path.join(folder, f) for f in sorted(os.listdir(folder))
                           if f.rsplit(".", 1)[0] in (name + "A", name + "B"))
            pairs.append(LabelledPair("magsac/" + name, None, None, None, gt, gt_F, images))
        else:
            pairs.append(LabelledPair("adelaide/" + name, a.copy(), b.copy(), labels))
    return pairs


def magsac_given_pairs(folder):
    """The vpts pairs from their *_pts.txt rows as given (the annotated matches and the other
    putative matches the dataset ships), as a user who has only those correspondences runs them;
    labels: 1 for the annotated rows, which judge (an estimator does not know them)."""
    pairs = []
    for raw in magsac_pairs(folder):
        if not raw.images:
            continue
        name = raw.name[len("magsac/"):]
        rows = np.loadtxt(os.path.join(folder, name + "_pts.txt"), ndmin=2)
        pairs.append(LabelledPair(raw.name, rows[:, 0:2].copy(), rows[:, 3:5].copy(),
                                  rows[:, 6].astype(int), raw.gt_points, raw.gt_F))
    return pairs


def rows_of_another_pair(given, threshold):
    """The given pairs whose unlabelled rows are another pair's: {name: (owner, share under its
    own F, share under the owner's F)}. Two pairs with the same unlabelled rows, row for row, hold
    them once: they belong to the pair under whose F (the dataset's, or the 8-point fit of its
    labelled rows) most of them lie within `threshold` (Sampson, px); the other pair's input is
    its few labelled rows among another image pair's matches. Rows that no pair's F holds (the
    outliers two labellings of one image pair share, AdelaideRMF's johnssona and johnssonb) are
    nobody's. Read from the rows, not from a list of names."""
    def unlabelled(pair):
        keep = pair.labels <= 0
        return np.hstack([pair.points1[keep], pair.points2[keep]])

    def own_f(pair):
        if pair.gt_F is not None:
            return pair.gt_F
        truth = pair.labels > 0
        return _fit_fundamental(pair.points1[truth], pair.points2[truth]) \
            if truth.sum() >= 8 else None

    def share(F, rows):
        if F is None:
            return 0.0
        return float(np.mean(sampson_distance(F, rows[:, :2], rows[:, 2:]) <= threshold))

    by_rows = {}
    for pair in given:
        rows = unlabelled(pair)
        if len(rows):
            by_rows.setdefault(rows.tobytes(), []).append(pair)
    found = {}
    for group in by_rows.values():
        if len(group) < 2:
            continue
        rows = unlabelled(group[0])
        shares = [share(own_f(pair), rows) for pair in group]
        owner = int(np.argmax(shares))
        if shares[owner] < 0.5:
            continue
        for k, pair in enumerate(group):
            if k != owner:
                found[pair.name] = (group[owner].name, shares[k], shares[owner])
    return found


def load_all(data_dir):
    """The sequences and the labelled pairs found under data_dir (missing folders are skipped)."""
    sequences, pairs = [], []
    loaders = [("kitti_odometry_01_frames000-050", "KITTI-01", kitti_sequence),
               ("kitti_odometry_06_frames000-050", "KITTI-06", kitti_sequence),
               ("epfl_strecha_fountain-P11", "fountain-P11", fountain_sequence),
               ("middlebury_templeSparseRing", "templeSR", temple_sequence)]
    for folder, name, loader in loaders:
        path = os.path.join(data_dir, folder)
        if os.path.isdir(path):
            sequences.append(loader(path, name))
    path = os.path.join(data_dir, "magsac_fundamental_pairs")
    if os.path.isdir(path):
        pairs = magsac_pairs(path)
    return sequences, pairs
