// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Real roots by Sturm sequences (Sturm's theorem: the number of sign changes of p0 = p,
// p1 = p', p(k+1) = -(p(k-1) mod p(k)) drops by the number of distinct roots between two
// points). Bisection on that count isolates each root in an interval of its own; Newton steps
// kept inside the interval finish it. The 5-point solver's degree-10 polynomial needs this once
// per sample, so it must be cheap: a companion-matrix eigen decomposition costs ten times more.

#include "solvers/real_roots.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cv {
namespace rcme {
namespace detail {

namespace {

constexpr int kMaxTerms = kMaxRootDegree + 1;

//! p(x) by Horner's rule; coefficients ascending.
double evaluate(const double* p, int degree, double x)
{
    double value = p[degree];
    for (int i = degree - 1; i >= 0; --i)
        value = value * x + p[i];
    return value;
}

//! Scales p to a largest coefficient of magnitude one (a positive factor: signs are kept).
void rescale(double* p, int degree)
{
    double largest = 0;
    for (int i = 0; i <= degree; ++i)
        largest = std::max(largest, std::abs(p[i]));
    if (largest > 0)
        for (int i = 0; i <= degree; ++i)
            p[i] /= largest;
}

struct SturmSequence
{
    double p[kMaxTerms][kMaxTerms];
    int degree[kMaxTerms];
    int length = 0;

    explicit SturmSequence(const double* monic, int n)
    {
        std::copy(monic, monic + n + 1, p[0]);
        degree[0] = n;
        rescale(p[0], n);
        for (int i = 1; i <= n; ++i)
            p[1][i - 1] = i * monic[i];
        degree[1] = n - 1;
        rescale(p[1], n - 1);
        length = 2;
        // p(k+1) = -(p(k-1) mod p(k)), until a constant; a vanishing remainder means repeated
        // roots, and the sequence then ends at their greatest common divisor (still a valid count
        // of the distinct roots).
        while (length < kMaxTerms && degree[length - 1] > 0) {
            const double* divisor = p[length - 1];
            const int m = degree[length - 1];
            double remainder[kMaxTerms];
            const int dividendDegree = degree[length - 2];
            std::copy(p[length - 2], p[length - 2] + dividendDegree + 1, remainder);
            for (int i = dividendDegree; i >= m; --i) {
                const double q = remainder[i] / divisor[m];
                for (int j = 0; j <= m; ++j)
                    remainder[i - m + j] -= q * divisor[j];
            }
            int r = m - 1;
            constexpr double kNegligible = 1e-14; // next to the dividend's unit-size coefficients
            while (r >= 0 && std::abs(remainder[r]) <= kNegligible)
                --r;
            if (r < 0)
                break;
            for (int i = 0; i <= r; ++i)
                p[length][i] = -remainder[i];
            degree[length] = r;
            rescale(p[length], r);
            ++length;
        }
    }

    int signChanges(double x) const
    {
        int changes = 0;
        double previous = 0;
        for (int k = 0; k < length; ++k) {
            const double value = evaluate(p[k], degree[k], x);
            if (value == 0)
                continue;
            if (previous != 0 && (value < 0) != (previous < 0))
                ++changes;
            previous = value;
        }
        return changes;
    }
};

//! The one root of the sequence's p in (lo, hi].
double polishIsolatedRoot(const SturmSequence& sturm, double lo, double hi)
{
    const double* p = sturm.p[0];
    const int n = sturm.degree[0];
    const double fLo = evaluate(p, n, lo), fHi = evaluate(p, n, hi);
    if (fHi == 0)
        return hi;
    constexpr int kMaxSteps = 100;
    if ((fLo < 0) == (fHi < 0)) {
        // A root of even multiplicity: p keeps its sign, so bisect on the count.
        const int vLo = sturm.signChanges(lo);
        for (int step = 0; step < kMaxSteps && hi - lo > 1e-15 * std::abs(hi); ++step) {
            const double mid = 0.5 * (lo + hi);
            (vLo - sturm.signChanges(mid) >= 1 ? hi : lo) = mid;
        }
        return 0.5 * (lo + hi);
    }
    // Newton from the middle; a step that leaves the bracket is replaced by bisection.
    double x = 0.5 * (lo + hi);
    for (int step = 0; step < kMaxSteps; ++step) {
        double f = p[n], df = 0;
        for (int i = n - 1; i >= 0; --i) {
            df = df * x + f;
            f = f * x + p[i];
        }
        if (f == 0)
            return x;
        ((f < 0) == (fLo < 0) ? lo : hi) = x;
        double next = df != 0 ? x - f / df : lo;
        if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
        const bool converged =
            std::abs(next - x) <= 4 * std::numeric_limits<double>::epsilon() * std::abs(next);
        x = next;
        if (converged || hi - lo <= 4 * std::numeric_limits<double>::epsilon() * std::abs(x))
            break;
    }
    return x;
}

} // namespace

int realRoots(const double* coefficients, int degree, double* roots)
{
    if (degree < 1 || degree > kMaxRootDegree)
        return 0;
    double largest = 0;
    for (int i = 0; i <= degree; ++i) {
        if (!std::isfinite(coefficients[i]))
            return 0;
        largest = std::max(largest, std::abs(coefficients[i]));
    }
    int n = degree;
    constexpr double kNegligibleLeading = 1e-13;
    while (n > 0 && std::abs(coefficients[n]) <= kNegligibleLeading * largest)
        --n;
    if (n < 1)
        return 0;
    double monic[kMaxTerms];
    for (int i = 0; i <= n; ++i)
        monic[i] = coefficients[i] / coefficients[n];
    monic[n] = 1;

    // Fujiwara's bound: every root lies within 2 max |a(n-i)|^(1/i), the last term halved.
    double bound = 0;
    for (int i = 1; i <= n; ++i) {
        const double a = std::abs(monic[n - i]) / (i == n ? 2.0 : 1.0);
        bound = std::max(bound, std::pow(a, 1.0 / i));
    }
    bound = 2.01 * bound + 1e-300; // roots can lie on the bound itself: widened a little

    const SturmSequence sturm(monic, n);
    struct Interval
    {
        double lo, hi;
        int changesLo, changesHi;
    };
    // Depth-first, left half on top: the roots come out in increasing order. A binary split
    // never holds more than its depth plus one intervals.
    constexpr int kStack = 128;
    Interval stack[kStack];
    int top = 0, found = 0;
    stack[top++] = {-bound, bound, sturm.signChanges(-bound), sturm.signChanges(bound)};
    while (top > 0 && found < n) {
        const Interval interval = stack[--top];
        const int count = interval.changesLo - interval.changesHi;
        if (count <= 0)
            continue;
        if (count == 1) {
            roots[found++] = polishIsolatedRoot(sturm, interval.lo, interval.hi);
            continue;
        }
        const double mid = 0.5 * (interval.lo + interval.hi);
        // Roots closer than the arithmetic can tell apart are one root; so is a split deeper
        // than the stack.
        if (interval.hi - interval.lo <= 1e-13 * std::max(1.0, std::abs(mid)) || top + 2 > kStack) {
            roots[found++] = mid;
            continue;
        }
        const int changesMid = sturm.signChanges(mid);
        stack[top++] = {mid, interval.hi, changesMid, interval.changesHi};
        stack[top++] = {interval.lo, mid, interval.changesLo, changesMid};
    }
    return found;
}

} // namespace detail
} // namespace rcme
} // namespace cv
