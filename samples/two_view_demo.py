#!/usr/bin/env python3
# This file is part of the rcme module. It is subject to the license terms in the LICENSE file
# found in the top-level directory of this distribution.
"""Two-view camera motion with rcme on a real image pair (Python twin of two_view_demo.cpp).

Detects SIFT features in two images, matches them (brute force, k = 2, Lowe's ratio test 0.8),
estimates the relative motion with rcme.recoverPose (or only the fundamental matrix with
rcme.findFundamentalMat when no camera matrix is given) and, on the same matches, with OpenCV's
own estimator (cv2.findEssentialMat RANSAC + cv2.recoverPose, or cv2.findFundamentalMat
FM_RANSAC), compares both with the ground truth when one is given, and writes a picture with one
row per estimator: the inlier and outlier matches and a few epipolar lines.

Without image arguments it runs on the bundled pair of samples/data (fountain-P11, see
samples/data/PROVENANCE.md) with its camera matrix and ground-truth pose.

The rcme API comes from cv2.rcme when the installed OpenCV was built with the module, otherwise
from the standalone module `rcme` (build it with the project, then
PYTHONPATH=<build>/python). SIFT and the drawing use cv2 (Debian: python3-opencv).

Exit codes: 0 success; 1 the estimation did not succeed (non-success status) or the rotation
error exceeds --max-rotation-error-deg; 2 usage or input/output error; 3 error raised by the
library.
"""

import argparse
import os
import sys
import time

import numpy as np

try:
    import cv2
except ImportError:
    sys.exit("error: this sample needs OpenCV's Python bindings (cv2), e.g. python3-opencv")

EXIT_OK, EXIT_NOT_SUCCESS, EXIT_USAGE, EXIT_LIBRARY_ERROR = 0, 1, 2, 3

DATA_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
DEFAULT_IMAGE1, DEFAULT_IMAGE2 = "fountain_0004.jpg", "fountain_0006.jpg"
DEFAULT_K, DEFAULT_GT = "K.txt", "pose_gt.txt"


class UsageError(Exception):
    """Usage or input/output error: reported with exit code 2."""


def load_rcme():
    """The rcme API and its error type: cv2.rcme if present, else the standalone module."""
    module = getattr(cv2, "rcme", None)
    if module is not None:
        return module, cv2.error, "cv2.rcme"
    try:
        import rcme
    except ImportError:
        raise UsageError("neither cv2.rcme nor the standalone module 'rcme' can be imported; "
                         "build the project and set PYTHONPATH=<build>/python")
    return rcme, rcme.error, "rcme (standalone)"


def parse_args(argv):
    parser = argparse.ArgumentParser(
        description="Estimates the camera motion between two images with rcme (SIFT + ratio "
                    "test). Without images, runs on the bundled pair of samples/data with its "
                    "camera matrix and ground-truth pose.",
        epilog="Exit codes (from rcme's result; OpenCV's is only shown): 0 success; 1 estimation not successful or rotation error too "
               "large; 2 usage or input/output error; 3 error raised by the library.")
    parser.add_argument("images", nargs="*", metavar="img", help="img1 img2 (default: bundled)")
    parser.add_argument("--method", default="standard",
                        help="rcme's method: %s (default standard)" % method_names())
    parser.add_argument("--solver", default="auto",
                        help="auto (default: five with K, else eight), eight, seven, five")
    parser.add_argument("--opencv-method", choices=("essential", "fundamental", "none"),
                        help="essential (findEssentialMat RANSAC + recoverPose; needs a camera "
                             "matrix), fundamental (findFundamentalMat FM_RANSAC), or none. "
                             "Default: essential with a camera matrix, else fundamental")
    parser.add_argument("--opencv-threshold", type=float, default=0.0, metavar="T",
                        help="OpenCV's inlier threshold in pixels (default: rcme's)")
    parser.add_argument("--k", dest="k_path", metavar="FILE",
                        help="3x3 camera matrix (9 numbers); 'none' estimates only F. Default: "
                             "the bundled K.txt without images, none with images")
    parser.add_argument("--gt", dest="gt_path", metavar="FILE",
                        help="ground truth: R (3 rows) then unit t, x2 = R x1 + t; 'none' to "
                             "skip. Default: the bundled pose_gt.txt without images")
    parser.add_argument("--data", default=DATA_DIR, metavar="DIR",
                        help="directory of the bundled pair (default %(default)s)")
    parser.add_argument("--out", default="rcme_two_view_demo_py.png", metavar="FILE",
                        help="output picture, PNG (default %(default)s) or, by its extension, "
                             "JPEG")
    parser.add_argument("--picture-width", type=int, default=0, metavar="W",
                        help="scale the picture to W pixels wide (default 0: natural size)")
    parser.add_argument("--sigma", type=float, default=1.0,
                        help="noise sigma in pixels (Params.sigma, default 1)")
    parser.add_argument("--threshold", type=float, default=0.0,
                        help="inlier threshold in pixels (Params.threshold, default: from sigma)")
    parser.add_argument("--seed", type=int, default=0,
                        help="rcme's random generator state (default 0; OpenCV's RANSAC has a "
                             "fixed internal seed)")
    parser.add_argument("--max-rotation-error-deg", type=float, default=-1.0, metavar="X",
                        help="exit with 1 when rcme's rotation error w.r.t. the ground truth "
                             "exceeds X degrees (needs a camera matrix and ground truth)")
    args = parser.parse_args(argv)
    if args.picture_width < 0:
        raise UsageError("--picture-width must be >= 0")
    if len(args.images) not in (0, 2):
        raise UsageError("give two images or none (got %d)" % len(args.images))
    return args


