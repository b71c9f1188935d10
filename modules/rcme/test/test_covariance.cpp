// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The motion's uncertainty: the covariance of the whole estimator against Monte Carlo, the noise
// estimated from the residuals, and the 6x6 pose covariance against finite differences. Its
// calibration over many scenes (NEES) is measured by samples/benchmark/covariance_calibration.py.

#include "test_precomp.hpp"

#include <numeric>

namespace opencv_test {
namespace {

Matx33d rotationFromVector(const Vec3d& omega)
{
    Matx33d R;
    Rodrigues(omega, R);
    return R;
}

// The inverse of rotationFromVector, accurate for tiny angles too (cv::Rodrigues rounds rotations
// below ~1e-5 rad to zero, too coarse for finite differences).
Vec3d rotationVector(const Matx33d& R)
{
    const Vec3d w(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1)); // 2 sin(angle) axis
    const double s = 0.5 * cv::norm(w);
    const double angle = std::atan2(s, 0.5 * (R(0, 0) + R(1, 1) + R(2, 2) - 1.0));
    return s > 1e-300 ? w * (0.5 * angle / s) : 0.5 * w;
}

// The squared length of the 5-DoF tangent error of (R, t) at the truth: |omega|^2 + |beta|^2,
// which does not depend on the basis of t's complement.
double squaredTangentError(const Matx33d& R, const Vec3d& t, const Matx33d& Rgt, const Vec3d& tgt)
{
    const Vec3d omega = rotationVector(Rgt.t() * R);
    const Vec3d tu = t / cv::norm(t), tg = tgt / cv::norm(tgt);
    const Vec3d beta = tu / tu.dot(tg) - tg;
    return omega.dot(omega) + beta.dot(beta);
}

TEST(Rcme_Covariance, matches_monte_carlo_of_the_refined_motion)
{
    // The same scene re-estimated (RANSAC, refinement, everything) from noisy copies of its
    // exact correspondences: the spread of the estimates against the reported covariance.
    const double sigma = 1.0;
    SceneParams sp = testSceneParams(SCENE_GENERIC, 3, 1.0, 0.0, 200);
    const SyntheticScene exact = generateScene(sp);
    const Matx33d Rgt(exact.R);
    const Vec3d tgt(exact.t);
    RNG rng(11);
    double errorSum = 0, traceSum = 0;
    int runs = 0;
    for (int trial = 0; trial < 200; ++trial) {
        Mat p1 = exact.points1.clone(), p2 = exact.points2.clone();
        Mat noise(p1.size(), CV_64F);
        rng.fill(noise, RNG::NORMAL, 0, sigma);
        p1 += noise;
        rng.fill(noise, RNG::NORMAL, 0, sigma);
        p2 += noise;
        Params params;
        params.sigma = sigma;
        params.randomGeneratorState = trial;
        const Report r = estimateRelativeMotion(p1, p2, exact.cameraMatrix, params);
        if (r.status != STATUS_SUCCESS)
            continue;
        ASSERT_EQ(r.covariance.size(), Size(5, 5));
        errorSum += squaredTangentError(Matx33d(r.R), Vec3d(r.t), Rgt, tgt);
        traceSum += cv::trace(r.covariance)[0];
        ++runs;
    }
    ASSERT_GT(runs, 190);
    // Measured 0.93; without the factor for the band's truncation (1.32) it would be 1.23.
    const double ratio = errorSum / traceSum;
    std::cout << "Monte Carlo mean squared error / mean covariance trace: " << ratio << std::endl;
    EXPECT_NEAR(ratio, 1.0, 0.15);
}

TEST(Rcme_Covariance, covers_noise_that_grows_with_leverage)
{
    // Real matches' noise differs from point to point. Here the points far from the image centre,
    // which determine the rotation most, are nine times noisier than the central ones: one
    // sigma for all (the model-based covariance) is over-confident, and the reported covariance,
    // raised to the residuals' sandwich (components/residual_covariance.cpp), must still cover
    // the spread of the estimates.
    SceneParams sp = testSceneParams(SCENE_GENERIC, 5, 1.0, 0.0, 300);
    const SyntheticScene exact = generateScene(sp);
    const Matx33d Rgt(exact.R), K(exact.cameraMatrix);
    const Vec3d tgt(exact.t);
    const int trials = testRuns(200, 60);
    RNG rng(17);
    double errorSum = 0, traceSum = 0;
    int runs = 0;
    for (int trial = 0; trial < trials; ++trial) {
        Mat p1 = exact.points1.clone(), p2 = exact.points2.clone();
        for (int i = 0; i < p1.rows; ++i) {
            const double dx = p1.at<double>(i, 0) - K(0, 2), dy = p1.at<double>(i, 1) - K(1, 2);
            const double sigma = std::hypot(dx, dy) > 0.6 * K(0, 2) ? 0.9 : 0.1;
            for (Mat* p : {&p1, &p2})
                for (int c = 0; c < 2; ++c)
                    p->at<double>(i, c) += rng.gaussian(sigma);
        }
        Params params;
        params.randomGeneratorState = trial;
        const Report r = estimateRelativeMotion(p1, p2, exact.cameraMatrix, params);
        if (r.status != STATUS_SUCCESS)
            continue;
        errorSum += squaredTangentError(Matx33d(r.R), Vec3d(r.t), Rgt, tgt);
        traceSum += cv::trace(r.covariance)[0];
        ++runs;
    }
    ASSERT_GT(runs, trials * 9 / 10);
    const double ratio = errorSum / traceSum;
    std::cout << "noise growing with leverage: mean squared error / mean covariance trace " << ratio
              << std::endl;
    // Measured 0.74 (the polish keeps this mixture's motion and its M-estimator's sandwich
    // covers it; 1.13 with least squares' covariance, 2.11 with least squares' scaled by the
    // loss's one variance factor, doc/covariance.md); 1.20 with the plain sandwich (no leverage
    // correction), 1.44 with the model-based covariance alone (the stage off).
    if (kChecksStatistics)
        EXPECT_LT(ratio, 1.3);
}

// The basis B = (b1, b2) of t's complement that Report::covariance uses: b1 = normalize(t x e_k),
// e_k the axis of t's smallest absolute component, b2 = t x b1.
void tangentBasis(const Vec3d& t, Vec3d& b1, Vec3d& b2)
{
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(t[k]) < std::abs(t[axis]))
            axis = k;
    Vec3d e(0, 0, 0);
    e[axis] = 1;
    b1 = cv::normalize(t.cross(e));
    b2 = t.cross(b1);
}

