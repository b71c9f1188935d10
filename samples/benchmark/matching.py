"""SIFT correspondences with Lowe's ratio test, cached on disk so that reruns are fast.

The cache key is a hash of the two images' contents and the matching parameters (not their
modification times: a re-copied data folder keeps its cache); the points are stored in the
images' original pixel coordinates even when the images are downscaled for detection."""
import argparse
import hashlib
import json
import os

import numpy as np
import cv2

MATCHING_VERSION = 2  # bump when the matching changes, so that old cache entries are not reused


def default_cache_dir(repo_root):
    return os.path.join(repo_root, "build", "benchmark_cache")


def benchmark_arguments(doc, repo_root, out):
    """A benchmark script's argument parser, described by the first line of its `doc`, with the
    options the scripts share: --data (the real data beside the checkout), --cache (these matches'
    cache) and --out (default `out`)."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("--data", default=os.path.join(repo_root, "..", "shared", "data"))
    ap.add_argument("--cache", default=default_cache_dir(repo_root))
    ap.add_argument("--out", default=out)
    return ap


class Matcher:
    def __init__(self, cache_dir, ratio=0.8, max_side=1600, max_features=8000):
        self.cache_dir = cache_dir
        self.ratio = ratio
        self.max_side = max_side
        self.max_features = max_features
        self._features = {}
        self._digests = {}
        os.makedirs(cache_dir, exist_ok=True)

    def _digest(self, path):
        if path not in self._digests:
            with open(path, "rb") as f:
                self._digests[path] = hashlib.sha1(f.read()).hexdigest()
        return self._digests[path]

    def _key(self, path1, path2, max_side):
        digests = [self._digest(p) for p in (path1, path2)]
        text = json.dumps([digests, self.ratio, max_side, self.max_features, MATCHING_VERSION])
        return hashlib.sha1(text.encode()).hexdigest()

    def _detect(self, path, max_side):
        key = (path, max_side)
        if key not in self._features:
            image = cv2.imread(path, cv2.IMREAD_GRAYSCALE)
            if image is None:
                raise IOError("cannot read image %s" % path)
            scale = 1.0
            if max_side and max(image.shape) > max_side:
                scale = max_side / max(image.shape)
                image = cv2.resize(image, None, fx=scale, fy=scale, interpolation=cv2.INTER_AREA)
            sift = cv2.SIFT_create(nfeatures=self.max_features)
            keypoints, descriptors = sift.detectAndCompute(image, None)
            points = np.array([k.pt for k in keypoints], np.float64).reshape(-1, 2)
            # back to original pixels; (x + 0.5) / s - 0.5 maps pixel centres of the resize
            points = (points + 0.5) / scale - 0.5
            self._features[key] = (points, descriptors)
        return self._features[key]

    def match(self, path1, path2, max_side=None):
        """(points1, points2, quality): (N, 2) float64 and the negated distance ratio (higher
        is better), sorted by decreasing quality. Mutual best ratio-test matches only."""
        max_side = self.max_side if max_side is None else max_side
        cache = os.path.join(self.cache_dir, self._key(path1, path2, max_side) + ".npz")
        if os.path.exists(cache):
            data = np.load(cache)
            return data["points1"], data["points2"], data["quality"]
        (pts1, desc1), (pts2, desc2) = self._detect(path1, max_side), self._detect(path2, max_side)
        empty = np.zeros((0, 2))
        if desc1 is None or desc2 is None or len(desc1) < 2 or len(desc2) < 2:
            result = (empty, empty, np.zeros(0))
        else:
            matcher = cv2.BFMatcher(cv2.NORM_L2)
            forward = matcher.knnMatch(desc1, desc2, k=2)
            backward = {m[0].queryIdx: m[0].trainIdx
                        for m in matcher.knnMatch(desc2, desc1, k=1) if m}
            rows = [(m.queryIdx, m.trainIdx, m.distance / max(n.distance, 1e-9))
                    for m, n in (pair for pair in forward if len(pair) == 2)
                    if m.distance < self.ratio * n.distance
                    and backward.get(m.trainIdx) == m.queryIdx]
            rows.sort(key=lambda r: r[2])
            if rows:
                idx1, idx2, ratios = (np.array(c) for c in zip(*rows))
                result = (pts1[idx1.astype(int)], pts2[idx2.astype(int)], -ratios)
            else:
                result = (empty, empty, np.zeros(0))
        np.savez(cache, points1=result[0], points2=result[1], quality=result[2])
        return result
