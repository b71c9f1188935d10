#!/usr/bin/python3
"""Tests of the benchmark's judges (ctest rcme_benchmark_judges): the F-only judge's blindness
test (metrics.epipole_blind), the confusion table's handling of unjudgeable runs, the given
pairs whose rows are another pair's (datasets.rows_of_another_pair), and the covariance
calibration's loop tests (covariance_calibration.loop_nees, loop_translation_nees) and its
medians' interval (median_interval), vo_front_end.py's and bundle_adjustment.py's refusal of bad
arguments, PoseLib's options at the benchmark's settings (methods.poselib_ransac_options), and the
bundle adjustment that measures fountain-P11's and templeSR's ground-truth
error (bundle_adjustment).

    PYTHONPATH=build/python /usr/bin/python3 samples/benchmark/test_judges.py"""
import contextlib
import io
import types
import unittest

import numpy as np

import bundle_adjustment as bundle
import covariance_calibration as calibration
import datasets
import f_only
import methods
import metrics
import report
import vo_front_end
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

    def test_targets_per_dataset_compare_the_default_with_the_peer(self):
        exact = {"ok": True, "rot": 0.0, "trans": 0.0}
        off = {"ok": True, "rot": 5.0, "trans": 0.0}
        rows = [dict(exact, method="ours", dataset="a"), dict(off, method="peer", dataset="a"),
                dict(off, method="ours", dataset="b"), dict(exact, method="peer", dataset="b"),
                dict(exact, method="ours", dataset="c")]
        groups = [(d, [r for r in rows if r["dataset"] == d]) for d in "abc"]
        table = report.auc_targets([("runs", groups)], "ours", "peer").splitlines()
        self.assertEqual(len(table), 4)  # header, rule, a and b: c has no run of the peer
        self.assertEqual(table[2], "| runs | a | 1.0000 >= 0.5000 | met |")
        self.assertEqual(table[3], "| runs | b | 0.5000 >= 1.0000 | **not met** |")


def _loop(centres, rotations):
    """The reports of pairs (0, 1), (1, 2), (0, 2) of three exact cameras x = R (X - C): R, and t
    of unit length."""
    reports = []
    for a, b in ((0, 1), (1, 2), (0, 2)):
        R = rotations[b] @ rotations[a].T
        t = rotations[b] @ (centres[a] - centres[b])
        reports.append(types.SimpleNamespace(R=R, t=t / np.linalg.norm(t)))
    return reports


class LoopTests(unittest.TestCase):
    centres = [np.zeros(3), np.r_[1.0, 0.2, 0.3], np.r_[2.0, -0.3, 0.4]]
    rotations = [np.eye(3), metrics.rotation_exp([0.02, -0.05, 0.01]),
                 metrics.rotation_exp([-0.03, 0.04, 0.02])]

    def test_exact_estimates_close_both_loops(self):
        reports = _loop(self.centres, self.rotations)
        covariances = [np.diag([1e-6, 1e-6, 1e-6, 1e-6, 1e-6])] * 3
        self.assertLess(calibration.loop_nees(reports, covariances), 1e-12)
        nees1, conditioning = calibration.loop_translation_nees(reports, covariances)
        self.assertLess(nees1, 1e-12)
        self.assertGreater(conditioning, 10)

    def test_coplanarity_is_the_angle_out_of_the_plane_over_its_std(self):
        reports = _loop(self.centres, self.rotations)
        (_, tij), (Rjk, tjk), _ = ((r.R, r.t) for r in reports)
        normal = np.cross(Rjk @ tij, tjk)
        normal /= np.linalg.norm(normal)
        angle, std = 0.003, 0.001
        reports[2].t = np.cos(angle) * reports[2].t + np.sin(angle) * normal
        only_ik = [np.zeros((5, 5)), np.zeros((5, 5)), np.diag([0, 0, 0, std ** 2, std ** 2])]
        nees1, _ = calibration.loop_translation_nees(reports, only_ik)
        self.assertAlmostEqual(nees1, (angle / std) ** 2, delta=1e-3 * (angle / std) ** 2)
        # the rotation of (j, k) turns t_ij into k's frame: its error moves the plane too
        with_rotation_jk = [only_ik[0], np.diag([std ** 2] * 3 + [0, 0]), only_ik[2]]
        self.assertLess(calibration.loop_translation_nees(reports, with_rotation_jk)[0],
                        0.9 * nees1)

    def test_calibrated_on_synthetic_triplets_only_with_split_keypoints(self):
        values = calibration.synthetic_loop_values(
            40, seed=3, geometries=calibration.SYNTHETIC_LOOP_GEOMETRIES[:1])
        split = values["sideways", "keypoints split between the pairs"]
        shared = values["sideways", "shared keypoints"]
        self.assertGreaterEqual(len(split), 35)
        # chi-square(3) and chi-square(1) means over 40 loops: 3 +- 0.4 and 1 +- 0.22 (1 sigma)
        self.assertTrue(2.0 < np.mean(split[:, 0]) < 4.2, np.mean(split[:, 0]))
        self.assertTrue(0.5 < np.mean(split[:, 1]) < 1.7, np.mean(split[:, 1]))
        self.assertLess(np.mean(shared[:, 1]), 0.5 * np.mean(split[:, 1]))


