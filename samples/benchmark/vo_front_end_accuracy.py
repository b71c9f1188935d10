#!/usr/bin/env python3
"""Where rcme's accuracy goes on the VO suite's pairs against PoseLib (issue 39): per pair, the
rotation / translation errors of rcme's default and of PoseLib on the same matches, and of
PoseLib's own bundle adjustment (its final refinement, Cauchy loss) started from each answer on
each one's inliers. A refit of rcme's answer on rcme's inliers that lands at PoseLib's error says
the loss is rcme's final fit; one that needs PoseLib's inliers says it is the inlier set.

  PYTHONPATH=build/python build/poselib-venv/bin/python \
      samples/benchmark/vo_front_end_accuracy.py [--inputs ORB] [--kinds "i+1,after stale"]
"""
import argparse
import os
import sys

import numpy as np
import poselib
import rcme

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import methods  # noqa: E402
import vo_front_end  # noqa: E402


def errors(R, t, pair):
    e = rcme.compareMotion(np.asarray(R), np.asarray(t).reshape(3, 1), pair.R_gt,
                           pair.t_gt.reshape(3, 1))
    return e.rotationDeg, e.translationDeg


def score(rot, trans):
    return max(0.0, 1.0 - max(rot, trans) / 10.0)


def refined(p1, p2, mask, R, t, camera):
    pose = poselib.CameraPose()
    pose.R = np.asarray(R)
    pose.t = np.asarray(t).ravel()
    out, _ = poselib.refine_relative_pose(p1[mask], p2[mask], pose, camera, camera, {})
    return np.asarray(out.R), np.asarray(out.t)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--sequence", default="KITTI 01")
    parser.add_argument("--inputs", default="ORB")
    parser.add_argument("--kinds", default="i+1,after stale")
    parser.add_argument("--sigma", type=float, default=1.0)
    args = parser.parse_args(argv)
    kinds = args.kinds.split(",")
    data_dir = os.path.join(vo_front_end.REPO_ROOT, "..", "shared", "data")
    budget = methods.Budget(vo_front_end.N, args.sigma, 0, adaptive=True)
    columns = ("rcme", "PoseLib", "BA(rcme | rcme inl)", "BA(rcme | PL inl)",
               "BA(PL | rcme inl)", "BA(PL | PL inl)")
    sums = {c: 0.0 for c in columns}
    count = 0
    for label, sequence in vo_front_end.load_sequences(data_dir):
        if label != args.sequence:
            continue
        for kind, pair, _ in vo_front_end.vo_pairs(sequence, label,
                                                    inputs=tuple(args.inputs.split(","))):
            if kind not in kinds:
                continue
            p1 = np.ascontiguousarray(pair.points1, np.float64)
            p2 = np.ascontiguousarray(pair.points2, np.float64)
            camera = methods.poselib_camera(pair.K)
            ours = methods.run(methods.DEFAULT_METHOD, p1, p2, pair.K, budget)
            peer = methods.run("PoseLib relpose", p1, p2, pair.K, budget)
            if not ours.ok or not peer.ok:
                print("%s %s: rcme ok %s, PoseLib ok %s" % (pair.dataset, pair.name, ours.ok,
                                                            peer.ok))
                continue
            runs = {"rcme": (ours.R, ours.t), "PoseLib": (peer.R, peer.t),
                    "BA(rcme | rcme inl)": refined(p1, p2, ours.mask, ours.R, ours.t, camera),
                    "BA(rcme | PL inl)": refined(p1, p2, peer.mask, ours.R, ours.t, camera),
                    "BA(PL | rcme inl)": refined(p1, p2, ours.mask, peer.R, peer.t, camera),
                    "BA(PL | PL inl)": refined(p1, p2, peer.mask, peer.R, peer.t, camera)}
            cells = []
            for c in columns:
                rot, trans = errors(*runs[c], pair)
                sums[c] += score(rot, trans)
                cells.append("%.2f/%.2f" % (rot, trans))
            count += 1
            print("| %s %s | %d | %d | %d | %s |" % (
                pair.dataset, pair.name, len(p1), ours.mask.sum(), peer.mask.sum(),
                " | ".join(cells)), flush=True)
    print("| AUC@10 over %d pairs | | | | %s |" % (
        count, " | ".join("%.4f" % (sums[c] / max(count, 1)) for c in columns)))
    print("columns: pair | matches | rcme inliers | PoseLib inliers | " +
          " | ".join(c + " rot/trans deg" for c in columns))


if __name__ == "__main__":
    main()