def method_names():
    """The --method values, as the usage lists them: the library's name (methodName) of each
    METHOD_* constant, in the order of their values."""
    try:
        rcme = load_rcme()[0]
    except UsageError:  # reported when the estimation starts
        return "the names of rcme's methods"
    values = sorted(getattr(rcme, name) for name in dir(rcme) if name.startswith("METHOD_"))
    return ", ".join(rcme.methodName(value) for value in values)


def parse_method(rcme, name):
    """The library's names (methodFromString); a usage error for any other."""
    try:
        return rcme.methodFromString(name)
    except Exception:  # rcme.error or cv2.error, which name the accepted values too
        raise UsageError("unknown --method '%s' (%s)" % (name, method_names()))


def parse_solver(rcme, name):
    solvers = {"eight": rcme.SOLVER_EIGHT_POINT, "8": rcme.SOLVER_EIGHT_POINT,
               "seven": rcme.SOLVER_SEVEN_POINT, "7": rcme.SOLVER_SEVEN_POINT,
               "five": rcme.SOLVER_FIVE_POINT, "5": rcme.SOLVER_FIVE_POINT,
               "auto": rcme.SOLVER_AUTO}
    if name not in solvers:
        raise UsageError("unknown --solver '%s' (auto, eight, seven, five)" % name)
    return solvers[name]


def read_numbers(path, expected, what):
    """Whitespace-separated numbers; '#' starts a comment that runs to the end of the line."""
    try:
        with open(path) as f:
            lines = f.readlines()
    except OSError as e:
        raise UsageError("cannot open %s file '%s': %s" % (what, path, e.strerror))
    values = []
    for line in lines:
        for token in line.split("#", 1)[0].split():
            try:
                v = float(token)
            except ValueError:
                v = float("nan")
            if not np.isfinite(v):
                raise UsageError("bad number '%s' in %s file '%s'" % (token, what, path))
            values.append(v)
    if len(values) != expected:
        raise UsageError("%s file '%s' must hold %d numbers, found %d"
                         % (what, path, expected, len(values)))
    return np.array(values)


def read_camera_matrix(path):
    K = read_numbers(path, 9, "camera matrix").reshape(3, 3)
    if abs(np.linalg.det(K)) < 1e-12:
        raise UsageError("camera matrix in '%s' is singular" % path)
    return K


def read_ground_truth(path):
    v = read_numbers(path, 12, "ground-truth pose")
    R, t = v[:9].reshape(3, 3), v[9:].reshape(3, 1)
    if np.abs(R @ R.T - np.eye(3)).max() > 1e-4 or np.linalg.det(R) < 0:
        raise UsageError("R in ground-truth file '%s' is not a rotation" % path)
    if np.linalg.norm(t) < 1e-12:
        raise UsageError("t in ground-truth file '%s' is zero" % path)
    return R, t / np.linalg.norm(t)


def read_image(path):
    if not os.path.exists(path):
        raise UsageError("image not found: '%s'" % path)
    img = cv2.imread(path, cv2.IMREAD_GRAYSCALE)
    if img is None:
        raise UsageError("cannot read image '%s' (not an image or unsupported format)" % path)
    return img