// The 5-DoF NEES x^T Sigma^-1 x of a reported motion, x = (omega, beta) in the tangent of
// Report::covariance (R_true = R exp([omega]x), t_true ~ t + B beta).
double motionNees(const Report& r, const Matx33d& Rgt, const Vec3d& tgt)
{
    const Matx33d R(r.R);
    const Vec3d t = Vec3d(r.t) / cv::norm(Vec3d(r.t)), tg = tgt / cv::norm(tgt);
    Vec3d b1, b2;
    tangentBasis(t, b1, b2);
    const Vec3d omega = rotationVector(R.t() * Rgt), along = tg / t.dot(tg) - t;
    const Matx<double, 5, 1> x(omega[0], omega[1], omega[2], b1.dot(along), b2.dot(along));
    const Matx<double, 5, 5> covariance(r.covariance);
    return (x.t() * covariance.inv(DECOMP_CHOLESKY) * x)(0);
}

// The default's report on a corridor with 30 % outliers at the stated true sigma, if it is a right
// answer (a gross error, a wall's plane, is a status question): false otherwise.
bool rightCorridorAnswer(int seed, double sigma, int numPoints, SyntheticScene& scene,
                         Report& report)
{
    scene = testScene(SCENE_CORRIDOR, seed, 0.7, sigma, numPoints);
    Params params;
    params.sigma = sigma;
    params.randomGeneratorState = seed;
    report = estimateRelativeMotion(scene.points1, scene.points2, scene.cameraMatrix, params);
    if (report.status != STATUS_SUCCESS)
        return false;
    const MotionError e = compareMotion(report.R, report.t, scene.R, scene.t);
    return e.rotationDeg <= 5 && e.translationDeg <= 15;
}

