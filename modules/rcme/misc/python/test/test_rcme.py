#!/usr/bin/env python3
"""Tests of the rcme Python API, run against every binding that is importable.

There is one test body and there are two bindings: the standalone pybind11 module `rcme` and
`cv2.rcme`, which OpenCV's generator produces in an in-tree build. Both are meant to expose the
same names, argument orders and result tuples. A binding that is absent is skipped, and
`test_a_binding_is_importable` fails when neither is.

The tests are unittest classes, so both pytest (`python3 -m pytest -q <this folder>`) and
OpenCV's own Python test runner can run them. OpenCV's runner (`modules/python/test/test.py` of
an OpenCV source tree, run from the build folder) collects misc/python/test/test_*.py of every
wrapped module and puts its `tests_common` on the path; the cv2 class then derives from
`NewOpenCVTests`, as contrib modules' tests do, and plain `unittest.TestCase` otherwise. They
only use synthetic scenes and finish in a few seconds.

RCME_TEST_REQUIRE (a comma-separated list of `standalone`, `cv2`) turns the skip of an absent
binding into an error: the in-tree build script sets RCME_TEST_REQUIRE=cv2, so a cv2 without
rcme fails the run instead of passing it with every test skipped.
"""

import os
import pickle
import threading
import time
import unittest

import numpy as np

try:  # OpenCV's runner (modules/python/test/test.py) puts tests_common on sys.path
    from tests_common import NewOpenCVTests as _Cv2TestCase
except ImportError:  # pytest, or plain unittest outside an OpenCV source tree
    _Cv2TestCase = unittest.TestCase

FM_RANSAC = 8  # cv2.FM_RANSAC == cv2.RANSAC == 8, accepted by the drop-in overloads
UNKNOWN_METHOD = 99  # neither an OpenCV method flag nor a METHOD_* value


def _load_standalone():
    try:
        import rcme
    except ImportError:
        return None
    return rcme, rcme.error


def _load_cv2():
    try:
        import cv2
    except ImportError:
        return None
    module = getattr(cv2, "rcme", None)
    if module is None:
        return None
    return module, cv2.error


def _usac_params_type():
    try:
        import cv2
    except ImportError:
        return None
    return getattr(cv2, "UsacParams", None)


def _sampson(F, p1, p2):
    """Sampson distances (pixels) of the correspondences p1[i] <-> p2[i] under F."""
    x1 = np.hstack([p1, np.ones((len(p1), 1))])
    x2 = np.hstack([p2, np.ones((len(p2), 1))])
    Fx1 = x1 @ F.T
    Ftx2 = x2 @ F
    num = np.sum(x2 * Fx1, axis=1)
    den = Fx1[:, 0] ** 2 + Fx1[:, 1] ** 2 + Ftx2[:, 0] ** 2 + Ftx2[:, 1] ** 2
    return np.abs(num) / np.sqrt(den)


_MISC_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def _header_tables():
    """The public headers as misc/generate_tables.py reads them (the tables of the library and
    of the pybind11 module are generated from this reading): ({enum: [value]}, {struct:
    [field]}, [function]) of every header, each value with .name and .value, each field with
    .type and .name."""
    import importlib.util
    spec = importlib.util.spec_from_file_location(
        "generate_tables", os.path.join(_MISC_DIR, "generate_tables.py"))
    generator = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(generator)
    headers = sorted(n for n in os.listdir(generator.HEADER_DIR) if n.endswith(".hpp"))
    return generator.parse(headers)


def _public_header_names():
    """What the public headers declare for Python: {struct: [fields]} of the
    CV_EXPORTS_W_SIMPLE structs' CV_PROP_RW fields, {NAME: value} of the enum constants, and
    the CV_EXPORTS_W function names. The bindings are checked against this, so a field or
    constant added to a header and missing from a binding fails a test."""
    enums, structs, functions = _header_tables()
    constants = {v.name: v.value for values in enums.values() for v in values}
    return ({s: [f.name for f in fields] for s, fields in structs.items()}, constants,
            set(functions))


def _mask_quality(mask, truth):
    """Recall of the true inliers and precision of the estimated ones."""
    m = mask.ravel().astype(bool)
    g = truth.ravel().astype(bool)
    found = np.count_nonzero(m & g)
    return found / max(np.count_nonzero(g), 1), found / max(np.count_nonzero(m), 1)


