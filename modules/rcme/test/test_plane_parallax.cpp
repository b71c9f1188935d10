// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Without K, a homography that explains most inliers leaves F = [e']x H to the points off its
// plane (components/plane_parallax.cpp): a dominant plane with enough points off it keeps its
// F, a plane with none stays degenerate.

#include "test_precomp.hpp"

#ifdef RCME_STANDALONE_TESTS
#include "components/homography_comparison.hpp"
#include "estimation/homography_search.hpp"
#include "framework/two_view_data.hpp"

#include <opencv2/core/eigen.hpp>
#endif

namespace opencv_test {
namespace {

// Depths of the true points off the plane and of the probes that judge F (3-20 m unless named).
struct DepthRange
{
    double nearest = 3.0, farthest = 20.0;
};

// A plane 8 m away filling the view with `onPlane` true correspondences (230 unless named),
// `offPlane` more true ones at depths in `offPlaneDepths`, and uniform outliers up to `total`
// (500 unless named; sigma 1 px, 640x480, f = 500).
struct PlaneScene
{
    Mat points1, points2;
    Matx33d F; //!< the true F, ||F|| = 1
    int inliers = 0;
};

PlaneScene planeWithPointsOffIt(int offPlane, int seed, DepthRange offPlaneDepths = {},
                                int onPlane = 230, int total = 500)
{
    cv::RNG rng(static_cast<uint64>(seed) + 11);
    const Matx33d K(500, 0, 320, 0, 500, 240, 0, 0, 1);
    Matx33d R;
    Rodrigues(Vec3d(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)), R);
    const Vec3d t(1.0, 0.1, 0.2);
    const Vec3d normal = normalize(Vec3d(0.1, -0.2, 1.0));
    PlaneScene scene;
    scene.inliers = onPlane + offPlane;
    int drawn = 0;
    projectTwoViews(
        rng, K, R, t, Size(640, 480), 1.0, scene.inliers, total,
        [&](const Vec3d& ray) {
            return drawn++ < offPlane ? rng.uniform(offPlaneDepths.nearest, offPlaneDepths.farthest)
                                      : 8.0 / ray.dot(normal);
        },
        scene.points1, scene.points2);
    const Matx33d Kinv = K.inv();
    const Matx33d tx(0, -t[2], t[1], t[2], 0, -t[0], -t[1], t[0], 0);
    scene.F = Kinv.t() * tx * R * Kinv;
    scene.F *= 1.0 / cv::norm(scene.F);
    return scene;
}

// RMS Sampson distance (px) under F of noise-free correspondences of the true motion spread over
// the view at `depths`: F's epipolar geometry off the plane too.
double rmsSampsonOffThePlane(const Mat& F, int seed, DepthRange depths = {})
{
    cv::RNG rng(static_cast<uint64>(seed) + 11);
    const Matx33d K(500, 0, 320, 0, 500, 240, 0, 0, 1);
    Matx33d R;
    Rodrigues(Vec3d(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)), R);
    Mat probe1, probe2;
    projectTwoViews(
        rng, K, R, Vec3d(1.0, 0.1, 0.2), Size(640, 480), 0.0, 200, 200,
        [&](const Vec3d&) { return rng.uniform(depths.nearest, depths.farthest); }, probe1, probe2);
    const Matx33d f(F);
    double sum = 0;
    for (int i = 0; i < probe1.rows; ++i) {
        const Vec3d x1(probe1.at<double>(i, 0), probe1.at<double>(i, 1), 1.0);
        const Vec3d x2(probe2.at<double>(i, 0), probe2.at<double>(i, 1), 1.0);
        const Vec3d l2 = f * x1, l1 = f.t() * x2;
        const double e = x2.dot(l2);
        sum += e * e / (l2[0] * l2[0] + l2[1] * l2[1] + l1[0] * l1[0] + l1[1] * l1[1]);
    }
    return std::sqrt(sum / probe1.rows);
}

