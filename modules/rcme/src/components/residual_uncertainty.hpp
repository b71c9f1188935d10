// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_COMPONENTS_RESIDUAL_UNCERTAINTY_HPP
#define OPENCV_RCME_COMPONENTS_RESIDUAL_UNCERTAINTY_HPP

#include "framework/components.hpp"

#include <algorithm>
#include <limits>

namespace cv {
namespace rcme {
namespace detail {

/** A model's first-order uncertainty propagated to the Sampson distance of a correspondence
(doc/algorithm.md, "Inliers by propagated uncertainty"). With r = x2^T F x1, J = dr/d(x1, x2),
the Sampson distance is d = r / |J|, and to first order its variance is

    v = sigma^2 + s * a^T M a / |J|^2,   a = vec(x2 x1^T),   M = D Sigma D^T,

D holding the model's directions dF/dtheta_k as columns and Sigma their covariance: the noise of
the point plus the model's own uncertainty (s = +1, the paper's choice), or minus it for a point
that built the model (s = -1, its leverage). The Sampson error vector is rank one, so this scalar
variance is all of its covariance on its support. */
class ResidualUncertainty
{
public:
    //! The model's uncertainty must be known.
    ResidualUncertainty(const Model& model, double sigma);

    //! Squared Sampson distance d^2 and its variance v (pixels^2); v is kept positive.
    void evaluate(const Eigen::Vector2d& x1, const Eigen::Vector2d& x2, bool leverage,
                  double& distanceSquared, double& variance) const;
    /** The same (s = +1) for the `count` correspondences from points1[0] and points2[0], into
    distancesSquared[] and variances[]: the scorers' loop, vectorized across points, with the
    arithmetic of the one-point form (the same results). */
    void evaluate(const Eigen::Vector2d* points1, const Eigen::Vector2d* points2, size_t count,
                  double* distancesSquared, double* variances) const;

private:
    double F_[9]; //!< row-major
    //! C with C^T C = M, row-major: a^T M a = |C a|^2 (rows beyond the model's DoF are zero).
    double factor_[7 * 9];
    int rows_ = 0; //!< the model's DoF: the rows of the factor that are not zero
    double sigmaSquared_;
};

/** Calls visit(i, distanceSquared, variance) for every point that is an inlier of `model` by
its propagated uncertainty, d^2 <= bound * min(v, maxVariance) (the paper's eq. 4, Cov-RANSAC's
test); for no point when the model has no uncertainty. */
template <class Visit>
void forEachUncertainInlier(const TwoViewData& data, const Model& model, double sigma, double bound,
                            Visit&& visit,
                            double maxVariance = std::numeric_limits<double>::infinity())
{
    constexpr size_t kBlock = 256;
    if (!model.uncertainty.isKnown())
        return;
    const ResidualUncertainty uncertainty(model, sigma);
    double distancesSquared[kBlock], variances[kBlock];
    const size_t n = data.points1.size();
    for (size_t begin = 0; begin < n; begin += kBlock) {
        const size_t count = std::min(kBlock, n - begin);
        uncertainty.evaluate(&data.points1[begin], &data.points2[begin], count, distancesSquared,
                             variances);
        for (size_t j = 0; j < count; ++j) {
            const double variance = std::min(variances[j], maxVariance);
            if (distancesSquared[j] <= bound * variance)
                visit(begin + j, distancesSquared[j], variance);
        }
    }
}

//! The mask of forEachUncertainInlier's points (resized to data.size()).
inline void classifyByUncertainty(const TwoViewData& data, const Model& model, double sigma,
                                  double bound, std::vector<uchar>& mask,
                                  double maxVariance = std::numeric_limits<double>::infinity())
{
    mask.assign(data.points1.size(), 0);
    forEachUncertainInlier(
        data, model, sigma, bound, [&](size_t i, double, double) { mask[i] = 1; }, maxVariance);
}

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_COMPONENTS_RESIDUAL_UNCERTAINTY_HPP
