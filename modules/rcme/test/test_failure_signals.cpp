// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The motion tests behind STATUS_UNDETERMINED_MOTION: the uncertainty bound and the ambiguity
// test (Params::maxRotationStdDeg, maxTranslationStdDeg, ambiguityMargin), each on and off.

#include "test_precomp.hpp"

namespace opencv_test {
namespace {

SyntheticScene genericScene(int seed)
{
    SceneParams sp;
    sp.kind = SCENE_GENERIC;
    sp.seed = seed;
    sp.numPoints = 300;
    sp.inlierRatio = 0.7;
    return generateScene(sp);
}

TEST(Rcme_FailureSignals, uncertainty_bound_flags_only_motions_above_it)
{
    const SyntheticScene s = genericScene(1);
    cv::rcme::Params params;
    const Report free = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
    ASSERT_EQ(free.status, STATUS_SUCCESS) << free.message;
    ASSERT_TRUE(std::isfinite(free.translationStdDeg));

    params.maxTranslationStdDeg = 0.5 * free.translationStdDeg;
    const Report tight = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
    EXPECT_EQ(tight.status, STATUS_UNDETERMINED_MOTION);
    EXPECT_TRUE(tight.R.empty());
    EXPECT_FALSE(tight.rejectedR.empty()); // the motion turned down is reported
    EXPECT_EQ(countNonZero(tight.mask), 0);
    EXPECT_NE(tight.message.find("maxTranslationStdDeg"), std::string::npos) << tight.message;

    params.maxTranslationStdDeg = 2.0 * free.translationStdDeg;
    params.maxRotationStdDeg = 0.5 * cv::norm(free.rotationStdDeg, NORM_INF);
    const Report rotation = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
    EXPECT_EQ(rotation.status, STATUS_UNDETERMINED_MOTION);
    EXPECT_NE(rotation.message.find("maxRotationStdDeg"), std::string::npos) << rotation.message;

    params.maxRotationStdDeg = 2.0 * cv::norm(free.rotationStdDeg, NORM_INF);
    const Report loose = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
    EXPECT_EQ(loose.status, STATUS_SUCCESS) << loose.message;
}

TEST(Rcme_FailureSignals, ambiguity_test_reports_its_gap_and_flags_below_the_margin)
{
    int flagged = 0, tested = 0;
    for (int seed = 0; seed < 6; ++seed) {
        const SyntheticScene s = genericScene(seed);
        cv::rcme::Params params;
        params.solver = SOLVER_FIVE_POINT;
        const Report off = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        EXPECT_TRUE(std::isnan(off.rivalCostGap)); // off by default
        params.ambiguityMargin = 2.0;
        const Report on = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        if (on.status == STATUS_SUCCESS) {
            ++tested;
            EXPECT_GE(on.rivalCostGap, 2.0); // a success has no rival within the margin
            // A well-conditioned scene keeps its right motion.
            const MotionError e = compareMotion(on.R, on.t, s.R, s.t);
            EXPECT_LT(e.rotationDeg, 2.0);
            EXPECT_LT(e.translationDeg, 5.0);
        } else if (on.status == STATUS_UNDETERMINED_MOTION) {
            ++flagged;
            EXPECT_LT(on.rivalCostGap, 2.0);
            EXPECT_FALSE(on.rejectedR.empty());
        }
        // Every finite gap is large with a margin below it: the status follows the gap.
        params.ambiguityMargin = 1e9;
        const Report all = estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
        if (std::isfinite(all.rivalCostGap))
            EXPECT_EQ(all.status, STATUS_UNDETERMINED_MOTION);
    }
    EXPECT_GE(tested, 4) << flagged << " flagged";
}

TEST(Rcme_FailureSignals, nan_bounds_are_rejected_naming_the_field)
{
    const SyntheticScene s = genericScene(0);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const char* field : {"ambiguityMargin", "maxRotationStdDeg", "maxTranslationStdDeg"}) {
        cv::rcme::Params params;
        const std::string name(field);
        (name == "ambiguityMargin" ? params.ambiguityMargin
         : name == "maxRotationStdDeg" ? params.maxRotationStdDeg
                                       : params.maxTranslationStdDeg) = nan;
        try {
            estimateRelativeMotion(s.points1, s.points2, s.cameraMatrix, params);
            ADD_FAILURE() << field << ": NaN accepted";
        } catch (const cv::Exception& e) {
            EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
        }
    }
}

TEST(Rcme_FailureSignals, statusToString_names_the_new_status)
{
    EXPECT_EQ(statusToString(STATUS_UNDETERMINED_MOTION), "undetermined motion");
}

} // namespace
} // namespace opencv_test
