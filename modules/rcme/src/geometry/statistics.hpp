// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_GEOMETRY_STATISTICS_HPP
#define OPENCV_RCME_GEOMETRY_STATISTICS_HPP

namespace cv {
namespace rcme {
namespace detail {

//! Phi^-1(p), the standard normal quantile, for p in (0, 1).
double normalQuantile(double p);

//! F_k^-1(p), the chi-square quantile with k degrees of freedom, for p in (0, 1).
double chiSquareQuantile(double p, int dof);

/** Smallest k with P(Binomial(trials, p) >= k) <= level: how many successes chance alone
exceeds only with probability `level`. */
int binomialTailBound(int trials, double p, double level);

//! log C(n, k), for 0 <= k <= n.
double logBinomialCoefficient(int n, int k);

/** log P(X >= successes), X ~ Binomial(trials, p), summed in logarithms (a real pair's tail,
10^-400 and below, underflows in probabilities). */
double logBinomialTail(int trials, double p, int successes);

/** RANSAC's bound: how many independent samples hold at least one good sample with probability
`confidence`, when each is good with probability `goodSample`: log(1 - confidence) /
log(1 - goodSample); +infinity when goodSample <= 0. */
double samplesForConfidence(double confidence, double goodSample);

/** E[z^2 | |z| < k] for a standard normal z: the variance left to residuals that an inlier band
of half-width k sigma truncates (1 for k -> infinity, k^2 / 3 for k -> 0). */
double truncatedNormalVariance(double k);

/** variance / truncatedNormalVariance(threshold / sqrt(variance)): the factor on (J^T J)^-1 of a
fit's model-based covariance at noise variance `variance` whose residuals a band |d| < threshold
has truncated. */
double truncatedNoiseVariance(double variance, double threshold);

/** The sigma of zero-mean Gaussian residuals from the mean square of those kept by the band
|d| < threshold: solves sigma^2 truncatedNormalVariance(threshold / sigma) = meanSquare. NaN
when meanSquare is not below threshold^2 / 3 (residuals spread as uniformly as the band allows:
no Gaussian explains them) or not positive. */
double noiseFromTruncatedResiduals(double meanSquare, double threshold);

/** The noise variance of a fit whose residuals estimate sigma as `estimated` with `dof` degrees of
freedom, with the `stated` sigma as a prior worth `priorDof` degrees of freedom: the mean of
sigma^2's scaled-inverse-chi-square posterior, (priorDof stated^2 + dof estimated^2) /
(priorDof + dof - 2). It moves from the stated sigma towards the estimate as the residuals
accumulate, with no jump, and the -2 widens it by what the estimate's own uncertainty adds to
the error's spread (the error is Student-t). `stated` alone when the estimate is not finite or
dof < 1; needs priorDof > 2. */
double posteriorNoiseVariance(double stated, double estimated, int dof, double priorDof);

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_GEOMETRY_STATISTICS_HPP
