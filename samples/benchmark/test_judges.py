#!/usr/bin/python3
"""Tests of the benchmark's judges (ctest rcme_benchmark_judges): the F-only judge's blindness
test (metrics.epipole_blind), the confusion table's handling of unjudgeable runs, and the given
pairs whose rows are another pair's (datasets.rows_of_another_pair).

    PYTHONPATH=build/python /usr/bin/python3 samples/benchmark/test_judges.py"""
import unittest

import numpy as np

import datasets
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


def _scene(seed):
    params = rcme.SceneParams()
    params.kind, params.numPoints, params.inlierRatio, params.sigma, params.seed = (
        rcme.SCENE_GENERIC, 100, 0.9, 0.5, seed)
    scene = rcme.generateScene(params)
    return np.asarray(scene.points1), np.asarray(scene.points2), np.asarray(scene.F)


class RowsOfAnotherPair(unittest.TestCase):
    def test_the_pair_whose_unlabelled_rows_fit_another_pair_is_found(self):
        # Both pairs: 10 annotated rows of their own, then the same 90 rows of scene 0 (90 %
        # true under its F); "theirs" is scene 0, "mine" scene 1.
        p1, p2, F = _scene(0)
        q1, q2, G = _scene(1)
        labels = np.concatenate([np.ones(10, int), np.zeros(90, int)])
        theirs = datasets.LabelledPair("theirs", p1, p2, labels, None, F)
        mine = datasets.LabelledPair("mine", np.vstack([q1[:10], p1[10:]]),
                                     np.vstack([q2[:10], p2[10:]]), labels, None, G)
        found = datasets.rows_of_another_pair([theirs, mine], 1.96)
        self.assertEqual(list(found), ["mine"])
        owner, own_share, owner_share = found["mine"]
        self.assertEqual(owner, "theirs")
        self.assertLess(own_share, 0.2)
        self.assertGreater(owner_share, 0.7)

    def test_shared_rows_that_no_pair_holds_are_nobodys(self):
        # two labellings of one pair's outliers (AdelaideRMF's johnssona and johnssonb)
        rng = np.random.default_rng(0)
        p1, p2, F = _scene(0)
        noise1, noise2 = rng.uniform(0, 640, (30, 2)), rng.uniform(0, 480, (30, 2))
        labels = np.concatenate([np.ones(100, int), np.zeros(30, int)])
        a = datasets.LabelledPair("a", np.vstack([p1, noise1]), np.vstack([p2, noise2]), labels)
        b = datasets.LabelledPair("b", np.vstack([p1[:50], noise1]), np.vstack([p2[:50], noise2]),
                                  labels[50:])
        self.assertEqual(datasets.rows_of_another_pair([a, b], 1.96), {})

    def test_unshared_rows_are_nobody_elses(self):
        p1, p2, F = _scene(0)
        q1, q2, G = _scene(1)
        labels = np.concatenate([np.ones(10, int), np.zeros(90, int)])
        pairs = [datasets.LabelledPair("a", p1, p2, labels, None, F),
                 datasets.LabelledPair("b", q1, q2, labels, None, G)]
        self.assertEqual(datasets.rows_of_another_pair(pairs, 1.96), {})


class Auc(unittest.TestCase):
    def test_mean_of_the_error_ramp_with_flags_as_infinite_errors(self):
        rows = [{"ok": True, "rot": 0.0, "trans": 0.0}, {"ok": True, "rot": 1.0, "trans": 5.0},
                {"ok": True, "rot": 20.0, "trans": 1.0}, {"ok": False, "flagged": True}]
        self.assertAlmostEqual(report.auc(rows), (1.0 + 0.5 + 0.0 + 0.0) / 4)
        self.assertIsNone(report.auc([]))


if __name__ == "__main__":
    unittest.main()
