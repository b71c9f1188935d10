"""Type-checked by run_pip_test.sh with mypy against the installed stub (rcme/__init__.pyi):
the calls below must check clean, and the last line's misspelt field must be the one error."""

import rcme

p = rcme.Params(sigma=0.5, method=rcme.METHOD_RCME)
p.maxIterations = 200
s = rcme.generateScene(rcme.SceneParams(numPoints=100))
F, mask, status = rcme.findFundamentalMat(s.points1, s.points2, p)
report: rcme.Report = rcme.estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, p)
reports = rcme.estimateRelativeMotionBatch([(s.points1, s.points2)], s.cameraMatrix, p, threads=2)
inliers: int = reports[0].inlierCount
retval, E, R, t, mask, status, covariance = rcme.recoverPose(s.points1, s.points2,
                                                            s.cameraMatrix, p)
error: rcme.MotionError = rcme.compareMotion(R, t, s.R, s.t)
p.sigmaa = 3.0  # misspelt on purpose