// The default method on the scene, no camera matrix.
Report withoutK(const PlaneScene& scene, int seed, bool degeneracyTest = true)
{
    Params params;
    params.randomGeneratorState = seed;
    params.degeneracyTest = degeneracyTest;
    return estimateRelativeMotion(scene.points1, scene.points2, noArray(), params);
}

TEST(Rcme_PlaneParallax, a_dominant_plane_with_points_off_it_keeps_its_f_without_k)
{
    for (int seed = 0; seed < 3; ++seed) {
        const PlaneScene scene = planeWithPointsOffIt(40, seed);
        const Report r = withoutK(scene, seed);
        ASSERT_EQ(r.status, STATUS_SUCCESS) << seed << ": " << r.message;
        EXPECT_LT(rmsSampsonOffThePlane(r.F, seed), 3.0) << seed;
        // The loop's F stands without the degeneracy test too (that GRIC prefers the homography
        // on these scenes is the next test's).
        ASSERT_EQ(withoutK(scene, seed, false).status, STATUS_SUCCESS) << seed;
    }
}

#ifdef RCME_STANDALONE_TESTS
cv::rcme::detail::TwoViewData twoViewData(const PlaneScene& scene)
{
    cv::rcme::detail::TwoViewData data;
    for (int i = 0; i < scene.points1.rows; ++i) {
        data.points1.emplace_back(scene.points1.at<double>(i, 0), scene.points1.at<double>(i, 1));
        data.points2.emplace_back(scene.points2.at<double>(i, 0), scene.points2.at<double>(i, 1));
    }
    data.sigma = 1.0;
    data.threshold = 1.96;
    return data;
}

TEST(Rcme_PlaneParallax, the_screen_finds_the_plane_of_f_among_a_wider_band)
{
    // The plane's 230 correspondences are nearly all that the true F holds, but fewer than half of
    // the candidates when the method's band (its mask) takes in all 500: the screen's samples,
    // drawn among F's points, find the plane every time (drawn among all candidates, 50 of them
    // held four plane points with probability 0.9: 2 of these 20 scenes were missed).
    for (int seed = 0; seed < 20; ++seed) {
        const PlaneScene scene = planeWithPointsOffIt(0, seed);
        Eigen::Matrix3d F;
        cv::cv2eigen(Mat(scene.F), F);
        const std::vector<uchar> everyPoint(static_cast<size_t>(scene.points1.rows), 1);
        EXPECT_TRUE(cv::rcme::detail::compareWithHomography(twoViewData(scene), F, everyPoint)
                        .homographyExplainsInliers)
            << seed;
    }
}

// The homography test's quick search (estimation/homography_search.cpp) finds the plane among
// more outliers than plane points, within 1 px RMS over the view of the true plane's transfer
// (0.2-0.5 px on these seeds; cv::findHomography about 0.6): it decides alone where its
// homography loses clearly, so a search that misses planes would hide them.
TEST(Rcme_PlaneParallax, the_quick_search_finds_the_plane_among_more_outliers)
{
    const Matx33d K(500, 0, 320, 0, 500, 240, 0, 0, 1);
    const double transferThreshold = 1.0 * std::sqrt(2.0 * 5.991);
    for (int seed = 0; seed < 10; ++seed) {
        const PlaneScene scene = planeWithPointsOffIt(0, seed);
        // The scene's plane: n.X = 8 in camera 1, so X2 = (R + t n^T / 8) X1.
        cv::RNG rng(static_cast<uint64>(seed) + 11);
        Matx33d R;
        Rodrigues(Vec3d(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1)), R);
        const Vec3d t(1.0, 0.1, 0.2), normal = normalize(Vec3d(0.1, -0.2, 1.0));
        const Matx33d truth = K * (R + t * normal.t() * (1.0 / 8.0)) * K.inv();
        std::vector<Point2d> p1, p2;
        for (int i = 0; i < scene.points1.rows; ++i) {
            p1.emplace_back(scene.points1.at<double>(i, 0), scene.points1.at<double>(i, 1));
            p2.emplace_back(scene.points2.at<double>(i, 0), scene.points2.at<double>(i, 1));
        }
        Eigen::Matrix3d found;
        ASSERT_TRUE(cv::rcme::detail::dominantHomography(p1, p2, transferThreshold, found)) << seed;
        Matx33d H;
        eigen2cv(found, H);
        double squared = 0;
        int probes = 0;
        for (double x = 0; x <= 640; x += 64)
            for (double y = 0; y <= 480; y += 48) {
                const Vec3d a = H * Vec3d(x, y, 1), b = truth * Vec3d(x, y, 1);
                const double dx = a[0] / a[2] - b[0] / b[2], dy = a[1] / a[2] - b[1] / b[2];
                squared += dx * dx + dy * dy;
                ++probes;
            }
        EXPECT_LT(std::sqrt(squared / probes), 1.0) << "seed " << seed;
    }
    // Too few correspondences for a homography, or views of different sizes: no answer.
    const std::vector<Point2d> three = {{0, 0}, {100, 0}, {0, 100}},
                               four = {{0, 0}, {100, 0}, {0, 100}, {100, 100}};
    Eigen::Matrix3d H;
    EXPECT_FALSE(cv::rcme::detail::dominantHomography(three, three, transferThreshold, H));
    EXPECT_FALSE(cv::rcme::detail::dominantHomography(four, three, transferThreshold, H));
    EXPECT_TRUE(cv::rcme::detail::dominantHomography(four, four, transferThreshold, H));
    EXPECT_LT((H - Eigen::Matrix3d::Identity()).norm(), 1e-9);
}

