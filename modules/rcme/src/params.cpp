// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#include "precomp.hpp"

namespace cv {
namespace rcme {

Params::Params()
    : method(METHOD_STANDARD), sampler(SAMPLER_UNIFORM), solver(SOLVER_AUTO),
      verification(VERIFICATION_AUTO), sigma(1.0), threshold(0.0), confidence(0.99),
      cleanSampleSuccessRate(0.3), maxIterations(1000), exactIterations(false),
      randomGeneratorState(0), refine(true), refineIterations(20), useEstimatedNoise(true),
      alpha(0.05), entropyThreshold(1.27), inlierRatioFactor(0.9), priorInlierRatio(0.0),
      consistencyDof(1), sampleFitIterations(5), sampleLeverage(false),
      earlyTerminationEntropy(0.0), localOptimization(true), degeneracyTest(true),
      ambiguityMargin(2.0), maxRotationStdDeg(2.0), maxTranslationStdDeg(6.0), isParallel(false),
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

String statusToString(Status status)
{
    switch (status) {
    case STATUS_SUCCESS:
        return "success";
    case STATUS_POOR_QUALITY_INPUT:
        return "poor quality input";
    case STATUS_NOT_ENOUGH_POINTS:
        return "not enough points";
    case STATUS_DEGENERATE_CONFIGURATION:
        return "degenerate configuration";
    case STATUS_PURE_ROTATION:
        return "pure rotation";
    case STATUS_UNDETERMINED_MOTION:
        return "undetermined motion";
    }
    return cv::format("unknown status %d", static_cast<int>(status));
}

namespace {

constexpr Method kMethods[] = {METHOD_RCME, METHOD_PRCME, METHOD_STANDARD, METHOD_MLESAC,
                               METHOD_COV_RANSAC};

const char* nameOf(Method method)
{
    switch (method) {
    case METHOD_RCME:
        return "rcme";
    case METHOD_PRCME:
        return "prcme";
    case METHOD_STANDARD:
        return "standard";
    case METHOD_MLESAC:
        return "mlesac";
    case METHOD_COV_RANSAC:
        return "covransac";
    }
    return nullptr;
}

} // namespace

String methodName(Method method)
{
    const char* name = nameOf(method);
    if (!name)
        CV_Error(Error::StsBadArg,
                 cv::format("method: unknown value %d", static_cast<int>(method)));
    return name;
}

Method methodFromString(const String& name)
{
    std::string key = name;
    std::transform(key.begin(), key.end(), key.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    key.erase(std::remove_if(key.begin(), key.end(), [](char c) { return c == '-' || c == '_'; }),
              key.end());
    std::string accepted;
    for (Method method : kMethods) {
        if (key == nameOf(method))
            return method;
        accepted += (accepted.empty() ? "" : ", ") + std::string(nameOf(method));
    }
    CV_Error(Error::StsBadArg,
             cv::format("name: unknown method '%s' (%s)", name.c_str(), accepted.c_str()));
}

} // namespace rcme
} // namespace cv