def _multi_view(seed, cameras=6, points=300, sigma=0.5):
    """Cameras on an arc looking at a box of points, every point seen by every camera with
    Gaussian noise: (problem, true state)."""
    rng = np.random.default_rng(seed)
    K = np.array([[1400.0, 0, 768], [0, 1400.0, 512], [0, 0, 1]])
    X = rng.uniform([-2, -1.5, 6], [2, 1.5, 9], (points, 3))
    R, C = [], []
    for a in np.radians(np.linspace(-15, 15, cameras)):
        centre = np.array([7.5 * np.sin(a), 0.1 * rng.standard_normal(), 7.5 - 7.5 * np.cos(a)])
        forward = np.array([0.0, 0.0, 7.5]) - centre
        forward /= np.linalg.norm(forward)
        right = np.cross([0.0, 1.0, 0.0], forward)
        right /= np.linalg.norm(right)
        R.append(np.array([right, np.cross(forward, right), forward]))
        C.append(centre)
    R, C = np.array(R), np.array(C)
    cam, pt = np.repeat(np.arange(cameras), points), np.tile(np.arange(points), cameras)
    truth = (R, C, X, np.array([K[0, 0], K[1, 1], K[0, 2], K[1, 2]]))
    problem = bundle.Problem(cam, pt, np.zeros((len(cam), 2)), cameras, points)
    problem.uv = problem.residuals(truth)[0] + sigma * rng.standard_normal((len(cam), 2))
    return problem, truth


class VoFrontEndArguments(unittest.TestCase):
    """Bad arguments of vo_front_end.py stop it with argparse's error (exit 2) naming them, before
    any data is read."""

    def assert_refused(self, argv, name):
        err = io.StringIO()
        with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as stop:
            vo_front_end.main(argv)
        self.assertEqual(stop.exception.code, 2)
        self.assertIn(name, err.getvalue())

    def test_each_bad_argument_is_named(self):
        self.assert_refused(["--methods", "rcme default,nope"], "--methods")
        self.assert_refused(["--other-states", "1,x"], "--other-states")
        self.assert_refused(["--first-frame", "-1"], "--first-frame")
        self.assert_refused(["--frames", "1"], "--frames")
        self.assert_refused(["--sequence", "KITTI 99"], "--sequence")


class BundleAdjustmentArguments(unittest.TestCase):
    """Bad arguments of bundle_adjustment.py stop it with argparse's error (exit 2) naming them,
    before any data is read."""

    def test_each_bad_argument_is_named(self):
        for argv, name in ((["--sequence", "nope"], "--sequence"),
                           (["--bootstrap", "-1"], "--bootstrap"),
                           (["--max-side", "-5"], "--max-side"),
                           (["--bootstrap", "x"], "--bootstrap"),
                           (["--judge", "no such method"], "--judge")):
            err = io.StringIO()
            with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as stop:
                bundle.main(argv + ["--data", "/nonexistent"])
            self.assertEqual(stop.exception.code, 2, argv)
            self.assertIn(name, err.getvalue())


