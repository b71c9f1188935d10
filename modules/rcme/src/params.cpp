// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "precomp.hpp"

#include "params_check.hpp"

#include "generated/enum_tables.inc"

namespace cv {
namespace rcme {

Params::Params()
    : method(METHOD_STANDARD), sampler(SAMPLER_UNIFORM), solver(SOLVER_AUTO),
      verification(VERIFICATION_AUTO), scoring(SCORING_AUTO), sigma(1.0), threshold(0.0),
      confidence(0.99), cleanSampleSuccessRate(0.0), maxIterations(1000), exactIterations(false),
      randomGeneratorState(0), refine(true), refineIterations(20), useEstimatedNoise(true),
      alpha(0.05), entropyThreshold(1.27), inlierRatioFactor(0.9), priorInlierRatio(0.0),
      consistencyDof(1), sampleFitIterations(5), sampleLeverage(false),
      earlyTerminationEntropy(0.0), localOptimization(true), degeneracyTest(true),
      ambiguityMargin(2.0), maxRotationStdDeg(4.0), maxTranslationStdDeg(8.0), isParallel(false),
      timeBudget(0.0)
{
}

Params::Params(const UsacParams& usac) : Params()
{
    confidence = usac.confidence;
    maxIterations = usac.maxIterations;
    randomGeneratorState = usac.randomGeneratorState;
    threshold = usac.threshold;
    isParallel = usac.isParallel;
    switch (usac.sampler) {
    case SAMPLING_UNIFORM:
        sampler = SAMPLER_UNIFORM;
        break;
    case SAMPLING_PROSAC:
        sampler = SAMPLER_PROSAC;
        break;
    default:
        CV_Error(Error::StsBadArg,
                 "usacParams.sampler: only SAMPLING_UNIFORM and SAMPLING_PROSAC have a "
                 "counterpart in rcme");
    }
}

Params Params::fromUsacParams(const UsacParams& usacParams)
{
    return Params(usacParams);
}

Params Params::asPublished(Method method)
{
    Params p;
    p.method = method;
    if (method == METHOD_STANDARD)
        p.scoring = SCORING_INLIER_COUNT;
    p.solver = SOLVER_EIGHT_POINT;
    p.localOptimization = false;
    p.cleanSampleSuccessRate = 1.0;
    p.ambiguityMargin = 0.0;
    p.maxRotationStdDeg = 0.0;
    p.maxTranslationStdDeg = 0.0;
    return p;
}

Report::Report()
    : status(STATUS_POOR_QUALITY_INPUT), inlierCount(0), iterations(0),
      pointsPerHypothesis(std::numeric_limits<double>::quiet_NaN()),
      meanEntropy(std::numeric_limits<double>::quiet_NaN()),
      noiseSigma(std::numeric_limits<double>::quiet_NaN()),
      translationStdDeg(std::numeric_limits<double>::quiet_NaN()),
      rivalCostGap(std::numeric_limits<double>::quiet_NaN()), timeSeconds(0)
{
}

namespace {

//! One value of a public enum and its name in the generated tables.
template <class E> struct NamedValue
{
    E value;
    const char* name; //!< lower case, words joined by dashes: "cov-ransac", "poor-quality-input"
};

#define RCME_NAMED_VALUE(value, name) {value, name},
constexpr NamedValue<Method> kMethods[] = {RCME_METHOD_VALUES(RCME_NAMED_VALUE)};
constexpr NamedValue<SamplerKind> kSamplers[] = {RCME_SAMPLER_KIND_VALUES(RCME_NAMED_VALUE)};
constexpr NamedValue<MinimalSolverKind> kSolvers[] = {
    RCME_MINIMAL_SOLVER_KIND_VALUES(RCME_NAMED_VALUE)};
constexpr NamedValue<VerificationKind> kVerifications[] = {
    RCME_VERIFICATION_KIND_VALUES(RCME_NAMED_VALUE)};
constexpr NamedValue<ScoringKind> kScorings[] = {RCME_SCORING_KIND_VALUES(RCME_NAMED_VALUE)};
constexpr NamedValue<Status> kStatuses[] = {RCME_STATUS_VALUES(RCME_NAMED_VALUE)};
#undef RCME_NAMED_VALUE

//! The generated name of `value`, or nullptr when it is no value of the enum.
template <class E, size_t N> const char* nameOf(const NamedValue<E> (&table)[N], E value)
{
    for (const NamedValue<E>& entry : table)
        if (entry.value == value)
            return entry.name;
    return nullptr;
}

//! A generated name with each dash replaced by `joint` (or dropped when it is 0).
std::string spelled(const char* name, char joint)
{
    std::string out;
    for (const char* c = name; *c; ++c)
        if (*c != '-')
            out += *c;
        else if (joint)
            out += joint;
    return out;
}

template <class E, size_t N>
void checkEnum(const NamedValue<E> (&table)[N], E value, const char* field)
{
    if (!nameOf(table, value))
        CV_Error(Error::StsBadArg,
                 cv::format("Params.%s: unknown value %d", field, static_cast<int>(value)));
}

void checkRange(bool ok, const char* message)
{
    if (!ok)
        CV_Error(Error::StsBadArg, message);
}

} // namespace

namespace detail {

void validateParams(const Params& p)
{
    checkEnum(kMethods, p.method, "method");
    checkEnum(kSamplers, p.sampler, "sampler");
    checkEnum(kSolvers, p.solver, "solver");
    checkEnum(kVerifications, p.verification, "verification");
    checkEnum(kScorings, p.scoring, "scoring");
    checkRange(std::isfinite(p.sigma) && p.sigma > 0, "Params.sigma must be positive and finite");
    checkRange(std::isfinite(p.threshold), "Params.threshold must be finite (<= 0: from sigma)");
    checkRange(p.confidence > 0 && p.confidence < 1, "Params.confidence must be in (0, 1)");
    checkRange(p.cleanSampleSuccessRate >= 0 && p.cleanSampleSuccessRate <= 1,
               "Params.cleanSampleSuccessRate must be in (0, 1] (0: by the camera matrix)");
    checkRange(p.maxIterations >= 1 && p.maxIterations <= kMaxIterationsLimit,
               "Params.maxIterations must be in [1, 10000000]");
    checkRange(p.refineIterations >= 0 && p.refineIterations <= 1000,
               "Params.refineIterations must be in [0, 1000]");
    checkRange(p.alpha > 0 && p.alpha < 1, "Params.alpha must be in (0, 1)");
    checkRange(std::isfinite(p.entropyThreshold), "Params.entropyThreshold must be finite");
    checkRange(p.inlierRatioFactor > 0 && p.inlierRatioFactor <= 1,
               "Params.inlierRatioFactor must be in (0, 1]");
    checkRange(p.priorInlierRatio <= 1 && !std::isnan(p.priorInlierRatio),
               "Params.priorInlierRatio must be <= 1 (<= 0: estimated)");
    checkRange(p.consistencyDof >= 1 && p.consistencyDof <= 4,
               "Params.consistencyDof must be in [1, 4]");
    checkRange(p.sampleFitIterations >= 0 && p.sampleFitIterations <= 100,
               "Params.sampleFitIterations must be in [0, 100]");
    checkRange(std::isfinite(p.earlyTerminationEntropy),
               "Params.earlyTerminationEntropy must be finite (<= 0: off)");
    checkRange(!std::isnan(p.timeBudget), "Params.timeBudget must be a number (<= 0: none)");
    checkRange(!std::isnan(p.ambiguityMargin),
               "Params.ambiguityMargin must be a number (<= 0: off)");
    checkRange(!std::isnan(p.maxRotationStdDeg),
               "Params.maxRotationStdDeg must be a number (<= 0: off)");
    checkRange(!std::isnan(p.maxTranslationStdDeg),
               "Params.maxTranslationStdDeg must be a number (<= 0: off)");
}

} // namespace detail

String statusToString(Status status)
{
    // The generated names, words joined by spaces: "poor quality input".
    if (const char* name = nameOf(kStatuses, status))
        return spelled(name, ' ');
    return cv::format("unknown status %d", static_cast<int>(status));
}

// A method's name is its generated one without dashes ("covransac"); methodFromString drops
// dashes and underscores from its argument, so "cov-ransac" and "cov_ransac" are accepted too.
String methodName(Method method)
{
    const char* name = nameOf(kMethods, method);
    if (!name)
        CV_Error(Error::StsBadArg,
                 cv::format("method: unknown value %d", static_cast<int>(method)));
    return spelled(name, 0);
}

Method methodFromString(const String& name)
{
    std::string key = name;
    std::transform(key.begin(), key.end(), key.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    key.erase(std::remove_if(key.begin(), key.end(), [](char c) { return c == '-' || c == '_'; }),
              key.end());
    std::string accepted;
    for (const NamedValue<Method>& method : kMethods) {
        const std::string methodKey = spelled(method.name, 0);
        if (key == methodKey)
            return method.value;
        accepted += (accepted.empty() ? "" : ", ") + methodKey;
    }
    CV_Error(Error::StsBadArg,
             cv::format("name: unknown method '%s' (%s)", name.c_str(), accepted.c_str()));
}

} // namespace rcme
} // namespace cv
