// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The pure math under src/solvers/ and the scoring kernel, called directly (no RANSAC state).
// Internal (cv::rcme::detail), so standalone build only, like test_components.cpp.

#include "test_precomp.hpp"

#ifdef RCME_STANDALONE_TESTS

#include "geometry/epipolar.hpp"
#include "geometry/residual_bands.hpp"
#include "geometry/sampson_gradients.hpp"
#include "solvers/epipolar_null_space.hpp"
#include "solvers/essential_five_point.hpp"
#include "solvers/real_roots.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cstring>

namespace opencv_test {
namespace {

using namespace cv::rcme::detail;

/* The null space of M epipolar equations by elimination (the 7- and 8-point solvers') against
the one by QR (the 5-point solver's): orthonormal, solving the equations, the same space; both
turn down equations of which two coincide. */
template <int M> void expectNullSpacesAgree(cv::RNG& rng)
{
    for (int trial = 0; trial < 500; ++trial) {
        Eigen::Vector3d x1[M], x2[M];
        for (int k = 0; k < M; ++k) {
            x1[k] = Eigen::Vector3d(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), 1.0);
            x2[k] = Eigen::Vector3d(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), 1.0);
        }
        Eigen::Matrix<double, 9, 9 - M> byQr, byElimination;
        ASSERT_TRUE(epipolarNullSpace<M>(x1, x2, 1e-5, byQr)) << M << " equations, trial " << trial;
        ASSERT_TRUE(epipolarNullSpaceByElimination<M>(x1, x2, 1e-5, byElimination))
            << M << " equations, trial " << trial;
        const Eigen::Matrix<double, 9 - M, 9 - M> gram = byElimination.transpose() * byElimination;
        EXPECT_LT((gram - decltype(gram)::Identity()).norm(), 1e-12);
        for (int k = 0; k < M; ++k)
            for (int f = 0; f < 9 - M; ++f) {
                const Eigen::Matrix3d F =
                    Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(
                        byElimination.col(f).data());
                EXPECT_LT(std::abs(x2[k].dot(F * x1[k])), 1e-12)
                    << M << " equations, trial " << trial;
            }
        // The QR basis's part outside the elimination's space.
        EXPECT_LT((byQr - byElimination * (byElimination.transpose() * byQr)).norm(), 1e-9)
            << M << " equations, trial " << trial;

        x1[M - 1] = x1[M - 2];
        x2[M - 1] = x2[M - 2];
        EXPECT_FALSE(epipolarNullSpace<M>(x1, x2, 1e-5, byQr));
        EXPECT_FALSE(epipolarNullSpaceByElimination<M>(x1, x2, 1e-5, byElimination));
    }
}

TEST(Rcme_EpipolarNullSpace, elimination_spans_the_qr_null_space)
{
    cv::RNG rng(7);
    expectNullSpacesAgree<7>(rng);
    expectNullSpacesAgree<8>(rng);
}

//! Coefficients (ascending) of prod (x - roots[k]) times `scale`.
std::vector<double> fromRoots(const std::vector<double>& roots, double scale = 1.0)
{
    std::vector<double> p = {scale};
    for (double r : roots) {
        std::vector<double> next(p.size() + 1, 0.0);
        for (size_t i = 0; i < p.size(); ++i) {
            next[i + 1] += p[i];
            next[i] -= r * p[i];
        }
        p = next;
    }
    return p;
}