def match_sift(img1, img2):
    """SIFT, brute force k = 2, Lowe's ratio test 0.8: the matched points as (N, 2) float32."""
    sift = cv2.SIFT_create()
    kp1, desc1 = sift.detectAndCompute(img1, None)
    kp2, desc2 = sift.detectAndCompute(img2, None)
    pts1, pts2 = [], []
    if desc1 is not None and desc2 is not None and len(desc2) >= 2:
        for m in cv2.BFMatcher(cv2.NORM_L2).knnMatch(desc1, desc2, k=2):
            if len(m) == 2 and m[0].distance < 0.8 * m[1].distance:
                pts1.append(kp1[m[0].queryIdx].pt)
                pts2.append(kp2[m[0].trainIdx].pt)
    pts1 = np.array(pts1, np.float32).reshape(-1, 2)
    pts2 = np.array(pts2, np.float32).reshape(-1, 2)
    return len(kp1), len(kp2), pts1, pts2


def format_mat(m):
    rows = ["[" + ", ".join("%.6g" % v for v in row) + "]" for row in np.atleast_2d(m)]
    return ";\n    ".join(rows)


STATUS_EXPLANATIONS = {
    0: "a model was found",
    1: "no hypothesis passed the method's acceptance tests: the matches are too poor to trust "
       "any motion computed from them",
    2: "fewer valid correspondences than the minimal solver needs",
    3: "the configuration does not determine the motion: a homography explains the inliers as "
       "well as F (planar scene, pure rotation or too little parallax) and, without K, too few "
       "points off its plane fix the epipole, the samples were degenerate (identical or "
       "collinear points), or cheirality cannot resolve the motion",
}


def line_in_image(l, size):
    """Two points where the line a x + b y + c = 0 crosses the image (w, h), or None."""
    a, b, c = l
    w, h = size
    big = 4.0 * (w + h)
    if abs(b) >= abs(a):  # closer to horizontal
        if abs(b) < 1e-300:
            return None
        q1, q2 = (-big, -(c - a * big) / b), (big, -(c + a * big) / b)
    else:
        q1, q2 = (-(c - b * big) / a, -big), (-(c + b * big) / a, big)
    if not all(abs(v) < 1e9 for v in q1 + q2):
        return None
    ok, p1, p2 = cv2.clipLine((0, 0, w, h), tuple(int(round(v)) for v in q1),
                              tuple(int(round(v)) for v in q2))
    return (p1, p2) if ok else None