// The four-point homography from the two projective bases: exact on four points of a known H
// (perspective, a mirror included), none where three of the four lie on a line in either image.
TEST(Rcme_PlaneParallax, the_four_point_homography_is_exact_and_refuses_collinear_points)
{
    cv::RNG rng(5);
    const int sample[4] = {0, 1, 2, 3};
    for (int trial = 0; trial < 50; ++trial) {
        Eigen::Matrix3d truth;
        truth << rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0), rng.uniform(-1.0, 1.0),
            rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0), rng.uniform(-1.0, 1.0),
            rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 1;
        std::vector<Point2d> from, to;
        for (int k = 0; k < 4; ++k) {
            const Point2d p(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5));
            const Eigen::Vector3d x = truth * Eigen::Vector3d(p.x, p.y, 1);
            from.push_back(p);
            to.emplace_back(x.x() / x.z(), x.y() / x.z());
        }
        Eigen::Matrix3d H;
        ASSERT_TRUE(cv::rcme::detail::homographyOfFour(from, to, sample, H)) << trial;
        EXPECT_DOUBLE_EQ(H(2, 2), 1.0);
        for (int k = 0; k < 4; ++k) {
            const Eigen::Vector3d x = H * Eigen::Vector3d(from[k].x, from[k].y, 1);
            EXPECT_NEAR(x.x() / x.z(), to[k].x, 1e-8 * (1 + std::abs(to[k].x))) << trial;
            EXPECT_NEAR(x.y() / x.z(), to[k].y, 1e-8 * (1 + std::abs(to[k].y))) << trial;
        }
        // Every triple on a line in turn, in the first image and then in the second.
        for (int image = 0; image < 2; ++image)
            for (int left = 0; left < 4; ++left) {
                std::vector<Point2d> a = from, b = to;
                std::vector<Point2d>& moved = image == 0 ? a : b;
                const int i = (left + 1) % 4, j = (left + 2) % 4, k = (left + 3) % 4;
                moved[static_cast<size_t>(k)] =
                    moved[static_cast<size_t>(i)] +
                    0.37 * (moved[static_cast<size_t>(j)] - moved[static_cast<size_t>(i)]);
                EXPECT_FALSE(cv::rcme::detail::homographyOfFour(a, b, sample, H))
                    << trial << ", image " << image << ", triple without " << left;
            }
    }
}

