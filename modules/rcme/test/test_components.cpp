// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The framework's components one by one. They are internal (cv::rcme::detail), so these tests
// need the module's objects linked in, which only the standalone build does; inside an OpenCV
// build the shared library hides them.

#include "test_precomp.hpp"

#ifdef RCME_STANDALONE_TESTS

#include "framework/candidate_set.hpp"
#include "framework/component_factories.hpp"
#include "framework/model_space.hpp"
#include "framework/rival_motions.hpp"
#include "geometry/covariance_combination.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/motion_parameterization.hpp"
#include "geometry/residual_bands.hpp"
#include "geometry/statistics.hpp"
#include "test_internal_helpers.hpp"

#include <opencv2/core/eigen.hpp>

#include <algorithm>
#include <limits>

namespace opencv_test {
namespace {

using namespace cv::rcme::detail;

SyntheticScene noiseFreeScene(int seed, double sigma = 0.0)
{
    SceneParams sp;
    sp.kind = SCENE_GENERIC;
    sp.sigma = sigma;
    sp.inlierRatio = 1.0;
    sp.numPoints = 100;
    sp.seed = seed;
    return generateScene(sp);
}

Eigen::Matrix3d trueF(const SyntheticScene& scene)
{
    Eigen::Matrix3d F;
    cv2eigen(scene.F, F);
    return normalizeFundamental(F);
}

TEST(Rcme_EightPointSolver, exact_on_noise_free_data)
{
    for (int seed = 0; seed < 10; ++seed) {
        const SyntheticScene scene = noiseFreeScene(seed);
        for (bool calibrated : {false, true}) {
            const TwoViewData data = sceneData(scene, calibrated);
            const std::vector<int> sample = {0, 11, 22, 33, 44, 55, 66, 77};
            for (bool essential : {false, true}) {
                std::vector<Model> models;
                auto solver = createEightPointSolver(essential);
                ASSERT_EQ(solver->estimate(data, sample, models), 1);
                EXPECT_LT((models[0].F - trueF(scene)).norm(), 1e-6) << "seed " << seed;
                EXPECT_EQ(models[0].essential().isZero(), !(essential && calibrated));
                for (size_t i = 0; i < data.points1.size(); ++i)
                    EXPECT_LT(sampsonDistanceSquared(models[0].F, data.points1[i], data.points2[i]),
                              1e-10);
            }
        }
    }
}

TEST(Rcme_EightPointSolver, rejects_degenerate_samples)
{
    TwoViewData data;
    for (int i = 0; i < 8; ++i) {
        data.points1.emplace_back(100.0, 100.0); // coincident
        data.points2.emplace_back(10.0 * i, 5.0 * i);
    }
    std::vector<Model> models;
    auto solver = createEightPointSolver(false);
    const std::vector<int> sample = {0, 1, 2, 3, 4, 5, 6, 7};
    EXPECT_EQ(solver->estimate(data, sample, models), 0);
    for (int i = 0; i < 8; ++i) // collinear in both images
        data.points1[static_cast<size_t>(i)] = Eigen::Vector2d(3.0 * i, 2.0 * i + 1);
    EXPECT_EQ(solver->estimate(data, sample, models), 0);
    EXPECT_TRUE(solver->isOverParameterized());
}

TEST(Rcme_UniformSampler, distinct_in_range_deterministic_and_uniform)
{
    const int n = 20, m = 8;
    auto sampler = createUniformSampler(n, m, 123);
    auto same = createUniformSampler(n, m, 123);
    auto other = createUniformSampler(n, m, 124);
    std::vector<int> counts(n, 0), a, b, c;
    int differing = 0;
    const int draws = 5000;
    for (int it = 0; it < draws; ++it) {
        sampler->generateSample(it, a);
        same->generateSample(it, b);
        other->generateSample(it, c);
        ASSERT_EQ(a, b);
        differing += a != c;
        std::vector<int> sorted = a;
        std::sort(sorted.begin(), sorted.end());
        ASSERT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
        for (int i : a) {
            ASSERT_GE(i, 0);
            ASSERT_LT(i, n);
            ++counts[static_cast<size_t>(i)];
        }
    }
    EXPECT_GT(differing, draws * 9 / 10);
    // Each index is drawn with probability m/n: expected 2000, sd ~35.
    for (int count : counts)
        EXPECT_NEAR(count, draws * m / n, 200);
    // The sample of an iteration does not depend on which iterations came before.
    sampler->generateSample(4321, a);
    auto fresh = createUniformSampler(n, m, 123);
    fresh->generateSample(4321, b);
    EXPECT_EQ(a, b);
}

TEST(Rcme_Termination, adaptive_bound_and_exact_count)
{
    auto adaptive = createAdaptiveTermination(0.99, 5000, 8);
    EXPECT_EQ(adaptive->iterationBound(), 5000);
    Score score;
    score.inlierCount = 50; // w = 0.5: log(0.01) / log(1 - 2^-8) = 1176.6
    adaptive->update(score, 100);
    EXPECT_EQ(adaptive->iterationBound(), 1177);
    score.inlierCount = 10; // a worse ratio never raises the bound
    adaptive->update(score, 100);
    EXPECT_EQ(adaptive->iterationBound(), 1177);
    score.inlierCount = 100;
    adaptive->update(score, 100);
    EXPECT_EQ(adaptive->iterationBound(), 0);

    // Only a fraction q of the clean samples assumed good: log(0.01) / log(1 - 0.25 * 2^-8).
    auto cautious = createAdaptiveTermination(0.99, 5000, 8, 0.25);
    score.inlierCount = 50;
    cautious->update(score, 100);
    EXPECT_EQ(cautious->iterationBound(), 4714);
    score.inlierCount = 100; // every sample clean, a quarter of them good: log(0.01) / log(0.75)
    cautious->update(score, 100);
    EXPECT_EQ(cautious->iterationBound(), 17);

    auto exact = createExactTermination(250);
    exact->update(score, 100);
    EXPECT_EQ(exact->iterationBound(), 250);
}

// Central differences of the Sampson distance along each tangent direction.
template <class ApplyF, int P>
void expectGradientMatchesFiniteDifferences(const Eigen::Matrix3d& F, const Eigen::Matrix3d* dF,
                                            ApplyF applyAt, const TwoViewData& data)
{
    for (size_t i = 0; i < data.points1.size(); i += 7) {
        double d = 0;
        Eigen::Matrix<double, 1, P> g;
        ASSERT_TRUE(sampsonDistanceAndGradient<P>(F, dF, data.points1[i], data.points2[i], d, g));
        for (int k = 0; k < P; ++k) {
            const double h = 1e-6;
            Eigen::Matrix<double, P, 1> step = Eigen::Matrix<double, P, 1>::Zero();
            step(k) = h;
            double plus = 0, minus = 0;
            Eigen::Matrix<double, 1, P> unused;
            const Eigen::Matrix3d Fp = applyAt(step), Fm = applyAt(-step);
            sampsonDistanceAndGradient<P>(Fp, dF, data.points1[i], data.points2[i], plus, unused);
            sampsonDistanceAndGradient<P>(Fm, dF, data.points1[i], data.points2[i], minus, unused);
            const double numeric = (plus - minus) / (2 * h);
            // Pixel-unit F makes these derivatives large (~1e6); second-order terms of the central
            // difference leave a relative error of a few 1e-5, a wrong derivative is off by O(1).
            EXPECT_NEAR(g(k), numeric, 2e-4 * (1 + std::abs(numeric)))
                << "point " << i << " k " << k;
        }
    }
}

// MSAC's truncated cost: each squared Sampson distance capped at 1.5 thresholds, in units of the
// threshold squared; the inliers and the candidate test are the count's band.
TEST(Rcme_TruncatedCostScorer, sums_the_capped_distances_and_counts_the_band)
{
    const SyntheticScene s = testScene(SCENE_GENERIC, 3, 0.5, 1.0, 300);
    const TwoViewData data = sceneData(s, false, /*inliersOnly=*/false);
    const double t2 = data.threshold * data.threshold;
    Model model;
    model.F = trueF(s);
    model.F(0, 2) += 1e-4 * model.F.norm(); // off the truth: distances of every size
    double cost = 0;
    int inliers = 0;
    for (size_t i = 0; i < data.points1.size(); ++i) {
        const double d2 = sampsonDistanceSquared(model.F, data.points1[i], data.points2[i]);
        cost += std::min(d2, 2.25 * t2);
        inliers += d2 <= t2;
    }
    ASSERT_GT(inliers, 20);
    ASSERT_LT(inliers, 250);
    std::unique_ptr<Scorer> scorer = createTruncatedCostScorer(data, 7, 1000);
    const Score score = scorer->evaluate(data, model);
    EXPECT_NEAR(score.value, cost / t2, 1e-9 * cost / t2);
    EXPECT_EQ(score.inlierCount, inliers);
    EXPECT_TRUE(score.isCandidate);
    std::vector<uchar> mask;
    scorer->classify(data, model, mask);
    EXPECT_EQ(countNonZero(mask), inliers);
    EXPECT_EQ(countInSampsonBand(model.F, data.points1, data.points2, t2), inliers);

    // A hypothesis dominated by a candidate of lower cost and more inliers stops early, with no
    // candidate; one that is not is read to the end.
    CandidateFront front;
    HypothesisBar bar;
    bar.inliersThatMatter = static_cast<int>(data.size()) + 1;
    bar.front = &front;
    front.steps = {{score.value / 2, static_cast<int>(data.size())}};
    int read = 0;
    const Score stopped = scorer->evaluateUpTo(data, model, bar, read);
    EXPECT_LT(read, static_cast<int>(data.size()));
    EXPECT_FALSE(stopped.isCandidate);
    front.steps = {{score.value / 2, inliers - 1}};
    const Score whole = scorer->evaluateUpTo(data, model, bar, read);
    EXPECT_EQ(read, static_cast<int>(data.size()));
    EXPECT_EQ(whole.value, score.value);
    EXPECT_EQ(whole.inlierCount, inliers);
}

// The candidate set decides by its front's steps, which the loop hands to the scorers: they refuse
// exactly what some candidate offered so far beats in both score and inlier count.
TEST(Rcme_CandidateSet, its_front_refuses_what_it_refuses)
{
    const std::vector<std::pair<double, int>> offered = {
        {-3.0, 40}, {-5.0, 30}, {-1.0, 60}, {-4.0, 45}, {-2.0, 45}, {-6.0, 10}, {-1.0, 70}};
    CandidateSet set;
    for (const auto& [value, inliers] : offered) {
        Score score;
        score.value = value;
        score.inlierCount = inliers;
        set.add(Model(), score);
    }
    // The front: (-6, 10), (-5, 30), (-4, 45), (-1, 70); (-3, 40), (-2, 45), (-1, 60) are beaten.
    const std::vector<std::pair<double, int>> steps = {
        {-6.0, 10}, {-5.0, 30}, {-4.0, 45}, {-1.0, 70}};
    EXPECT_EQ(set.front().steps, steps);
    for (double value = -7.0; value <= 0.0; value += 0.5)
        for (int inliers = 0; inliers <= 80; inliers += 5) {
            Score score;
            score.value = value;
            score.inlierCount = inliers;
            const bool beaten = std::any_of(offered.begin(), offered.end(), [&](const auto& c) {
                return c.first <= value && c.second >= inliers;
            });
            CandidateSet copy = set;
            EXPECT_EQ(!copy.add(Model(), score), beaten) << value << " " << inliers;
            EXPECT_EQ(set.front().mostInliersAtOrBelow(value) >= inliers, beaten)
                << value << " " << inliers;
        }
    Score undefined;
    undefined.value = std::numeric_limits<double>::quiet_NaN();
    undefined.inlierCount = 1;
    EXPECT_EQ(set.front().mostInliersAtOrBelow(undefined.value), -1);
    EXPECT_TRUE(set.add(Model(), undefined)); // beaten by no member, and it makes no step
    EXPECT_EQ(set.front().steps, steps);
}

TEST(Rcme_Parameterization, motion_jacobian_matches_finite_differences)
{
    const SyntheticScene scene = noiseFreeScene(3, 1.0);
    const TwoViewData data = sceneData(scene, true);
    Eigen::Matrix3d R;
    Eigen::Vector3d t;
    cv2eigen(scene.R, R);
    cv2eigen(scene.t, t);
    const MotionTangent tangent(R, t);
    Eigen::Matrix3d dE[5], dF[5];
    tangent.essentialDerivatives(dE);
    for (int k = 0; k < 5; ++k)
        dF[k] = data.Kinv.transpose() * dE[k] * data.Kinv;
    auto applyAt = [&](const Eigen::Matrix<double, 5, 1>& theta) {
        Eigen::Matrix3d Rt;
        Eigen::Vector3d tt;
        tangent.apply(theta, Rt, tt);
        return Eigen::Matrix3d(data.Kinv.transpose() * skew(tt) * Rt * data.Kinv);
    };
    const Eigen::Matrix3d F = applyAt(Eigen::Matrix<double, 5, 1>::Zero());
    expectGradientMatchesFiniteDifferences<decltype(applyAt), 5>(F, dF, applyAt, data);
}

TEST(Rcme_Parameterization, fundamental_jacobian_matches_finite_differences)
{
    const SyntheticScene scene = noiseFreeScene(4, 1.0);
    const TwoViewData data = sceneData(scene, false);
    const FundamentalTangent tangent(trueF(scene));
    EXPECT_LT((normalizeFundamental(tangent.compose()) - trueF(scene)).norm(), 1e-9);
    Eigen::Matrix3d dF[7];
    tangent.derivatives(dF);
    auto applyAt = [&](const Eigen::Matrix<double, 7, 1>& theta) { return tangent.apply(theta); };
    expectGradientMatchesFiniteDifferences<decltype(applyAt), 7>(tangent.compose(), dF, applyAt,
                                                                 data);
}

// The tangent at a step, taken from the step's rotated factors (FundamentalTangent::moved), is
// the one the SVD of the stepped F gives: the same F, rotations for U and V, s in [0, 1], and the
// same derivatives up to the signs of the null-space columns (compared through dF's effect on F).
// A step that takes s past 1 or below 0 falls back to the SVD and still gives an ordered tangent.
TEST(Rcme_Parameterization, a_moved_fundamental_tangent_is_the_svd_of_the_stepped_f)
{
    const SyntheticScene scene = noiseFreeScene(4, 1.0);
    const FundamentalTangent tangent(trueF(scene));
    cv::RNG rng(7);
    for (int trial = 0; trial < 50; ++trial) {
        Eigen::Matrix<double, 7, 1> theta;
        for (int k = 0; k < 7; ++k)
            theta(k) = rng.gaussian(trial < 40 ? 0.05 : 1.0);
        const FundamentalTangent moved = tangent.moved(theta);
        const FundamentalTangent bySvd(tangent.apply(theta));
        EXPECT_LT(
            (normalizeFundamental(moved.compose()) - normalizeFundamental(tangent.apply(theta)))
                .norm(),
            1e-12)
            << "trial " << trial;
        EXPECT_NEAR(moved.s, bySvd.s, 1e-12) << "trial " << trial;
        EXPECT_GE(moved.s, 0.0);
        EXPECT_LE(moved.s, 1.0);
        EXPECT_NEAR(moved.U.determinant(), 1.0, 1e-12);
        EXPECT_NEAR(moved.V.determinant(), 1.0, 1e-12);
        EXPECT_LT((moved.U.transpose() * moved.U - Eigen::Matrix3d::Identity()).norm(), 1e-12);
        // The first two columns span the same planes: the tangent spaces agree.
        EXPECT_LT((moved.U.leftCols<2>() * moved.U.leftCols<2>().transpose() -
                   bySvd.U.leftCols<2>() * bySvd.U.leftCols<2>().transpose())
                      .norm(),
                  1e-9)
            << "trial " << trial;
    }
}

TEST(Rcme_GoldStandardRefiner, improves_a_perturbed_estimate)
{
    for (bool calibrated : {false, true}) {
        SCOPED_TRACE(calibrated ? "calibrated" : "uncalibrated");
        const SyntheticScene scene = noiseFreeScene(5, 0.5);
        const TwoViewData data = sceneData(scene, calibrated);
        Eigen::Matrix3d R;
        Eigen::Vector3d t;
        cv2eigen(scene.R, R);
        cv2eigen(scene.t, t);
        Model model;
        // Start a couple of degrees and a few degrees of heading away from the truth.
        R = R * rotationExp(Eigen::Vector3d(0.03, -0.02, 0.01));
        t = (t + Eigen::Vector3d(0.05, 0.05, -0.05)).normalized();
        Eigen::Matrix3d K;
        cv2eigen(scene.cameraMatrix, K);
        model.F = fundamentalFromEssential(skew(t) * R, K.inverse());
        // A motion is refined as a motion (5 DoF); otherwise the refiner works on F (7 DoF).
        if (calibrated)
            model.form = Motion{R, t};
        else
            std::get<FundamentalForm>(model.form).essential = skew(t) * R;
        const std::vector<uchar> all(data.points1.size(), 1);
        auto cost = [&](const Eigen::Matrix3d& F) {
            double c = 0;
            for (size_t i = 0; i < data.points1.size(); ++i)
                c += sampsonDistanceSquared(F, data.points1[i], data.points2[i]);
            return c;
        };
        const double before = cost(model.F);
        auto refiner = createGoldStandardRefiner(30, createModelSpace(data));
        ASSERT_TRUE(refiner->refine(data, all, model));
        const double after = cost(model.F);
        EXPECT_LT(after, 0.1 * before);
        // Near the noise floor: mean squared Sampson distance about sigma^2 = 0.25.
        EXPECT_LT(after / data.points1.size(), 0.5);
        EXPECT_LT((model.F - trueF(scene)).norm(), 0.02);
        // The uncertainty of what the model is refined as: the motion's with K, else F's.
        EXPECT_TRUE(calibrated ? model.uncertainty.as<MotionUncertainty>() != nullptr
                               : model.uncertainty.as<FundamentalUncertainty>() != nullptr);
        if (calibrated) {
            EXPECT_NE(model.motion(), nullptr);
        }
    }
}

TEST(Rcme_Cheirality, picks_the_true_decomposition)
{
    for (int seed = 0; seed < 5; ++seed) {
        const SyntheticScene scene = noiseFreeScene(seed);
        const TwoViewData data = sceneData(scene, true);
        Eigen::Matrix3d E, R;
        Eigen::Vector3d t;
        cv2eigen(scene.E, E);
        for (double sign : {1.0, -1.0}) { // E and -E are the same essential matrix
            const int count = recoverMotionFromEssential(sign * E, data.points1, data.points2,
                                                         data.Kinv, nullptr, R, t);
            EXPECT_EQ(count, data.size());
            Eigen::Matrix3d Rgt;
            Eigen::Vector3d tgt;
            cv2eigen(scene.R, Rgt);
            cv2eigen(scene.t, tgt);
            EXPECT_LT((R - Rgt).norm(), 1e-9);
            EXPECT_LT((t - tgt).norm(), 1e-9);
        }
    }
}

// The four decompositions counted in one pass choose as countPointsInFront of each in turn (the
// count and the first candidate of the most points), on noisy scenes with outliers and a selection.
TEST(Rcme_Cheirality, one_pass_over_the_decompositions_counts_as_each_in_turn)
{
    for (int seed = 0; seed < 8; ++seed) {
        SceneParams sp;
        sp.kind = seed % 2 ? SCENE_CORRIDOR : SCENE_GENERIC;
        sp.sigma = 1.0;
        sp.inlierRatio = 0.5;
        sp.numPoints = 400;
        sp.seed = seed;
        const TwoViewData data = sceneData(generateScene(sp), true);
        std::vector<uchar> selection(data.points1.size());
        for (size_t i = 0; i < selection.size(); ++i)
            selection[i] = (i * 7 + static_cast<size_t>(seed)) % 3 != 0;
        // A rough E of the scene: the first 8 points' least-squares fit, so that the four
        // candidates keep different shares of the points.
        Eigen::Matrix<double, 8, 9> A;
        for (int i = 0; i < 8; ++i) {
            const Eigen::Vector3d y1 = data.Kinv * homogeneous(data.points1[i]);
            const Eigen::Vector3d y2 = data.Kinv * homogeneous(data.points2[i]);
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 3; ++c)
                    A(i, 3 * r + c) = y2(r) * y1(c);
        }
        Eigen::JacobiSVD<Eigen::Matrix<double, 8, 9>> svd(A, Eigen::ComputeFullV);
        const Eigen::Matrix<double, 9, 1> e = svd.matrixV().col(8);
        Eigen::Matrix3d E;
        E << e(0), e(1), e(2), e(3), e(4), e(5), e(6), e(7), e(8);
        const std::vector<uchar>* selections[2] = {nullptr, &selection};
        for (const std::vector<uchar>* chosen : selections)
            for (double distance : {50.0, std::numeric_limits<double>::infinity(), 2.0}) {
                Eigen::Matrix3d R;
                Eigen::Vector3d t;
                const int count = recoverMotionFromEssential(E, data.points1, data.points2,
                                                             data.Kinv, chosen, R, t, distance);
                // The reference: each candidate in turn, as cv::recoverPose.
                Eigen::JacobiSVD<Eigen::Matrix3d> d(E, Eigen::ComputeFullU | Eigen::ComputeFullV);
                Eigen::Matrix3d U = d.matrixU(), V = d.matrixV();
                if (U.determinant() < 0)
                    U = -U;
                if (V.determinant() < 0)
                    V = -V;
                Eigen::Matrix3d W;
                W << 0, -1, 0, 1, 0, 0, 0, 0, 1;
                const Eigen::Matrix3d rotations[2] = {U * W * V.transpose(),
                                                      U * W.transpose() * V.transpose()};
                const Eigen::Vector3d direction = U.col(2).normalized();
                int best = -1;
                Eigen::Matrix3d bestR;
                Eigen::Vector3d bestT;
                for (int candidate = 0; candidate < 4; ++candidate) {
                    const Eigen::Vector3d tc =
                        candidate % 2 == 0 ? direction : Eigen::Vector3d(-direction);
                    const int c =
                        countPointsInFront(rotations[candidate / 2], tc, data.points1, data.points2,
                                           data.Kinv, chosen, nullptr, distance);
                    if (c > best) {
                        best = c;
                        bestR = rotations[candidate / 2];
                        bestT = tc;
                    }
                }
                EXPECT_EQ(count, best) << "seed " << seed << " distance " << distance;
                EXPECT_TRUE(R == bestR && t == bestT) << "seed " << seed;
            }
    }
}

// maskIndices without a branch lists the ones of a mask in order, whatever the buffer held.
TEST(Rcme_MaskIndices, lists_the_ones_in_order)
{
    cv::RNG rng(37);
    std::vector<int> indices = {5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
    for (int trial = 0; trial < 30; ++trial) {
        std::vector<uchar> mask(static_cast<size_t>(rng.uniform(0, 40)));
        for (uchar& m : mask)
            m = static_cast<uchar>(rng.uniform(0, 3) == 0 ? 0 : rng.uniform(1, 256));
        maskIndices(mask, indices);
        std::vector<int> expected;
        for (size_t i = 0; i < mask.size(); ++i)
            if (mask[i])
                expected.push_back(static_cast<int>(i));
        EXPECT_EQ(indices, expected) << "trial " << trial;
    }
}

// Once every place is taken, a hypothesis enters the rivals only by beating the least supported
// one: the loop's bail-out (inliersThatMatter) may stop counting below that, and an offer at or
// below it is dropped before its motion is decomposed.
TEST(Rcme_RivalMotions, a_full_memory_considers_only_counts_above_its_least)
{
    const TwoViewData data = sceneData(noiseFreeScene(0), true);
    const auto offer = [&](RivalMotions& rivals, double angleDeg, int count) {
        Model model;
        Motion motion;
        motion.R = Eigen::AngleAxisd(angleDeg * CV_PI / 180.0, Eigen::Vector3d::UnitY())
                       .toRotationMatrix();
        motion.t = Eigen::Vector3d(1, 0, 0);
        model.form = motion;
        Score score;
        score.inlierCount = count;
        score.value = -count;
        score.isCandidate = true;
        rivals.offer(data, {0, 1, 2, 3, 4}, model, score);
    };
    const auto counts = [](const RivalMotions& rivals) {
        std::vector<int> c;
        for (const RivalMotions::Rival& rival : rivals.rivals())
            c.push_back(rival.score.inlierCount);
        std::sort(c.begin(), c.end());
        return c;
    };
    RivalMotions rivals(2);
    offer(rivals, 0.0, 100);
    EXPECT_EQ(rivals.leastSupportConsidered(true), 50); // half the best while a place is free
    offer(rivals, 20.0, 90);
    EXPECT_EQ(rivals.leastSupportConsidered(true), 91);
    // A score other than the count can let in a motion of fewer inliers than any kept.
    EXPECT_EQ(rivals.leastSupportConsidered(false), 50);
    offer(rivals, 40.0, 90); // a third motion no better than the least kept
    EXPECT_EQ(counts(rivals), std::vector<int>({90, 100}));
    offer(rivals, 40.0, 95); // better: it takes the least one's place
    EXPECT_EQ(counts(rivals), std::vector<int>({95, 100}));
    EXPECT_EQ(rivals.leastSupportConsidered(true), 96);
    offer(rivals, 0.5, 120); // the same motion as the best, better: it replaces it
    EXPECT_EQ(counts(rivals), std::vector<int>({95, 120}));
    EXPECT_EQ(rivals.leastSupportConsidered(true), 96);
}

TEST(Rcme_RivalMotions, distinct_beyond_5_deg_of_rotation_or_15_of_translation_and_without_a_motion)
{
    Model a, b;
    a.form = Motion{Eigen::Matrix3d::Identity(), Eigen::Vector3d::UnitX()};
    b.form =
        Motion{Eigen::AngleAxisd(4.0 * CV_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix(),
               Eigen::AngleAxisd(14.0 * CV_PI / 180.0, Eigen::Vector3d::UnitZ()) *
                   Eigen::Vector3d::UnitX()};
    EXPECT_FALSE(areDistinctMotions(a, b));
    b.motion()->R =
        Eigen::AngleAxisd(6.0 * CV_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
    EXPECT_TRUE(areDistinctMotions(a, b));
    // A model still a fundamental matrix (its E had no decomposition) is no motion of either.
    const Model unlifted;
    EXPECT_TRUE(areDistinctMotions(unlifted, a));
    EXPECT_TRUE(areDistinctMotions(a, unlifted));
}

TEST(Rcme_Statistics, binomial_tail_bound_small_and_large_samples)
{
    // Exact values (summed with Python's integer binomial coefficients): P(X >= 16) = 0.040 and
    // P(X >= 15) = 0.073 for Binomial(100, 0.1).
    EXPECT_EQ(binomialTailBound(100, 0.1, 0.05), 16);
    EXPECT_EQ(binomialTailBound(100, 0.0, 0.05), 1);
    EXPECT_EQ(binomialTailBound(100, 1.0, 0.05), 101);
    // Large samples, where (1 - p)^n underflows: mean + 3.9 standard deviations.
    EXPECT_EQ(binomialTailBound(100000, 0.01, 5e-5), 1126);
    EXPECT_EQ(binomialTailBound(1000000, 0.01, 5e-5), 10390);
}

TEST(Rcme_Statistics, posterior_noise_moves_from_the_stated_sigma_to_the_estimate)
{
    // Stated 1 px as a prior worth 4 degrees of freedom, estimate 0.3 px.
    EXPECT_EQ(posteriorNoiseVariance(1.0, 0.3, 0, 4.0), 1.0);
    EXPECT_EQ(posteriorNoiseVariance(1.0, std::numeric_limits<double>::quiet_NaN(), 50, 4.0), 1.0);
    EXPECT_NEAR(posteriorNoiseVariance(1.0, 0.3, 30, 4.0), (4.0 + 30 * 0.09) / 32.0, 1e-15);
    // No jump anywhere: each further degree of freedom moves it by less than 1/(dof + 2) of the
    // gap between prior and estimate, and it tends to the estimate.
    for (int dof = 1; dof < 400; ++dof) {
        const double before = posteriorNoiseVariance(1.0, 0.3, dof, 4.0);
        const double after = posteriorNoiseVariance(1.0, 0.3, dof + 1, 4.0);
        EXPECT_LT(after, before) << dof;
        EXPECT_LT(before - after, 1.0 / (dof + 2)) << dof;
    }
    EXPECT_NEAR(posteriorNoiseVariance(1.0, 0.3, 1000000, 4.0), 0.09, 1e-5);
}

TEST(Rcme_Statistics, sandwich_taken_only_beyond_its_noise)
{
    // In the model-based covariance's whitened coordinates (here it is diag(4, 1)), with 50
    // residuals the margin is 2 sqrt(2 / 50) = 0.4: the sandwich's 2.0 along x is taken as 1.6,
    // its 0.3 along y stays 1 unless lowering is asked for, then 0.7; within the margin nothing
    // moves.
    const Eigen::Matrix2d modelBased = Eigen::Vector2d(4.0, 1.0).asDiagonal();
    const Eigen::Matrix2d sandwich = Eigen::Vector2d(8.0, 0.3).asDiagonal();
    const Eigen::Matrix2d raised = sandwichBeyondItsNoise<2>(modelBased, sandwich, 50, false);
    EXPECT_NEAR(raised(0, 0), 6.4, 1e-12);
    EXPECT_NEAR(raised(1, 1), 1.0, 1e-12);
    EXPECT_NEAR(raised(0, 1), 0.0, 1e-12);
    const Eigen::Matrix2d both = sandwichBeyondItsNoise<2>(modelBased, sandwich, 50, true);
    EXPECT_NEAR(both(0, 0), 6.4, 1e-12);
    EXPECT_NEAR(both(1, 1), 0.7, 1e-12);
    const Eigen::Matrix2d near = Eigen::Vector2d(4.0 * 1.3, 0.8).asDiagonal();
    EXPECT_LT((sandwichBeyondItsNoise<2>(modelBased, near, 50, true) - modelBased).norm(), 1e-12);
    // A sandwich of (negative) roundoff along a direction keeps the margin.
    const Eigen::Matrix2d roundoff = Eigen::Vector2d(4.0, -1e-20).asDiagonal();
    EXPECT_NEAR(sandwichBeyondItsNoise<2>(modelBased, roundoff, 50, true)(1, 1), 0.4, 1e-12);
    // Rotated frames: the rule is applied to the whitened sandwich's eigen-directions.
    const Eigen::Matrix2d Q = Eigen::Rotation2Dd(0.3).toRotationMatrix();
    const Eigen::Matrix2d rotated = sandwichBeyondItsNoise<2>(
        Q * modelBased * Q.transpose(), Q * sandwich * Q.transpose(), 50, true);
    EXPECT_LT((rotated - Q * both * Q.transpose()).norm(), 1e-9);
}

TEST(Rcme_Statistics, log_binomial_coefficient_and_tail)
{
    // Values from Python's math.lgamma and exact integer sums (fractions.Fraction).
    EXPECT_NEAR(logBinomialCoefficient(100, 50), 66.78384165201737, 1e-10);
    EXPECT_NEAR(logBinomialCoefficient(200, 2), 9.89847501071256, 1e-12);
    EXPECT_NEAR(logBinomialCoefficient(1000000, 500000), 693140.047013063, 1e-6);
    EXPECT_EQ(logBinomialCoefficient(7, 0), 0.0);
    // P(X >= 16) = 0.03989 for Binomial(100, 0.1); a tail far below double's range.
    EXPECT_NEAR(logBinomialTail(100, 0.1, 16), -3.221616399036225, 1e-9);
    EXPECT_NEAR(logBinomialTail(1000, 0.01, 200), -432.0878226388231, 1e-8);
    EXPECT_EQ(logBinomialTail(100, 0.1, 0), 0.0);
    EXPECT_EQ(logBinomialTail(100, 0.1, 101), -std::numeric_limits<double>::infinity());
}

// A subset is the same problem (camera, noise, bounds) on fewer correspondences, in their order.
TEST(Rcme_TwoViewData, subsets_keep_the_problem_and_the_order)
{
    TwoViewData data;
    data.calibrated = true;
    data.K << 500, 0, 320, 0, 510, 240, 0, 0, 1;
    data.Kinv = data.K.inverse();
    data.sigma = 0.7;
    data.threshold = 1.3;
    data.consistencyBound = 5.99;
    data.useEstimatedNoise = false;
    for (int i = 0; i < 50; ++i) {
        data.points1.emplace_back(i, -i);
        data.points2.emplace_back(2 * i, 0.5 * i);
    }
    const auto expectSameProblem = [&](const TwoViewData& part) {
        EXPECT_EQ(part.calibrated, data.calibrated);
        EXPECT_EQ(part.K, data.K);
        EXPECT_EQ(part.Kinv, data.Kinv);
        EXPECT_EQ(part.sigma, data.sigma);
        EXPECT_EQ(part.threshold, data.threshold);
        EXPECT_EQ(part.consistencyBound, data.consistencyBound);
        EXPECT_EQ(part.useEstimatedNoise, data.useEstimatedNoise);
        ASSERT_EQ(part.points1.size(), part.points2.size());
    };

    const TwoViewData every7th = evenlySpacedSubset(data, 8); // stride 7 leaves 8 of 50
    expectSameProblem(every7th);
    ASSERT_EQ(every7th.size(), 8);
    for (size_t k = 0; k < 8; ++k) {
        EXPECT_EQ(every7th.points1[k], data.points1[7 * k]);
        EXPECT_EQ(every7th.points2[k], data.points2[7 * k]);
    }
    EXPECT_EQ(evenlySpacedSubset(data, 50).points1, data.points1);
}

TEST(Rcme_Statistics, quantiles_match_their_closed_forms)
{
    // The bisections stop once the interval holds no double: they must still reach the root.
    for (const double p : {1e-6, 0.05, 0.5, 0.95, 0.99, 0.999}) {
        EXPECT_NEAR(chiSquareQuantile(p, 2), -2.0 * std::log1p(-p), 1e-12) << p;
        const double z = normalQuantile(0.5 * (1.0 + p));
        EXPECT_NEAR(chiSquareQuantile(p, 1), z * z, 1e-9 * std::max(1.0, z * z)) << p;
        EXPECT_NEAR(0.5 * std::erfc(-normalQuantile(p) / std::sqrt(2.0)), p, 1e-15) << p;
    }
    EXPECT_NEAR(normalQuantile(0.975), 1.959963984540054, 1e-14);
    EXPECT_NEAR(chiSquareQuantile(0.95, 4), 9.487729036781154, 1e-11);
}

} // namespace
} // namespace opencv_test

#endif // RCME_STANDALONE_TESTS
