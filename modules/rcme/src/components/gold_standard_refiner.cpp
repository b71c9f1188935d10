// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Box 4 of Fig. 1, model refinement: the Gold Standard fit of estimation/model_fit.cpp on the
// selected model's inliers, and the final estimate's inlier band and covariance.

#include "estimation/model_fit.hpp"
#include "framework/component_factories.hpp"
#include "framework/model_space.hpp"
#include "geometry/epipolar.hpp"
#include "geometry/motion_parameterization.hpp"
#include "geometry/sampson_gradients.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

class GoldStandardRefiner final : public Refiner
{
public:
    GoldStandardRefiner(int maxIterations, std::shared_ptr<const ModelSpace> space)
        : space_(std::move(space)), maxIterations_(maxIterations)
    {
    }

    bool refine(const TwoViewData& data, const std::vector<uchar>& mask, Model& model) override
    {
        maskIndices(mask, inliers_);
        return fitModelOn(data, space_->formOf(model), inliers_, maxIterations_, model);
    }

    // The final covariance (setFinalUncertainty) is that of least squares on the points inside
    // the band of the final estimate itself. The scorer's mask is the band of the model before
    // the fit, so the band is taken again at each fit until it no longer changes. Each round moves
    // the model only about half the way (the band of the model before it truncates the fit
    // towards that model), and on a large set the band never stops changing at its edges: four
    // rounds on every point stopped short by many times the reported deviation
    // (doc/performance.md, "Large inputs"). So a large set settles its band on the evenly spaced
    // subset of the fits' iterations first (kMaxIteratedPoints), where a round is cheap, and then
    // takes three rounds on every point (each halves what is left of the subset's noise).
    void finalize(const TwoViewData& data, std::vector<uchar>& mask, Model& model,
                  FinalModel kind) override
    {
        constexpr int kMaxRounds = 4, kMaxSubsetRounds = 12, kRoundsAfterSubset = 3;
        const int iterations = kind == FinalModel::kFitted ? maxIterations_ : 0;
        selection_ = mask;
        int rounds = kMaxRounds;
        const size_t stride = subsetStride(data.points1.size());
        if (stride > 1) {
            const TwoViewData subset = evenlySpacedSubset(data, kMaxIteratedPoints);
            std::vector<uchar> subsetSelection;
            for (size_t i = 0; i < selection_.size(); i += stride)
                subsetSelection.push_back(selection_[i]);
            if (settleBand(subset, subsetSelection, model, kMaxSubsetRounds, iterations)) {
                takeBand(data, model.F, selection_);
                rounds = kRoundsAfterSubset;
            }
        }
        if (!settleBand(data, selection_, model, rounds, iterations))
            return;
        std::fill(mask.begin(), mask.end(), 0);
        for (int i : finalInliers_)
            mask[static_cast<size_t>(i)] = 1;
    }

private:
    // The points within the threshold of F.
    static void takeBand(const TwoViewData& data, const Eigen::Matrix3d& F,
                         std::vector<uchar>& band)
    {
        markWithinSampsonDistance(F, data.points1, data.points2, data.threshold * data.threshold,
                                  band);
    }

    // Fits on `selection` (`iterations` of least squares each) and takes the fit's band as the
    // next selection, until it no longer changes or after `maxRounds` fits; finalInliers_ are the
    // points of the last fit. False when no fit was possible.
    bool settleBand(const TwoViewData& data, std::vector<uchar>& selection, Model& model,
                    int maxRounds, int iterations)
    {
        finalInliers_.clear();
        for (int round = 0; round < maxRounds; ++round) {
            if (!fitFinal(data, selection, model, iterations, /*firstFit=*/round == 0))
                break;
            finalInliers_ = confirmed_;
            if (round + 1 == maxRounds)
                break;
            takeBand(data, model.F, band_);
            if (band_ == selection)
                break;
            selection.swap(band_);
        }
        return !finalInliers_.empty();
    }

    // One final fit on `selection`: the inliers in front of both cameras (calibrated), least
    // squares, the unconfirmed inliers dropped (confirmed_), the final uncertainty. False (model
    // unchanged) when the points do not determine the model, or when a refit after the first is
    // undone (below).
    bool fitFinal(const TwoViewData& data, const std::vector<uchar>& selection, Model& model,
                  int iterations, bool firstFit)
    {
        const std::vector<uchar>* chosen = &selection;
        if (model.motion()) {
            // An inlier whose point triangulates behind a camera is no correspondence of this
            // motion but an outlier that fell into its band by chance. Such points lie near the
            // epipoles or at extreme depths, where one of them outweighs dozens of true ones:
            // kept, they pull the motion and make its covariance confident where it is wrong.
            // Far points are kept (no distance bound): only a negative depth says "outlier".
            // When that would drop most inliers, their depths are not determined (rays nearly
            // parallel: a pure rotation) and cheirality says nothing about them.
            const int inFront = countPointsInFront(
                model.motion()->R, model.motion()->t, data.points1, data.points2, data.Kinv,
                &selection, &inFront_, std::numeric_limits<double>::infinity());
            if (2 * inFront >= static_cast<int>(std::count(selection.begin(), selection.end(), 1)))
                chosen = &inFront_;
        }
        maskIndices(*chosen, inliers_);
        Model fitted = model;
        const ModelForm form = space_->formOf(model);
        if (!fitFinalModelOn(data, form, inliers_, iterations, fitted, confirmed_))
            return false;
        // Where the points do not determine the motion (a pure rotation leaves t free, when the
        // degeneracy test is off), the refit may turn t into the decomposition that puts the
        // points behind the cameras; then the motion stays and only its uncertainty is updated.
        // Counted within recoverPose's 50 baselines, unlike the inliers' check above (negative
        // depths only cost the default's corridor confusion cells, doc/architecture.md, "Final
        // fit and covariance"). After a first final fit, the previous fit stands whole, its motion
        // with the mask and covariance it was fitted with: this fit's mask and covariance with the
        // previous motion left it off its mask's least-squares minimum.
        if (model.motion() &&
            2 * countPointsInFront(fitted.motion()->R, fitted.motion()->t, data.points1,
                                   data.points2, data.Kinv, &selection, nullptr) <
                static_cast<int>(inliers_.size())) {
            if (!firstFit)
                return false;
            fitted = model;
            if (!fitFinalModelOn(data, form, inliers_, 0, fitted, confirmed_))
                return false;
        }
        model = fitted;
        return true;
    }

    // Reused, and sized for every point at once (maskIndices): local optimisation refines inside
    // the hypothesis loop, which must not allocate.
    std::shared_ptr<const ModelSpace> space_;
    std::vector<uchar> selection_, band_, inFront_;
    std::vector<int> confirmed_, finalInliers_;
    int maxIterations_;
    std::vector<int> inliers_;
};

} // namespace

std::unique_ptr<Refiner> createGoldStandardRefiner(int maxIterations,
                                                   std::shared_ptr<const ModelSpace> space)
{
    return std::make_unique<GoldStandardRefiner>(maxIterations, std::move(space));
}

} // namespace detail
} // namespace rcme
} // namespace cv
