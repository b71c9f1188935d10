// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The estimate's final fit (Refiner::finalize, components/gold_standard_refiner.cpp): the motion
// it returns is the least-squares fit of the points its mask marks; without K it is kept only as
// a refinement is kept (components/final_fit.cpp). Internal (cv::rcme::detail), so standalone
// only, as test_components.cpp.

#include "test_precomp.hpp"

#ifdef RCME_STANDALONE_TESTS

#include "estimation/model_fit.hpp"
#include "framework/component_factories.hpp"
#include "framework/estimator_factory.hpp"
#include "framework/ransac_loop.hpp"
#include "framework/refinement.hpp"
#include "geometry/epipolar.hpp"
#include "test_internal_helpers.hpp"

#include <opencv2/core/eigen.hpp>

namespace opencv_test {
namespace {

using namespace cv::rcme::detail;

// The sum of squared Sampson distances of the points `indices` under F.
double squaredResiduals(const TwoViewData& data, const Eigen::Matrix3d& F,
                        const std::vector<int>& indices)
{
    double cost = 0;
    for (int i : indices)
        cost += sampsonDistanceSquared(F, data.points1[static_cast<size_t>(i)],
                                       data.points2[static_cast<size_t>(i)]);
    return cost;
}

/* A corridor (1000 points, 30 % outliers, sigma 2 px) where a later round of the final fit is
undone by its cheirality check (within 50 baselines): the previous round's motion was returned
with this round's mask and covariance, 2.4 standard deviations off the least-squares minimum of
that mask. The previous round stands whole now: refitted by least squares on the returned mask,
the motion lowers the squared residuals by less than a quarter of sigma^2 (half a deviation). */
TEST(Rcme_FinalFit, returns_the_least_squares_fit_of_its_own_mask)
{
    constexpr double kSigma = 2.0;
    const SyntheticScene scene = testScene(SCENE_CORRIDOR, 54, 0.7, kSigma, 1000);
    Params params;
    params.sigma = kSigma;
    const Report report =
        estimateRelativeMotion(scene.points1, scene.points2, scene.cameraMatrix, params);
    ASSERT_EQ(report.status, STATUS_SUCCESS);
    TwoViewData data = sceneData(scene, /*calibrated=*/true, /*inliersOnly=*/false);
    data.sigma = kSigma;
    data.threshold = 1.96 * kSigma;
    Model refit;
    Motion& motion = refit.form.emplace<Motion>();
    cv2eigen(report.R, motion.R);
    cv2eigen(report.t, motion.t);
    const Eigen::Matrix3d returnedF =
        fundamentalFromEssential(skew(motion.t) * motion.R, data.Kinv);
    std::vector<int> indices;
    for (int i = 0; i < report.mask.rows; ++i)
        if (report.mask.at<uchar>(i))
            indices.push_back(i);
    ASSERT_TRUE(fitModelOn(data, ModelForm::kMotion, indices, 20, refit));
    const double decrease =
        squaredResiduals(data, returnedF, indices) - squaredResiduals(data, refit.F, indices);
    EXPECT_LT(decrease, 0.25 * kSigma * kSigma);
}

/* A generic scene without K, half of its points true, as the pipeline sees it: its components,
and the true F refined as the selected model is (the F the final fit starts from). */
struct SceneWithoutK
{
    SceneWithoutK(int points, int seed)
        : scene(testScene(SCENE_GENERIC, seed, 0.5, 1.0, points)),
          data(makeTwoViewData(scene.points1, scene.points2, noArray(), Params())),
          components(createEstimator(Params(), data)),
          refinement(*components.scorer, components.refiner.get())
    {
        Scorer& scorer = *components.scorer;
        cv2eigen(scene.F, entry.model.F);
        scorer.classify(data, entry.model, entry.inliers);
        entry.score = scorer.score(data, entry.model);
        refinement.refineSelected(data, entry);
    }