TEST(Rcme_RealRoots, finds_the_roots_of_a_product_of_factors)
{
    cv::RNG rng(3);
    for (int trial = 0; trial < 500; ++trial) {
        const int degree = 1 + trial % kMaxRootDegree;
        std::vector<double> roots;
        for (int k = 0; k < degree; ++k)
            roots.push_back(rng.uniform(-10.0, 10.0));
        std::sort(roots.begin(), roots.end());
        const std::vector<double> p = fromRoots(roots, rng.uniform(0.1, 100.0));
        double found[kMaxRootDegree];
        const int count = realRoots(p.data(), degree, found);
        // Roots closer than 1e-3 are allowed to merge into one.
        int distinct = 1;
        for (int k = 1; k < degree; ++k)
            distinct += roots[size_t(k)] - roots[size_t(k - 1)] > 1e-3;
        ASSERT_GE(count, distinct) << "trial " << trial;
        ASSERT_LE(count, degree);
        for (int k = 0; k < count; ++k) {
            double nearest = 1e300;
            for (double r : roots)
                nearest = std::min(nearest, std::abs(r - found[k]));
            EXPECT_LT(nearest, 1e-6) << "trial " << trial;
            if (k > 0)
                EXPECT_LT(found[k - 1], found[k]) << "increasing order";
        }
    }
}

TEST(Rcme_RealRoots, agrees_with_the_companion_matrix_on_random_polynomials)
{
    cv::RNG rng(5);
    int total = 0;
    for (int trial = 0; trial < 500; ++trial) {
        double p[kMaxRootDegree + 1];
        for (double& c : p)
            c = rng.gaussian(1.0);
        Eigen::Matrix<double, kMaxRootDegree, kMaxRootDegree> C;
        C.setZero();
        for (int i = 1; i < kMaxRootDegree; ++i)
            C(i, i - 1) = 1;
        for (int i = 0; i < kMaxRootDegree; ++i)
            C(i, kMaxRootDegree - 1) = -p[i] / p[kMaxRootDegree];
        const Eigen::EigenSolver<decltype(C)> eig(C, false);
        std::vector<double> expected;
        for (int i = 0; i < kMaxRootDegree; ++i)
            if (std::abs(eig.eigenvalues()(i).imag()) < 1e-9)
                expected.push_back(eig.eigenvalues()(i).real());
        std::sort(expected.begin(), expected.end());
        double found[kMaxRootDegree];
        const int count = realRoots(p, kMaxRootDegree, found);
        ASSERT_EQ(static_cast<size_t>(count), expected.size()) << "trial " << trial;
        for (int k = 0; k < count; ++k)
            EXPECT_NEAR(found[k], expected[size_t(k)], 1e-7 * (1 + std::abs(expected[size_t(k)])));
        total += count;
    }
    EXPECT_GT(total, 500); // random polynomials of degree 10 have real roots
}

TEST(Rcme_RealRoots, negligible_leading_coefficients_and_no_roots)
{
    // (x - 1)(x - 2) with a leading x^3 coefficient at the rounding level.
    const double p[] = {2.0, -3.0, 1.0, 1e-20};
    double found[kMaxRootDegree];
    ASSERT_EQ(realRoots(p, 3, found), 2);
    EXPECT_NEAR(found[0], 1.0, 1e-12);
    EXPECT_NEAR(found[1], 2.0, 1e-12);
    const double positive[] = {1.0, 0.0, 1.0}; // x^2 + 1
    EXPECT_EQ(realRoots(positive, 2, found), 0);
    const double constant[] = {1.0, 0.0};
    EXPECT_EQ(realRoots(constant, 1, found), 0);
    const double notFinite[] = {1.0, std::numeric_limits<double>::quiet_NaN()};
    EXPECT_EQ(realRoots(notFinite, 1, found), 0);
    const double doubleRoot[] = {1.0, -2.0, 1.0}; // (x - 1)^2
    ASSERT_EQ(realRoots(doubleRoot, 2, found), 1);
    EXPECT_NEAR(found[0], 1.0, 1e-7);
}

