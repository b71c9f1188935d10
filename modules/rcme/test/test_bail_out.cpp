// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Early bail-out of the inlier count (Scorer::evaluateUpTo): a hypothesis stops being read once it
// cannot reach the count that matters to the run. Internal, so standalone only, as
// test_components.cpp.

#include "test_precomp.hpp"

#ifdef RCME_STANDALONE_TESTS

#include "framework/estimator_factory.hpp"
#include "framework/ransac_loop.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/residual_bands.hpp"
#include "test_internal_helpers.hpp"

#include <opencv2/core/eigen.hpp>

namespace opencv_test {
namespace {

using namespace cv::rcme::detail;

TEST(Rcme_BailOut, count_is_exact_when_reachable_and_stops_early_otherwise)
{
    const SyntheticScene s = testScene(SCENE_GENERIC, 3, 0.5, 1.0, 1000);
    const TwoViewData data = sceneData(s, false, /*inliersOnly=*/false);
    const double thresholdSquared = data.threshold * data.threshold;
    Eigen::Matrix3d trueF;
    cv2eigen(s.F, trueF);
    const int trueCount = countInSampsonBand(trueF, data.points1, data.points2, thresholdSquared);
    ASSERT_GT(trueCount, 400);
    size_t read = 0;
    for (int needed : {0, 1, trueCount / 2, trueCount}) {
        EXPECT_EQ(countInSampsonBandReaching(trueF, data.points1, data.points2, thresholdSquared,
                                             needed, read),
                  trueCount)
            << needed;
        EXPECT_EQ(read, data.points1.size()) << needed;
    }
    // Any count below the one needed is fine once it is out of reach; here it is seen after a
    // few blocks, as the true model's inliers are half of the points.
    EXPECT_LT(countInSampsonBandReaching(trueF, data.points1, data.points2, thresholdSquared,
                                         static_cast<int>(data.points1.size()), read),
              static_cast<int>(data.points1.size()));
    EXPECT_LT(read, 100u);

    // A wrong model holds few of the points: it stops soon after the points left cannot make up
    // for its misses.
    Eigen::Matrix3d wrongF = trueF;
    wrongF(0, 2) += 0.5 * trueF.norm();
    const int wrongCount = countInSampsonBand(wrongF, data.points1, data.points2, thresholdSquared);
    ASSERT_LT(wrongCount, 200);
    const int reached = countInSampsonBandReaching(wrongF, data.points1, data.points2,
                                                   thresholdSquared, trueCount, read);
    EXPECT_LT(reached, trueCount);
    EXPECT_LE(reached, wrongCount);
    EXPECT_LT(read, 0.75 * data.points1.size());
    EXPECT_GE(read + static_cast<size_t>(trueCount), data.points1.size() - wrongCount);
}

// The method's scorer, reading every point of every hypothesis (the default evaluateUpTo).
class EveryPointScorer final : public Scorer
{
public:
    explicit EveryPointScorer(std::unique_ptr<Scorer> scorer) : scorer_(std::move(scorer)) {}
    Score evaluate(const TwoViewData& data, const Model& model) override
    {
        return scorer_->evaluate(data, model);
    }
    void commit(Score& score) override { scorer_->commit(score); }
    std::unique_ptr<Scorer> clone() const override
    {
        return std::make_unique<EveryPointScorer>(scorer_->clone());
    }
    void classify(const TwoViewData& data, const Model& model, std::vector<uchar>& mask) override
    {
        scorer_->classify(data, model, mask);
    }
    bool isStillCandidate(const Score& score) const override
    {
        return scorer_->isStillCandidate(score);
    }
    bool keepsRefinement(const Score& before, const Score& refined) const override
    {
        return scorer_->keepsRefinement(before, refined);
    }

private:
    std::unique_ptr<Scorer> scorer_;
};

RansacResult estimateWith(const SyntheticScene& scene, const Params& params, bool everyPoint)
{
    const TwoViewData data =
        makeTwoViewData(scene.points1, scene.points2, scene.cameraMatrix, params);
    EstimatorComponents components = createEstimator(params, data);
    if (everyPoint)
        components.scorer = std::make_unique<EveryPointScorer>(std::move(components.scorer));
    return estimateModel(data, components);
}

// The rivals' inlier counts, in increasing order: the motions the ambiguity test remembered.
std::vector<int> rivalCounts(const RansacResult& result)
{
    std::vector<int> counts;
    for (const RivalMotions::Rival& rival : result.rivals)
        counts.push_back(rival.score.inlierCount);
    std::sort(counts.begin(), counts.end());
    return counts;
}

TEST(Rcme_BailOut, a_run_is_the_same_as_with_every_point_read)
{
    // Standard (inlier count) with the 7-point solver, and the default (5-point, local
    // optimisation, the ambiguity test's rivals, inner sampling at w = 0.3); serial and
    // parallel, exactly N and adaptive.
    Params standard = Params::asPublished(METHOD_STANDARD);
    standard.solver = SOLVER_SEVEN_POINT;
    const Params methods[] = {standard, Params()};
    double pointsRead[2] = {0, 0};
    int runs = 0;
    for (int seed = 0; seed < testRuns(4, 1); ++seed)
        for (double inlierRatio : {0.3, 0.8}) {
            const SyntheticScene scene = testScene(SCENE_CORRIDOR, seed, inlierRatio);
            for (Params params : methods)
                for (bool exact : {false, true})
                    for (bool parallel : {false, true}) {
                        params.randomGeneratorState = seed;
                        params.maxIterations = 300;
                        params.exactIterations = exact;
                        params.isParallel = parallel;
                        const RansacResult bail = estimateWith(scene, params, false);
                        const RansacResult full = estimateWith(scene, params, true);
                        const std::string what = cv::format(
                            "seed %d w %.1f solver %d exact %d parallel %d", seed, inlierRatio,
                            static_cast<int>(params.solver), exact, parallel);
                        ASSERT_EQ(bail.status, full.status) << what;
                        EXPECT_EQ(bail.iterations, full.iterations) << what;
                        EXPECT_EQ(bail.hypotheses, full.hypotheses) << what;
                        EXPECT_EQ((bail.model.F - full.model.F).norm(), 0.0) << what;
                        EXPECT_EQ(bail.mask, full.mask) << what;
                        EXPECT_EQ(rivalCounts(bail), rivalCounts(full)) << what;
                        EXPECT_TRUE(bail.rivalCostGap == full.rivalCostGap ||
                                    (cvIsNaN(bail.rivalCostGap) && cvIsNaN(full.rivalCostGap)))
                            << what;
                        EXPECT_EQ(full.pointsPerHypothesis, scene.points1.rows) << what;
                        pointsRead[0] += bail.pointsPerHypothesis;
                        pointsRead[1] += full.pointsPerHypothesis;
                        ++runs;
                    }
        }
    std::cout << "points read per hypothesis: " << pointsRead[0] / runs << " with bail-out, "
              << pointsRead[1] / runs << " without" << std::endl;
    // 0.86 on these scenes (a hypothesis stops once it misses more points than the best one
    // does, and at w = 0.3 the best misses most); real pairs, at w = 0.66-0.99, save more.
    EXPECT_LT(pointsRead[0], 0.9 * pointsRead[1]);
}

} // namespace
} // namespace opencv_test

#endif // RCME_STANDALONE_TESTS
