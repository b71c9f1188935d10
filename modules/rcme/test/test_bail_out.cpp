// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Early bail-out of the inlier count (Scorer::evaluateUpTo): a hypothesis stops being read once it
// cannot reach the count that matters to the run. Internal, so standalone only, as
// test_components.cpp.

#include "test_precomp.hpp"

#ifdef RCME_STANDALONE_TESTS

#include "framework/estimation_pipeline.hpp"
#include "framework/estimator_factory.hpp"
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

// The method's scorer, reading every point of every hypothesis (the default evaluateUpTo), or
// with its bail-out (`bailsOut`); either way it reads the points of a hypothesis whose inliers a
// verifier has counted (the default scoreOfBandCount).
class ReadingScorer final : public Scorer
{
public:
    ReadingScorer(std::unique_ptr<Scorer> scorer, bool bailsOut)
        : scorer_(std::move(scorer)), bailsOut_(bailsOut)
    {
    }
    Score evaluate(const TwoViewData& data, const Model& model) override
    {
        return scorer_->evaluate(data, model);
    }
    Score evaluateUpTo(const TwoViewData& data, const Model& model, const HypothesisBar& bar,
                       int& pointsRead) override
    {
        return bailsOut_ ? scorer_->evaluateUpTo(data, model, bar, pointsRead)
                         : Scorer::evaluateUpTo(data, model, bar, pointsRead);
    }
    bool ranksByInlierCount() const override { return scorer_->ranksByInlierCount(); }
    void commit(Score& score) override { scorer_->commit(score); }
    std::unique_ptr<Scorer> clone() const override
    {
        return std::make_unique<ReadingScorer>(scorer_->clone(), bailsOut_);
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
    bool bailsOut_;
};

enum class Reading
{
    kAsTheMethod,     // the method's scorer
    kEveryPoint,      // ReadingScorer without bail-out
    kWithBailOutOnly, // ReadingScorer with bail-out
};

// A method, and whether it is given the camera matrix.
struct Configuration
{
    Params params;
    bool calibrated = true;
};

Estimation estimateWith(const SyntheticScene& scene, const Configuration& configuration,
                        Reading reading)
{
    const Params& params = configuration.params;
    const TwoViewData data =
        makeTwoViewData(scene.points1, scene.points2,
                        configuration.calibrated ? scene.cameraMatrix : Mat(), params);
    EstimatorComponents components = createEstimator(params, data);
    if (reading != Reading::kAsTheMethod)
        components.scorer = std::make_unique<ReadingScorer>(std::move(components.scorer),
                                                            reading == Reading::kWithBailOutOnly);
    return estimateModel(data, components);
}

// The rivals' inlier counts, in increasing order: the motions the ambiguity test remembered.
std::vector<int> rivalCounts(const Estimation& result)
{
    std::vector<int> counts;
    for (const RivalMotions::Rival& rival : result.search.rivals)
        counts.push_back(rival.score.inlierCount);
    std::sort(counts.begin(), counts.end());
    return counts;
}

// The corridor at inlier ratios 0.3 and 0.8, testRuns(4, 1) seeds each.
std::vector<SyntheticScene> corridorScenes()
{
    std::vector<SyntheticScene> scenes;
    for (int seed = 0; seed < testRuns(4, 1); ++seed)
        for (double inlierRatio : {0.3, 0.8})
            scenes.push_back(testScene(SCENE_CORRIDOR, seed, inlierRatio));
    return scenes;
}

// Runs each configuration on each scene (seeded by its position; exact and adaptive, serial and
// parallel) as the method and with the scorer `reading`, expects the same runs, and returns the
// mean points read per hypothesis of both.
std::pair<double, double> compareReading(const std::vector<Configuration>& methods, Reading reading,
                                         const std::vector<SyntheticScene>& scenes)
{
    double pointsRead[2] = {0, 0};
    int runs = 0;
    for (size_t s = 0; s < scenes.size(); ++s) {
        for (Configuration configuration : methods)
            for (bool exact : {false, true})
                for (bool parallel : {false, true}) {
                    Params& params = configuration.params;
                    params.randomGeneratorState = static_cast<int>(s);
                    params.maxIterations = 300;
                    params.exactIterations = exact;
                    params.isParallel = parallel;
                    const Estimation bail =
                        estimateWith(scenes[s], configuration, Reading::kAsTheMethod);
                    const Estimation full = estimateWith(scenes[s], configuration, reading);
                    const std::string what =
                        cv::format("scene %d solver %d scoring %d K %d exact %d parallel %d",
                                   static_cast<int>(s), static_cast<int>(params.solver),
                                   static_cast<int>(params.scoring), configuration.calibrated,
                                   exact, parallel);
                    EXPECT_EQ(bail.estimate.status, full.estimate.status) << what;
                    EXPECT_EQ(bail.search.iterations, full.search.iterations) << what;
                    EXPECT_EQ(bail.search.hypotheses, full.search.hypotheses) << what;
                    EXPECT_EQ((bail.estimate.model.F - full.estimate.model.F).norm(), 0.0) << what;
                    EXPECT_EQ(bail.estimate.mask, full.estimate.mask) << what;
                    EXPECT_EQ(rivalCounts(bail), rivalCounts(full)) << what;
                    EXPECT_TRUE(bail.estimate.rivalCostGap == full.estimate.rivalCostGap ||
                                (cvIsNaN(bail.estimate.rivalCostGap) &&
                                 cvIsNaN(full.estimate.rivalCostGap)))
                        << what;
                    pointsRead[0] += bail.search.pointsPerHypothesis;
                    pointsRead[1] += full.search.pointsPerHypothesis;
                    ++runs;
                }
    }
    return {pointsRead[0] / runs, pointsRead[1] / runs};
}

// The band's count is the same on every machine: whichever clone the loader picks (AVX-512, AVX2
// or the baseline, geometry/vector_clones.hpp), each point's (x2^T F x1)^2 <= t^2 |J|^2 is the
// arithmetic written below, operation for operation, with no fused multiply-add. Each point in
// turn is put exactly on the band's edge (t^2 its own ratio), where a rounding of one unit in
// the last place decides it; a clone that rounds otherwise flips about half of them.
TEST(Rcme_BailOut, the_band_count_rounds_as_the_scalar_arithmetic_at_the_edge)
{
    cv::RNG rng(21);
    Eigen::Matrix<double, 3, 3, Eigen::RowMajor> F;
    for (int k = 0; k < 9; ++k)
        F.data()[k] = rng.uniform(-1.0, 1.0) * (k == 8                 ? 100.0
                                                : k % 3 == 2 || k >= 6 ? 1e-2
                                                                       : 1e-5);
    const int n = 200; // several vector blocks and a remainder
    std::vector<Eigen::Vector2d> points1(n), points2(n);
    for (int i = 0; i < n; ++i) {
        points1[i] = Eigen::Vector2d(rng.uniform(0.0, 1000.0), rng.uniform(0.0, 800.0));
        points2[i] = Eigen::Vector2d(rng.uniform(0.0, 1000.0), rng.uniform(0.0, 800.0));
    }
    // (x2^T F x1)^2 and the squared norm of its gradient, as residual_bands.cpp writes them.
    const auto sampsonParts = [&](int i, double& rr, double& jj) {
        const double x1 = points1[i].x(), y1 = points1[i].y(), x2 = points2[i].x(),
                     y2 = points2[i].y();
        const double* f = F.data();
        const double l0 = f[0] * x1 + f[1] * y1 + f[2];
        const double l1 = f[3] * x1 + f[4] * y1 + f[5];
        const double l2 = f[6] * x1 + f[7] * y1 + f[8];
        const double m0 = f[0] * x2 + f[3] * y2 + f[6];
        const double m1 = f[1] * x2 + f[4] * y2 + f[7];
        const double r = x2 * l0 + y2 * l1 + l2;
        rr = r * r;
        jj = l0 * l0 + l1 * l1 + m0 * m0 + m1 * m1;
    };
    const Eigen::Matrix3d Fc = F;
    int onEdge = 0;
    for (int k = 0; k < n; ++k) {
        double rrK = 0, jjK = 0;
        sampsonParts(k, rrK, jjK);
        const double thresholdSquared = rrK / jjK;
        int expected = 0;
        for (int i = 0; i < n; ++i) {
            double rr = 0, jj = 0;
            sampsonParts(i, rr, jj);
            expected += (rr <= thresholdSquared * jj) & (jj > 0);
            if (i == k)
                onEdge += rr == thresholdSquared * jj;
        }
        ASSERT_EQ(countInSampsonBand(Fc, points1, points2, thresholdSquared), expected) << k;
    }
    EXPECT_GT(onEdge, 0); // some points sit on the edge to the last bit
}

TEST(Rcme_BailOut, a_run_is_the_same_as_with_every_point_read)
{
    // Standard (inlier count) with the 7-point solver, and the default (5-point, local
    // optimisation, the ambiguity test's rivals, inner sampling at w = 0.3).
    Params standard = Params::asPublished(METHOD_STANDARD);
    standard.solver = SOLVER_SEVEN_POINT;
    const auto [bail, full] = compareReading({{standard, true}, {Params(), true}},
                                             Reading::kEveryPoint, corridorScenes());
    std::cout << "points read per hypothesis: " << bail << " with bail-out, " << full << " without"
              << std::endl;
    EXPECT_EQ(full, testScene(SCENE_CORRIDOR, 0, 0.3).points1.rows);
    // 0.86 on these scenes (a hypothesis stops once it misses more points than the best one
    // does, and at w = 0.3 the best misses most); real pairs, at w = 0.66-0.99, save more.
    EXPECT_LT(bail, 0.9 * full);
}

// The truncated cost (the default without K; with K too when asked, where the rival memory cannot
// take the count's bound) stops reading a hypothesis that can no longer change the run: the same
// runs, fewer points read. Besides the corridor, scenes of the F-only hard cases' kinds (few
// points, few true ones, wide noise). Which hypotheses the rule must keep reading is checked on
// the scorer itself (test_components.cpp): with local optimisation these runs rarely meet one.
TEST(Rcme_BailOut, the_truncated_cost_run_is_the_same_as_with_every_point_read)
{
    Params withK;
    withK.scoring = SCORING_TRUNCATED_COST;
    Params standard = Params::asPublished(METHOD_STANDARD);
    standard.scoring = SCORING_TRUNCATED_COST;
    std::vector<SyntheticScene> scenes = corridorScenes();
    size_t points = 0;
    for (int seed = 0; seed < testRuns(4, 2); ++seed) {
        scenes.push_back(testScene(SCENE_GENERIC, seed, 0.5, 1.0, 40));
        scenes.push_back(testScene(SCENE_GENERIC, seed, 0.2, 1.0, 300));
        scenes.push_back(testScene(SCENE_GENERIC, seed, 0.5, 2.0, 100));
    }
    for (const SyntheticScene& scene : scenes)
        points += static_cast<size_t>(scene.points1.rows);
    const auto [bail, full] = compareReading({{Params(), false}, {standard, false}, {withK, true}},
                                             Reading::kEveryPoint, scenes);
    std::cout << "points read per hypothesis, truncated cost: " << bail << " with bail-out, "
              << full << " without" << std::endl;
    EXPECT_NEAR(full, static_cast<double>(points) / scenes.size(), 1e-9);
    EXPECT_LT(bail, 0.95 * full);
}

// SPRT on the band counts the inliers of a hypothesis it passes on every point; the inlier count
// takes that count instead of reading the points again (with or without bail-out), and the run
// stays the same.
TEST(Rcme_BailOut, a_count_taken_by_sprt_is_not_taken_again)
{
    Params standard = Params::asPublished(METHOD_STANDARD);
    standard.solver = SOLVER_SEVEN_POINT;
    Params byDefault;
    for (Params* params : {&standard, &byDefault})
        params->verification = VERIFICATION_SPRT;
    const auto [counted, readAgain] = compareReading({{standard, true}, {byDefault, true}},
                                                     Reading::kWithBailOutOnly, corridorScenes());
    std::cout << "points read per hypothesis with SPRT: " << counted << ", " << readAgain
              << " when a passed hypothesis is read again" << std::endl;
    EXPECT_LT(counted, 0.95 * readAgain);
}

} // namespace
} // namespace opencv_test

#endif // RCME_STANDALONE_TESTS
