// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "test_precomp.hpp"

#include "opencv2/rcme/opencv_geometry.hpp"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace opencv_test {
namespace {

SceneParams makeParams(SceneKind kind, int seed, int n = 500, double w = 0.5, double sigma = 1.0)
{
    return testSceneParams(kind, seed, w, sigma, n);
}

double maxAbsDiff(const Mat& a, const Mat& b)
{
    if (a.size() != b.size() || a.type() != b.type())
        return std::numeric_limits<double>::infinity();
    return cv::norm(a, b, NORM_INF);
}

Mat skew(const Mat& t)
{
    const double x = t.at<double>(0), y = t.at<double>(1), z = t.at<double>(2);
    return Mat(Matx33d(0, -z, y, z, 0, -x, -y, x, 0));
}

Mat rotation(double angleDeg, double ax, double ay, double az)
{
    const double len = std::sqrt(ax * ax + ay * ay + az * az);
    Mat rvec = Mat(Vec3d(ax, ay, az)) * (angleDeg * CV_PI / 180.0 / len);
    Mat R;
    cv::Rodrigues(rvec, R);
    return R;
}

// First-order geometric distance (pixels) of a correspondence to the epipolar geometry of F.
double sampson(const Mat& F, const Mat& p1, const Mat& p2, int i)
{
    const Mat x1 = Mat(Vec3d(p1.at<double>(i, 0), p1.at<double>(i, 1), 1.0));
    const Mat x2 = Mat(Vec3d(p2.at<double>(i, 0), p2.at<double>(i, 1), 1.0));
    const Mat Fx1 = F * x1;
    const Mat Ftx2 = F.t() * x2;
    const double r = x2.dot(Fx1);
    const double g = Fx1.at<double>(0) * Fx1.at<double>(0) + Fx1.at<double>(1) * Fx1.at<double>(1) +
                     Ftx2.at<double>(0) * Ftx2.at<double>(0) +
                     Ftx2.at<double>(1) * Ftx2.at<double>(1);
    return std::abs(r) / std::sqrt(g);
}

// Inlier correspondences triangulated in camera 1's frame (metric when the baseline is 1).
std::vector<Point3d> triangulateInliers(const SyntheticScene& s)
{
    Mat P1 = Mat::zeros(3, 4, CV_64F), P2(3, 4, CV_64F);
    Mat(Mat::eye(3, 3, CV_64F)).copyTo(P1.colRange(0, 3));
    s.R.copyTo(P2.colRange(0, 3));
    s.t.copyTo(P2.col(3));
    P1 = s.cameraMatrix * P1;
    P2 = s.cameraMatrix * P2;

    std::vector<Point2d> a, b;
    for (int i = 0; i < s.points1.rows; ++i)
        if (s.inlierMask.at<uchar>(i)) {
            a.emplace_back(s.points1.at<double>(i, 0), s.points1.at<double>(i, 1));
            b.emplace_back(s.points2.at<double>(i, 0), s.points2.at<double>(i, 1));
        }
    Mat X4, X;
    cv::triangulatePoints(P1, P2, a, b, X4);
    X4.convertTo(X, CV_64F);
    std::vector<Point3d> out;
    for (int i = 0; i < X.cols; ++i) {
        const double w = X.at<double>(3, i);
        out.emplace_back(X.at<double>(0, i) / w, X.at<double>(1, i) / w, X.at<double>(2, i) / w);
    }
    return out;
}

// Depth of a camera-1 point in camera 2.
double depthInCamera2(const SyntheticScene& s, const Point3d& X)
{
    const Mat x2 = s.R * Mat(Vec3d(X.x, X.y, X.z)) + s.t;
    return x2.at<double>(2);
}

// Expects StsBadArg from f with `needle` (the offending field or argument) in the message.
void expectBadArg(const std::function<void()>& f, const std::string& needle)
{
    EXPECT_THROW(f(), cv::Exception) << needle;
    try {
        f();
    } catch (const cv::Exception& e) {
        EXPECT_EQ(cv::Error::StsBadArg, e.code) << e.what();
        EXPECT_NE(std::string::npos, std::string(e.what()).find(needle))
            << "expected '" << needle << "' in: " << e.what();
    }
}

TEST(Rcme_Synthetic, defaults_are_the_documented_ones)
{
    const SceneParams p;
    EXPECT_EQ(SCENE_CORRIDOR, p.kind);
    EXPECT_EQ(500, p.numPoints);
    EXPECT_EQ(0.5, p.inlierRatio);
    EXPECT_EQ(1.0, p.sigma);
    EXPECT_EQ(0, p.seed);
    EXPECT_EQ(500.0, p.focalLength);
    EXPECT_EQ(640, p.imageWidth);
    EXPECT_EQ(480, p.imageHeight);
    EXPECT_EQ(1.0, p.baseline);
    EXPECT_EQ(50.0, p.corridorDepth);
    EXPECT_EQ(4.0, p.corridorWidth);
    EXPECT_EQ(3.0, p.corridorHeight);
    EXPECT_EQ(1.0, p.inlierRegion);
    EXPECT_EQ(0.0, p.planeRelief);
    EXPECT_FALSE(p.forwardMotion);

    const MotionError e;
    EXPECT_TRUE(std::isnan(e.dq));
    EXPECT_TRUE(std::isnan(e.dt));
    EXPECT_TRUE(std::isnan(e.rotationDeg));
    EXPECT_TRUE(std::isnan(e.translationDeg));
}

TEST(Rcme_Synthetic, output_types_and_shapes)
{
    for (SceneKind kind : {SCENE_CORRIDOR, SCENE_GENERIC}) {
        const SyntheticScene s = generateScene(makeParams(kind, 3, 123, 0.4));
        EXPECT_EQ(CV_64FC1, s.points1.type());
        EXPECT_EQ(CV_64FC1, s.points2.type());
        EXPECT_EQ(Size(2, 123), s.points1.size());
        EXPECT_EQ(Size(2, 123), s.points2.size());
        EXPECT_EQ(CV_8UC1, s.inlierMask.type());
        EXPECT_EQ(Size(1, 123), s.inlierMask.size());
        for (const Mat* m : {&s.cameraMatrix, &s.R, &s.F, &s.E}) {
            EXPECT_EQ(CV_64FC1, m->type());
            EXPECT_EQ(Size(3, 3), m->size());
        }
        EXPECT_EQ(CV_64FC1, s.t.type());
        EXPECT_EQ(Size(1, 3), s.t.size());
        const Mat K = Mat(Matx33d(500, 0, 320, 0, 500, 240, 0, 0, 1));
        EXPECT_EQ(0.0, maxAbsDiff(K, s.cameraMatrix));
    }
}

TEST(Rcme_Synthetic, same_seed_gives_identical_scene)
{
    for (SceneKind kind : {SCENE_CORRIDOR, SCENE_GENERIC}) {
        const SceneParams p = makeParams(kind, 42, 300, 0.3, 2.0);
        const SyntheticScene a = generateScene(p);
        const SyntheticScene b = generateScene(p);
        EXPECT_EQ(0.0, maxAbsDiff(a.points1, b.points1));
        EXPECT_EQ(0.0, maxAbsDiff(a.points2, b.points2));
        EXPECT_EQ(0.0, maxAbsDiff(a.inlierMask, b.inlierMask));
        EXPECT_EQ(0.0, maxAbsDiff(a.R, b.R));
        EXPECT_EQ(0.0, maxAbsDiff(a.t, b.t));
        EXPECT_EQ(0.0, maxAbsDiff(a.F, b.F));
        EXPECT_EQ(0.0, maxAbsDiff(a.E, b.E));
    }
}

TEST(Rcme_Synthetic, motion_depends_on_seed_and_geometry_only)
{
    for (SceneKind kind : {SCENE_CORRIDOR, SCENE_GENERIC}) {
        const SyntheticScene a = generateScene(makeParams(kind, 8, 500, 0.5, 1.0));
        const SyntheticScene b = generateScene(makeParams(kind, 8, 37, 0.0, 0.0));
        const SyntheticScene c = generateScene(makeParams(kind, 8, 2000, 1.0, 4.0));
        EXPECT_EQ(0.0, maxAbsDiff(a.R, b.R));
        EXPECT_EQ(0.0, maxAbsDiff(a.t, b.t));
        EXPECT_EQ(0.0, maxAbsDiff(a.R, c.R));
        EXPECT_EQ(0.0, maxAbsDiff(a.t, c.t));
        EXPECT_EQ(0.0, maxAbsDiff(a.F, c.F));
    }
}

TEST(Rcme_Synthetic, narrow_field_of_view_still_gives_a_scene)
{
    // About 18 x 14 degrees: the tilted corridor cameras often look at disjoint parts of the
    // corridor, and such pairs are redrawn.
    for (int seed = 0; seed < 40; ++seed) {
        SceneParams p = makeParams(SCENE_CORRIDOR, seed, 200, 1.0);
        p.imageWidth = 160;
        p.imageHeight = 120;
        p.baseline = 3.0;
        SyntheticScene s;
        ASSERT_NO_THROW(s = generateScene(p)) << "seed " << seed;
        EXPECT_EQ(200, countNonZero(s.inlierMask));
    }
    // A one-pixel image sees (almost) nothing: an error naming the configuration, not a hang.
    SceneParams p = makeParams(SCENE_CORRIDOR, 0, 10, 0.5);
    p.imageWidth = 1;
    p.imageHeight = 1;
    try {
        generateScene(p);
        ADD_FAILURE() << "expected an exception";
    } catch (const cv::Exception& e) {
        EXPECT_EQ(cv::Error::StsError, e.code);
        EXPECT_NE(std::string::npos, std::string(e.what()).find("image 1x1")) << e.what();
    }
}

TEST(Rcme_Synthetic, different_seeds_give_different_scenes)
{
    // Includes 0 and -1, which cv::RNG alone would map to the same state.
    const int seeds[] = {0, 1, 2, -1, 1000};
    for (SceneKind kind : {SCENE_CORRIDOR, SCENE_GENERIC}) {
        std::vector<SyntheticScene> scenes;
        for (int seed : seeds)
            scenes.push_back(generateScene(makeParams(kind, seed)));
        for (size_t i = 0; i < scenes.size(); ++i)
            for (size_t j = i + 1; j < scenes.size(); ++j) {
                EXPECT_GT(maxAbsDiff(scenes[i].points1, scenes[j].points1), 1.0) << i << " " << j;
                EXPECT_GT(maxAbsDiff(scenes[i].R, scenes[j].R), 1e-6) << i << " " << j;
                EXPECT_GT(maxAbsDiff(scenes[i].t, scenes[j].t), 1e-6) << i << " " << j;
            }
    }
}

TEST(Rcme_Synthetic, inlier_count_is_rounded_ratio)
{
    struct Case
    {
        int n;
        double w;
        int expected;
    };
    // round half up: 3.5 -> 4, 2.5 -> 3
    const Case cases[] = {{500, 0.5, 250}, {7, 0.5, 4},       {10, 0.25, 3}, {3, 0.33, 1},
                          {1, 0.0, 0},     {1, 1.0, 1},       {200, 0.0, 0}, {200, 1.0, 200},
                          {999, 0.1, 100}, {1000, 0.123, 123}};
    for (SceneKind kind : {SCENE_CORRIDOR, SCENE_GENERIC})
        for (const Case& c : cases) {
            const SyntheticScene s = generateScene(makeParams(kind, 5, c.n, c.w));
            EXPECT_EQ(c.expected, countNonZero(s.inlierMask)) << c.n << " " << c.w;
            EXPECT_EQ(c.n, s.points1.rows);
            for (int i = 0; i < s.inlierMask.rows; ++i)
                ASSERT_LE(s.inlierMask.at<uchar>(i), 1);
        }
}

TEST(Rcme_Synthetic, inliers_and_outliers_are_interleaved)
{
    const SyntheticScene s = generateScene(makeParams(SCENE_CORRIDOR, 9, 400, 0.5));
    // Unshuffled, the first half would be all inliers and the second half all outliers.
    const int firstHalf = countNonZero(s.inlierMask.rowRange(0, 200));
    EXPECT_GT(firstHalf, 60);
    EXPECT_LT(firstHalf, 140);
}

TEST(Rcme_Synthetic, all_points_inside_the_images)
{
    for (SceneKind kind : {SCENE_CORRIDOR, SCENE_GENERIC})
        for (int seed = 0; seed < 10; ++seed) {
            SceneParams p = makeParams(kind, seed, 1000, 0.6, 5.0);
            p.imageWidth = 320;
            p.imageHeight = 200;
            const SyntheticScene s = generateScene(p);
            for (const Mat* pts : {&s.points1, &s.points2})
                for (int i = 0; i < pts->rows; ++i) {
                    const double u = pts->at<double>(i, 0), v = pts->at<double>(i, 1);
                    ASSERT_TRUE(u >= 0 && u < 320 && v >= 0 && v < 200)
                        << static_cast<int>(kind) << " seed " << seed << " point " << i << ": " << u
                        << ", " << v;
                }
        }
}

TEST(Rcme_Synthetic, outliers_are_uniform_in_the_images)
{
    const SyntheticScene s = generateScene(makeParams(SCENE_CORRIDOR, 4, 4000, 0.0));
    Scalar mean1, std1, mean2, std2;
    meanStdDev(s.points1.col(0), mean1, std1);
    EXPECT_NEAR(320.0, mean1[0], 10.0);
    EXPECT_NEAR(640.0 / std::sqrt(12.0), std1[0], 6.0);
    meanStdDev(s.points2.col(1), mean2, std2);
    EXPECT_NEAR(240.0, mean2[0], 8.0);
    EXPECT_NEAR(480.0 / std::sqrt(12.0), std2[0], 5.0);
}

TEST(Rcme_Synthetic, noise_free_inliers_satisfy_the_epipolar_constraint)
{
    for (SceneKind kind : {SCENE_CORRIDOR, SCENE_GENERIC})
        for (int seed = 0; seed < 5; ++seed) {
            const SyntheticScene s = generateScene(makeParams(kind, seed, 600, 0.5, 0.0));
            int outliers = 0, farOutliers = 0;
            for (int i = 0; i < s.points1.rows; ++i) {
                const Mat x1 =
                    Mat(Vec3d(s.points1.at<double>(i, 0), s.points1.at<double>(i, 1), 1.0));
                const Mat x2 =
                    Mat(Vec3d(s.points2.at<double>(i, 0), s.points2.at<double>(i, 1), 1.0));
                const double algebraic = std::abs(x2.dot(s.F * x1));
                const double d = sampson(s.F, s.points1, s.points2, i);
                if (s.inlierMask.at<uchar>(i)) {
                    EXPECT_LT(algebraic, 1e-10)
                        << static_cast<int>(kind) << " seed " << seed << " point " << i;
                    EXPECT_LT(d, 1e-7)
                        << static_cast<int>(kind) << " seed " << seed << " point " << i;
                } else {
                    ++outliers;
                    farOutliers += d > 2.0;
                }
            }
            EXPECT_GT(farOutliers, 0.85 * outliers) << static_cast<int>(kind) << " seed " << seed;
        }
}

TEST(Rcme_Synthetic, noisy_inlier_residuals_match_sigma)
{
    const double sigma = 1.5;
    for (SceneKind kind : {SCENE_CORRIDOR, SCENE_GENERIC}) {
        const SyntheticScene s = generateScene(makeParams(kind, 11, 4000, 1.0, sigma));
        double sum2 = 0;
        for (int i = 0; i < s.points1.rows; ++i) {
            const double d = sampson(s.F, s.points1, s.points2, i);
            sum2 += d * d;
        }
        // The Sampson distance of 4-D noise with per-coordinate sigma has standard deviation sigma.
        EXPECT_NEAR(sigma, std::sqrt(sum2 / s.points1.rows), 0.1 * sigma) << static_cast<int>(kind);
    }
}

TEST(Rcme_Synthetic, ground_truth_is_consistent)
{
    for (SceneKind kind : {SCENE_CORRIDOR, SCENE_GENERIC})
        for (int seed = 0; seed < 20; ++seed) {
            SceneParams p = makeParams(kind, seed, 50);
            p.focalLength = 700;
            p.imageWidth = 800;
            p.imageHeight = 600;
            const SyntheticScene s = generateScene(p);
            const Mat K = Mat(Matx33d(700, 0, 400, 0, 700, 300, 0, 0, 1));
            EXPECT_EQ(0.0, maxAbsDiff(K, s.cameraMatrix));

            EXPECT_LT(maxAbsDiff(s.R.t() * s.R, Mat::eye(3, 3, CV_64F)), 1e-12);
            EXPECT_NEAR(1.0, determinant(s.R), 1e-12);
            EXPECT_NEAR(1.0, cv::norm(s.t), 1e-12);
            EXPECT_LT(maxAbsDiff(s.E, skew(s.t) * s.R), 1e-12);

            Mat expectedF = K.inv().t() * s.E * K.inv();
            expectedF /= cv::norm(expectedF);
            double minVal, maxVal;
            minMaxLoc(s.F, &minVal, &maxVal);
            // Sign convention: the entry of largest magnitude is positive.
            EXPECT_GT(maxVal, -minVal);
            if (expectedF.dot(s.F) < 0)
                expectedF = -expectedF;
            EXPECT_LT(maxAbsDiff(expectedF, s.F), 1e-12);
            EXPECT_NEAR(1.0, cv::norm(s.F), 1e-12);
        }
}

TEST(Rcme_Synthetic, noise_free_inliers_are_in_front_of_both_cameras)
{
    for (SceneKind kind : {SCENE_CORRIDOR, SCENE_GENERIC})
        for (int seed = 0; seed < 5; ++seed) {
            const SyntheticScene s = generateScene(makeParams(kind, seed, 400, 0.5, 0.0));
            const std::vector<Point3d> X = triangulateInliers(s);
            ASSERT_EQ(200u, X.size());
            for (const Point3d& x : X) {
                EXPECT_GT(x.z, 0.0);
                EXPECT_GT(depthInCamera2(s, x), 0.0);
            }

            // recoverPose picks, among the four decompositions of E, the one with the points in
            // front: it must give back exactly the stored R and t (same conventions).
            Mat in1, in2;
            for (int i = 0; i < s.points1.rows; ++i)
                if (s.inlierMask.at<uchar>(i)) {
                    in1.push_back(s.points1.row(i));
                    in2.push_back(s.points2.row(i));
                }
            Mat R, t;
            const int good = cv::recoverPose(s.E, in1, in2, s.cameraMatrix, R, t);
            EXPECT_GT(good, 150) << static_cast<int>(kind) << " seed " << seed;
            const MotionError err = compareMotion(R, t, s.R, s.t);
            EXPECT_LT(err.rotationDeg, 1e-6) << static_cast<int>(kind) << " seed " << seed;
            EXPECT_LT(err.translationDeg, 1e-6) << static_cast<int>(kind) << " seed " << seed;
        }
}

// Greedy plane extraction on noise-free triangulated points: returns (normal, offset) pairs.
std::vector<Vec4d> extractPlanes(std::vector<Point3d> pts, double tol, size_t minSupport)
{
    std::vector<Vec4d> planes;
    RNG rng(7);
    while (pts.size() >= minSupport && planes.size() < 10) {
        Vec4d best;
        size_t bestCount = 0;
        for (int it = 0; it < 2000; ++it) {
            const Point3d a = pts[rng.uniform(0, (int)pts.size())];
            const Point3d b = pts[rng.uniform(0, (int)pts.size())];
            const Point3d c = pts[rng.uniform(0, (int)pts.size())];
            Point3d nrm = (b - a).cross(c - a);
            const double len = cv::norm(nrm);
            if (len < 1e-6)
                continue;
            nrm *= 1.0 / len;
            const double d = nrm.dot(a);
            size_t count = 0;
            for (const Point3d& p : pts)
                count += std::abs(nrm.dot(p) - d) < tol;
            if (count > bestCount) {
                bestCount = count;
                best = Vec4d(nrm.x, nrm.y, nrm.z, d);
            }
        }
        if (bestCount < minSupport)
            break;
        planes.push_back(best);
        std::vector<Point3d> rest;
        for (const Point3d& p : pts)
            if (std::abs(best[0] * p.x + best[1] * p.y + best[2] * p.z - best[3]) >= tol)
                rest.push_back(p);
        pts.swap(rest);
    }
    return planes;
}

TEST(Rcme_Synthetic, corridor_points_lie_on_several_walls_over_a_long_depth_range)
{
    for (int seed = 0; seed < 4; ++seed) {
        const SyntheticScene s = generateScene(makeParams(SCENE_CORRIDOR, seed, 1500, 1.0, 0.0));
        const std::vector<Point3d> X = triangulateInliers(s);
        double minDepth = 1e9, maxDepth = 0;
        for (const Point3d& x : X) {
            minDepth = std::min(minDepth, x.z);
            maxDepth = std::max(maxDepth, x.z);
        }
        // Baseline 1 m, so the triangulation is metric: the 50 m corridor is seen from a few
        // metres out to its far end.
        EXPECT_LT(minDepth, 6.0) << "seed " << seed;
        EXPECT_GT(maxDepth, 35.0) << "seed " << seed;

        // Keep the well-triangulated points (the nearer half) for the plane test.
        std::vector<Point3d> nearPts;
        for (const Point3d& x : X)
            if (x.z < 20.0)
                nearPts.push_back(x);
        const std::vector<Vec4d> planes = extractPlanes(nearPts, 1e-4, nearPts.size() / 50);
        // Several walls with support, each pair of them parallel or perpendicular, and parallel
        // walls 3 m or 4 m apart.
        EXPECT_GE(planes.size(), 3u) << "seed " << seed;
        EXPECT_LE(planes.size(), 5u) << "seed " << seed;
        for (size_t i = 0; i < planes.size(); ++i)
            for (size_t j = i + 1; j < planes.size(); ++j) {
                const double c = planes[i][0] * planes[j][0] + planes[i][1] * planes[j][1] +
                                 planes[i][2] * planes[j][2];
                if (std::abs(c) < 1e-3)
                    continue;
                EXPECT_NEAR(1.0, std::abs(c), 1e-6) << "seed " << seed;
                const double gap = std::abs(planes[i][3] - c * planes[j][3]);
                EXPECT_TRUE(std::abs(gap - 3.0) < 1e-3 || std::abs(gap - 4.0) < 1e-3)
                    << "seed " << seed << " gap " << gap;
            }
    }
}

TEST(Rcme_Synthetic, corridor_cameras_look_down_the_corridor)
{
    for (int seed = 0; seed < 50; ++seed) {
        const SyntheticScene s = generateScene(makeParams(SCENE_CORRIDOR, seed, 20));
        const MotionError e = compareMotion(s.R, s.t, Mat::eye(3, 3, CV_64F), s.t);
        // Each camera is tilted by at most 15 degrees about each of its axes.
        EXPECT_GT(e.rotationDeg, 0.1) << "seed " << seed;
        EXPECT_LT(e.rotationDeg, 55.0) << "seed " << seed;
    }
}

TEST(Rcme_Synthetic, generic_scene_depths_and_motion)
{
    for (double baseline : {1.0, 2.0})
        for (int seed = 0; seed < 5; ++seed) {
            SceneParams p = makeParams(SCENE_GENERIC, seed, 400, 1.0, 0.0);
            p.baseline = baseline;
            const SyntheticScene s = generateScene(p);
            // t has unit length, so triangulated depths are divided by the baseline.
            for (const Point3d& x : triangulateInliers(s)) {
                EXPECT_GE(x.z * baseline, 4.0 - 1e-6);
                EXPECT_LE(x.z * baseline, 20.0 + 1e-6);
            }
        }
    for (int seed = 0; seed < 200; ++seed) {
        const SyntheticScene s = generateScene(makeParams(SCENE_GENERIC, seed, 10));
        EXPECT_GT(std::abs(s.t.at<double>(0)), 0.8) << "mostly sideways, seed " << seed;
        const MotionError e = compareMotion(s.R, s.t, Mat::eye(3, 3, CV_64F), s.t);
        EXPECT_GE(e.rotationDeg, 3.0) << "seed " << seed;
        EXPECT_LT(e.rotationDeg, 16.0) << "seed " << seed;
    }
}

TEST(Rcme_Synthetic, inliers_in_a_region_of_image_1_outliers_everywhere)
{
    for (SceneKind kind : {SCENE_CORRIDOR, SCENE_GENERIC})
        for (int seed = 0; seed < 3; ++seed) {
            SceneParams p = makeParams(kind, seed, 400, 0.5);
            p.inlierRegion = 0.5;
            const SyntheticScene s = generateScene(p);
            EXPECT_EQ(200, countNonZero(s.inlierMask));
            int outliersElsewhere = 0;
            for (int i = 0; i < s.points1.rows; ++i) {
                const double x = s.points1.at<double>(i, 0), y = s.points1.at<double>(i, 1);
                const bool inRegion = x < 320 && y < 240;
                if (s.inlierMask.at<uchar>(i))
                    EXPECT_TRUE(inRegion) << "inlier " << i << " at " << x << ", " << y;
                else
                    outliersElsewhere += !inRegion;
            }
            EXPECT_GT(outliersElsewhere, 100); // about 3/4 of 200
        }
}

TEST(Rcme_Synthetic, plane_relief_moves_points_off_the_plane_within_the_bound)
{
    // x2 = R x1 + t, |t| = baseline = 1: triangulated points are in metres, camera 1's frame.
    const Vec3d normal = normalize(Vec3d(0.1, -0.2, 1.0));
    for (double relief : {0.0, 0.5}) {
        SceneParams p = makeParams(SCENE_PLANE, 2, 300, 1.0, 0.0);
        p.planeRelief = relief;
        double largest = 0;
        for (const Point3d& x : triangulateInliers(generateScene(p)))
            largest = std::max(largest, std::abs(normal.dot(Vec3d(x)) - 12.0));
        if (relief == 0)
            EXPECT_LT(largest, 1e-6);
        else {
            EXPECT_LE(largest, relief + 1e-6);
            EXPECT_GT(largest, 0.4 * relief);
        }
    }
    // Without relief no draw is added: the plane's scenes are those of before the field.
    SceneParams flat = makeParams(SCENE_PLANE, 4, 50), rough = flat;
    rough.planeRelief = 0.01;
    EXPECT_GT(maxAbsDiff(generateScene(flat).points1, generateScene(rough).points1), 0);
}

TEST(Rcme_Synthetic, forward_motion_puts_the_epipole_near_the_image_centre)
{
    for (int seed = 0; seed < 100; ++seed)
        for (SceneKind kind : {SCENE_GENERIC, SCENE_PLANE}) {
            SceneParams p = makeParams(kind, seed, 10);
            p.forwardMotion = true;
            const SyntheticScene forward = generateScene(p);
            // The translation within 30 deg of the optical axis: 17 deg of jitter, 6 of tilt.
            EXPECT_GT(std::abs(forward.t.at<double>(2)), std::cos(30 * CV_PI / 180))
                << "seed " << seed;
            const MotionError e =
                compareMotion(forward.R, forward.t, Mat::eye(3, 3, CV_64F), forward.t);
            EXPECT_GE(e.rotationDeg, 3.0) << "seed " << seed;
            EXPECT_LT(e.rotationDeg, 16.0) << "seed " << seed;
        }
}

TEST(Rcme_Synthetic, larger_baseline_fits_in_the_corridor)
{
    SceneParams p = makeParams(SCENE_CORRIDOR, 1, 300, 0.5, 0.0);
    p.baseline = 5.0;
    const SyntheticScene s = generateScene(p);
    EXPECT_EQ(150, countNonZero(s.inlierMask));
}

TEST(Rcme_Synthetic, bad_parameters_throw_naming_the_field)
{
    const auto run = [](const std::function<void(SceneParams&)>& edit, const std::string& field) {
        SceneParams p;
        edit(p);
        expectBadArg([&] { generateScene(p); }, "SceneParams." + field);
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    run([](SceneParams& p) { p.kind = static_cast<SceneKind>(4); }, "kind");
    run([](SceneParams& p) { p.kind = static_cast<SceneKind>(-1); }, "kind");
    run([](SceneParams& p) { p.numPoints = 0; }, "numPoints");
    run([](SceneParams& p) { p.numPoints = -5; }, "numPoints");
    run([](SceneParams& p) { p.numPoints = 10000001; }, "numPoints");
    run([](SceneParams& p) { p.inlierRatio = -0.01; }, "inlierRatio");
    run([](SceneParams& p) { p.inlierRatio = 1.01; }, "inlierRatio");
    run([&](SceneParams& p) { p.inlierRatio = nan; }, "inlierRatio");
    run([](SceneParams& p) { p.sigma = -1; }, "sigma");
    run([&](SceneParams& p) { p.sigma = nan; }, "sigma");
    run([&](SceneParams& p) { p.sigma = inf; }, "sigma");
    run([](SceneParams& p) { p.focalLength = 0; }, "focalLength");
    run([&](SceneParams& p) { p.focalLength = inf; }, "focalLength");
    run([](SceneParams& p) { p.imageWidth = 0; }, "imageWidth");
    run([](SceneParams& p) { p.imageHeight = -480; }, "imageHeight");
    run([](SceneParams& p) { p.baseline = 0; }, "baseline");
    run([&](SceneParams& p) { p.baseline = nan; }, "baseline");
    run([](SceneParams& p) { p.baseline = 1000; }, "baseline"); // cannot fit in the corridor
    run([](SceneParams& p) { p.corridorDepth = -50; }, "corridorDepth");
    run([](SceneParams& p) { p.corridorWidth = 0; }, "corridorWidth");
    run([&](SceneParams& p) { p.corridorHeight = nan; }, "corridorHeight");
    run([](SceneParams& p) { p.inlierRegion = 0; }, "inlierRegion");
    run([](SceneParams& p) { p.inlierRegion = 1.5; }, "inlierRegion");
    run([&](SceneParams& p) { p.inlierRegion = nan; }, "inlierRegion");
    run([](SceneParams& p) { p.planeRelief = -0.1; }, "planeRelief");
    run([&](SceneParams& p) { p.planeRelief = inf; }, "planeRelief");
    run(
        [](SceneParams& p) {
            p.kind = SCENE_GENERIC;
            p.corridorWidth = -1;
        },
        "corridorWidth");

    // The boundary values are accepted.
    SceneParams ok;
    ok.numPoints = 1;
    ok.inlierRatio = 1.0;
    ok.sigma = 0.0;
    EXPECT_NO_THROW(generateScene(ok));
}

TEST(Rcme_Synthetic, compare_motion_identical_inputs_give_zero_error)
{
    const Mat R = rotation(37.0, 0.3, -1.0, 0.5);
    const Mat t = Mat(Vec3d(0.2, -0.4, 0.9));
    const MotionError e = compareMotion(R, t, R, t);
    EXPECT_NEAR(0.0, e.dq, 1e-12);
    EXPECT_NEAR(0.0, e.dt, 1e-12);
    EXPECT_NEAR(0.0, e.rotationDeg, 1e-9);
    EXPECT_NEAR(0.0, e.translationDeg, 1e-9);

    // Translation scale does not matter.
    const MotionError scaled = compareMotion(R, t * 7.0, R, t * 0.01);
    EXPECT_NEAR(0.0, scaled.dt, 1e-12);
    EXPECT_NEAR(0.0, scaled.translationDeg, 1e-9);
}

TEST(Rcme_Synthetic, compare_motion_known_errors)
{
    const Mat Rgt = rotation(25.0, 1.0, 0.2, -0.3);
    const Mat tgt = Mat(Vec3d(1.0, 0.0, 0.0));
    const double angles[] = {1e-6, 0.5, 10.0, 90.0, 170.0, 180.0};
    for (double deg : angles) {
        const Mat R = Rgt * rotation(deg, 1.0, 2.0, 3.0);
        // 30 degrees away from tgt, in the XY plane.
        const Mat t = Mat(Vec3d(std::cos(CV_PI / 6), std::sin(CV_PI / 6), 0.0));
        const MotionError e = compareMotion(R, t, Rgt, tgt);
        // |q - q_gt| = 2 sin(theta / 4) for unit quaternions theta apart.
        EXPECT_NEAR(2.0 * std::sin(deg * CV_PI / 180.0 / 4.0), e.dq, 1e-9) << deg;
        EXPECT_NEAR(deg, e.rotationDeg, 1e-7 * std::max(1.0, deg)) << deg;
        EXPECT_NEAR(2.0 * std::sin(CV_PI / 12), e.dt, 1e-12);
        EXPECT_NEAR(30.0, e.translationDeg, 1e-9);
    }
    // Small angles keep their relative accuracy.
    const MotionError tiny =
        compareMotion(rotation(1e-6, 0, 0, 1), tgt, Mat::eye(3, 3, CV_64F), tgt);
    EXPECT_NEAR(1e-6, tiny.rotationDeg, 1e-12);

    // Opposite translations.
    const MotionError opposite = compareMotion(Rgt, -tgt, Rgt, tgt);
    EXPECT_NEAR(2.0, opposite.dt, 1e-12);
    EXPECT_NEAR(180.0, opposite.translationDeg, 1e-9);
}

TEST(Rcme_Synthetic, compare_motion_is_insensitive_to_quaternion_sign)
{
    // 179 and 181 degrees about the same axis are 2 degrees apart, although their quaternions
    // as converted may have opposite signs of the scalar part.
    const Mat a = rotation(179.0, 0.0, 1.0, 0.0);
    const Mat b = rotation(-179.0, 0.0, 1.0, 0.0);
    const Mat t = Mat(Vec3d(0, 0, 1));
    const MotionError e = compareMotion(a, t, b, t);
    EXPECT_NEAR(2.0, e.rotationDeg, 1e-7);
    EXPECT_NEAR(2.0 * std::sin(2.0 * CV_PI / 180.0 / 4.0), e.dq, 1e-9);
    const MotionError swapped = compareMotion(b, t, a, t);
    EXPECT_NEAR(e.dq, swapped.dq, 1e-12);

    // 30 and -130 degrees about X are 160 degrees apart; the matrix-to-quaternion conversion
    // returns quaternions with a negative dot product for this pair, so only the min over the
    // two signs gives 2 sin(160 deg / 4).
    const MotionError far = compareMotion(rotation(30.0, 1, 0, 0), t, rotation(-130.0, 1, 0, 0), t);
    EXPECT_NEAR(160.0, far.rotationDeg, 1e-9);
    EXPECT_NEAR(2.0 * std::sin(40.0 * CV_PI / 180.0), far.dq, 1e-9);

    // For any pair, dq = 2 sin(theta / 4) with theta the relative angle in [0, 180].
    RNG rng(123);
    for (int i = 0; i < 500; ++i) {
        const Mat Ra = rotation(rng.uniform(-180.0, 180.0), rng.gaussian(1.0), rng.gaussian(1.0),
                                rng.gaussian(1.0));
        const Mat Rb = rotation(rng.uniform(-180.0, 180.0), rng.gaussian(1.0), rng.gaussian(1.0),
                                rng.gaussian(1.0));
        const MotionError r = compareMotion(Ra, t, Rb, t);
        ASSERT_LE(r.rotationDeg, 180.0);
        ASSERT_NEAR(2.0 * std::sin(r.rotationDeg * CV_PI / 180.0 / 4.0), r.dq, 1e-9) << i;
    }
}

TEST(Rcme_Synthetic, compare_motion_accepts_float_and_row_vectors)
{
    const Mat R = rotation(12.0, 0.0, 0.0, 1.0), Rgt = rotation(2.0, 0.0, 0.0, 1.0);
    const Mat t = Mat(Vec3d(0, 1, 1)), tgt = Mat(Vec3d(0, 0, 1));
    const MotionError ref = compareMotion(R, t, Rgt, tgt);
    Mat Rf, tf;
    R.convertTo(Rf, CV_32F);
    Mat(t.t()).convertTo(tf, CV_32F);
    const MotionError e = compareMotion(Rf, tf, Rgt, Vec3d(0, 0, 1));
    EXPECT_NEAR(10.0, ref.rotationDeg, 1e-9);
    EXPECT_NEAR(45.0, ref.translationDeg, 1e-9);
    EXPECT_NEAR(ref.rotationDeg, e.rotationDeg, 1e-4);
    EXPECT_NEAR(ref.translationDeg, e.translationDeg, 1e-4);
    EXPECT_NEAR(ref.dq, e.dq, 1e-6);
    EXPECT_NEAR(ref.dt, e.dt, 1e-6);
}

TEST(Rcme_Synthetic, compare_motion_bad_inputs_throw_naming_the_argument)
{
    const Mat I = Mat::eye(3, 3, CV_64F);
    const Mat t = Mat(Vec3d(0, 0, 1));
    Mat nanR = I.clone();
    nanR.at<double>(1, 2) = std::numeric_limits<double>::quiet_NaN();
    const Mat reflection = Mat(Matx33d(1, 0, 0, 0, 1, 0, 0, 0, -1));
    const Mat scaled = I * 2.0;
    const Mat intR = Mat::eye(3, 3, CV_32S);
    const Mat bad23 = Mat::zeros(2, 3, CV_64F);
    const Mat zero = Mat::zeros(3, 1, CV_64F);
    const Mat four = Mat(Vec4d(0, 0, 1, 0));
    const Mat t33 = Mat::eye(3, 3, CV_64F);
    const Mat infT = Mat(Vec3d(0, std::numeric_limits<double>::infinity(), 1));

    for (const Mat* bad : {(const Mat*)&nanR, &reflection, &scaled, &intR, &bad23}) {
        expectBadArg([&] { compareMotion(*bad, t, I, t); }, "compareMotion: R ");
        expectBadArg([&] { compareMotion(I, t, *bad, t); }, "compareMotion: Rgt ");
    }
    expectBadArg([&] { compareMotion(Mat(), t, I, t); }, "compareMotion: R ");
    for (const Mat* bad : {&zero, &four, &t33, &infT}) {
        expectBadArg([&] { compareMotion(I, *bad, I, t); }, "compareMotion: t ");
        expectBadArg([&] { compareMotion(I, t, I, *bad); }, "compareMotion: tgt ");
    }
}

} // namespace
} // namespace opencv_test