class _RcmeSuite:
    """The test body; subclasses pick the binding."""

    loader = None  # a function returning (module, error type) or None
    binding_name = ""
    binding_key = ""  # its name in RCME_TEST_REQUIRE
    b = None
    error = Exception

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        loaded = cls.loader()
        if loaded is None:
            required = os.environ.get("RCME_TEST_REQUIRE", "").replace(" ", "").split(",")
            if cls.binding_key in required:
                raise RuntimeError("binding %s is not importable, and RCME_TEST_REQUIRE=%s "
                                   "requires it" % (cls.binding_name,
                                                    os.environ["RCME_TEST_REQUIRE"]))
            raise unittest.SkipTest("binding %s is not importable" % cls.binding_name)
        cls.b, cls.error = loaded

    # --- helpers (attribute assignment only, which both bindings support)

    def make_params(self, **fields):
        p = self.b.Params()
        p.method = self.b.METHOD_STANDARD
        p.randomGeneratorState = 1
        for name, value in fields.items():
            setattr(p, name, value)
        return p

    def make_scene(self, **fields):
        sp = self.b.SceneParams()
        sp.kind = self.b.SCENE_GENERIC
        sp.numPoints = 400
        sp.inlierRatio = 0.5
        sp.sigma = 1.0
        sp.seed = 11
        for name, value in fields.items():
            setattr(sp, name, value)
        return self.b.generateScene(sp)

    def assertRaisesNaming(self, words, func, *args, **kwargs):
        """func(*args) raises the binding's error with a message naming one of `words`."""
        with self.assertRaises(self.error) as ctx:
            func(*args, **kwargs)
        message = str(ctx.exception)
        self.assertTrue(any(w in message for w in words), "%r names none of %r" % (message, words))

    def assertValidMask(self, mask, n):
        self.assertIsInstance(mask, np.ndarray)
        self.assertEqual(mask.shape, (n, 1))
        self.assertEqual(mask.dtype, np.uint8)
        self.assertTrue(np.all((mask == 0) | (mask == 1)))

    def assertRotation(self, R):
        self.assertEqual(R.shape, (3, 3))
        self.assertEqual(R.dtype, np.float64)
        np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-9)
        self.assertAlmostEqual(np.linalg.det(R), 1.0, places=9)

    def assertUnitTranslation(self, t):
        self.assertEqual(t.shape, (3, 1))
        self.assertEqual(t.dtype, np.float64)
        self.assertAlmostEqual(np.linalg.norm(t), 1.0, places=9)

    # --- constants and structs

    def test_constants(self):
        b = self.b
        expected = {
            "METHOD_RCME": 1024, "METHOD_PRCME": 1025, "METHOD_STANDARD": 1026,
            "METHOD_MLESAC": 1027, "METHOD_COV_RANSAC": 1028,
            "SAMPLER_UNIFORM": 0, "SAMPLER_PROSAC": 1,
            "SOLVER_EIGHT_POINT": 0, "SOLVER_SEVEN_POINT": 1, "SOLVER_FIVE_POINT": 2,
            "SOLVER_AUTO": 3,
            "VERIFICATION_AUTO": 0, "VERIFICATION_NONE": 1, "VERIFICATION_SPRT": 2,
            "STATUS_SUCCESS": 0, "STATUS_POOR_QUALITY_INPUT": 1, "STATUS_NOT_ENOUGH_POINTS": 2,
            "STATUS_DEGENERATE_CONFIGURATION": 3, "STATUS_PURE_ROTATION": 4,
            "SCENE_CORRIDOR": 0, "SCENE_GENERIC": 1, "SCENE_PLANE": 2, "SCENE_PURE_ROTATION": 3,
        }
        for name, value in expected.items():
            self.assertIs(type(getattr(b, name)), int, name)
            self.assertEqual(getattr(b, name), value, name)

    def test_params_defaults(self):
        b = self.b
        p = b.Params()
        self.assertEqual(p.method, b.METHOD_STANDARD)
        self.assertEqual(p.sampler, b.SAMPLER_UNIFORM)
        self.assertEqual(p.solver, b.SOLVER_AUTO)
        self.assertEqual(p.verification, b.VERIFICATION_AUTO)
        self.assertEqual(p.scoring, b.SCORING_AUTO)
        for name in ("method", "sampler", "solver", "verification", "scoring"):
            self.assertIs(type(getattr(p, name)), int, name)
        self.assertEqual(p.sigma, 1.0)
        self.assertLessEqual(p.threshold, 0.0)
        self.assertAlmostEqual(p.confidence, 0.99)
        self.assertEqual(p.cleanSampleSuccessRate, 0.0)  # 0.3 with K, 1 without
        self.assertEqual(p.maxIterations, 1000)
        self.assertIs(p.exactIterations, False)
        self.assertEqual(p.randomGeneratorState, 0)
        self.assertIs(p.refine, True)
        self.assertEqual(p.refineIterations, 20)
        self.assertIs(p.useEstimatedNoise, True)
        self.assertAlmostEqual(p.alpha, 0.05)
        self.assertLessEqual(p.priorInlierRatio, 0.0)
        self.assertEqual(p.consistencyDof, 1)
        self.assertIs(p.degeneracyTest, True)
        self.assertTrue(0.5 <= p.inlierRatioFactor <= 1.0)
        self.assertTrue(np.isfinite(p.entropyThreshold))
        self.assertIs(p.isParallel, False)
        self.assertIs(p.localOptimization, True)
        self.assertEqual((p.ambiguityMargin, p.maxRotationStdDeg, p.maxTranslationStdDeg),
                         (2.0, 4.0, 8.0))

    def test_params_as_published(self):
        b = self.b
        as_published = getattr(b.Params, "asPublished", None) or b.Params_asPublished
        p = as_published(b.METHOD_RCME)
        self.assertEqual(p.method, b.METHOD_RCME)
        self.assertEqual(p.solver, b.SOLVER_EIGHT_POINT)
        self.assertIs(p.localOptimization, False)
        self.assertEqual(p.cleanSampleSuccessRate, 1.0)
        self.assertEqual(p.scoring, b.SCORING_AUTO)
        self.assertEqual(as_published(b.METHOD_STANDARD).scoring, b.SCORING_INLIER_COUNT)
        self.assertEqual((p.ambiguityMargin, p.maxRotationStdDeg, p.maxTranslationStdDeg),
                         (0.0, 0.0, 0.0))
        self.assertEqual(p.maxIterations, b.Params().maxIterations)  # the rest: the defaults

    def test_binding_has_every_name_of_the_headers(self):
        b = self.b
        structs, constants, functions = _public_header_names()
        self.assertIn("cleanSampleSuccessRate", structs["Params"])  # the reader reads the header
        self.assertGreater(len(constants), 20)
        for struct, fields in structs.items():
            instance = getattr(b, struct)()
            for field in fields:
                self.assertTrue(hasattr(instance, field), "%s.%s" % (struct, field))
        for constant, value in constants.items():
            self.assertEqual(getattr(b, constant, None), value, constant)
        for function in functions:
            self.assertTrue(callable(getattr(b, function, None)), function)

    def test_every_params_field_round_trips(self):
        """Every field of the header's Params, set on one object to a value other than its
        default, reads back as set with the type it was set with (enums: another value of the
        field's enum), so no two fields share storage; a new object keeps the defaults. The
        fields and their enums come from the header, so a new field is covered without an edit
        here."""
        b = self.b
        enums, structs, _ = _header_tables()
        defaults, p, values = b.Params(), b.Params(), {}
        self.assertGreater(len(structs["Params"]), 25)
        for field in structs["Params"]:
            default = getattr(defaults, field.name)
            if field.type in enums:
                values[field.name] = next(v.value for v in enums[field.type]
                                          if v.value != default)
            elif isinstance(default, bool):
                values[field.name] = not default
            elif isinstance(default, int):
                values[field.name] = default + 3
            elif isinstance(default, float):
                values[field.name] = default + 0.25
            else:  # a Mat (matchQuality)
                self.assertEqual(field.type, "Mat", field.name)
                values[field.name] = np.arange(4, dtype=np.float64).reshape(4, 1)
            setattr(p, field.name, values[field.name])
        self.assertEqual(list(values), [f.name for f in structs["Params"]])
        for field, value in values.items():
            got = getattr(p, field)
            if isinstance(value, np.ndarray):
                np.testing.assert_array_equal(np.asarray(got).reshape(4, 1), value, field)
            else:
                self.assertEqual(got, value, field)
                self.assertIs(type(got), type(value), field)
        fresh = b.Params()
        for field in values:
            if not isinstance(values[field], np.ndarray):
                self.assertEqual(getattr(fresh, field), getattr(defaults, field), field)

    def test_params_from_usac_params(self):
        UsacParams = _usac_params_type()
        if UsacParams is None:
            self.skipTest("cv2.UsacParams is not available")
        import cv2
        u = UsacParams()
        u.confidence = 0.95
        u.maxIterations = 321
        u.randomGeneratorState = 7
        u.threshold = 2.5
        u.sampler = cv2.SAMPLING_PROSAC
        u.isParallel = True
        p = self.b.Params.fromUsacParams(u)
        self.assertIs(p.isParallel, True)
        self.assertAlmostEqual(p.confidence, 0.95)
        self.assertEqual(p.maxIterations, 321)
        self.assertEqual(p.randomGeneratorState, 7)
        self.assertAlmostEqual(p.threshold, 2.5)
        self.assertEqual(p.sampler, self.b.SAMPLER_PROSAC)
        self.assertEqual(self.b.Params_fromUsacParams(u).maxIterations, 321)
        u.sampler = cv2.SAMPLING_NAPSAC
        self.assertRaisesNaming(["usacParams.sampler"], self.b.Params.fromUsacParams, u)

    def test_scene_params_defaults_and_round_trip(self):
        b = self.b
        sp = b.SceneParams()
        self.assertEqual(sp.kind, b.SCENE_CORRIDOR)
        self.assertIs(type(sp.kind), int)
        self.assertEqual(sp.numPoints, 500)
        self.assertEqual(sp.inlierRatio, 0.5)
        self.assertEqual(sp.sigma, 1.0)
        self.assertEqual(sp.seed, 0)
        self.assertEqual(sp.focalLength, 500.0)
        self.assertEqual((sp.imageWidth, sp.imageHeight), (640, 480))
        self.assertEqual(sp.baseline, 1.0)
        self.assertEqual(sp.corridorDepth, 50.0)
        self.assertEqual(sp.corridorWidth, 4.0)
        self.assertEqual(sp.corridorHeight, 3.0)
        sp.kind = b.SCENE_GENERIC
        sp.numPoints = 123
        sp.corridorHeight = 2.5
        self.assertEqual((sp.kind, sp.numPoints, sp.corridorHeight), (b.SCENE_GENERIC, 123, 2.5))

    def test_other_structs(self):
        b = self.b
        r = b.Report()
        r.status = b.STATUS_POOR_QUALITY_INPUT
        r.message = "why"
        r.F = np.eye(3)
        r.inlierCount = 5
        r.meanEntropy = 1.5
        self.assertEqual(r.status, b.STATUS_POOR_QUALITY_INPUT)
        self.assertEqual(r.message, "why")
        np.testing.assert_array_equal(r.F, np.eye(3))
        self.assertEqual((r.inlierCount, r.meanEntropy), (5, 1.5))
        s = b.SyntheticScene()
        s.R = np.eye(3)
        np.testing.assert_array_equal(s.R, np.eye(3))
        e = b.MotionError()
        e.rotationDeg = 2.0
        self.assertEqual(e.rotationDeg, 2.0)

    def test_generate_scene(self):
        b = self.b
        s = self.make_scene(numPoints=300, inlierRatio=0.4, seed=5)
        for name in ("points1", "points2"):
            arr = getattr(s, name)
            self.assertEqual(arr.shape, (300, 2), name)
            self.assertEqual(arr.dtype, np.float64, name)
            self.assertTrue(np.all(np.isfinite(arr)), name)
        self.assertValidMask(s.inlierMask, 300)
        self.assertEqual(int(s.inlierMask.sum()), 120)
        self.assertEqual(s.cameraMatrix.shape, (3, 3))
        self.assertRotation(s.R)
        self.assertUnitTranslation(s.t)
        self.assertAlmostEqual(np.linalg.norm(s.F), 1.0, places=9)
        # E = [t]x R, and F is K^-T E K^-1 up to scale
        t = s.t.ravel()
        tx = np.array([[0, -t[2], t[1]], [t[2], 0, -t[0]], [-t[1], t[0], 0]])
        np.testing.assert_allclose(s.E, tx @ s.R, atol=1e-9)
        Kinv = np.linalg.inv(s.cameraMatrix)
        F = Kinv.T @ s.E @ Kinv
        F /= np.linalg.norm(F)
        self.assertLess(min(np.abs(F - s.F).max(), np.abs(F + s.F).max()), 1e-9)
        # true correspondences lie near their epipolar lines
        inl = s.inlierMask.ravel().astype(bool)
        self.assertLess(np.median(_sampson(s.F, s.points1[inl], s.points2[inl])), 2.0)
        # the same seed gives the same scene, another seed another one
        s2 = self.make_scene(numPoints=300, inlierRatio=0.4, seed=5)
        np.testing.assert_array_equal(s.points1, s2.points1)
        np.testing.assert_array_equal(s.inlierMask, s2.inlierMask)
        s3 = self.make_scene(numPoints=300, inlierRatio=0.4, seed=6)
        self.assertFalse(np.array_equal(s.points1, s3.points1))
        # the default scene is the paper's corridor
        corridor = b.generateScene()
        self.assertEqual(corridor.points1.shape, (500, 2))

    # --- estimation

    def test_find_fundamental_mat(self):
        b = self.b
        s = self.make_scene()
        n = len(s.points1)
        result = b.findFundamentalMat(s.points1, s.points2, self.make_params(threshold=3.0))
        self.assertIsInstance(result, tuple)
        self.assertEqual(len(result), 3)
        F, mask, status = result
        self.assertEqual(status, b.STATUS_SUCCESS)
        self.assertIs(type(status), int)
        self.assertEqual(F.shape, (3, 3))
        self.assertEqual(F.dtype, np.float64)
        self.assertAlmostEqual(np.linalg.norm(F), 1.0, places=6)
        self.assertValidMask(mask, n)
        recall, precision = _mask_quality(mask, s.inlierMask)
        self.assertGreater(recall, 0.9)
        self.assertGreater(precision, 0.9)
        inl = s.inlierMask.ravel().astype(bool)
        self.assertLess(np.median(_sampson(F, s.points1[inl], s.points2[inl])), 1.5)

    def test_find_fundamental_mat_mask_respects_threshold(self):
        s = self.make_scene(seed=12)
        thr = 2.0
        F, mask, status = self.b.findFundamentalMat(s.points1, s.points2,
                                                    self.make_params(threshold=thr))
        self.assertEqual(status, self.b.STATUS_SUCCESS)
        marked = mask.ravel().astype(bool)
        self.assertGreater(np.count_nonzero(marked), 0.3 * s.inlierMask.sum())
        self.assertLessEqual(_sampson(F, s.points1[marked], s.points2[marked]).max(), thr * 1.001)

    def test_find_fundamental_mat_calibrated(self):
        b = self.b
        s = self.make_scene(seed=13)
        F, mask, status = b.findFundamentalMat(s.points1, s.points2, s.cameraMatrix,
                                               self.make_params(threshold=3.0))
        self.assertEqual(status, b.STATUS_SUCCESS)
        self.assertEqual(F.shape, (3, 3))
        self.assertValidMask(mask, len(s.points1))
        sv = np.linalg.svd(s.cameraMatrix.T @ F @ s.cameraMatrix, compute_uv=False)
        self.assertAlmostEqual(sv[1] / sv[0], 1.0, places=6)
        self.assertLess(sv[2] / sv[0], 1e-6)
        self.assertGreater(_mask_quality(mask, s.inlierMask)[0], 0.9)

    def test_find_fundamental_mat_drop_in(self):
        b = self.b
        s = self.make_scene(seed=14)
        n = len(s.points1)
        for method in (FM_RANSAC, b.METHOD_STANDARD):
            result = b.findFundamentalMat(s.points1, s.points2, method, 3.0, 0.99, 2000)
            self.assertEqual(len(result), 2)
            F, mask = result
            self.assertEqual(F.shape, (3, 3))
            self.assertValidMask(mask, n)
            self.assertGreater(_mask_quality(mask, s.inlierMask)[0], 0.9)
        F2, mask2 = b.findFundamentalMat(points1=s.points1, points2=s.points2, method=FM_RANSAC,
                                         ransacReprojThreshold=3.0, confidence=0.99,
                                         maxIters=2000)
        np.testing.assert_array_equal(F2, F)  # the drop-in is deterministic
        # OpenCV's defaulted form: (points1, points2[, method[, threshold[, confidence[, mask]]]]).
        for args in ((), (FM_RANSAC,), (FM_RANSAC, 3.0, 0.99)):
            F3, mask3 = b.findFundamentalMat(s.points1, s.points2, *args)
            self.assertEqual(F3.shape, (3, 3))
            self.assertValidMask(mask3, n)
            np.testing.assert_array_equal(F3, b.findFundamentalMat(s.points1, s.points2, FM_RANSAC,
                                                                   3.0, 0.99, 1000)[0])
        np.testing.assert_array_equal(mask2, mask)
        self.assertRaisesNaming(["method"], b.findFundamentalMat, s.points1, s.points2,
                                UNKNOWN_METHOD, 3.0, 0.99, 2000)

    def test_output_array_is_written_in_place(self):
        s = self.make_scene(seed=15)
        n = len(s.points1)
        out = np.full((n, 1), 7, np.uint8)
        F, mask, status = self.b.findFundamentalMat(s.points1, s.points2, self.make_params(),
                                                    out)
        self.assertIs(mask, out)
        self.assertValidMask(out, n)
        wrong = np.zeros((n, 1), np.int32)  # wrong type: a new array comes back, as in cv2
        F, mask = self.b.findFundamentalMat(s.points1, s.points2, FM_RANSAC, 3.0, 0.99, 1000,
                                            mask=wrong)
        self.assertIsNot(mask, wrong)
        self.assertValidMask(mask, n)

    def test_find_essential_mat(self):
        b = self.b
        s = self.make_scene(seed=16)
        n = len(s.points1)
        K = s.cameraMatrix
        result = b.findEssentialMat(s.points1, s.points2, K, self.make_params(threshold=3.0))
        self.assertEqual(len(result), 3)
        E, mask, status = result
        self.assertEqual(status, b.STATUS_SUCCESS)
        self.assertEqual(E.shape, (3, 3))
        self.assertEqual(E.dtype, np.float64)
        np.testing.assert_allclose(np.linalg.svd(E, compute_uv=False), [1, 1, 0], atol=1e-6)
        self.assertValidMask(mask, n)
        recall, precision = _mask_quality(mask, s.inlierMask)
        self.assertGreater(recall, 0.9)
        self.assertGreater(precision, 0.9)

    def test_find_essential_mat_drop_in(self):
        b = self.b
        # OpenCV's default threshold (1 px) fits sub-pixel noise, as in real matches.
        s = self.make_scene(seed=17, sigma=0.3)
        n = len(s.points1)
        K = s.cameraMatrix
        result = b.findEssentialMat(s.points1, s.points2, K)
        self.assertEqual(len(result), 2)
        E, mask = result
        self.assertEqual(E.shape, (3, 3))
        self.assertValidMask(mask, n)
        E1, mask1 = b.findEssentialMat(s.points1, s.points2, K, b.METHOD_STANDARD, 0.999, 3.0,
                                       2000)
        E2, mask2 = b.findEssentialMat(s.points1, s.points2, cameraMatrix=K,
                                       method=b.METHOD_STANDARD, prob=0.999, threshold=3.0,
                                       maxIters=2000)
        np.testing.assert_array_equal(E1, E2)
        np.testing.assert_array_equal(mask1, mask2)
        self.assertGreater(_mask_quality(mask1, s.inlierMask)[0], 0.9)
        # focal length and principal point: the same camera, the same result
        self.assertEqual(K[0, 0], K[1, 1])
        focal, pp = float(K[0, 0]), (float(K[0, 2]), float(K[1, 2]))
        E3, mask3 = b.findEssentialMat(s.points1, s.points2, focal, pp, b.METHOD_STANDARD,
                                       0.999, 3.0, 2000)
        np.testing.assert_allclose(E3, E1, atol=1e-9)
        np.testing.assert_array_equal(mask3, mask1)
        E4, mask4 = b.findEssentialMat(s.points1, s.points2, focal=focal, pp=pp,
                                       method=b.METHOD_STANDARD, prob=0.999, threshold=3.0,
                                       maxIters=2000)
        np.testing.assert_allclose(E4, E1, atol=1e-9)

    def test_recover_pose(self):
        b = self.b
        s = self.make_scene(numPoints=500, seed=18)
        n = len(s.points1)
        result = b.recoverPose(s.points1, s.points2, s.cameraMatrix, self.make_params())
        self.assertIsInstance(result, tuple)
        self.assertEqual(len(result), 7)
        retval, E, R, t, mask, status, covariance = result
        self.assertEqual(status, b.STATUS_SUCCESS)
        self.assertIs(type(retval), int)
        self.assertEqual(E.shape, (3, 3))
        self.assertRotation(R)
        self.assertUnitTranslation(t)
        self.assertValidMask(mask, n)
        self.assertEqual(retval, int(mask.sum()))
        self.assertGreater(retval, 0.7 * s.inlierMask.sum())
        if covariance is not None:
            self.assertEqual(covariance.shape, (5, 5))
            np.testing.assert_allclose(covariance, covariance.T, atol=1e-12)
        err = b.compareMotion(R, t, s.R, s.t)
        self.assertLess(err.rotationDeg, 1.0)
        self.assertLess(err.translationDeg, 10.0)
        # the optional outputs may be passed positionally, cv2-style
        result2 = b.recoverPose(s.points1, s.points2, s.cameraMatrix, self.make_params(),
                                None, None, None, None, None)
        np.testing.assert_array_equal(result2[2], R)

    def test_recover_pose_from_essential(self):
        b = self.b
        s = self.make_scene(numPoints=500, seed=19)
        n = len(s.points1)
        K = s.cameraMatrix
        # decompose the true E: every true inlier in front of both cameras
        result = b.recoverPose(s.E, s.points1, s.points2, K)
        self.assertEqual(len(result), 4)
        retval, R, t, mask = result
        self.assertRotation(R)
        self.assertUnitTranslation(t)
        self.assertValidMask(mask, n)
        self.assertEqual(retval, int(mask.sum()))
        self.assertLess(b.compareMotion(R, t, s.R, s.t).rotationDeg, 1e-6)
        # an input mask selects the points used; the output keeps a subset of it
        selected = s.inlierMask.copy()
        retval2, R2, t2, mask2 = b.recoverPose(s.E, s.points1, s.points2, K, mask=selected)
        self.assertValidMask(mask2, n)
        self.assertTrue(np.all(mask2 <= s.inlierMask))
        self.assertGreater(retval2, 0.9 * s.inlierMask.sum())
        np.testing.assert_allclose(R2, s.R, atol=1e-6)
        # focal length and principal point
        focal, pp = float(K[0, 0]), (float(K[0, 2]), float(K[1, 2]))
        retval3, R3, t3, mask3 = b.recoverPose(s.E, s.points1, s.points2, focal=focal, pp=pp)
        self.assertEqual(retval3, retval)
        np.testing.assert_allclose(R3, R, atol=1e-9)
        np.testing.assert_allclose(t3, t, atol=1e-9)

    def test_estimate_relative_motion(self):
        b = self.b
        s = self.make_scene(numPoints=500, seed=20)
        n = len(s.points1)
        rep = b.estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, self.make_params())
        self.assertIsInstance(rep, b.Report)
        self.assertEqual(rep.status, b.STATUS_SUCCESS)
        self.assertIs(type(rep.status), int)
        self.assertEqual(rep.message, "")
        for name in ("F", "E"):
            self.assertEqual(getattr(rep, name).shape, (3, 3), name)
        self.assertRotation(rep.R)
        self.assertUnitTranslation(rep.t)
        self.assertValidMask(rep.mask, n)
        self.assertEqual(rep.inlierCount, int(rep.mask.sum()))
        self.assertGreaterEqual(rep.iterations, 1)
        # Standard's count stops once a hypothesis cannot beat the best one
        self.assertLessEqual(rep.pointsPerHypothesis, n)
        self.assertGreater(rep.pointsPerHypothesis, 0.1 * n)
        self.assertGreaterEqual(rep.timeSeconds, 0.0)
        self.assertTrue(np.isnan(rep.meanEntropy))  # only RCME computes it
        for name in ("rejectedF", "rejectedR", "rejectedT"):  # only without success
            self.assertIsNone(getattr(rep, name), name)
        if rep.covariance is not None:
            self.assertEqual(rep.covariance.shape, (5, 5))
        self.assertLess(b.compareMotion(rep.R, rep.t, s.R, s.t).rotationDeg, 1.0)
        # uncalibrated: F only, the calibrated outputs are empty (None)
        rep2 = b.estimateRelativeMotion(s.points1, s.points2, None, self.make_params())
        self.assertEqual(rep2.status, b.STATUS_SUCCESS)
        self.assertEqual(rep2.F.shape, (3, 3))
        for name in ("E", "R", "t"):
            self.assertIsNone(getattr(rep2, name), name)
        self.assertValidMask(rep2.mask, n)
        # params is optional
        rep3 = b.estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix)
        self.assertValidMask(rep3.mask, n)

    def test_uncertainty_fields(self):
        b = self.b
        s = self.make_scene(numPoints=400, seed=21, sigma=0.5)
        rep = b.estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, self.make_params())
        self.assertEqual(rep.status, b.STATUS_SUCCESS)
        self.assertIs(type(rep.noiseSigma), float)
        self.assertAlmostEqual(rep.noiseSigma, 0.5, delta=0.05)
        C = rep.covariance
        np.testing.assert_allclose(np.asarray(rep.rotationStdDeg).ravel(),
                                   np.degrees(np.sqrt(np.diag(C)[:3])), rtol=1e-12)
        self.assertAlmostEqual(rep.translationStdDeg,
                               np.degrees(np.sqrt(np.linalg.eigvalsh(C[3:, 3:]).max())))
        # the 6x6 pose covariance: [rotation, translation], singular along the scale R^T t
        pose = b.poseCovariance(rep.R, rep.t, C)
        self.assertEqual(pose.shape, (6, 6))
        np.testing.assert_allclose(pose[:3, :3], C[:3, :3], rtol=1e-12)
        u = np.r_[np.zeros(3), rep.R.T @ rep.t.ravel()]
        self.assertLess(np.linalg.norm(pose @ u), 1e-12)
        np.testing.assert_allclose(b.poseCovariance(rep.R, rep.t, C, 0.1) @ u, 0.01 * u,
                                   atol=1e-12)
        # the inverse pose's rotation block is R C_rr R^T
        inverse = b.poseCovariance(rep.R, rep.t, C, 0.1, True)
        np.testing.assert_allclose(inverse[:3, :3], rep.R @ C[:3, :3] @ rep.R.T, rtol=1e-9,
                                   atol=1e-15)
        # the stated sigma (1 px, twice the noise) gives a wider covariance of the same motion
        stated = b.estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix,
                                          self.make_params(useEstimatedNoise=False))
        np.testing.assert_allclose(stated.R, rep.R, atol=1e-12)
        self.assertGreater(np.trace(stated.covariance), 2 * np.trace(C))
        # uncalibrated: the noise estimate, no motion uncertainty
        rep2 = b.estimateRelativeMotion(s.points1, s.points2, None, self.make_params())
        self.assertAlmostEqual(rep2.noiseSigma, 0.5, delta=0.05)
        self.assertTrue(np.isnan(rep2.translationStdDeg))
        # failure: NaN
        self.assertTrue(np.isnan(b.Report().noiseSigma))
        with self.assertRaises(Exception):
            b.poseCovariance(rep.R, rep.t, np.eye(6))

    def test_degenerate_scenes(self):
        b = self.b
        rng = np.random.default_rng(7)
        K = np.array([[500.0, 0, 320], [0, 500.0, 240], [0, 0, 1]])
        a = np.deg2rad(4.0)
        R = np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])

        def project(X, R, t):
            x = (K @ (R @ X.T + t.reshape(3, 1))).T
            return x[:, :2] / x[:, 2:]

        n = 300
        on_plane = np.column_stack([rng.uniform(-3, 3, n), rng.uniform(-2, 2, n), np.full(n, 8.0)])
        in_depth = np.column_stack([rng.uniform(-3, 3, n), rng.uniform(-2, 2, n),
                                    rng.uniform(4, 12, n)])
        scenes = {
            "plane": (on_plane, np.array([0.5, 0.1, 0.0])),
            "pure rotation": (in_depth, np.zeros(3)),
        }
        for name, (X, t) in scenes.items():
            p1 = project(X, np.eye(3), np.zeros(3)) + rng.normal(0, 0.5, (n, 2))
            p2 = project(X, R, t) + rng.normal(0, 0.5, (n, 2))
            for method in (b.METHOD_STANDARD, b.METHOD_RCME):
                params = self.make_params(method=method)
                # without K, F is not determined: degenerate
                F, mask, status = b.findFundamentalMat(p1, p2, params)
                self.assertEqual(status, b.STATUS_DEGENERATE_CONFIGURATION, name)
                self.assertIsNone(F, name)
                rep = b.estimateRelativeMotion(p1, p2, None, params)
                self.assertEqual(rep.status, b.STATUS_DEGENERATE_CONFIGURATION, name)
                self.assertIn("homography", rep.message, name)
                self.assertValidMask(rep.mask, n)
                self.assertEqual(int(rep.mask.sum()), 0, name)
                # rejected, for diagnostics: the F the degeneracy test turned down
                self.assertEqual(rep.rejectedF.shape, (3, 3), name)
                self.assertIsNone(rep.rejectedR, name)
                # with K: a plane gives its motion, a pure rotation its rotation
                rep = b.estimateRelativeMotion(p1, p2, K, params)
                self.assertValidMask(rep.mask, n)
                self.assertRotation(rep.R)
                # a frontal plane trades rotation against translation a little (0.76 deg here)
                self.assertLess(b.compareMotion(rep.R, np.array([[1.0], [0], [0]]), R,
                                                np.array([[1.0], [0], [0]])).rotationDeg,
                                2.0 if name == "plane" else 0.5)
                if name == "plane":
                    self.assertEqual(rep.status, b.STATUS_SUCCESS, name)
                    # a frontal plane, 0.5 baselines at depth 8, determines t loosely: the
                    # reported covariance gives it 4.6 deg; measured error 11 deg (85 deg when
                    # the motion is not taken from the homography: degeneracyTest=False)
                    self.assertLess(b.compareMotion(rep.R, rep.t, R, t.reshape(3, 1))
                                    .translationDeg, 15.0)
                else:
                    self.assertEqual(rep.status, b.STATUS_PURE_ROTATION, name)
                    np.testing.assert_array_equal(rep.t, np.zeros((3, 1)))
                    self.assertIsNone(rep.E, name)
                    self.assertEqual(rep.covariance.shape, (3, 3))
                    self.assertRotation(rep.rejectedR)  # the motion it turned down
            # switched off (with the ambiguity and uncertainty tests, which flag these scenes
            # too), the same input gives a (non-unique) model
            rep = b.estimateRelativeMotion(p1, p2, K, self.make_params(
                degeneracyTest=False, ambiguityMargin=0.0, maxRotationStdDeg=0.0,
                maxTranslationStdDeg=0.0))
            self.assertEqual(rep.status, b.STATUS_SUCCESS, name)
        # a scene with depth and translation is not flagged
        p1 = project(in_depth, np.eye(3), np.zeros(3)) + rng.normal(0, 0.5, (n, 2))
        p2 = project(in_depth, R, np.array([0.5, 0.1, 0.0])) + rng.normal(0, 0.5, (n, 2))
        rep = b.estimateRelativeMotion(p1, p2, K, self.make_params())
        self.assertEqual(rep.status, b.STATUS_SUCCESS)

    def test_compare_motion(self):
        b = self.b
        R = np.eye(3)
        t = np.array([[1.0], [0.0], [0.0]])
        e = b.compareMotion(R, t, R, t)
        self.assertIsInstance(e, b.MotionError)
        for name in ("dq", "dt", "rotationDeg", "translationDeg"):
            self.assertAlmostEqual(getattr(e, name), 0.0, places=9)
        c, s_ = np.cos(np.radians(10)), np.sin(np.radians(10))
        Rz = np.array([[c, -s_, 0], [s_, c, 0], [0, 0, 1]])
        e = b.compareMotion(Rz, np.array([0.0, 2.0, 0.0]), R, t)
        self.assertAlmostEqual(e.rotationDeg, 10.0, places=6)
        self.assertAlmostEqual(e.translationDeg, 90.0, places=6)
        self.assertRaisesNaming(["R"], b.compareMotion, np.eye(2), t, R, t)
        self.assertRaisesNaming(["tgt"], b.compareMotion, R, t, R, np.array([np.nan, 0, 0]))

    def test_status_to_string(self):
        b = self.b
        statuses = [b.STATUS_SUCCESS, b.STATUS_POOR_QUALITY_INPUT, b.STATUS_NOT_ENOUGH_POINTS,
                    b.STATUS_DEGENERATE_CONFIGURATION, b.STATUS_PURE_ROTATION]
        names = [b.statusToString(st) for st in statuses]
        for name in names:
            self.assertIsInstance(name, str)
            self.assertTrue(name)
        self.assertEqual(len(set(names)), len(names))
        self.assertIn("success", names[0])
        self.assertEqual(names[1], "poor quality input")

    def test_method_names(self):
        b = self.b
        _, constants, _ = _public_header_names()
        methods = [v for k, v in constants.items() if k.startswith("METHOD_")]
        names = [b.methodName(m) for m in methods]
        self.assertEqual(len(set(names)), len(methods))
        for method, name in zip(methods, names):
            self.assertIsInstance(name, str)
            self.assertEqual(b.methodFromString(name), method, name)
            self.assertEqual(b.methodFromString(name.upper()), method, name)
        self.assertEqual(b.methodFromString("cov-ransac"), b.METHOD_COV_RANSAC)
        self.assertRaisesNaming(["name", "standard"], b.methodFromString, "ransac")

    # --- input layouts and robustness

    def test_point_layouts(self):
        b = self.b
        s = self.make_scene(seed=21)
        n = len(s.points1)
        p = self.make_params()
        F, mask, status = b.findFundamentalMat(s.points1, s.points2, p)
        self.assertEqual(status, b.STATUS_SUCCESS)
        for shape in ((n, 1, 2), (1, n, 2)):
            F2, mask2, status2 = b.findFundamentalMat(s.points1.reshape(shape),
                                                      s.points2.reshape(shape), p)
            self.assertEqual(status2, b.STATUS_SUCCESS, shape)
            np.testing.assert_array_equal(F2, F)
            np.testing.assert_array_equal(mask2, mask)
        # non-contiguous views give the same result as contiguous arrays
        both = np.hstack([s.points1, s.points2])
        F3, mask3, _ = b.findFundamentalMat(both[:, :2], both[:, 2:], p)
        np.testing.assert_array_equal(F3, F)
        F4, mask4, status4 = b.findFundamentalMat(s.points1.astype(np.float32),
                                                  s.points2.astype(np.float32), p)
        self.assertEqual(status4, b.STATUS_SUCCESS)
        self.assertValidMask(mask4, n)
        self.assertGreater(_mask_quality(mask4, s.inlierMask)[0],
                           _mask_quality(mask, s.inlierMask)[0] - 0.1)

    def test_same_seed_same_result(self):
        b = self.b
        s = self.make_scene(seed=22)
        p = self.make_params(randomGeneratorState=1234)
        F1, mask1, _ = b.findFundamentalMat(s.points1, s.points2, p)
        F2, mask2, _ = b.findFundamentalMat(s.points1, s.points2, p)
        np.testing.assert_array_equal(F1, F2)
        np.testing.assert_array_equal(mask1, mask2)
        r1 = b.recoverPose(s.points1, s.points2, s.cameraMatrix, p)
        r2 = b.recoverPose(s.points1, s.points2, s.cameraMatrix, p)
        self.assertEqual(r1[0], r2[0])
        np.testing.assert_array_equal(r1[2], r2[2])
        np.testing.assert_array_equal(r1[4], r2[4])

    def test_parallel_same_result_whatever_the_thread_count(self):
        # Params.isParallel spreads hypotheses over cv2's threads; every method must give the
        # result of a sequential run, bit for bit, with 1, 2 or 3 threads
        try:
            import cv2
        except ImportError:  # a venv with the pip-installed rcme and no cv2
            self.skipTest("cv2 is needed to set OpenCV's thread count")
        b = self.b
        s = self.make_scene(seed=24)
        previous = cv2.getNumThreads()
        try:
            for method in (b.METHOD_STANDARD, b.METHOD_RCME, b.METHOD_PRCME, b.METHOD_MLESAC,
                           b.METHOD_COV_RANSAC):
                p = self.make_params(method=method, randomGeneratorState=5, maxIterations=300)
                reference = b.estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, p)
                p.isParallel = True
                for threads in (1, 2, 3):
                    cv2.setNumThreads(threads)
                    r = b.estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, p)
                    self.assertEqual(r.status, reference.status, (method, threads))
                    self.assertEqual(r.iterations, reference.iterations, (method, threads))
                    np.testing.assert_array_equal(r.mask, reference.mask)
                    if reference.status == b.STATUS_SUCCESS:
                        np.testing.assert_array_equal(r.F, reference.F)
                        np.testing.assert_array_equal(r.R, reference.R)
        finally:
            cv2.setNumThreads(previous)

    def test_all_outliers(self):
        b = self.b
        s = self.make_scene(inlierRatio=0.0, seed=23)
        n = len(s.points1)
        F, mask, status = b.findFundamentalMat(s.points1, s.points2, self.make_params())
        self.assertValidMask(mask, n)
        if status != b.STATUS_SUCCESS:
            self.assertIsNone(F)
            self.assertEqual(int(mask.sum()), 0)
        rep = b.estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, self.make_params())
        self.assertValidMask(rep.mask, n)
        if rep.status != b.STATUS_SUCCESS:
            self.assertTrue(rep.message)
            for name in ("F", "E", "R", "t"):
                self.assertIsNone(getattr(rep, name), name)

    def test_too_few_points(self):
        b = self.b
        s = self.make_scene(seed=24)
        p1, p2 = s.points1[:5], s.points2[:5]
        try:
            F, mask, status = b.findFundamentalMat(p1, p2, self.make_params())
        except self.error as e:
            self.assertIn("points", str(e))
        else:
            self.assertEqual(status, b.STATUS_NOT_ENOUGH_POINTS)
            self.assertIsNone(F)
            self.assertValidMask(mask, 5)
            self.assertEqual(int(mask.sum()), 0)

    def test_bad_inputs_raise(self):
        b = self.b
        s = self.make_scene(seed=25)
        p1, p2, K = s.points1, s.points2, s.cameraMatrix
        p = self.make_params()
        self.assertRaisesNaming(["points1", "points2"], b.findFundamentalMat, p1, p2[:-1], p)
        bad = p1.copy()
        bad[3, 1] = np.nan
        self.assertRaisesNaming(["points1"], b.findFundamentalMat, bad, p2, p)
        bad = p2.copy()
        bad[4, 0] = np.inf
        self.assertRaisesNaming(["points2"], b.estimateRelativeMotion, p1, bad, K, p)
        self.assertRaisesNaming(["points1"], b.findFundamentalMat, np.hstack([p1, p1]), p2, p)
        self.assertRaisesNaming(["points1"], b.findFundamentalMat, p1[:0], p2[:0], p)
        self.assertRaisesNaming(["cameraMatrix"], b.findEssentialMat, p1, p2, np.eye(2), p)
        self.assertRaisesNaming(["cameraMatrix"], b.recoverPose, p1, p2, np.eye(4), p)
        self.assertRaisesNaming(["cameraMatrix"], b.estimateRelativeMotion, p1, p2,
                                np.ones((3, 2)), p)
        badK = K.copy()
        badK[0, 0] = np.nan
        self.assertRaisesNaming(["cameraMatrix"], b.findEssentialMat, p1, p2, badK, p)
        with self.assertRaises((self.error, TypeError)):
            b.findFundamentalMat("not points", p2, p)
        with self.assertRaises((self.error, TypeError)):
            b.findFundamentalMat(p1, p2, "not a method")  # no overload takes a string
        self.assertRaisesNaming(["method"], b.findFundamentalMat, p1, p2, UNKNOWN_METHOD)
        sp = b.SceneParams()
        sp.inlierRatio = 2.0
        self.assertRaisesNaming(["inlierRatio"], b.generateScene, sp)

    def test_error_type(self):
        self.assertTrue(issubclass(self.error, Exception))
        try:
            self.b.findFundamentalMat(np.zeros((10, 2)), np.zeros((9, 2)), self.make_params())
        except self.error as e:
            self.assertIsInstance(e.code, int)
            self.assertNotEqual(e.code, 0)
        else:
            self.fail("no error raised")

    def test_unimplemented_methods_raise_or_report(self):
        # Only METHOD_STANDARD is required in this milestone: the others either raise the
        # binding's error (not implemented) or run and report a status.
        b = self.b
        s = self.make_scene(seed=26)
        for method in (b.METHOD_RCME, b.METHOD_PRCME, b.METHOD_MLESAC, b.METHOD_COV_RANSAC):
            try:
                F, mask, status = b.findFundamentalMat(s.points1, s.points2,
                                                       self.make_params(method=method))
            except self.error:
                continue
            self.assertIn(status, (b.STATUS_SUCCESS, b.STATUS_POOR_QUALITY_INPUT,
                                   b.STATUS_NOT_ENOUGH_POINTS,
                                   b.STATUS_DEGENERATE_CONFIGURATION))
            self.assertValidMask(mask, len(s.points1))

    def test_concurrent_calls(self):
        # the bindings release the GIL; concurrent calls must give the serial results
        b = self.b
        scenes = [self.make_scene(seed=30 + i) for i in range(4)]
        p = self.make_params()
        serial = [b.findFundamentalMat(s.points1, s.points2, p) for s in scenes]
        results = [None] * len(scenes)

        def work(i):
            results[i] = b.findFundamentalMat(scenes[i].points1, scenes[i].points2, p)

        threads = [threading.Thread(target=work, args=(i,)) for i in range(len(scenes))]
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        for (F1, m1, s1), (F2, m2, s2) in zip(serial, results):
            np.testing.assert_array_equal(F1, F2)
            np.testing.assert_array_equal(m1, m2)
            self.assertEqual(s1, s2)


    def test_opencv_forms_have_cv2s_signatures_and_results(self):
        """Every OpenCV form that cv2 wraps, called as cv2 calls it: same arity of the result,
        masks of cv2's shape and dtype, an empty E -> a standing camera (cv2 raises there)."""
        try:
            import cv2
        except ImportError:
            self.skipTest("no cv2 to compare with")
        s = self.make_scene(numPoints=60, inlierRatio=1.0)
        p1, p2, K = s.points1, s.points2, s.cameraMatrix
        d = np.array([0.01, -0.001, 0.0, 0.0, 0.0])
        focal, pp = float(K[0, 0]), (float(K[0, 2]), float(K[1, 2]))
        E_true = s.E
        calls = {
            "F 6 args": lambda m: m.findFundamentalMat(p1, p2, cv2.FM_RANSAC, 3.0, 0.99, 1000),
            "F defaults": lambda m: m.findFundamentalMat(p1, p2),
            "F method only": lambda m: m.findFundamentalMat(p1, p2, cv2.FM_LMEDS),
            "F usac": lambda m: m.findFundamentalMat(p1, p2, cv2.UsacParams()),
            "E K": lambda m: m.findEssentialMat(p1, p2, K),
            "E K keywords": lambda m: m.findEssentialMat(p1, p2, K, method=cv2.RANSAC, prob=0.999,
                                                         threshold=1.0, maxIters=500),
            "E focal": lambda m: m.findEssentialMat(p1, p2, focal, pp, cv2.RANSAC, 0.999, 1.0),
            "E two cameras": lambda m: m.findEssentialMat(p1, p2, K, d, K, d),
            "E two cameras usac": lambda m: m.findEssentialMat(p1, p2, K, K, d, d,
                                                               cv2.UsacParams()),
            "R two cameras": lambda m: m.recoverPose(p1, p2, K, d, K, d),
            "R from E": lambda m: m.recoverPose(E_true, p1, p2, K),
            "R from E focal": lambda m: m.recoverPose(E_true, p1, p2, focal=focal, pp=pp),
            "R distanceThresh": lambda m: m.recoverPose(E_true, p1, p2, K, distanceThresh=50.0),
        }
        for name, call in calls.items():
            with self.subTest(form=name):
                expected, got = call(cv2), call(self.b)
                self.assertEqual(len(got), len(expected))
                for a, b in zip(expected, got):
                    if isinstance(a, np.ndarray) and a.dtype == np.uint8:  # the mask
                        self.assertEqual(b.shape, a.shape)
                        self.assertEqual(b.dtype, a.dtype)
        retval, R, t, mask = self.b.recoverPose(None, p1, p2, K)
        self.assertEqual(retval, 0)
        np.testing.assert_array_equal(R, np.eye(3))
        np.testing.assert_array_equal(t, np.zeros((3, 1)))
        self.assertEqual(int(mask.sum()), 0)
        with self.assertRaises(cv2.error):
            cv2.recoverPose(np.zeros((0, 0)), p1, p2, K)

    def test_wrong_field_type_names_the_field(self):
        p = self.b.Params()
        with self.assertRaises((TypeError, self.error)) as ctx:  # what cv2's generator raises
            p.sigma = "x"
        if self.binding_key == "standalone":  # cv2's generator has its own message
            self.assertIn("Params.sigma", str(ctx.exception))
            self.assertLess(len(str(ctx.exception)), 200)

    def test_time_budget_returns_the_best_so_far(self):
        s = self.make_scene(numPoints=200, inlierRatio=0.8)
        p = self.make_params(maxIterations=10000000, exactIterations=True, timeBudget=0.05)
        r = self.b.estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, p)
        self.assertLess(r.iterations, 10000000)
        self.assertEqual(r.status, self.b.STATUS_SUCCESS)

    def assertRunsWithoutTheGil(self, call):
        """call() (one estimation, long enough) runs on a thread while this one keeps running
        Python: with the GIL held for the whole call this thread would stall for all of it."""
        duration = []
        done = threading.Event()

        def work():
            start = time.perf_counter()
            call()
            duration.append(time.perf_counter() - start)
            done.set()

        worker = threading.Thread(target=work)
        last = time.perf_counter()
        longest_stall = 0.0
        worker.start()
        while not done.is_set():
            now = time.perf_counter()
            longest_stall = max(longest_stall, now - last)
            last = now
        worker.join()
        self.assertGreater(duration[0], 0.05, "the call is too short to tell")
        self.assertLess(longest_stall, duration[0] / 2,
                        "this thread stalled %.3f s of a %.3f s call: the GIL was held"
                        % (longest_stall, duration[0]))

    def test_the_gil_is_released_during_an_estimation(self):
        b = self.b
        s = self.make_scene(numPoints=1000, seed=41)
        # About 0.15 s: long enough to tell a stall from scheduling noise on a slow machine.
        p = self.make_params(maxIterations=20000, exactIterations=True)
        self.assertRunsWithoutTheGil(
            lambda: b.estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, p))