TEST(Rcme_Covariance, calibrated_on_a_corridor_with_outliers)
{
    // The scenes whose band outliers made the covariance over-confident.
    const int scenes = testRuns(40, 8);
    std::vector<double> nees;
    for (int seed = 0; seed < scenes; ++seed) {
        SyntheticScene s;
        Report r;
        if (!rightCorridorAnswer(seed, 1.0, 300, s, r))
            continue;
        ASSERT_EQ(r.covariance.size(), Size(5, 5));
        nees.push_back(motionNees(r, Matx33d(s.R), Vec3d(s.t)));
    }
    ASSERT_GE(nees.size(), static_cast<size_t>(scenes / 4));
    std::sort(nees.begin(), nees.end());
    const double below =
        static_cast<double>(std::lower_bound(nees.begin(), nees.end(), 11.07) - nees.begin()) /
        nees.size();
    std::cout << "corridor, 30 % outliers, " << nees.size() << " scenes: median NEES5 "
              << nees[nees.size() / 2] << ", " << 100 * below << " % below 11.07" << std::endl;
    // chi-square(5): median 4.35, 95 % below 11.07; measured 3.7 and 92 % (35 of 38), 5.2 and 82 %
    // without the leverage correction and the outliers in the band (issue 36d); earlier 5.5 and
    // 89 % (24 of 27), with the final fit on the band of the model before it 6.7 and 85 %. Before
    // the final fit dropped unconfirmed and behind-camera inliers, 35 % of such scenes were below.
    if (kChecksStatistics) {
        EXPECT_GT(below, 0.8);
        EXPECT_LT(nees[nees.size() / 2], 6.5);
    }
}

// The rotation block's NEES omega^T Sigma_rr^-1 omega of a reported motion (R_true = R
// exp([omega]x)).
double rotationNees(const Report& r, const Matx33d& Rgt)
{
    const Vec3d omega = rotationVector(Matx33d(r.R).t() * Rgt);
    const Matx33d block = Matx<double, 5, 5>(r.covariance).get_minor<3, 3>(0, 0);
    return omega.dot(block.inv(DECOMP_CHOLESKY) * omega);
}

/* On matches whose noise has wide tails (per coordinate 0.3 px, one in four 1.2 px; 300 points, 75
% true) the final polish's Cauchy loss returns a motion more precise than least squares, and the
reported covariance is that M-estimate's (its own sandwich; components/residual_covariance.cpp).
With least squares' covariance the rotation NEES mean was 1.2 on such scenes (twice too wide);
measured 2.53 (chi-square(3): 3; 2.40 while the sandwich could only raise the one-noise form). */
TEST(Rcme_Covariance, polished_motion_on_heavy_tailed_matches_is_calibrated)
{
    const int scenes = testRuns(60, 10);
    std::vector<double> nees;
    for (int seed = 0; seed < scenes; ++seed) {
        const SyntheticScene scene = heavyTailedScene(seed, 300, static_cast<uint64>(3000 + seed));
        const Report r = estimateRelativeMotion(scene.points1, scene.points2, scene.cameraMatrix);
        if (r.status == STATUS_SUCCESS)
            nees.push_back(rotationNees(r, Matx33d(scene.R)));
    }
    ASSERT_GE(nees.size(), static_cast<size_t>(scenes * 3 / 4));
    const double mean = std::accumulate(nees.begin(), nees.end(), 0.0) / nees.size();
    std::cout << "heavy-tailed matches, " << nees.size() << " scenes: rotation NEES mean " << mean
              << std::endl;
    if (kChecksStatistics) {
        EXPECT_GT(mean, 2.0);
        EXPECT_LT(mean, 4.0);
    }
}

TEST(Rcme_Covariance, counts_the_outliers_inside_the_band)
{
    // 300 random matches among 1000: a few fall inside the band around the epipolar lines, each
    // with a leverage about a dozen times an inlier's.
    const int seeds = testRuns(40, 3);
    int runs = 0, above = 0;
    for (const double sigma : {0.5, 1.0, 2.0})
        for (int seed = 0; seed < seeds; ++seed) {
            SyntheticScene s;
            Report r;
            if (!rightCorridorAnswer(seed, sigma, 1000, s, r))
                continue;
            ASSERT_EQ(r.covariance.size(), Size(5, 5));
            ++runs;
            above += rotationNees(r, Matx33d(s.R)) > 7.815 ? 1 : 0;
        }
    ASSERT_GE(runs, 3 * seeds * 3 / 4);
    std::cout << "corridor, 1000 matches, 30 % outliers: rotation NEES above 7.815 in " << above
              << " of " << runs << " scenes" << std::endl;
    // chi-square(3): 5 %. Measured 4 of 113; 9 of 113 with the plain sandwich and no term for the
    // outliers in the band (main before issue 36d).
    if (kChecksStatistics)
        EXPECT_LE(above, runs * 7 / 100);
}