//! A random motion and five points in front of both cameras, as rays.
void randomProblem(cv::RNG& rng, Eigen::Matrix3d& E, Eigen::Vector3d q1[5], Eigen::Vector3d q2[5])
{
    const Eigen::Vector3d axis(rng.gaussian(1), rng.gaussian(1), rng.gaussian(1));
    const Eigen::Matrix3d R = Eigen::AngleAxisd(rng.uniform(0.0, 0.5), axis.normalized()).matrix();
    const Eigen::Vector3d t =
        Eigen::Vector3d(rng.gaussian(1), rng.gaussian(1), rng.gaussian(1)).normalized();
    E = skew(t) * R;
    for (int k = 0; k < 5; ++k) {
        Eigen::Vector3d X, Y;
        do {
            X = Eigen::Vector3d(rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0),
                                rng.uniform(3.0, 8.0));
            Y = R * X + t;
        } while (Y.z() <= 0.5);
        q1[k] = X / X.z();
        q2[k] = Y / Y.z();
    }
}

TEST(Rcme_EssentialFivePoint, the_true_essential_matrix_is_among_the_solutions)
{
    cv::RNG rng(11);
    int solutions = 0;
    for (int trial = 0; trial < 1000; ++trial) {
        Eigen::Matrix3d Etrue, E[kMaxFivePointSolutions];
        Eigen::Vector3d q1[5], q2[5];
        randomProblem(rng, Etrue, q1, q2);
        Etrue /= Etrue.norm();
        const int count = essentialFromFivePoints(q1, q2, E);
        ASSERT_GE(count, 1);
        ASSERT_LE(count, kMaxFivePointSolutions);
        solutions += count;
        double best = 1e300;
        for (int s = 0; s < count; ++s) {
            EXPECT_NEAR(E[s].norm(), 1.0, 1e-12);
            for (int k = 0; k < 5; ++k)
                EXPECT_LT(std::abs(q2[k].dot(E[s] * q1[k])), 1e-10);
            best = std::min({best, (E[s] - Etrue).norm(), (E[s] + Etrue).norm()});
        }
        EXPECT_LT(best, 1e-8) << "trial " << trial;
        // The truth puts every point in front of both cameras.
        EXPECT_TRUE(admitsCommonCheirality(Etrue, q1, q2, 5));
    }
    std::cout << "1000 samples, " << solutions << " solutions" << std::endl;
}

TEST(Rcme_EssentialFivePoint, degenerate_samples_give_no_solution)
{
    Eigen::Vector3d q1[5], q2[5];
    for (int k = 0; k < 5; ++k) {
        q1[k] = Eigen::Vector3d(0.1, 0.2, 1.0); // coincident in image 1
        q2[k] = Eigen::Vector3d(0.01 * k, 0.02 * k, 1.0);
    }
    Eigen::Matrix3d E[kMaxFivePointSolutions];
    EXPECT_EQ(essentialFromFivePoints(q1, q2, E), 0);
    q1[0] = Eigen::Vector3d::Zero(); // a zero ray
    EXPECT_EQ(essentialFromFivePoints(q1, q2, E), 0);
}

TEST(Rcme_Cheirality, points_split_between_twisted_pairs_admit_no_common_cheirality)
{
    cv::RNG rng(13);
    for (int trial = 0; trial < 100; ++trial) {
        Eigen::Matrix3d E;
        Eigen::Vector3d q1[5], q2[5];
        randomProblem(rng, E, q1, q2);
        ASSERT_TRUE(admitsCommonCheirality(E, q1, q2, 5));
        ASSERT_TRUE(admitsCommonCheirality(-E, q1, q2, 5)); // the sign of E does not matter
        // A point behind camera 2 only (its depths disagree in sign) splits the sample.
        const Eigen::Vector3d t = Eigen::Vector3d(E.col(0).cross(E.col(1))).normalized();
        Eigen::Vector3d flipped[5];
        std::copy(q2, q2 + 5, flipped);
        // The mirror of q2[0] in the epipolar plane through t keeps the epipolar constraint.
        const Eigen::Vector3d n = t.cross(q2[0]).normalized();
        flipped[0] = 2 * t.dot(q2[0]) * t - q2[0];
        ASSERT_LT(std::abs(flipped[0].dot(n)), 1e-12);
        EXPECT_FALSE(admitsCommonCheirality(E, q1, flipped, 5)) << "trial " << trial;
    }
}

