#!/usr/bin/env python3
# This file is part of the rcme module. It is subject to the license terms in the LICENSE file
# found in the top-level directory of this distribution.
"""Verifies every pair of an image folder with rcme: SIFT matches, one batch call, a CSV.

For each image (jpg, jpeg, png, ppm, pgm, bmp, tif, tiff; sorted by name) SIFT features are
detected once; every pair i < j is matched (brute force, k = 2, Lowe's ratio test 0.8) and
the pairs are estimated with rcme.estimateRelativeMotionBatch on every core (the GIL is
released), in chunks so that a progress bar can follow. The CSV has one row per pair: the
images, the match count, the status (number and text), the inlier count and, on success, the
motion x2 = R x1 + t as R's nine entries (row-major), its angle in degrees and t's three
entries; the estimation's time too.

    PYTHONPATH=build/python /usr/bin/python3 samples/verify_image_folder.py FOLDER \
        [--k K.txt] [--out pairs.csv] [--method standard] [--threads 0] [--dask]

--k takes the folder's K.txt when present (nine numbers, the camera matrix shared by every
image); without one only F is estimated and the motion columns stay empty. --dask sends the
chunks to Dask (dask.bag, processes by default; a dask.distributed Client created before the
call is used instead) when dask is installed; it is not a dependency of rcme.

Needs cv2 with SIFT (Debian's python3-opencv or pip's opencv-python[-headless]) and the
standalone module rcme (the batch call is not in cv2.rcme). Exit codes: 0 every pair was
estimated (whatever its status); 2 usage or input/output error; 3 error raised by rcme.
"""

import argparse
import csv
import itertools
import os
import sys
import time

import numpy as np

try:
    import cv2
except ImportError:
    sys.exit("error: this sample needs OpenCV's Python bindings (cv2) with SIFT")

from two_view_demo import (UsageError, method_names, parse_method,
                           read_camera_matrix, read_image)

EXIT_OK, EXIT_USAGE, EXIT_LIBRARY_ERROR = 0, 2, 3
IMAGE_EXTENSIONS = (".jpg", ".jpeg", ".png", ".ppm", ".pgm", ".bmp", ".tif", ".tiff")
CSV_COLUMNS = (["image1", "image2", "matches", "status", "status_text", "inliers"] +
               ["R%d%d" % (i, j) for i in range(3) for j in range(3)] +
               ["rotation_deg", "tx", "ty", "tz", "seconds"])


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder", help="folder of images")
    ap.add_argument("--k", help="camera matrix file (9 numbers); 'none': uncalibrated; "
                                "default: FOLDER/K.txt when it exists")
    ap.add_argument("--out", default="pairs.csv", help="CSV to write (default pairs.csv)")
    ap.add_argument("--method", default="standard", help="rcme method: " + method_names())
    ap.add_argument("--sigma", type=float, default=1.0, help="pixel noise (default 1)")
    ap.add_argument("--threads", type=int, default=0,
                    help="threads of the batch call; 0: every core")
    ap.add_argument("--max-features", type=int, default=4000, help="SIFT features per image")
    ap.add_argument("--chunk", type=int, default=32, help="pairs per batch call (progress step)")
    ap.add_argument("--dask", action="store_true", help="run the chunks on Dask")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    return ap.parse_args(argv)


class Progress:
    """A one-line progress bar on stderr (none with --quiet)."""

    def __init__(self, label, total, quiet):
        self.label, self.total, self.quiet = label, max(total, 1), quiet
        self.start = time.perf_counter()
        self.update(0)

    def update(self, done):
        if self.quiet:
            return
        width = 30
        filled = int(width * done / self.total)
        elapsed = time.perf_counter() - self.start
        sys.stderr.write("\r%-10s [%s%s] %d/%d %.1f s" % (self.label, "#" * filled,
                                                         "." * (width - filled), done,
                                                         self.total, elapsed))
        if done >= self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def list_images(folder):
    if not os.path.isdir(folder):
        raise UsageError("not a folder: '%s'" % folder)
    names = sorted(n for n in os.listdir(folder) if n.lower().endswith(IMAGE_EXTENSIONS))
    if len(names) < 2:
        raise UsageError("folder '%s' holds %d image(s); at least two are needed"
                         % (folder, len(names)))
    return names


def detect(folder, names, max_features, quiet):
    sift = cv2.SIFT_create(max_features)
    features = []
    progress = Progress("features", len(names), quiet)
    for i, name in enumerate(names):
        keypoints, descriptors = sift.detectAndCompute(read_image(os.path.join(folder, name)), None)
        points = np.float64([k.pt for k in keypoints]).reshape(-1, 2)
        features.append((points, descriptors))
        progress.update(i + 1)
    return features


