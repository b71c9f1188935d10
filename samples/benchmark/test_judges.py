#!/usr/bin/python3
"""Tests of the benchmark's judges (ctest rcme_benchmark_judges): the F-only judge's blindness
test (metrics.epipole_blind) and the confusion table's handling of unjudgeable runs.

    PYTHONPATH=build/python /usr/bin/python3 samples/benchmark/test_judges.py"""
import unittest

import numpy as np

import metrics
import report
from methods import rcme


def _true_matches(kind, seed):
    params = rcme.SceneParams()
    params.kind, params.numPoints, params.inlierRatio, params.sigma, params.seed = (
        kind, 200, 1.0, 1.0, seed)
    scene = rcme.generateScene(params)
    truth = np.asarray(scene.inlierMask).ravel() > 0
    return np.hstack([np.asarray(scene.points1)[truth], np.asarray(scene.points2)[truth]])


class EpipoleBlind(unittest.TestCase):
    def test_one_plane_cannot_tell_the_epipole(self):
        for seed in range(3):
            self.assertTrue(metrics.epipole_blind(_true_matches(rcme.SCENE_PLANE, seed)), seed)

    def test_a_scene_with_depth_can(self):
        for seed in range(3):
            self.assertFalse(metrics.epipole_blind(_true_matches(rcme.SCENE_GENERIC, seed)), seed)

    def test_too_few_matches_are_not_blind(self):
        self.assertFalse(metrics.epipole_blind(np.zeros((3, 4))))


class ConfusionCells(unittest.TestCase):
    def test_unjudgeable_runs_are_shown_and_left_out_of_the_rates(self):
        rows = [{"ok": True, "gt_fail": False}, {"ok": True, "gt_fail": True},
                {"ok": False, "flagged": True, "rejected_wrong": False},
                {"ok": False, "flagged": True, "rejected_wrong": False, "unjudgeable": True},
                {"ok": True, "gt_fail": False, "unjudgeable": True}]
        counts = report.confusion_counts(rows)
        self.assertEqual(counts["unjudgeable"], 2)
        self.assertEqual((counts["returned_right"], counts["returned_wrong"],
                          counts["flagged_right"]), (1, 1, 1))
        rates = report.confusion_rates(counts)
        self.assertEqual(rates["runs"], 3)
        self.assertEqual(rates["undetected"], report._pct(1, 3))
        self.assertEqual(rates["false_alarm"], report._pct(1, 2))


class Auc(unittest.TestCase):
    def test_mean_of_the_error_ramp_with_flags_as_infinite_errors(self):
        rows = [{"ok": True, "rot": 0.0, "trans": 0.0}, {"ok": True, "rot": 1.0, "trans": 5.0},
                {"ok": True, "rot": 20.0, "trans": 1.0}, {"ok": False, "flagged": True}]
        self.assertAlmostEqual(report.auc(rows), (1.0 + 0.5 + 0.0 + 0.0) / 4)
        self.assertIsNone(report.auc([]))


if __name__ == "__main__":
    unittest.main()
