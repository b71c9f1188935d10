"""pip's cv2 (opencv-python-headless) and the pip-installed rcme in one process.

The two link different OpenCV builds: rcme Debian's shared libopencv_*.so.406, pip's cv2 a
static copy inside cv2.abi3.so that exports no OpenCV symbol (so nothing clashes). Arrays pass
between them as NumPy arrays. Each import order runs in a process of its own, since only the
first import of a process decides what is loaded. Run by run_pip_test.sh in its venv.
"""

import os
import subprocess
import sys
import unittest

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "samples", "data")

# SIFT matches from pip's cv2 -> rcme's motion -> pip's cv2 again (Rodrigues, recoverPose), and
# pip's arrays (a cv2 mask, cv2.UsacParams) into rcme.
SCRIPT = r"""
import sys, numpy as np
IMPORTS
data = sys.argv[1]
maps = open("/proc/self/maps").read()
assert "libopencv_core.so.4.6" in maps, "rcme's OpenCV (Debian's 4.6) is not loaded"
assert "site-packages/cv2" in cv2.__file__, cv2.__file__
img1 = cv2.imread(data + "/fountain_0004.jpg", cv2.IMREAD_GRAYSCALE)
img2 = cv2.imread(data + "/fountain_0006.jpg", cv2.IMREAD_GRAYSCALE)
sift = cv2.SIFT_create(2000)
k1, d1 = sift.detectAndCompute(img1, None)
k2, d2 = sift.detectAndCompute(img2, None)
good = [a for a, b in cv2.BFMatcher().knnMatch(d1, d2, k=2) if a.distance < 0.8 * b.distance]
p1 = np.float64([k1[m.queryIdx].pt for m in good])
p2 = np.float64([k2[m.trainIdx].pt for m in good])
K = np.loadtxt(data + "/K.txt").reshape(3, 3)
gt = np.loadtxt(data + "/pose_gt.txt").ravel()
R_gt = gt[:9].reshape(3, 3)

report = rcme.estimateRelativeMotion(p1, p2, K, rcme.Params(sigma=1.0, randomGeneratorState=1))
assert report.status == rcme.STATUS_SUCCESS, rcme.statusToString(report.status)
rvec, _ = cv2.Rodrigues(report.R @ R_gt.T)  # rcme's array into pip's cv2
error_deg = np.degrees(np.linalg.norm(rvec))
assert error_deg < 1.0, error_deg

E, mask = cv2.findEssentialMat(p1, p2, K, cv2.RANSAC, 0.999, 1.0)
inliers, R, t, mask_rcme = rcme.recoverPose(E[:3], p1, p2, K, mask=mask)  # pip's arrays into rcme
_, R_cv2, t_cv2, _ = cv2.recoverPose(E[:3], p1, p2, K, mask=mask.copy())
assert np.allclose(R, R_cv2, atol=1e-6) and np.allclose(t, t_cv2, atol=1e-6)
usac = cv2.UsacParams()
usac.maxIterations = 123
assert rcme.Params.fromUsacParams(usac).maxIterations == 123
print("cv2 %s with rcme: %d matches, rotation error %.3f deg" % (cv2.__version__, len(good),
                                                                 error_deg))
"""


class Cv2Coexistence(unittest.TestCase):
    def run_order(self, imports):
        script = SCRIPT.replace("IMPORTS", imports)
        result = subprocess.run([sys.executable, "-c", script, DATA], capture_output=True,
                                text=True, timeout=120)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        print(imports, "->", result.stdout.strip())

    def test_cv2_first(self):
        self.run_order("import cv2, rcme")

    def test_rcme_first(self):
        self.run_order("import rcme, cv2")


if __name__ == "__main__":
    unittest.main()