def draw_matches(img1, img2, pts1, pts2, mask, F, header):
    line_height = 20
    banner = line_height * len(header) + 8
    h = max(img1.shape[0], img2.shape[0])
    canvas = np.zeros((h + banner, img1.shape[1] + img2.shape[1], 3), np.uint8)
    off1, off2 = np.array([0, banner]), np.array([img1.shape[1], banner])
    canvas[banner:banner + img1.shape[0], :img1.shape[1]] = cv2.cvtColor(img1, cv2.COLOR_GRAY2BGR)
    canvas[banner:banner + img2.shape[0], img1.shape[1]:] = cv2.cvtColor(img2, cv2.COLOR_GRAY2BGR)
    green, red = (0, 200, 0), (0, 0, 255)
    shift = 4

    def fx(p, off):
        return tuple(int(round(v)) for v in (np.asarray(p, np.float64) + off) * (1 << shift))

    inl = np.zeros(len(pts1), bool) if mask is None else mask.ravel().astype(bool)
    inliers, outliers = np.flatnonzero(inl), np.flatnonzero(~inl)

    # match lines (at most 150 of each kind), blended over the images; inliers get a circle
    lines = canvas.copy()
    for idx, color in ((outliers, red), (inliers, green)):
        step = max(1, -(-len(idx) // 150))
        for i in idx[::step]:
            cv2.line(lines, fx(pts1[i], off1), fx(pts2[i], off2), color, 1, cv2.LINE_AA, shift)
    canvas = cv2.addWeighted(lines, 0.7, canvas, 0.3, 0.0)
    for i in inliers:
        cv2.circle(canvas, fx(pts1[i], off1), 2 << shift, green, 1, cv2.LINE_AA, shift)
        cv2.circle(canvas, fx(pts2[i], off2), 2 << shift, green, 1, cv2.LINE_AA, shift)

    # epipolar lines of a few inliers spread over the list, in both images
    if F is not None and len(inliers):
        palette = [(255, 255, 0), (255, 0, 255), (0, 255, 255), (255, 128, 0), (128, 0, 255),
                   (0, 128, 255), (255, 255, 255), (128, 255, 128)]
        n = min(8, len(inliers))
        for k in range(n):
            i = inliers[(k * len(inliers)) // n + len(inliers) // (2 * n)]
            color = palette[k % 8]
            x1 = np.array([pts1[i][0], pts1[i][1], 1.0])
            x2 = np.array([pts2[i][0], pts2[i][1], 1.0])
            for l, size, off in ((F @ x1, img2.shape[1::-1], off2),
                                 (F.T @ x2, img1.shape[1::-1], off1)):
                seg = line_in_image(l, size)
                if seg is not None:
                    cv2.line(canvas, tuple(int(v) for v in seg[0] + off),
                             tuple(int(v) for v in seg[1] + off), color, 2, cv2.LINE_AA)
            cv2.circle(canvas, fx(pts1[i], off1), 5 << shift, color, 2, cv2.LINE_AA, shift)
            cv2.circle(canvas, fx(pts2[i], off2), 5 << shift, color, 2, cv2.LINE_AA, shift)

    for k, text in enumerate(header):
        cv2.putText(canvas, text, (8, line_height * (k + 1)), cv2.FONT_HERSHEY_SIMPLEX, 0.5,
                    (255, 255, 255), 1, cv2.LINE_AA)
    return canvas


class Estimate:
    """One estimator's result on the matches, as drawn in one row of the picture."""

    def __init__(self, name):
        self.name = name        # e.g. "rcme.recoverPose, method rcme"
        self.success = False    # rcme: STATUS_SUCCESS; OpenCV: a model was returned
        self.outcome = ""       # status text
        self.F = self.R = self.t = self.mask = None
        self.inliers = 0
        self.inliers_pass_cheirality = False  # the mask is recoverPose's
        self.milliseconds = 0.0
        self.rotation_error = self.translation_error = None


def estimate_with_rcme(rcme, pts1, pts2, K, params, method_name):
    covariance = None
    start = time.perf_counter()
    if K is not None:
        est = Estimate("rcme.recoverPose, method %s" % method_name)
        est.inliers_pass_cheirality = True
        est.inliers, E, est.R, est.t, est.mask, status, covariance = rcme.recoverPose(
            pts1, pts2, K, params)
    else:
        est = Estimate("rcme.findFundamentalMat, method %s" % method_name)
        est.F, est.mask, status = rcme.findFundamentalMat(pts1, pts2, params)
        est.inliers = int(np.count_nonzero(est.mask)) if est.mask is not None else 0
    est.milliseconds = 1000 * (time.perf_counter() - start)
    est.success = status == rcme.STATUS_SUCCESS
    est.outcome = rcme.statusToString(status)
    if est.success and K is not None:
        Kinv = np.linalg.inv(K)
        est.F = Kinv.T @ E @ Kinv
        est.F /= np.linalg.norm(est.F)

    print("\n[%s]" % est.name)
    print("status: %s" % est.outcome)
    print("time: %.2f ms" % est.milliseconds)
    if not est.success:
        print("estimation failed: %s" % STATUS_EXPLANATIONS.get(status, "unknown status"))
    elif covariance is not None and covariance.shape == (5, 5):
        sd = np.degrees(np.sqrt(np.diag(covariance)))
        print("std of the rotation increment (deg): %.4f %.4f %.4f, of the translation "
              "direction (deg): %.4f %.4f" % tuple(sd))
    return est


def estimate_with_opencv(pts1, pts2, K, method, threshold, confidence):
    """OpenCV's estimator on the same matches: findEssentialMat (RANSAC) + recoverPose, or
    findFundamentalMat (FM_RANSAC), whose F gives a motion through E = K^T F K when K is known."""
    start = time.perf_counter()
    E = None
    if method == "essential":
        est = Estimate("OpenCV findEssentialMat RANSAC + recoverPose")
        if len(pts1) >= 5:
            E, est.mask = cv2.findEssentialMat(pts1, pts2, K, cv2.RANSAC, confidence, threshold)
    else:
        est = Estimate("OpenCV findFundamentalMat FM_RANSAC")
        if len(pts1) >= 8:
            est.F, est.mask = cv2.findFundamentalMat(pts1, pts2, cv2.FM_RANSAC, threshold,
                                                     confidence)
        if est.F is not None and est.F.shape[0] > 3:
            est.F = est.F[:3]  # the first of several solutions
        if est.F is not None and K is not None:
            E = K.T @ est.F @ K
    if E is not None and E.shape[0] > 3:
        E = E[:3]  # the first of several solutions
    if E is not None and K is not None:
        pose_inliers, est.R, est.t, pose_mask = cv2.recoverPose(E, pts1, pts2, K,
                                                                mask=est.mask.copy())
        if method == "essential":
            est.inliers, est.mask = pose_inliers, pose_mask  # inliers passing cheirality
            est.inliers_pass_cheirality = True
            Kinv = np.linalg.inv(K)
            est.F = Kinv.T @ E @ Kinv
    est.milliseconds = 1000 * (time.perf_counter() - start)
    if method == "fundamental":
        est.inliers = int(np.count_nonzero(est.mask)) if est.mask is not None else 0
    if est.F is not None:
        est.F = est.F / np.linalg.norm(est.F)
    est.success = est.F is not None
    est.outcome = "model returned" if est.success else "no model returned"
    print("\n[%s]" % est.name)
    print("result: %s (OpenCV has no failure status)" % est.outcome)
    print("time: %.2f ms" % est.milliseconds)
    return est


def report_estimate(rcme, est, num_matches, K, R_gt, t_gt):
    """Prints an estimate's model and its errors against the ground truth (when both known)."""
    if not est.success:
        return
    print("inliers: %d / %d%s" % (est.inliers, num_matches,
                                  " (passing cheirality)" if est.inliers_pass_cheirality
                                  else ""))
    print("F = " + format_mat(est.F))
    if est.R is not None:
        print("R = " + format_mat(est.R))
        print("t = " + format_mat(est.t.T) + "^T")
    if est.R is not None and R_gt is not None:
        err = rcme.compareMotion(est.R, est.t, R_gt, t_gt)
        est.rotation_error, est.translation_error = err.rotationDeg, err.translationDeg
        print("rotation error: %.3f deg" % est.rotation_error)
        print("translation direction error: %.3f deg" % est.translation_error)
    elif R_gt is not None and K is None:
        print("ground truth given but no camera matrix: motion errors not computed")


def banner_of(est, num_matches, threshold):
    """The banner lines of an estimate's row in the picture."""
    header = ["%s: %s, %d / %d matches are inliers, %.1f ms, threshold %.2f px"
              % (est.name, est.outcome, est.inliers, num_matches, est.milliseconds, threshold)]
    if est.rotation_error is not None:
        header.append("error vs ground truth: rotation %.2f deg, translation direction %.2f deg"
                      % (est.rotation_error, est.translation_error))
    header.append("green: inliers, red: outliers (at most 150 lines each)"
                  + ("" if est.F is None else ", colours: epipolar lines of 8 inliers"))
    return header


def run(argv):
    args = parse_args(argv)
    rcme, _, binding = load_rcme()

    bundled = not args.images
    path1 = os.path.join(args.data, DEFAULT_IMAGE1) if bundled else args.images[0]
    path2 = os.path.join(args.data, DEFAULT_IMAGE2) if bundled else args.images[1]
    if args.k_path is None:
        k_path = os.path.join(args.data, DEFAULT_K) if bundled else ""
    else:
        k_path = "" if args.k_path == "none" else args.k_path
    if args.gt_path is None:
        gt_path = os.path.join(args.data, DEFAULT_GT) if bundled else ""
    else:
        gt_path = "" if args.gt_path == "none" else args.gt_path

    params = rcme.Params()
    params.method = parse_method(rcme, args.method)
    params.solver = parse_solver(rcme, args.solver)
    params.sigma = args.sigma
    params.threshold = args.threshold
    params.randomGeneratorState = args.seed
    # rcme's inlier threshold: Params.threshold, or 1.96 sigma (chi2 with 1 DoF at 0.95)
    rcme_threshold = args.threshold if args.threshold > 0 else 1.959964 * args.sigma

    img1, img2 = read_image(path1), read_image(path2)
    K = read_camera_matrix(k_path) if k_path else None
    R_gt, t_gt = read_ground_truth(gt_path) if gt_path else (None, None)
    if args.max_rotation_error_deg >= 0 and (K is None or R_gt is None):
        raise UsageError("--max-rotation-error-deg needs a camera matrix (--k) and a ground "
                         "truth (--gt)")
    opencv_method = args.opencv_method or ("fundamental" if K is None else "essential")
    if opencv_method == "essential" and K is None:
        raise UsageError("--opencv-method essential needs a camera matrix (--k)")
    opencv_threshold = args.opencv_threshold if args.opencv_threshold > 0 else rcme_threshold

    print("binding: %s" % binding)
    print("image 1: %s (%dx%d)" % (path1, img1.shape[1], img1.shape[0]))
    print("image 2: %s (%dx%d)" % (path2, img2.shape[1], img2.shape[0]))
    print("camera matrix: %s" % (k_path or "none (fundamental matrix only)"))
    print("ground truth: %s" % (gt_path or "none"))
    print("method: %s, solver: %s, sigma: %g px, seed: %d"
          % (args.method, args.solver, params.sigma, params.randomGeneratorState))
    print("OpenCV: %s, threshold %.2f px" % (opencv_method, opencv_threshold))

    start = time.perf_counter()
    n_kp1, n_kp2, pts1, pts2 = match_sift(img1, img2)
    print("keypoints: %d / %d, matches after ratio test: %d (%.1f ms)"
          % (n_kp1, n_kp2, len(pts1), 1000 * (time.perf_counter() - start)))

    # robust estimation: rcme, then OpenCV on the same matches
    estimates = [estimate_with_rcme(rcme, pts1, pts2, K, params, args.method)]
    report_estimate(rcme, estimates[-1], len(pts1), K, R_gt, t_gt)
    if opencv_method != "none":
        estimates.append(estimate_with_opencv(pts1, pts2, K, opencv_method, opencv_threshold,
                                              params.confidence))
        report_estimate(rcme, estimates[-1], len(pts1), K, R_gt, t_gt)

    # picture: one row per estimator, the same matches
    rows = [draw_matches(img1, img2, pts1, pts2, est.mask, est.F,
                         banner_of(est, len(pts1), rcme_threshold if k == 0 else opencv_threshold))
            for k, est in enumerate(estimates)]
    canvas = np.vstack(rows)
    if args.picture_width > 0:  # e.g. the smaller copy in doc/samples/
        height = int(round(canvas.shape[0] * args.picture_width / canvas.shape[1]))
        canvas = cv2.resize(canvas, (args.picture_width, height), interpolation=cv2.INTER_AREA)
    out_path = os.path.abspath(args.out)
    os.makedirs(os.path.dirname(out_path), exist_ok=True)
    try:
        # the smallest PNG, or a JPEG of moderate quality, as the C++ demo
        written = cv2.imwrite(out_path, canvas,
                              [cv2.IMWRITE_PNG_COMPRESSION, 9, cv2.IMWRITE_JPEG_QUALITY, 80])
    except cv2.error as e:
        raise UsageError("cannot write '%s': %s" % (out_path, e))
    if not written:
        raise UsageError("cannot write '%s'" % out_path)
    print("\nwrote %s" % out_path)

    rcme_estimate = estimates[0]
    if not rcme_estimate.success:
        return EXIT_NOT_SUCCESS
    if args.max_rotation_error_deg >= 0 and not (
            rcme_estimate.rotation_error is not None
            and rcme_estimate.rotation_error <= args.max_rotation_error_deg):
        print("FAILED: rotation error %s deg exceeds --max-rotation-error-deg %g"
              % ("n/a" if rcme_estimate.rotation_error is None
                 else "%.3f" % rcme_estimate.rotation_error, args.max_rotation_error_deg))
        return EXIT_NOT_SUCCESS
    return EXIT_OK


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    try:
        return run(argv)
    except UsageError as e:
        print("error: %s\n(run with --help for the usage)" % e, file=sys.stderr)
        return EXIT_USAGE
    except Exception as e:  # cv2.error / rcme.error raised by the library
        if type(e).__name__ == "error":
            print("OpenCV error: %s" % e, file=sys.stderr)
            return EXIT_LIBRARY_ERROR
        raise


if __name__ == "__main__":
    sys.exit(main())