    SyntheticScene scene;
    TwoViewData data;
    EstimatorComponents components;
    Refinement refinement;
    Fit entry;
};

/* Without K the final fit is kept only as a refinement is kept: 40 points, half of them true,
where the fit's rounds drop inliers of high leverage and often leave F at a higher truncated cost
than the F they started from. From the true F refined as the selected model is: the F returned is
the plain final fit wherever the scorer keeps that, and otherwise the F it started from, with the
inliers of its own band, never an F the scorer rates worse. */
TEST(Rcme_FinalFit, without_k_a_final_fit_the_scorer_rates_worse_is_not_kept)
{
    int undone = 0, kept = 0;
    for (int seed = 0; seed < 20; ++seed) {
        const SceneWithoutK c(40, seed);
        const TwoViewData& data = c.data;
        Scorer& scorer = *c.components.scorer;
        const Refinement& refinement = c.refinement;
        const Fit& entry = c.entry;

        Model plain = entry.model;
        std::vector<uchar> plainInliers = entry.inliers;
        refinement.finalFit(data, plain, plainInliers);
        Model chosen = entry.model;
        std::vector<uchar> chosenInliers = entry.inliers;
        refinement.finalFitUnlessWorse(data, chosen, chosenInliers);

        const Score entryScore = scorer.score(data, entry.model);
        if (scorer.keepsRefinement(entryScore, scorer.score(data, plain))) {
            ++kept;
            EXPECT_TRUE(chosen.F == plain.F) << "seed " << seed;
            EXPECT_EQ(chosenInliers, plainInliers) << "seed " << seed;
            continue;
        }
        ++undone;
        EXPECT_LT((chosen.F - entry.model.F).norm(), 1e-12) << "seed " << seed;
        EXPECT_LE(scorer.score(data, chosen).value, entryScore.value + 1e-9) << "seed " << seed;
        for (size_t i = 0; i < chosenInliers.size(); ++i)
            if (chosenInliers[i])
                EXPECT_LE(sampsonDistanceSquared(chosen.F, data.points1[i], data.points2[i]),
                          data.threshold * data.threshold)
                    << "seed " << seed << ", point " << i;
    }
    EXPECT_GE(undone, 5);
    EXPECT_GE(kept, 1);
}

/* The final fit stage without K (components/final_fit.cpp) chooses: where the outliers can have
put a point into the band by chance (at least one expected), the plain final fit, whatever the
scorer says of it; where they cannot, the fit kept as a refinement is kept. 40 points half true
(20 outliers, under one expected) and 500 points half true (250 outliers, several expected), from
the true F refined as the selected model is. */
TEST(Rcme_FinalFit, without_k_the_stage_keeps_the_plain_fit_where_chance_inliers_are_expected)
{
    int differ[2] = {0, 0}; // seeds where the two fits differ, per scene size
    for (const int points : {40, 500})
        for (int seed = 0; seed < 10; ++seed) {
            const SceneWithoutK c(points, seed);
            const TwoViewData& data = c.data;
            Scorer& scorer = *c.components.scorer;
            const Refinement& refinement = c.refinement;
            const Fit& entry = c.entry;
            const double outliers =
                static_cast<double>(std::count(entry.inliers.begin(), entry.inliers.end(), 0));
            const bool chanceInliers = outliers * chanceOfBand(data, data.threshold) >= 1.0;
            ASSERT_EQ(chanceInliers, points == 500) << points << " points, seed " << seed;

            Model plain = entry.model, kept = entry.model;
            std::vector<uchar> plainInliers = entry.inliers, keptInliers = entry.inliers;
            refinement.finalFit(data, plain, plainInliers);
            refinement.finalFitUnlessWorse(data, kept, keptInliers);
            differ[points == 500] += !(plain.F == kept.F);

            Estimate estimate;
            estimate.model = entry.model;
            estimate.score = entry.score;
            estimate.mask = entry.inliers;
            const SearchResult search;
            const StageContext context{data, search, scorer, refinement, *c.components.space};
            const StageOutcome outcome = createFinalFit()->run(context, estimate);
            ASSERT_TRUE(outcome.model && outcome.inliers);
            EXPECT_TRUE(outcome.model->F == (chanceInliers ? plain.F : kept.F))
                << points << " points, seed " << seed;
            EXPECT_EQ(*outcome.inliers, chanceInliers ? plainInliers : keptInliers)
                << points << " points, seed " << seed;
        }
    // Each side has seeds where the choice matters.
    EXPECT_GE(differ[0], 5);
    EXPECT_GE(differ[1], 3);
}

} // namespace
} // namespace opencv_test

#endif // RCME_STANDALONE_TESTS