// The vectorized transfer test (the AVX2 clone where the machine has it) marks the points the
// per-point expression does, on any subrange, points near the threshold's edge included.
TEST(Rcme_PlaneParallax, the_transfer_kernel_marks_what_the_per_point_test_does)
{
    cv::RNG rng(11);
    Eigen::Matrix3d H;
    H << 0.97, 0.05, 12.0, -0.03, 1.02, -7.0, 2e-5, -3e-5, 1;
    const double threshold2 = 2.5 * 2.5;
    std::vector<Point2d> from, to;
    for (int i = 0; i < 203; ++i) {
        const Point2d p(rng.uniform(0.0, 1280.0), rng.uniform(0.0, 960.0));
        const Eigen::Vector3d x = H * Eigen::Vector3d(p.x, p.y, 1);
        // Offsets from well inside to well outside the threshold, many within a hair of it.
        const double distance =
            i % 4 == 0 ? 2.5 * (1 + rng.uniform(-1e-12, 1e-12)) : rng.uniform(0.0, 6.0);
        const double angle = rng.uniform(0.0, 2 * CV_PI);
        from.push_back(p);
        to.emplace_back(x.x() / x.z() + distance * std::cos(angle),
                        x.y() / x.z() + distance * std::sin(angle));
    }
    const auto perPoint = [&](size_t i) {
        const Eigen::Vector3d x = H * Eigen::Vector3d(from[i].x, from[i].y, 1.0);
        const double dx = x.x() / x.z() - to[i].x, dy = x.y() / x.z() - to[i].y;
        return dx * dx + dy * dy <= threshold2;
    };
    int nearHeld = 0, nearNotHeld = 0;
    for (const size_t begin : {size_t(0), size_t(5), size_t(170)}) {
        const size_t end = std::min(from.size(), begin + cv::rcme::detail::kTransferBlock);
        uchar held[cv::rcme::detail::kTransferBlock];
        const int count =
            cv::rcme::detail::markTransferredWithin(H, from, to, begin, end, threshold2, held);
        int expected = 0;
        for (size_t i = begin; i < end; ++i) {
            EXPECT_EQ(held[i - begin] != 0, perPoint(i)) << "point " << i;
            expected += perPoint(i);
            nearHeld += i % 4 == 0 && perPoint(i);
            nearNotHeld += i % 4 == 0 && !perPoint(i);
        }
        EXPECT_EQ(count, expected) << "from " << begin;
    }
    // Points at the edge fall on either side of it.
    EXPECT_GT(nearHeld, 0);
    EXPECT_GT(nearNotHeld, 0);
}

// The quick search's count stops reading once a sample cannot beat the best: whatever the best,
// a count above it is exact (the search keeps that sample with it) and one that is not stays at or
// below it (the sample is dropped), wherever the held points lie in the list.
TEST(Rcme_PlaneParallax, the_quick_search_count_is_exact_wherever_it_can_beat_the_best)
{
    cv::RNG rng(7);
    for (int trial = 0; trial < 20; ++trial) {
        Eigen::Matrix3d H;
        H << 1 + rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-20.0, 20.0),
            rng.uniform(-0.1, 0.1), 1 + rng.uniform(-0.1, 0.1), rng.uniform(-20.0, 20.0),
            rng.uniform(-1e-4, 1e-4), rng.uniform(-1e-4, 1e-4), 1;
        const int n = 40 + trial;
        std::vector<Point2d> from, to;
        int held = 0;
        for (int i = 0; i < n; ++i) {
            const Point2d p(rng.uniform(0.0, 640.0), rng.uniform(0.0, 480.0));
            const Eigen::Vector3d x = H * Eigen::Vector3d(p.x, p.y, 1);
            Point2d q(x.x() / x.z(), x.y() / x.z());
            // Held points where the trial puts them: first, last, or every third.
            const bool onH = trial % 3 == 0 ? i < n / 2 : trial % 3 == 1 ? i >= n / 2 : i % 3 == 0;
            if (!onH)
                q += Point2d(rng.uniform(5.0, 50.0), rng.uniform(5.0, 50.0));
            held += onH;
            from.push_back(p);
            to.push_back(q);
        }
        const double threshold2 = 4.0;
        for (int toBeat = -1; toBeat <= n + 1; ++toBeat) {
            const int counted =
                cv::rcme::detail::transferredUnlessBeaten(from, to, H, threshold2, toBeat);
            if (held > toBeat)
                EXPECT_EQ(counted, held) << "trial " << trial << ", best " << toBeat;
            else
                EXPECT_LE(counted, toBeat) << "trial " << trial << ", best " << toBeat;
        }
    }
}