class FOnlyArguments(unittest.TestCase):
    """f_only.py's parts by their short names: a bad one stops it with argparse's error (exit 2)
    naming --parts, before any data is read."""

    def test_parts_by_short_name(self):
        self.assertEqual(f_only.parse_args([]).parts, list(f_only.PARTS))
        self.assertEqual(f_only.parse_args(["--parts", "given,sift"]).parts, ["given", "sift"])

    def test_a_bad_part_is_named(self):
        err = io.StringIO()
        with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as stop:
            f_only.main(["--parts", "given,nope", "--data", "/nonexistent"])
        self.assertEqual(stop.exception.code, 2)
        self.assertIn("--parts", err.getvalue())
        self.assertIn("nope", err.getvalue())

    def test_time_repeats_at_least_one(self):
        self.assertEqual(f_only.parse_args([]).time_repeats, 1)
        self.assertEqual(f_only.parse_args(["--time-repeats", "10"]).time_repeats, 10)
        err = io.StringIO()
        with contextlib.redirect_stderr(err), self.assertRaises(SystemExit) as stop:
            f_only.parse_args(["--time-repeats", "0"])
        self.assertEqual(stop.exception.code, 2)
        self.assertIn("--time-repeats", err.getvalue())


class PoseLibOptions(unittest.TestCase):
    """PoseLib runs at every method's settings: adaptive with no minimum number of samples (its
    own default is 100) at the given confidence, exactly N as both minimum and maximum."""

    def test_adaptive_has_no_minimum_and_exact_is_n(self):
        adaptive = methods.poselib_ransac_options(methods.Budget(1000, 1.0, 3, True), 0.999)
        self.assertEqual(adaptive["min_iterations"], 0)
        self.assertEqual(adaptive["max_iterations"], 1000)
        self.assertEqual(adaptive["success_prob"], 0.999)
        self.assertEqual(adaptive["seed"], 3)
        self.assertAlmostEqual(adaptive["max_epipolar_error"], methods.Budget(1, 1.0, 0).threshold)
        exact = methods.poselib_ransac_options(methods.Budget(500, 1.0, 0))
        self.assertEqual(exact["min_iterations"], 500)
        self.assertEqual(exact["max_iterations"], 500)
        self.assertGreater(exact["success_prob"], 1.0 - 1e-9)

    def test_camera_of_a_camera_matrix(self):
        K = np.array([[718.9, 0, 607.2], [0, 718.8, 185.2], [0, 0, 1]])
        camera = methods.poselib_camera(K)
        self.assertEqual(camera["model"], "PINHOLE")
        self.assertEqual((camera["width"], camera["height"]), (1214, 370))
        self.assertEqual(camera["params"], [718.9, 718.8, 607.2, 185.2])


class MedianInterval(unittest.TestCase):
    def test_order_statistics_of_a_small_sample(self):
        # n = 10: P(Binomial(10, 1/2) <= 1) = 0.011 <= 0.05 < P(<= 2) = 0.055, so x_(2) to x_(9)
        self.assertEqual(calibration.median_interval(range(1, 11)), (2.0, 9.0))
        self.assertIsNone(calibration.median_interval(range(4)))

    def test_covers_chi_square_median_at_its_level(self):
        rng = np.random.default_rng(3)
        covered = [lo <= 2.366 <= hi for lo, hi in
                   (calibration.median_interval(rng.chisquare(3, 35)) for _ in range(1000))]
        self.assertGreaterEqual(np.mean(covered), 0.88)
        self.assertLessEqual(np.mean(covered), 0.95)


