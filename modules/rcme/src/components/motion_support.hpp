// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_COMPONENTS_MOTION_SUPPORT_HPP
#define OPENCV_RCME_COMPONENTS_MOTION_SUPPORT_HPP

// How well a motion explains the points when cheirality counts: shared by the comparisons of
// distinct motions after the loop (a planar scene's, components/motion_space.cpp; the ambiguity
// test's, components/rival_motion_decision.cpp).

#include "framework/model.hpp"
#include "framework/rival_motions.hpp"

#include <limits>
#include <optional>
#include <vector>

namespace cv {
namespace rcme {
namespace detail {

//! A motion's fit to the points.
struct MotionSupport
{
    int support = -1; //!< points within the threshold and in front of both cameras
    //! MSAC's cost with cheirality: a point's squared Sampson distance, the squared threshold for
    //! a point outside the band or behind a camera.
    double cost = std::numeric_limits<double>::infinity();
};

/** The fit of `model` (with its motion); `within` marks the points within the threshold of its
F, `inFront` those of them in front of both cameras. */
MotionSupport motionSupport(const TwoViewData& data, const Model& model, std::vector<uchar>& within,
                            std::vector<uchar>& inFront);

//! MSAC's cost of F: each point's squared Sampson distance, at most the squared threshold.
double truncatedCost(const TwoViewData& data, const Eigen::Matrix3d& F);
//! The same with each point's cost at most `capSquared` (pixels^2).
double truncatedCost(const TwoViewData& data, const Eigen::Matrix3d& F, double capSquared);

/** Refits a motion on the points within its own band (a round: the band, then the fit on it),
twice, and returns its fit, `within` and `inFront` as motionSupport leaves them for the refitted
motion. Not on the selected model's inliers: those pull every other motion towards the selected
one (on a plane the selected F is one of a family). With `maxRounds` above two, the rounds go on
until a round's band is the previous one's or `maxRounds` are done. */
MotionSupport refitOnOwnPoints(const TwoViewData& data, Model& motion, std::vector<uchar>& within,
                               std::vector<uchar>& inFront, int maxRounds = 2);

//! Which rivals are worth refitting: those whose truncated cost as the loop left them, each
//! point's cost at most `capSquared` (pixels^2), is at most `maxCost`.
struct RawCostGate
{
    double capSquared;
    double maxCost;
};

/** The size of the evenly spaced subset on which the stages that weigh rivals refit them cheaply
(the rival decision's RefitScreen, the rival selection at the data's noise); a problem of at most
this many points is its own subset. Each stage says what it measured with it. */
constexpr size_t kRivalSubsetPoints = 300;

/** A cheaper first refit of each rival on an evenly spaced subset of `points`: a rival whose
subset refit costs more than `maxCost` on all the points (each at most `capSquared`) is returned
as that refit, the others are refitted on all the points. */
struct RefitScreen
{
    size_t points;
    double capSquared;
    double maxCost;
};

/** The loop's rival motions (SearchResult::rivals) that are other answers than `selected`: those
with at least half its support (`selectedInliers`; RivalMotions' own gate) and distinct from it,
each refitted on the points it explains itself and its decomposition chosen again by cheirality
on all the points of its band, as the selected model's was; a rival that is the selected motion
again once refitted (forward motion, far points: a sample's few points chose -t) is left out.
Refit and decomposition on an evenly spaced subset of a large problem (kMaxIteratedPoints). With
a `gate`, a rival it turns down is not refitted (its refit is the expensive part; the stages say
which rivals cannot come close) and its index in `rivals` is appended to `skipped` when given;
with a `screen`, a rival its subset refit shows to be far is not refitted on all the points.
`maxRounds`: refitOnOwnPoints'. */
std::vector<Model> refittedRivalMotions(const TwoViewData& data,
                                        const std::vector<RivalMotions::Rival>& rivals,
                                        const Model& selected, int selectedInliers,
                                        const std::optional<RawCostGate>& gate = std::nullopt,
                                        const std::optional<RefitScreen>& screen = std::nullopt,
                                        std::vector<int>* skipped = nullptr, int maxRounds = 2);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_COMPONENTS_MOTION_SUPPORT_HPP