TEST(Rcme_PlaneParallax, the_homography_explains_the_inliers_of_these_scenes)
{
    // The scenes above reach the plane and parallax decision: Torr's GRIC prefers the homography
    // to the returned F on its own inliers, which before this decision meant "degenerate". Which
    // seeds do depends on the build's rounding (the returned F and its inliers): with GCC's
    // vectorized residual loops all three, in the sanitizer builds (baseline loops, clang) seed 1
    // alone; at least one must, or the test above no longer tests the decision.
    int reached = 0;
    for (int seed = 0; seed < 3; ++seed) {
        const PlaneScene scene = planeWithPointsOffIt(40, seed);
        const Report r = withoutK(scene, seed);
        ASSERT_EQ(r.status, STATUS_SUCCESS) << seed;
        const cv::rcme::detail::TwoViewData data = twoViewData(scene);
        Eigen::Matrix3d F;
        cv::cv2eigen(Mat(r.F), F);
        std::vector<uchar> mask(r.mask.begin<uchar>(), r.mask.end<uchar>());
        reached += cv::rcme::detail::compareWithHomography(data, F, mask).homographyExplainsInliers;
    }
    EXPECT_GE(reached, 1);
}
#endif

TEST(Rcme_PlaneParallax, twenty_points_a_few_pixels_off_the_plane_fix_f_without_k)
{
    // 20 true points at 6-11 m (the plane is about 8 m away) among 130 outliers: of the 135-140
    // correspondences off the plane, the true epipole's support is at the edge of the chance
    // bound. A chance bound over the 500 epipoles tried (12 agreeing points here) returned 15 of
    // these 20 seeds with a right F; one over every pair (13-14) returned 7 and flagged the others
    // degenerate. The truncated cost without K leaves 14, and plane and parallax on a dominant
    // homography 13 (11 in the sanitizer builds' rounding: baseline loops, clang): it also runs
    // where F wins GRIC, and flags two more at the chance bound's edge (doc/f_only.md, "A dominant
    // homography without K"). Not every success is right: in the sanitizer builds seed 15 once
    // returned an F 5.4 px off with success, an undetected failure of the kind the F-only suite
    // counts; at most one is allowed here.
    const DepthRange nearThePlane{6.0, 11.0};
    int right = 0, wrong = 0;
    for (int seed = 0; seed < 20; ++seed) {
        const PlaneScene scene = planeWithPointsOffIt(20, seed, nearThePlane, 150, 300);
        const Report r = withoutK(scene, seed);
        if (r.status != STATUS_SUCCESS)
            continue;
        if (rmsSampsonOffThePlane(r.F, seed, nearThePlane) < 5.0)
            ++right;
        else
            ++wrong;
    }
    EXPECT_GE(right, 11);
    EXPECT_LE(wrong, 1);
}

TEST(Rcme_PlaneParallax, a_plane_with_no_point_off_it_stays_degenerate_and_says_why)
{
    for (int seed = 0; seed < 3; ++seed) {
        const PlaneScene scene = planeWithPointsOffIt(0, seed);
        const Report r = withoutK(scene, seed);
        ASSERT_EQ(r.status, STATUS_DEGENERATE_CONFIGURATION) << seed << ": " << r.message;
        EXPECT_NE(r.message.find("off its plane"), std::string::npos) << r.message;
        EXPECT_NE(r.message.find("chance"), std::string::npos) << r.message;
        ASSERT_EQ(r.rejectedF.size(), Size(3, 3)) << seed;
    }
}

} // namespace
} // namespace opencv_test