TEST(Rcme_SampsonBand, counts_and_masks_as_the_distance_per_point)
{
    cv::RNG rng(19);
    for (int trial = 0; trial < 50; ++trial) {
        const size_t n = static_cast<size_t>(rng.uniform(1, 300));
        std::vector<Eigen::Vector2d> p1(n), p2(n);
        for (size_t i = 0; i < n; ++i) {
            p1[i] = Eigen::Vector2d(rng.uniform(0.0, 640.0), rng.uniform(0.0, 480.0));
            p2[i] = p1[i] + Eigen::Vector2d(rng.uniform(-20.0, 20.0), rng.uniform(-3.0, 3.0));
        }
        Eigen::Matrix3d F;
        F << 0, -1e-3, 0.2, 1e-3, 0, -0.3, -0.2, 0.3, rng.uniform(-2.0, 2.0);
        const double thresholdSquared = rng.uniform(0.5, 30.0);
        std::vector<uchar> mask(n, 7);
        const int count = countInSampsonBand(F, p1, p2, thresholdSquared, mask.data());
        int expected = 0;
        for (size_t i = 0; i < n; ++i) {
            const bool within = sampsonDistanceSquared(F, p1[i], p2[i]) <= thresholdSquared;
            expected += within;
            EXPECT_EQ(mask[i], within ? 1 : 0);
        }
        EXPECT_EQ(count, expected);
        EXPECT_EQ(countInSampsonBand(F, p1, p2, thresholdSquared), expected);
    }
    // A point at the epipole (|J| = 0) is never within the band.
    Eigen::Matrix3d F = skew(Eigen::Vector3d(0, 0, 1));
    const std::vector<Eigen::Vector2d> origin = {Eigen::Vector2d(0, 0)};
    EXPECT_EQ(countInSampsonBand(F, origin, origin, 1.0), 0);
}

// The fits' block kernels must give sampsonDistanceAndGradient's and sampsonDistanceSquared's
// values to the last bit (model_fit.cpp sums them in the same order, and the estimator's results
// may not depend on which form computed them): entries of every magnitude, a point at the epipole.
TEST(Rcme_SampsonBlocks, equal_the_per_point_functions_bit_for_bit)
{
    cv::RNG rng(23);
    constexpr int P = 7;
    for (int trial = 0; trial < 200; ++trial) {
        Eigen::Matrix3d F, dF[P];
        for (int e = 0; e < 9; ++e) {
            F(e / 3, e % 3) = rng.gaussian(1.0) * std::pow(10.0, -rng.uniform(0, 6));
            for (Eigen::Matrix3d& D : dF)
                D(e / 3, e % 3) = rng.gaussian(1.0) * std::pow(10.0, -rng.uniform(0, 6));
        }
        const int count = rng.uniform(1, kSampsonBlock + 1);
        double x1[kSampsonBlock], y1[kSampsonBlock], x2[kSampsonBlock], y2[kSampsonBlock];
        for (int i = 0; i < count; ++i) {
            x1[i] = rng.uniform(-100.0, 1300.0);
            y1[i] = rng.uniform(-100.0, 1000.0);
            x2[i] = rng.uniform(-100.0, 1300.0);
            y2[i] = rng.uniform(-100.0, 1000.0);
        }
        if (trial == 0) { // F's epipole at the origin of both images: J vanishes there
            F = skew(Eigen::Vector3d(0, 0, 1));
            x1[0] = y1[0] = x2[0] = y2[0] = 0.0;
        }
        double distance[kSampsonBlock], gradients[P * kSampsonBlock], squared[kSampsonBlock];
        uchar valid[kSampsonBlock];
        sampsonGradientsOfBlock(F, dF, P, x1, y1, x2, y2, count, distance, gradients, valid);
        sampsonDistancesSquaredOfBlock(F, x1, y1, x2, y2, count, squared);
        for (int i = 0; i < count; ++i) {
            const Eigen::Vector2d p1(x1[i], y1[i]), p2(x2[i], y2[i]);
            double d = 0;
            Eigen::Matrix<double, 1, P> g;
            const bool ok = sampsonDistanceAndGradient<P>(F, dF, p1, p2, d, g);
            ASSERT_EQ(valid[i] != 0, ok) << "trial " << trial << " point " << i;
            const double expectedSquared = sampsonDistanceSquared(F, p1, p2);
            EXPECT_EQ(std::memcmp(&squared[i], &expectedSquared, sizeof(double)), 0)
                << squared[i] << " " << expectedSquared;
            if (!ok)
                continue;
            EXPECT_EQ(std::memcmp(&distance[i], &d, sizeof(double)), 0) << distance[i] << " " << d;
            for (int k = 0; k < P; ++k)
                EXPECT_EQ(std::memcmp(&gradients[k * kSampsonBlock + i], &g[k], sizeof(double)), 0)
                    << "trial " << trial << " point " << i << " parameter " << k;
        }
    }
}