def match(features, pairs, quiet):
    matcher = cv2.BFMatcher(cv2.NORM_L2)
    matched = []
    progress = Progress("matching", len(pairs), quiet)
    for n, (i, j) in enumerate(pairs):
        (points1, desc1), (points2, desc2) = features[i], features[j]
        index1, index2 = [], []
        if desc1 is not None and desc2 is not None and len(desc2) >= 2:
            for m in matcher.knnMatch(desc1, desc2, k=2):
                if len(m) == 2 and m[0].distance < 0.8 * m[1].distance:
                    index1.append(m[0].queryIdx)
                    index2.append(m[0].trainIdx)
        matched.append((points1[index1].reshape(-1, 2), points2[index2].reshape(-1, 2)))
        progress.update(n + 1)
    return matched


def estimate_chunk(chunk, K, params, threads):
    """One batch call; a module-level function, so that Dask can send it to its workers."""
    import rcme
    return rcme.estimateRelativeMotionBatch(chunk, K, params, threads)


def estimate(rcme, matched, K, params, args):
    chunks = [matched[i:i + args.chunk] for i in range(0, len(matched), args.chunk)]
    progress = Progress("estimating", len(matched), args.quiet)
    reports = []
    if args.dask:
        try:
            import dask.bag
        except ImportError:
            raise UsageError("--dask needs dask (pip install dask)")
        # one thread per call: Dask runs a chunk on each of its workers
        bag = dask.bag.from_sequence(chunks, npartitions=len(chunks))
        for chunk_reports in bag.map(estimate_chunk, K, params, 1).compute():
            reports.extend(chunk_reports)
        progress.update(len(reports))
        return reports
    for chunk in chunks:
        reports.extend(estimate_chunk(chunk, K, params, args.threads))
        progress.update(len(reports))
    return reports


def csv_row(rcme, names, pair, points, report):
    row = [names[pair[0]], names[pair[1]], len(points[0]), report.status,
           rcme.statusToString(report.status), report.inlierCount]
    if report.R is not None:
        angle = np.degrees(np.linalg.norm(cv2.Rodrigues(report.R)[0]))
        row += ["%.9g" % v for v in report.R.ravel()] + ["%.6g" % angle]
        row += ["%.9g" % v for v in report.t.ravel()]
    else:
        row += [""] * 13
    return row + ["%.6g" % report.timeSeconds]


def run(argv):
    args = parse_args(argv)
    try:
        import rcme
    except ImportError:
        raise UsageError("the standalone module 'rcme' cannot be imported: pip install <repo>, "
                         "or build the project and set PYTHONPATH=<build>/python")
    if args.chunk < 1:
        raise UsageError("--chunk must be at least 1")
    names = list_images(args.folder)
    k_path = args.k if args.k is not None else os.path.join(args.folder, "K.txt")
    K = None
    if k_path != "none" and (args.k is not None or os.path.exists(k_path)):
        K = read_camera_matrix(k_path)
    params = rcme.Params(method=parse_method(rcme, args.method), sigma=args.sigma)

    pairs = list(itertools.combinations(range(len(names)), 2))
    features = detect(args.folder, names, args.max_features, args.quiet)
    matched = match(features, pairs, args.quiet)
    start = time.perf_counter()
    try:
        reports = estimate(rcme, matched, K, params, args)
    except rcme.error as e:
        print("error: rcme: %s" % e, file=sys.stderr)
        return EXIT_LIBRARY_ERROR
    seconds = time.perf_counter() - start

    try:
        with open(args.out, "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(CSV_COLUMNS)
            for pair, points, report in zip(pairs, matched, reports):
                writer.writerow(csv_row(rcme, names, pair, points, report))
    except OSError as e:
        raise UsageError("cannot write '%s': %s" % (args.out, e.strerror))
    succeeded = sum(r.status == rcme.STATUS_SUCCESS for r in reports)
    print("%d images, %d pairs (%s): %d succeeded, %d not; %.2f s, %.1f pairs/s; wrote %s"
          % (len(names), len(pairs), "calibrated" if K is not None else "uncalibrated",
             succeeded, len(pairs) - succeeded, seconds, len(pairs) / max(seconds, 1e-9),
             args.out))
    return EXIT_OK


def main(argv=None):
    try:
        return run(sys.argv[1:] if argv is None else argv)
    except UsageError as e:
        print("error: %s" % e, file=sys.stderr)
        return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())
