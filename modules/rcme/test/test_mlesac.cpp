// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// MLESAC's scorer (components/mlesac_scorer.cpp): the EM mixing weight, the likelihood's
// ranking, the chance-support candidate test and the classification. Internal components, so
// standalone build only (see test_components.cpp).

#include "test_precomp.hpp"

#ifdef RCME_STANDALONE_TESTS

#include "framework/component_factories.hpp"
#include "framework/estimation_pipeline.hpp"
#include "framework/model_space.hpp"
#include "geometry/epipolar.hpp"
#include "test_internal_helpers.hpp"

#include <opencv2/core/eigen.hpp>

namespace cv {
namespace rcme {
namespace detail {
// Test hook defined in mlesac_scorer.cpp: the mixing weight EM fits to `model`.
double mlesacMixingWeight(const TwoViewData& data, const Model& model);
} // namespace detail
} // namespace rcme
} // namespace cv

namespace opencv_test {
namespace {

using namespace cv::rcme::detail;

SyntheticScene mlesacScene(double inlierRatio, int seed, int numPoints = 500)
{
    SceneParams sp;
    sp.kind = SCENE_GENERIC;
    sp.sigma = 1.0;
    sp.inlierRatio = inlierRatio;
    sp.numPoints = numPoints;
    sp.seed = seed;
    return generateScene(sp);
}

Model trueModel(const SyntheticScene& scene)
{
    Model model;
    Eigen::Matrix3d F;
    cv2eigen(scene.F, F);
    model.F = normalizeFundamental(F);
    return model;
}

// The scene's F with its rotation turned by `degrees` about a fixed axis.
Model perturbedModel(const SyntheticScene& scene, double degrees)
{
    Eigen::Matrix3d K, R;
    Eigen::Vector3d t;
    cv2eigen(scene.cameraMatrix, K);
    cv2eigen(scene.R, R);
    cv2eigen(scene.t, t);
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(degrees * CV_PI / 180.0, Eigen::Vector3d(1, 2, 3).normalized())
            .toRotationMatrix();
    const Eigen::Matrix3d Kinv = K.inverse();
    Model model;
    model.F = normalizeFundamental(Kinv.transpose() * skew(t) * (turn * R) * Kinv);
    return model;
}

double trueInlierFraction(const SyntheticScene& scene)
{
    return static_cast<double>(cv::countNonZero(scene.inlierMask)) / scene.inlierMask.rows;
}

TEST(Rcme_Mlesac, em_recovers_the_true_mixing_weight)
{
    const Params params;
    for (double ratio : {0.3, 0.5, 0.8}) {
        for (int seed = 0; seed < 3; ++seed) {
            const SyntheticScene scene = mlesacScene(ratio, seed);
            const TwoViewData data = sceneData(scene, false, /*inliersOnly=*/false);
            const double gamma = mlesacMixingWeight(data, trueModel(scene));
            EXPECT_NEAR(gamma, trueInlierFraction(scene), 0.05)
                << "ratio " << ratio << " seed " << seed;
            EXPECT_NEAR(gamma, ratio, 0.05) << "ratio " << ratio << " seed " << seed;
            RecordProperty(cv::format("gamma_%.1f_seed%d", ratio, seed), cv::format("%.4f", gamma));
        }
    }
}

TEST(Rcme_Mlesac, true_model_scores_better_than_perturbed)
{
    const Params params;
    for (int seed = 0; seed < 5; ++seed) {
        const SyntheticScene scene = mlesacScene(0.5, seed);
        const TwoViewData data = sceneData(scene, false, /*inliersOnly=*/false);
        // The perturbation is built from the motion: with no turn it is the scene's F.
        ASSERT_LT((perturbedModel(scene, 0).F - trueModel(scene).F).norm(), 1e-9);
        auto scorer = createMlesacScorer(data, 8, params.maxIterations);
        const Score truth = scorer->score(data, trueModel(scene));
        EXPECT_TRUE(truth.isCandidate) << "seed " << seed;
        Score previous = truth;
        for (double degrees : {0.25, 1.0, 4.0}) {
            const Score perturbed = scorer->score(data, perturbedModel(scene, degrees));
            EXPECT_TRUE(truth.isBetterThan(perturbed)) << "seed " << seed << ", " << degrees;
            EXPECT_TRUE(previous.isBetterThan(perturbed)) << "seed " << seed << ", " << degrees;
            previous = perturbed;
        }
    }
}

TEST(Rcme_Mlesac, all_outlier_input_has_no_candidate)
{
    Params params;
    for (int seed = 0; seed < 3; ++seed) {
        const SyntheticScene scene = mlesacScene(0.0, seed);
        const TwoViewData data = sceneData(scene, false, /*inliersOnly=*/false);
        auto scorer = createMlesacScorer(data, 8, params.maxIterations);
        EXPECT_FALSE(scorer->score(data, trueModel(scene)).isCandidate) << "seed " << seed;
        auto solver = createEightPointSolver(false);
        auto sampler = createUniformSampler(data.size(), 8, static_cast<uint64_t>(seed));
        std::vector<int> sample;
        std::vector<Model> models;
        int scored = 0;
        for (int it = 0; it < 200; ++it) {
            sampler->generateSample(it, sample);
            solver->estimate(data, sample, models);
            for (const Model& model : models) {
                const Score score = scorer->score(data, model);
                EXPECT_FALSE(score.isCandidate)
                    << "seed " << seed << " iteration " << it << ": " << score.inlierCount;
                EXPECT_TRUE(std::isfinite(score.value));
                ++scored;
            }
        }
        EXPECT_GT(scored, 150);
    }
}

TEST(Rcme_Mlesac, classify_agrees_with_inlier_count)
{
    const Params params;
    const SyntheticScene scene = mlesacScene(0.5, 7);
    const TwoViewData data = sceneData(scene, false, /*inliersOnly=*/false);
    auto scorer = createMlesacScorer(data, 8, params.maxIterations);
    std::vector<Model> models = {trueModel(scene), perturbedModel(scene, 1.0)};
    auto solver = createEightPointSolver(false);
    auto sampler = createUniformSampler(data.size(), 8, 3);
    std::vector<int> sample;
    std::vector<Model> hypotheses;
    for (int it = 0; it < 20; ++it) {
        sampler->generateSample(it, sample);
        solver->estimate(data, sample, hypotheses);
        models.insert(models.end(), hypotheses.begin(), hypotheses.end());
    }
    std::vector<uchar> mask;
    for (const Model& model : models) {
        const Score score = scorer->score(data, model);
        scorer->classify(data, model, mask);
        ASSERT_EQ(mask.size(), data.points1.size());
        EXPECT_EQ(std::count(mask.begin(), mask.end(), uchar(1)), score.inlierCount);
        for (size_t i = 0; i < mask.size(); ++i)
            EXPECT_EQ(mask[i] != 0,
                      sampsonDistanceSquared(model.F, data.points1[i], data.points2[i]) <=
                          data.threshold * data.threshold);
    }
    // The true model's inliers are almost exactly the true correspondences.
    scorer->classify(data, models[0], mask);
    int agree = 0;
    for (size_t i = 0; i < mask.size(); ++i)
        agree += mask[i] == scene.inlierMask.at<uchar>(static_cast<int>(i));
    EXPECT_GT(agree, 0.9 * data.size());
}

TEST(Rcme_Mlesac, deterministic)
{
    const Params params;
    const SyntheticScene scene = mlesacScene(0.5, 11);
    const TwoViewData data = sceneData(scene, false, /*inliersOnly=*/false);
    auto first = createMlesacScorer(data, 8, params.maxIterations);
    auto second = createMlesacScorer(data, 8, params.maxIterations);
    const Model model = perturbedModel(scene, 0.5), other = perturbedModel(scene, 3.0);
    const Score a = first->score(data, model);
    second->score(data, other); // a different hypothesis in between must not matter
    const Score b = second->score(data, model);
    const Score c = first->score(data, model);
    for (const Score& s : {b, c}) {
        EXPECT_EQ(s.value, a.value);
        EXPECT_EQ(s.inlierCount, a.inlierCount);
        EXPECT_EQ(s.isCandidate, a.isCandidate);
    }
    EXPECT_EQ(mlesacMixingWeight(data, model), mlesacMixingWeight(data, model));
}

// The scorer in the shared loop, assembled as the factory would for METHOD_MLESAC.
TEST(Rcme_Mlesac, runs_in_the_ransac_loop)
{
    Params params;
    for (double ratio : {0.5, 0.0}) {
        const SyntheticScene scene = mlesacScene(ratio, 5);
        const TwoViewData data = sceneData(scene, false, /*inliersOnly=*/false);
        EstimatorComponents c;
        c.space = createFundamentalSpace();
        c.solver = createEightPointSolver(false);
        c.sampler = createUniformSampler(data.size(), 8, 0);
        c.termination = createAdaptiveTermination(params.confidence, params.maxIterations, 8);
        c.scorer = createMlesacScorer(data, 8, params.maxIterations);
        c.refiner = createGoldStandardRefiner(params.refineIterations, c.space);
        c.stages.push_back(createCandidateSelection());
        c.stages.push_back(createSelectedModelRefinement());
        const Estimate result = estimateModel(data, c).estimate;
        if (ratio == 0.0) {
            EXPECT_EQ(result.status, STATUS_POOR_QUALITY_INPUT);
            continue;
        }
        ASSERT_EQ(result.status, STATUS_SUCCESS) << result.message;
        double sum = 0;
        int agree = 0, inliers = 0;
        for (int i = 0; i < data.size(); ++i) {
            const bool inlier = scene.inlierMask.at<uchar>(i) != 0;
            agree += (result.mask[static_cast<size_t>(i)] != 0) == inlier;
            if (inlier) {
                sum += sampsonDistanceSquared(result.model.F, data.points1[static_cast<size_t>(i)],
                                              data.points2[static_cast<size_t>(i)]);
                ++inliers;
            }
        }
        EXPECT_LT(std::sqrt(sum / inliers), 1.2); // sigma = 1: residuals of a good fit
        EXPECT_GT(agree, 0.9 * data.size());
    }
}

} // namespace
} // namespace opencv_test

#endif // RCME_STANDALONE_TESTS