// accumulateNormalEquations sums each entry of J^T J and J^T r of a block in four partial sums
// (point j into sum j % 4), added to the running entry as (s0 + s1) + (s2 + s3): the same bits in
// both clones and on every machine. An invalid point comes as zeros and adds nothing.
TEST(Rcme_SampsonBlocks, normal_equations_sum_in_four_lanes_per_block)
{
    cv::RNG rng(41);
    for (int P : {5, 7}) {
        std::vector<double> normal(static_cast<size_t>(P * (P + 1)), 0.0);
        std::vector<double> expected(normal.size(), 0.0);
        for (int blockIndex = 0; blockIndex < 20; ++blockIndex) {
            const int count = rng.uniform(1, kSampsonBlock + 1);
            double distance[kSampsonBlock], gradients[7 * kSampsonBlock];
            for (int j = 0; j < count; ++j) {
                const bool valid = rng.uniform(0, 10) > 0;
                distance[j] = valid ? rng.gaussian(1.0) * std::pow(10.0, rng.uniform(-3, 3)) : 0.0;
                for (int k = 0; k < P; ++k)
                    gradients[k * kSampsonBlock + j] =
                        valid ? rng.gaussian(1.0) * std::pow(10.0, rng.uniform(-6, 6)) : 0.0;
            }
            accumulateNormalEquations(P, distance, gradients, count, normal.data());
            for (int a = 0; a < P; ++a)
                for (int b = a; b <= P; ++b) {
                    double lanes[4] = {0.0, 0.0, 0.0, 0.0};
                    for (int j = 0; j < count; ++j)
                        lanes[j % 4] += gradients[a * kSampsonBlock + j] *
                                        (b < P ? gradients[b * kSampsonBlock + j] : distance[j]);
                    expected[static_cast<size_t>(a * (P + 1) + b)] +=
                        (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
                }
        }
        for (int a = 0; a < P; ++a)
            for (int b = a; b <= P; ++b) {
                const size_t e = static_cast<size_t>(a * (P + 1) + b);
                EXPECT_EQ(std::memcmp(&normal[e], &expected[e], sizeof(double)), 0)
                    << "P " << P << " entry " << a << ", " << b << ": " << normal[e] << " "
                    << expected[e];
            }
    }
}

// markWithinSampsonDistance (the final fit's band) is the per-point test on sampsonDistanceSquared,
// point for point, on points within a few ulps of the threshold too.
TEST(Rcme_SampsonBlocks, the_band_marks_as_the_distance_per_point)
{
    cv::RNG rng(29);
    for (int trial = 0; trial < 50; ++trial) {
        Eigen::Matrix3d F;
        for (int e = 0; e < 9; ++e)
            F(e / 3, e % 3) = rng.gaussian(1.0) * std::pow(10.0, -rng.uniform(0, 6));
        const int n = rng.uniform(0, 300);
        std::vector<Eigen::Vector2d> p1(n), p2(n);
        for (int i = 0; i < n; ++i) {
            p1[i] = Eigen::Vector2d(rng.uniform(-100.0, 1300.0), rng.uniform(-100.0, 1000.0));
            p2[i] = Eigen::Vector2d(rng.uniform(-100.0, 1300.0), rng.uniform(-100.0, 1000.0));
        }
        if (n > 0 && trial == 0) { // at the epipole of both images: infinite distance
            F = skew(Eigen::Vector3d(0, 0, 1));
            p1[0] = p2[0] = Eigen::Vector2d::Zero();
        }
        // A threshold equal to one point's distance: strictly below it is outside.
        const double thresholdSquared =
            n > 1 ? sampsonDistanceSquared(F, p1[1], p2[1]) : rng.uniform(0.1, 10.0);
        std::vector<uchar> within(3, 7); // a reused buffer of another size
        markWithinSampsonDistance(F, p1, p2, thresholdSquared, within);
        ASSERT_EQ(within.size(), static_cast<size_t>(n));
        for (int i = 0; i < n; ++i)
            EXPECT_EQ(within[i], sampsonDistanceSquared(F, p1[i], p2[i]) < thresholdSquared ? 1 : 0)
                << "trial " << trial << " point " << i;
    }
}

// Hartley's normalization of both images in one pass gives the bits of the textbook computation,
// one image at a time.
TEST(Rcme_Normalization, both_images_at_once_equal_one_at_a_time)
{
    const auto reference = [](const std::vector<Eigen::Vector2d>& points,
                              const std::vector<int>& indices, Eigen::Matrix3d& T) {
        Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
        for (int i : indices)
            centroid += points[static_cast<size_t>(i)];
        centroid /= static_cast<double>(indices.size());
        double meanDistance = 0;
        for (int i : indices)
            meanDistance += (points[static_cast<size_t>(i)] - centroid).norm();
        meanDistance /= static_cast<double>(indices.size());
        if (!(meanDistance > 1e-9 * (1.0 + centroid.norm())))
            return false;
        const double scale = std::sqrt(2.0) / meanDistance;
        T << scale, 0, -scale * centroid.x(), 0, scale, -scale * centroid.y(), 0, 0, 1;
        return true;
    };
    cv::RNG rng(31);
    for (int trial = 0; trial < 40; ++trial) {
        const int n = rng.uniform(1, 2000);
        std::vector<Eigen::Vector2d> p1(n), p2(n);
        for (int i = 0; i < n; ++i) {
            p1[i] = Eigen::Vector2d(rng.uniform(-100.0, 1300.0), rng.uniform(-100.0, 1000.0));
            p2[i] = trial == 1 ? Eigen::Vector2d(5, 5) // coincident points: no normalization
                               : Eigen::Vector2d(rng.uniform(0.0, 4000.0), rng.uniform(0.0, 3.0));
        }
        std::vector<int> indices;
        for (int i = 0; i < n; ++i)
            if (rng.uniform(0, 3) > 0)
                indices.push_back(i);
        if (indices.empty())
            indices.push_back(0);
        Eigen::Matrix3d T1, T2, R1, R2;
        const bool expected = reference(p1, indices, R1) & reference(p2, indices, R2);
        ASSERT_EQ(normalizingTransforms(p1, p2, indices, T1, T2), expected) << "trial " << trial;
        if (!expected)
            continue;
        EXPECT_EQ(std::memcmp(T1.data(), R1.data(), sizeof(T1)), 0) << "trial " << trial;
        EXPECT_EQ(std::memcmp(T2.data(), R2.data(), sizeof(T2)), 0) << "trial " << trial;
    }
}

} // namespace
} // namespace opencv_test

#endif // RCME_STANDALONE_TESTS