class BundleAdjustment(unittest.TestCase):
    def _adjusted(self, seed):
        problem, truth = _multi_view(seed)
        free = bundle.free_parameters(problem, truth[1])
        start = bundle.adjust(problem, truth, None, iterations=10)  # points alone
        state = bundle.adjust(problem, start, free, iterations=100)
        return problem, truth, start, state, free

    def test_relative_rotations_match_their_covariance(self):
        values = []
        for seed in range(8):
            problem, truth, _, state, free = self._adjusted(seed)
            cov = bundle.camera_covariance(problem, state, free)[0]
            R, C = state[:2]
            for i, j in ((0, 1), (1, 3), (2, 5)):
                theta = bundle.relative_theta(truth[0], truth[1], i, j, (
                    R[j] @ R[i].T, R[j] @ (C[i] - C[j])))
                Cij = bundle.relative_covariance(state, cov, i, j)
                values.append(float(theta[:3] @ np.linalg.solve(Cij[:3, :3], theta[:3])))
        self.assertTrue(1.8 < np.mean(values) < 4.5, np.mean(values))

    def test_exact_cameras_lower_the_cost_by_chi_square(self):
        problem, truth, start, state, free = self._adjusted(11)
        sigma = bundle.camera_covariance(problem, state, free)[1]
        drop = (bundle.huber_cost(problem.residuals(start)[0], bundle.HUBER_PX, 1.0) -
                bundle.huber_cost(problem.residuals(state)[0], bundle.HUBER_PX, 1.0)) / sigma ** 2
        dof = int(free.sum())
        self.assertLess(drop, dof + 5 * np.sqrt(2 * dof))
        self.assertAlmostEqual(sigma, 0.5, delta=0.05)

    def test_adjusted_relative_motions_are_the_truth_within_the_noise(self):
        """The motions --judge scores against: the adjustment's relative motions, within a tenth of
        a degree or so of the true ones on a synthetic scene with 0.5 px noise (the pairs' own
        turns are 6-18 deg: a pair taken the other way round or a reversed t would be degrees
        off), and motion_error_deg measures a known turn and a known change of direction."""
        problem, truth = _multi_view(13)
        start = bundle.adjust(problem, truth, None, iterations=10)
        pairs = [(0, 1), (1, 3), (2, 5)]
        motions = bundle.adjusted_relative_motions(problem, start, pairs)
        R, C = truth[:2]
        for i, j in pairs:
            error = bundle.motion_error_deg(*motions[(i, j)], R[j] @ R[i].T, R[j] @ (C[i] - C[j]))
            self.assertLess(error, 0.3, (i, j))
        turn = bundle.rotation_exp(np.radians([0.0, 0.0, 2.0]))
        self.assertAlmostEqual(bundle.motion_error_deg(turn, [1, 0, 0], np.eye(3), [1, 0, 0]), 2.0)
        self.assertAlmostEqual(bundle.motion_error_deg(np.eye(3), [1, 0, 0], np.eye(3),
                                                       [1, np.tan(np.radians(3.0)), 0]), 3.0)

    def test_a_rotated_camera_is_seen(self):
        """A ground truth with one camera turned by 0.05 deg: the adjustment, started from it,
        ends where it ends from the true cameras, and the wrong camera's relative rotation
        differs from it by the turn."""
        problem, truth, _, state, free = self._adjusted(12)
        turn = np.radians([0.0, 0.05, 0.0])
        wrong = truth[0].copy()
        wrong[3] = metrics.rotation_exp(turn) @ wrong[3]
        start = bundle.adjust(problem, (wrong, *truth[1:]), None, iterations=10)
        from_wrong = bundle.adjust(problem, start, free, iterations=100)
        R, C = from_wrong[:2]
        reference = (R[3] @ R[2].T, R[3] @ (C[2] - C[3]))
        difference = (bundle.relative_theta(wrong, truth[1], 2, 3, reference) -
                      bundle.relative_theta(truth[0], truth[1], 2, 3, reference))[:3]
        self.assertLess(np.degrees(np.linalg.norm(difference - reference[0].T @ turn)), 0.002)
        same = bundle.relative_theta(state[0], state[1], 2, 3, reference)
        self.assertLess(np.degrees(np.linalg.norm(same[:3])), 0.001)
        sigma = bundle.camera_covariance(problem, from_wrong, free)[1]
        drop = (bundle.huber_cost(problem.residuals(start)[0], bundle.HUBER_PX, 1.0) -
                bundle.huber_cost(problem.residuals(from_wrong)[0], bundle.HUBER_PX, 1.0))
        self.assertGreater(drop / sigma ** 2, 100)


if __name__ == "__main__":
    unittest.main()