TEST(Rcme_Covariance, noise_estimate_within_ten_percent)
{
    // Stated sigma 1 px; true noise from half to one and a half of it, with outliers; the median
    // over scenes of the estimated / true noise, with and without K. Measured (gcc, Release, 10
    // scenes): 1.01 / 1.01 at 0.5 px, 1.01 / 1.01 at 1 px, 0.94 / 0.87 at 1.5 px: where the noise
    // exceeds the stated sigma the band (1.96 px) cuts the residuals at 1.3 true sigmas, the
    // undoing of the truncation assumes a Gaussian cut exactly there, and single scenes ranged
    // from 0.78 to 1.13. So 10 % at and below the stated sigma, 15 % above it.
    const int runs = testRuns(10, 3);
    for (double trueSigma : {0.5, 1.0, 1.5}) {
        std::vector<double> withK, withoutK;
        for (int seed = 0; seed < runs; ++seed) {
            const SyntheticScene s = testScene(SCENE_GENERIC, seed, 0.7, trueSigma, 400);
            Params params;
            const Report r = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
            ASSERT_EQ(r.status, STATUS_SUCCESS) << trueSigma;
            ASSERT_GE(r.inlierCount, 200);
            withK.push_back(r.noiseSigma / trueSigma);
            const Report uncalibrated =
                estimateRelativeMotion(s.points1, s.points2, noArray(), params);
            ASSERT_EQ(uncalibrated.status, STATUS_SUCCESS) << trueSigma;
            withoutK.push_back(uncalibrated.noiseSigma / trueSigma);
        }
        if (!kChecksStatistics)
            continue;
        const double tolerance = trueSigma > 1.0 ? 0.15 : 0.1;
        for (std::vector<double>* ratios : {&withK, &withoutK}) {
            std::sort(ratios->begin(), ratios->end());
            EXPECT_NEAR((*ratios)[ratios->size() / 2], 1.0, tolerance) << trueSigma;
        }
    }
}

TEST(Rcme_Covariance, follows_the_noise_choice)
{
    const SyntheticScene s = testScene(SCENE_GENERIC, 6, 0.8, 0.5, 300);
    Params params;
    const Report estimated = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
    params.useEstimatedNoise = false;
    const Report stated = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
    ASSERT_EQ(estimated.status, STATUS_SUCCESS);
    ASSERT_EQ(stated.status, STATUS_SUCCESS);
    // Same motion; the stated 1 px is twice the true noise, so its covariance is wider (the
    // band's correction differs with sigma, so the ratio is not exactly sigma^2).
    EXPECT_LT(cv::norm(estimated.R - stated.R), 1e-12);
    EXPECT_NEAR(estimated.noiseSigma, stated.noiseSigma, 1e-12);
    const double ratio = cv::trace(stated.covariance)[0] / cv::trace(estimated.covariance)[0];
    EXPECT_GT(ratio, 2.0);
    // The standard deviations are those of the covariance.
    ASSERT_EQ(estimated.rotationStdDeg.size(), Size(1, 3));
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(estimated.rotationStdDeg.at<double>(k),
                    std::sqrt(estimated.covariance.at<double>(k, k)) * 180 / CV_PI, 1e-12);
    Mat directionBlock = estimated.covariance(Rect(3, 3, 2, 2)), eigenvalues;
    eigen(directionBlock, eigenvalues);
    EXPECT_NEAR(estimated.translationStdDeg, std::sqrt(eigenvalues.at<double>(0)) * 180 / CV_PI,
                1e-12);
}

TEST(Rcme_Covariance, few_inliers_lean_on_the_estimated_noise)
{
    // Stated sigma 1 px, true 0.25 px, 30 points: fewer than the 35 inliers from which the final
    // fit uses its own noise estimate. The reported covariance takes the posterior noise
    // (4 stated^2 + dof noiseSigma^2) / (dof + 2) instead of the stated sigma (before: the same
    // covariance as with useEstimatedNoise = false), so against the stated sigma's covariance the
    // ratio is that posterior times h(1.96) / h(1.96 / sigma_post), h(k) = E[z^2 | |z| < k]:
    // h(1.96) = 0.7589, and h is within 1e-3 of 1 at the posterior's 0.4-0.5 px.
    int checked = 0;
    for (int seed = 0; seed < 4; ++seed) {
        const SyntheticScene s = testScene(SCENE_GENERIC, seed, 1.0, 0.25, 30);
        Params params;
        const Report estimated =
            estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        params.useEstimatedNoise = false;
        const Report stated = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        if (estimated.status != STATUS_SUCCESS || estimated.covariance.rows != 5)
            continue;
        ASSERT_EQ(stated.status, STATUS_SUCCESS);
        ASSERT_LT(estimated.inlierCount, 35);
        EXPECT_LT(cv::norm(estimated.R - stated.R), 1e-12);
        const double dof = estimated.inlierCount - 5;
        const double posterior =
            (4.0 + dof * estimated.noiseSigma * estimated.noiseSigma) / (dof + 2.0);
        const double ratio = cv::trace(estimated.covariance)[0] / cv::trace(stated.covariance)[0];
        EXPECT_NEAR(ratio / posterior, 0.7589, 0.001) << seed;
        EXPECT_LT(ratio, 0.3) << seed;
        ++checked;
    }
    EXPECT_GE(checked, 2);
}

