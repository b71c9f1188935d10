// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_ESTIMATION_MODEL_FIT_HPP
#define OPENCV_RCME_ESTIMATION_MODEL_FIT_HPP

#include "framework/model.hpp"

#include <vector>

namespace cv {
namespace rcme {
namespace detail {

/** Gold Standard fit of `model` as `form` (ModelForm::kMotion: its motion, which it must have;
ModelForm::kFundamental: its F, the motion untouched) on the points `indices`, with the
first-order covariance of the result at the stated sigma (Model::uncertainty: the motion's or F's,
as `form`; none when the information matrix is ill-conditioned). False when there are too few
points to fit. */
bool fitModelOn(const TwoViewData& data, ModelForm form, const std::vector<int>& indices,
                int maxIterations, Model& model);

/** The final estimate's fit: as fitModelOn, then refitted without the inliers the others do not
confirm (leverage, studentized residual) when enough remain; `confirmed` gets the points used,
and the covariance is the final estimate's (the estimated noise, truncation-corrected; see
Report::covariance). */
bool fitFinalModelOn(const TwoViewData& data, ModelForm form, const std::vector<int>& indices,
                     int maxIterations, Model& model, std::vector<int>& confirmed);

/** How much more the Cauchy estimate of scale s varies than least squares on the same residuals
d_i (Huber's sandwich of an M-estimator, its scalar form): n^2 sum psi^2 / ((sum psi')^2 sum d^2),
psi(d) = d / (1 + d^2 / s^2) the loss's influence. For Gaussian noise inside a band of 1.96 sigma
it is 1.5 at s = sigma and 2.3 at s = sigma / 2 (the polish's scale at a threshold of 1.96 sigma):
the loss gives up precision; it falls below 1 where the residuals' tails are wider than a
Gaussian's. Accumulated one squared residual at a time; NaN when the loss's curvature is not
positive on the points (most of them beyond s: the polish does not apply). */
class CauchyVarianceFactor
{
public:
    explicit CauchyVarianceFactor(double scale2) : scale2_(scale2) {}
    void add(double squared);
    double value() const;

private:
    double scale2_, influence2_ = 0, curvature_ = 0, residual2_ = 0, count_ = 0;
};

/** The robust polish of a final estimate with a motion: the motion refitted on the points
`indices` with a Cauchy loss of scale `lossScale` (pixels) on their Sampson distances, so that
the few widest residuals among the inliers weigh less than in least squares; its covariance is
the final estimate's at the polished motion (fitFinalModelOn's formula), and
Model::polishLossScale the loss's scale, from which the reported covariance takes the polished
motion's own sandwich (components/residual_covariance.cpp). False (model
untouched) without a camera matrix or a motion, on fewer than 35 (30 residual degrees of freedom,
as the noise estimate) or more than kMaxIteratedPoints
points (two_view_data.hpp), when the loss is less precise than least squares on these residuals
(an M-estimator's sandwich, its inefficiency >= 1: Gaussian noise), or when the polished
motion's covariance is not defined. */
bool polishFinalMotionOn(const TwoViewData& data, const std::vector<int>& indices, double lossScale,
                         int maxIterations, Model& model);

/** Whether the final estimate's covariance is computed with the noise estimated from its
residuals (`noiseSigma`, Model::noiseSigma) rather than the stated sigma: Params::useEstimatedNoise
and at least 30 residual degrees of freedom (inliers minus the model's). */
bool usesEstimatedNoise(const TwoViewData& data, double noiseSigma, int residualDof);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_ESTIMATION_MODEL_FIT_HPP
