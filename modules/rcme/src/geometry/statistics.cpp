// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "geometry/statistics.hpp"

#include "geometry/core.hpp"

namespace cv {
namespace rcme {
namespace detail {

namespace {

// Regularized lower incomplete gamma P(a, x) by its series (converges for every x, and the
// chi-square arguments used here are small); gammaOfA = Gamma(a), computed once by the caller.
double lowerRegularizedGamma(double a, double gammaOfA, double x)
{
    if (x <= 0)
        return 0;
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 1000 && term > 1e-16 * sum; ++n) {
        term *= x / (a + n);
        sum += term;
    }
    return std::min(1.0, sum * std::exp(-x + a * std::log(x)) / gammaOfA);
}

// The root of below(x) (true left of it, false right of it) in [lo, hi], by at most 200
// halvings. They stop once no double lies strictly inside (about 60 halvings here): from then
// on a halving cannot change 0.5 (lo + hi), the value returned.
template <class Below> double bisect(double lo, double hi, const Below& below)
{
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (mid == lo || mid == hi)
            break;
        (below(mid) ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// log n!: summed below 128, Stirling's series above it (its next term is below 1e-20 there).
// Not std::lgamma: it writes the global signgam, a data race between threads (see above).
double logFactorial(int n)
{
    if (n < 128) {
        double sum = 0;
        for (int i = 2; i <= n; ++i)
            sum += std::log(double(i));
        return sum;
    }
    const double x = n, inverse = 1.0 / x, inverse2 = inverse * inverse;
    return x * std::log(x) - x + 0.5 * std::log(2.0 * CV_PI * x) +
           inverse *
               (1.0 / 12 - inverse2 * (1.0 / 360 - inverse2 * (1.0 / 1260 - inverse2 / 1680)));
}

} // namespace

double normalQuantile(double p)
{
    CV_Assert(p > 0 && p < 1);
    // Bisection on the CDF 0.5 erfc(-x / sqrt 2): plain, and exact to double precision.
    return bisect(-40, 40, [p](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)) < p; });
}

double chiSquareQuantile(double p, int dof)
{
    CV_Assert(p > 0 && p < 1 && dof >= 1);
    const double a = 0.5 * dof;
    // tgamma, not lgamma: lgamma writes the global signgam, a data race when several threads
    // estimate at once (found by TSan). a = dof / 2 is small here, far from tgamma's overflow.
    const double gammaOfA = std::tgamma(a);
    return bisect(0, 10.0 * dof + 100,
                  [&](double x) { return lowerRegularizedGamma(a, gammaOfA, 0.5 * x) < p; });
}

int binomialTailBound(int trials, double p, double level)
{
    if (p >= 1.0)
        return trials + 1;
    // The probabilities in logarithms: P(X = 0) = (1 - p)^trials underflows to zero for large
    // samples (p = 0.01 and 10^5 points), which would make every support "chance".
    const double logRatio = std::log(p) - std::log1p(-p);
    double logPmf = trials * std::log1p(-p); // log P(X = 0)
    double cdf = 0;
    for (int k = 0; k <= trials; ++k) {
        if (1.0 - cdf <= level) // 1 - cdf = P(X >= k)
            return k;
        cdf += std::exp(logPmf);
        logPmf += logRatio + std::log((trials - k) / (k + 1.0));
    }
    return trials + 1;
}

double logBinomialCoefficient(int n, int k)
{
    CV_Assert(k >= 0 && k <= n);
    return logFactorial(n) - logFactorial(k) - logFactorial(n - k);
}

double logBinomialTail(int trials, double p, int successes)
{
    if (successes <= 0 || p >= 1.0)
        return 0.0;
    if (successes > trials || p <= 0.0)
        return -std::numeric_limits<double>::infinity();
    const double logP = std::log(p), logQ = std::log1p(-p);
    double largest = -std::numeric_limits<double>::infinity(), sum = 0.0;
    for (int j = successes; j <= trials; ++j) {
        const double term = logBinomialCoefficient(trials, j) + j * logP + (trials - j) * logQ;
        if (term > largest) {
            sum = sum * std::exp(largest - term) + 1.0;
            largest = term;
        } else {
            sum += std::exp(term - largest);
            if (term < largest - 40.0) // the terms fall off geometrically past the mode
                break;
        }
    }
    return largest + std::log(sum);
}

double samplesForConfidence(double confidence, double goodSample)
{
    if (goodSample <= 0.0)
        return std::numeric_limits<double>::infinity();
    return std::log(1.0 - confidence) / std::log1p(-goodSample);
}

double truncatedNormalVariance(double k)
{
    CV_Assert(k > 0);
    if (k < 1e-4) // the series of the ratio below, where it cancels catastrophically
        return k * k / 3.0;
    const double density = std::exp(-0.5 * k * k) / std::sqrt(2.0 * CV_PI);
    const double mass = std::erf(k / std::sqrt(2.0)); // P(|z| < k)
    return 1.0 - 2.0 * k * density / mass;
}

double truncatedNoiseVariance(double variance, double threshold)
{
    return variance / truncatedNormalVariance(threshold / std::sqrt(variance));
}

double noiseFromTruncatedResiduals(double meanSquare, double threshold)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (!(meanSquare > 0) || !(threshold > 0) || !(meanSquare < threshold * threshold / 3.0))
        return nan;
    // sigma^2 h(c / sigma) grows with sigma from 0 towards c^2 / 3, and h <= 1 bounds sigma below
    // by the root mean square; bisection in log sigma.
    double lo = std::log(std::sqrt(meanSquare)), hi = lo + 1.0;
    auto secondMoment = [&](double logSigma) {
        const double sigma = std::exp(logSigma);
        return sigma * sigma * truncatedNormalVariance(threshold / sigma);
    };
    for (int i = 0; i < 200 && secondMoment(hi) < meanSquare; ++i)
        hi += 1.0;
    if (secondMoment(hi) < meanSquare)
        return nan;
    for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (secondMoment(mid) < meanSquare ? lo : hi) = mid;
    }
    return std::exp(0.5 * (lo + hi));
}

double posteriorNoiseVariance(double stated, double estimated, int dof, double priorDof)
{
    CV_Assert(stated > 0 && priorDof > 2);
    if (!(dof >= 1) || !std::isfinite(estimated))
        return stated * stated;
    const double nu = static_cast<double>(dof);
    return (priorDof * stated * stated + nu * estimated * estimated) / (priorDof + nu - 2.0);
}

} // namespace detail
} // namespace rcme
} // namespace cv