// The tangent of Report::covariance as documented there: R exp([omega]x), normalize(t + B beta).
void applyTangent(const Matx33d& R, const Vec3d& t, const Vec<double, 5>& theta, Matx33d& Rout,
                  Vec3d& tout)
{
    Vec3d b1, b2;
    tangentBasis(t, b1, b2);
    Rout = R * rotationFromVector(Vec3d(theta[0], theta[1], theta[2]));
    tout = cv::normalize(t + theta[3] * b1 + theta[4] * b2);
}

TEST(Rcme_Covariance, pose_covariance_matches_finite_differences)
{
    const Matx33d R = rotationFromVector(Vec3d(0.1, -0.3, 0.2));
    const Vec3d t = cv::normalize(Vec3d(0.8, -0.1, 0.3));
    Mat A(5, 5, CV_64F);
    RNG rng(5);
    rng.fill(A, RNG::NORMAL, 0, 1);
    const Mat covariance = A * A.t() * 1e-4 + Mat::eye(5, 5, CV_64F) * 1e-6;

    for (bool inverse : {false, true}) {
        // xi(theta) in the documented convention, its Jacobian by central differences.
        auto xi = [&](const Vec<double, 5>& theta) {
            Matx33d Rp;
            Vec3d tp;
            applyTangent(R, t, theta, Rp, tp);
            Vec<double, 6> out;
            Vec3d omega, v;
            if (!inverse) { // T_true = T Exp(xi): R' = R exp(omega), t' = t + R v
                omega = rotationVector(R.t() * Rp);
                v = R.t() * (tp - t);
            } else { // the same for T^-1 = [R^T | -R^T t]
                omega = rotationVector(R * Rp.t());
                v = R * (-(Rp.t() * tp) + R.t() * t);
            }
            for (int k = 0; k < 3; ++k) {
                out[k] = omega[k];
                out[3 + k] = v[k];
            }
            return out;
        };
        Mat J(6, 5, CV_64F);
        const double h = 1e-6;
        for (int k = 0; k < 5; ++k) {
            Vec<double, 5> step = Vec<double, 5>::all(0);
            step[k] = h;
            const Vec<double, 6> d = (xi(step) - xi(-step)) * (0.5 / h);
            for (int r = 0; r < 6; ++r)
                J.at<double>(r, k) = d[r];
        }
        const Mat expected = J * covariance * J.t();
        const Mat pose = poseCovariance(R, t, covariance, 0, inverse);
        ASSERT_EQ(pose.size(), Size(6, 6));
        EXPECT_LT(cv::norm(pose - expected), 1e-6 * cv::norm(expected)) << inverse;
    }

    // The scale direction carries scaleStd^2 and nothing else.
    const Mat withScale = poseCovariance(R, t, covariance, 0.5);
    Mat u = Mat::zeros(6, 1, CV_64F);
    Mat(R.t() * t).copyTo(u.rowRange(3, 6));
    EXPECT_LT(cv::norm(withScale * u - 0.25 * u), 1e-12);
    EXPECT_LT(cv::norm(poseCovariance(R, t, covariance) * u), 1e-12);

    EXPECT_THROW(poseCovariance(R, t, Mat::eye(6, 6, CV_64F)), cv::Exception);
    EXPECT_THROW(poseCovariance(R, t, covariance, -1.0), cv::Exception);
    EXPECT_THROW(poseCovariance(Mat::eye(3, 3, CV_64F) * 2, t, covariance), cv::Exception);
}

} // namespace
} // namespace opencv_test