class TestStandaloneRcme(_RcmeSuite, unittest.TestCase):
    """The pybind11 module `rcme`."""

    loader = staticmethod(_load_standalone)
    binding_name = "rcme (standalone)"
    binding_key = "standalone"

    # --- conveniences of the standalone module that cv2.rcme does not have

    def test_every_field_is_documented_from_the_header(self):
        """Each attribute's docstring is its header comment (doxygen markup dropped) and the
        value of a default-constructed object; keyword construction and pickling carry every
        field of the header's Params."""
        b = self.b
        enums, structs, _ = _header_tables()
        for struct in ("Params", "Report", "SceneParams", "SyntheticScene", "MotionError"):
            instance = getattr(b, struct)()
            for field in structs[struct]:
                doc = vars(getattr(b, struct))[field.name].__doc__ or ""
                words = field.doc.split()[:2]
                self.assertTrue(doc.startswith(" ".join(w.lstrip("#") for w in words)),
                                "%s.%s: %r" % (struct, field.name, doc))
                if field.type not in enums:  # an enum ends with its constant's name
                    default = getattr(instance, field.name)
                    self.assertTrue(doc.endswith("default %r" % (default,)),
                                    "%s.%s: %r" % (struct, field.name, doc))
        self.assertTrue(vars(b.Params)["method"].__doc__.endswith("; default METHOD_STANDARD"))
        self.assertIn("one of METHOD_RCME, METHOD_PRCME", vars(b.Params)["method"].__doc__)
        p = b.Params()
        values = {f.name: getattr(p, f.name) for f in structs["Params"]}
        values.update(sigma=0.5, method=b.METHOD_RCME, matchQuality=np.arange(3.0))
        q = b.Params(**values)
        self.assertEqual(repr(pickle.loads(pickle.dumps(q))), repr(q))
        self.assertIn("sigma=0.5", repr(q))

    def test_keyword_construction(self):
        b = self.b
        p = b.Params(method=b.METHOD_STANDARD, sigma=0.5, maxIterations=77, refine=False)
        self.assertEqual((p.method, p.sigma, p.maxIterations, p.refine),
                         (b.METHOD_STANDARD, 0.5, 77, False))
        self.assertEqual(p.confidence, b.Params().confidence)
        sp = b.SceneParams(kind=b.SCENE_GENERIC, numPoints=50, seed=3)
        self.assertEqual((sp.kind, sp.numPoints, sp.seed), (b.SCENE_GENERIC, 50, 3))
        with self.assertRaises(TypeError):
            b.Params(noSuchField=1)
        with self.assertRaises(TypeError):
            b.SceneParams(noSuchField=1)
        self.assertIn("maxIterations=77", repr(p))

    def test_python_sequences_and_integer_points(self):
        b = self.b
        s = self.make_scene(seed=27)
        p = self.make_params()
        F, mask, status = b.findFundamentalMat(s.points1, s.points2, p)
        F2, mask2, status2 = b.findFundamentalMat(s.points1.tolist(),
                                                  [tuple(q) for q in s.points2], p)
        np.testing.assert_array_equal(F2, F)
        np.testing.assert_array_equal(mask2, mask)
        r = b.findFundamentalMat(np.round(s.points1).astype(np.int32),
                                 np.round(s.points2).astype(np.int64), p)
        self.assertEqual(r[2], b.STATUS_SUCCESS)

    def test_error_attributes(self):
        b = self.b
        with self.assertRaises(b.error) as ctx:
            b.findFundamentalMat(np.zeros((10, 2)), np.zeros((9, 2)), self.make_params())
        e = ctx.exception
        for name in ("code", "err", "func", "file", "line"):
            self.assertTrue(hasattr(e, name), name)
        self.assertIn(e.err, str(e))
        self.assertEqual(b.error.__module__, "rcme")

    def test_docstrings_carry_cv2_signatures(self):
        b = self.b
        doc = b.findFundamentalMat.__doc__
        self.assertIn("findFundamentalMat(points1, points2, params[, mask]) -> retval, mask, "
                      "status", doc)
        self.assertIn("recoverPose(points1, points2, cameraMatrix, params[, E[, R[, t[, mask"
                      "[, covariance]]]]]) -> retval, E, R, t, mask, status, covariance",
                      b.recoverPose.__doc__)


    # --- many pairs at once (estimateRelativeMotionBatch), pickling, the type stub

    def assertSameReport(self, a, b):
        """Every field equal (NaN equal to NaN), timeSeconds aside."""
        state_a, state_b = a.__getstate__(), b.__getstate__()
        self.assertEqual(sorted(state_a), sorted(state_b))
        for name in state_a:
            if name == "timeSeconds":
                continue
            x, y = state_a[name], state_b[name]
            if isinstance(x, np.ndarray) or isinstance(y, np.ndarray):
                np.testing.assert_array_equal(x, y, err_msg=name)
            elif isinstance(x, float) and np.isnan(x):
                self.assertTrue(np.isnan(y), name)
            else:
                self.assertEqual(x, y, name)

    def test_batch_gives_the_serial_reports(self):
        b = self.b
        scenes = [self.make_scene(seed=60 + i, numPoints=150,
                                  kind=b.SCENE_GENERIC if i % 2 else b.SCENE_CORRIDOR)
                  for i in range(7)]
        pairs = [(s.points1, s.points2) for s in scenes]
        p = self.make_params(method=b.METHOD_RCME, maxIterations=200)
        cameras = [None if i % 3 == 1 else s.cameraMatrix for i, s in enumerate(scenes)]
        serial = [b.estimateRelativeMotion(s.points1, s.points2, k, p)
                  for s, k in zip(scenes, cameras)]
        for threads in (1, 2, 0):
            batch = b.estimateRelativeMotionBatch(pairs, cameras, p, threads=threads)
            self.assertEqual(len(batch), len(serial))
            for got, want in zip(batch, serial):
                self.assertSameReport(got, want)
        # one shared camera matrix, a generator of pairs, the default Params, and no K
        k = scenes[0].cameraMatrix
        shared = b.estimateRelativeMotionBatch(((s.points1, s.points2) for s in scenes), k)
        for got, s in zip(shared, scenes):
            self.assertSameReport(got, b.estimateRelativeMotion(s.points1, s.points2, k))
        uncalibrated = b.estimateRelativeMotionBatch(pairs, None, p, 2)
        self.assertSameReport(uncalibrated[3], b.estimateRelativeMotion(*pairs[3], None, p))
        self.assertEqual(b.estimateRelativeMotionBatch([], None), [])

    def test_batch_bad_inputs_name_the_argument(self):
        b = self.b
        s = self.make_scene(seed=70, numPoints=100)
        good = (s.points1, s.points2)
        with self.assertRaisesRegex(self.error, r"pairs\[1\] must be a pair"):
            b.estimateRelativeMotionBatch([good, s.points1], None)
        with self.assertRaisesRegex(self.error, r"pairs\[0\]\[1\]"):
            b.estimateRelativeMotionBatch([(s.points1, "text")], None)
        with self.assertRaisesRegex(self.error, "cameraMatrix is a list of 1"):
            b.estimateRelativeMotionBatch([good, good], [s.cameraMatrix])
        with self.assertRaisesRegex(self.error, "pair 1: "):
            b.estimateRelativeMotionBatch([good, (s.points1, s.points2[:50])], s.cameraMatrix)

    def test_the_gil_is_released_during_a_batch(self):
        b = self.b
        scenes = [self.make_scene(numPoints=1000, seed=80 + i) for i in range(3)]
        p = self.make_params(maxIterations=2000, exactIterations=True)
        self.assertRunsWithoutTheGil(lambda: b.estimateRelativeMotionBatch(
            [(s.points1, s.points2) for s in scenes], scenes[0].cameraMatrix, p, threads=1))

    def test_pickle_round_trip(self):
        b = self.b
        p = b.Params(method=b.METHOD_RCME, sigma=0.7, matchQuality=np.arange(5.0))
        q = pickle.loads(pickle.dumps(p))
        self.assertIs(type(q), b.Params)
        self.assertEqual(repr(q), repr(p))
        s = self.make_scene(seed=71)
        r = b.estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, self.make_params())
        self.assertSameReport(pickle.loads(pickle.dumps(r)), r)
        for value in (s, b.SceneParams(numPoints=9), b.compareMotion(s.R, s.t, s.R, s.t)):
            self.assertEqual(repr(pickle.loads(pickle.dumps(value))), repr(value))

    def test_package_ships_a_type_stub(self):
        import ast
        b = self.b
        folder = os.path.dirname(b.__file__)
        self.assertTrue(os.path.isfile(os.path.join(folder, "py.typed")))
        with open(os.path.join(folder, "__init__.pyi")) as f:
            tree = ast.parse(f.read())
        declared = {node.name for node in tree.body
                    if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
        declared |= {node.target.id for node in tree.body if isinstance(node, ast.AnnAssign)}
        public = {n for n in dir(b) if not n.startswith("_") and n not in ("annotations",)}
        self.assertEqual(public - declared, set())
        classes = {node.name: node for node in tree.body if isinstance(node, ast.ClassDef)}
        fields = {node.target.id for node in classes["Params"].body
                  if isinstance(node, ast.AnnAssign)}
        self.assertEqual(fields, set(b.Params().__getstate__()))


class TestCv2Rcme(_RcmeSuite, _Cv2TestCase):
    """cv2.rcme from an OpenCV build with the module (absent from Debian's python3-opencv).

    A NewOpenCVTests under OpenCV's runner (its setUp seeds cv2's RNG; the tests do not depend
    on that), a plain unittest.TestCase otherwise.
    """

    loader = staticmethod(_load_cv2)
    binding_name = "cv2.rcme"
    binding_key = "cv2"

    def test_root_alias(self):
        import cv2
        self.assertIs(cv2.rcme_Params, cv2.rcme.Params)


class TestBindingsAvailable(unittest.TestCase):
    def test_a_binding_is_importable(self):
        self.assertTrue(_load_standalone() is not None or _load_cv2() is not None,
                        "neither the standalone module `rcme` nor cv2.rcme can be imported")


if __name__ == "__main__":
    if _Cv2TestCase is not unittest.TestCase:
        _Cv2TestCase.bootstrap()  # NewOpenCVTests.bootstrap: --repo, OPENCV_TEST_DATA_PATH
    else:
        unittest.main()
