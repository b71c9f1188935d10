// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// libFuzzer target: bytes become correspondences (NaN, Inf, huge, duplicated values included), a
// camera matrix and Params, and every public function of opencv2/rcme/*.hpp is called with them.
// cv::Exception is the documented answer to bad input and is caught; anything else (another
// exception, a crash, a sanitizer report, a hang caught by -timeout, a broken output contract)
// is a finding. Built by RCME_FUZZ=ON (test/hardening/run_fuzzer.sh).

#include "fuzz_input.hpp"

#include <opencv2/rcme.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

using namespace cv;
using namespace cv::rcme;
using rcme_fuzz::FuzzCase;

// A broken promise of the API: report it like a crash so that libFuzzer keeps the input.
#define FUZZ_REQUIRE(condition)                                                                    \
    do {                                                                                           \
        if (!(condition)) {                                                                        \
            std::fprintf(stderr, "contract violated: %s (%s:%d)\n", #condition, __FILE__,          \
                         __LINE__);                                                                \
            std::abort();                                                                          \
        }                                                                                          \
    } while (0)

// Small iteration caps keep an execution fast; the top byte values give invalid ones so that
// the argument checks are exercised too.
int pickCount(uint8_t code, int modulus, int offset, std::initializer_list<int> invalid)
{
    const int numInvalid = static_cast<int>(invalid.size());
    if (code >= 256 - numInvalid)
        return invalid.begin()[255 - code];
    return offset + code % modulus;
}

Method pickMethod(uint8_t code)
{
    return static_cast<Method>(rcme_fuzz::kMethodCodes[code % rcme_fuzz::kNumMethodCodes]);
}

// The drop-ins also take every OpenCV method flag.
int pickMethodFlag(uint8_t code)
{
    static const int kOpenCVFlags[] = {FM_7POINT, FM_8POINT,     FM_LMEDS,      FM_RANSAC,
                                       RHO,       USAC_DEFAULT,  USAC_PARALLEL, USAC_FM_8PTS,
                                       USAC_FAST, USAC_ACCURATE, USAC_PROSAC,   USAC_MAGSAC};
    if (code % rcme_fuzz::kNumMethodCodes == rcme_fuzz::kNumMethods)
        return kOpenCVFlags[(code >> 3) % 12];
    return pickMethod(code);
}

Params makeParams(const FuzzCase& c, const Mat& quality)
{
    Params p;
    p.method = pickMethod(c.method);
    p.sampler = static_cast<SamplerKind>(c.sampler % 3);
    p.solver = static_cast<MinimalSolverKind>(c.solver % 5); // 4: invalid
    p.sigma = c.sigma;
    p.threshold = c.threshold;
    p.confidence = c.confidence;
    p.maxIterations = pickCount(c.maxIterations, 16, 1, {0, -1, INT_MIN, 10000001});
    p.exactIterations = c.flags & rcme_fuzz::FLAG_EXACT_ITERATIONS;
    p.randomGeneratorState = c.seed;
    p.refine = c.flags & rcme_fuzz::FLAG_REFINE;
    p.refineIterations = pickCount(c.refineIterations, 3, 0, {-1, 1001});
    p.alpha = c.alpha;
    p.entropyThreshold = c.entropyThreshold;
    p.inlierRatioFactor = c.inlierRatioFactor;
    p.priorInlierRatio = c.priorInlierRatio;
    p.consistencyDof = c.consistencyDof % 6;
    p.sampleFitIterations = pickCount(c.sampleFitIterations, 3, 0, {-1, 101});
    p.sampleLeverage = c.flags & rcme_fuzz::FLAG_SAMPLE_LEVERAGE;
    p.earlyTerminationEntropy = c.earlyTerminationEntropy;
    p.localOptimization = c.flags & rcme_fuzz::FLAG_LOCAL_OPTIMIZATION;
    if (c.flags & rcme_fuzz::FLAG_NO_MOTION_TESTS)
        p.ambiguityMargin = p.maxRotationStdDeg = p.maxTranslationStdDeg = 0.0;
    // A tiny budget now and then: the loop must stop early and still keep the output contract.
    p.timeBudget = (c.refineIterations & 0x80) ? 1e-4 : 0.0;
    p.matchQuality = quality;
    return p;
}

// Points in one of the layouts OpenCV accepts, or a malformed one. Holds the storage that the
// returned InputArray refers to.
struct PointInput
{
    Mat mat;
    std::vector<Point2d> vec;
    bool useVector = false;

    _InputArray array() const { return useVector ? _InputArray(vec) : _InputArray(mat); }
};

PointInput makePoints(const std::vector<float>& coords, int8_t scaleExponent, uint8_t layout)
{
    const int n = static_cast<int>(coords.size() / 2);
    Mat xy(n, 2, CV_64F);
    for (int i = 0; i < 2 * n; ++i)
        xy.at<double>(i) = std::ldexp(static_cast<double>(coords[i]), scaleExponent);
    PointInput in;
    switch (layout % 9) {
    case 0:
        in.mat = xy;
        break;
    case 1:
        xy.convertTo(in.mat, CV_32F);
        break;
    case 2: // (an empty matrix cannot be reshaped)
        in.mat = n > 0 ? xy.reshape(2, n) : Mat();
        break;
    case 3:
        xy.convertTo(in.mat, CV_32F);
        if (n > 0)
            in.mat = in.mat.reshape(2, 1);
        break;
    case 4:
        xy.convertTo(in.mat, CV_32S); // saturating: NaN becomes 0, huge values INT_MAX
        break;
    case 5:
        for (int i = 0; i < n; ++i)
            in.vec.emplace_back(xy.at<double>(i, 0), xy.at<double>(i, 1));
        in.useVector = true;
        break;
    case 6: { // not continuous: two columns of a wider matrix
        Mat wide(n, 4, CV_64F, Scalar(-1));
        in.mat = wide.colRange(1, 3);
        xy.copyTo(in.mat); // through a named header: copyTo(empty) releases it
        break;
    }
    case 7: // three columns
        in.mat = Mat(n, 3, CV_64F, Scalar(1));
        break;
    default: // an unsupported depth
        xy.convertTo(in.mat, CV_16U);
        break;
    }
    return in;
}

Mat makeCameraMatrix(const FuzzCase& c)
{
    const int depth = (c.flags & rcme_fuzz::FLAG_K_SINGLE_PRECISION) ? CV_32F : CV_64F;
    Mat K;
    switch (c.cameraMatrixMode % 5) {
    case 0:
        return Mat();
    case 1:
    case 2:
        K = Mat(Matx33d(c.fx, c.skew, c.cx, 0, c.fy, c.cy, 0, 0, 1));
        break;
    case 3: // a general 3x3 matrix, last row included
        K = Mat(
            Matx33d(c.fx, c.skew, c.cx, c.sigma, c.fy, c.cy, c.alpha, c.threshold, c.confidence));
        break;
    default:
        K = Mat(3, 4, CV_64F, Scalar(c.fx));
        break;
    }
    K.convertTo(K, depth);
    return K;
}

Mat makeQuality(const FuzzCase& c, int n)
{
    Mat q;
    switch (c.qualityMode % 4) {
    case 0:
        break;
    case 1: // one score per point, from the first coordinates
        q.create(n, 1, CV_32F);
        for (int i = 0; i < n; ++i)
            q.at<float>(i) = c.coords1[2 * i];
        break;
    case 2:
        q = Mat(n + 1, 1, CV_64F, Scalar(1));
        break;
    default:
        q = Mat(n, 1, CV_8U, Scalar(1));
        break;
    }
    return q;
}

// The output contract shared by the estimating functions: an Nx1 CV_8U mask of 0/1, a finite
// 3x3 CV_64F model on success and none otherwise.
void checkMask(const Mat& mask, int n, bool mustBeZero)
{
    FUZZ_REQUIRE(mask.rows == n && mask.cols == 1 && mask.type() == CV_8U);
    for (int i = 0; i < n; ++i) {
        const uchar v = mask.at<uchar>(i);
        FUZZ_REQUIRE(v == 0 || v == 1);
        FUZZ_REQUIRE(!mustBeZero || v == 0);
    }
}

void checkModel(const Mat& model, Status status)
{
    if (status != STATUS_SUCCESS) {
        FUZZ_REQUIRE(model.empty());
        return;
    }
    FUZZ_REQUIRE(model.rows == 3 && model.cols == 3 && model.type() == CV_64F);
    FUZZ_REQUIRE(checkRange(model));
}

// R comes with a success and with a pure rotation (t zero): the status R's check expects.
Status rotationStatus(Status status)
{
    return status == STATUS_PURE_ROTATION ? STATUS_SUCCESS : status;
}

void checkStatus(Status status)
{
    FUZZ_REQUIRE(status >= STATUS_SUCCESS && status <= STATUS_UNDETERMINED_MOTION);
    FUZZ_REQUIRE(!statusToString(status).empty());
}

// The contract of the functions that report a Status.
void checkEstimate(Status status, const Mat& mask, int n, const Mat& model)
{
    checkStatus(status);
    checkMask(mask, n, status != STATUS_SUCCESS && status != STATUS_PURE_ROTATION);
    checkModel(model, status);
}

// Runs one call; cv::Exception is the documented answer to bad input.
template <typename Call> void guarded(Call&& call)
{
    try {
        call();
    } catch (const cv::Exception&) {
    }
}

// A call that reports a Status, its output contract checked.
template <typename Estimate> void guardedEstimate(int n, Estimate&& estimate)
{
    guarded([&] {
        Mat mask;
        Status status;
        const Mat model = estimate(mask, status);
        checkEstimate(status, mask, n, model);
    });
}

// OpenCV's enum has no fixed type: only 0..3 are values of it (anything else is undefined
// behaviour in the caller, not a bad input).
UsacParams makeUsacParams(const FuzzCase& c)
{
    UsacParams usac;
    usac.confidence = c.usacConfidence;
    usac.threshold = c.usacThreshold;
    // Bounded like Params::maxIterations above, invalid counts included.
    usac.maxIterations = c.usacMaxIterations % 17;
    usac.randomGeneratorState = c.seed;
    usac.sampler = static_cast<SamplingMethod>(c.usacSampler & 3);
    usac.score = static_cast<ScoreMethod>((c.usacSampler >> 2) & 3);
    return usac;
}

struct Outputs
{
    Mat E, R, t; //!< from the first successful calibrated estimate
};

void callEstimators(const FuzzCase& c, const PointInput& p1, const PointInput& p2, const Mat& K,
                    const Params& params, Outputs& out)
{
    const int n = static_cast<int>(c.coords1.size() / 2);
    const bool sameCount =
        (c.flags & rcme_fuzz::FLAG_SECOND_VIEW_IS_FIRST) || c.coords1.size() == c.coords2.size();
    const int methodFlag = pickMethodFlag(c.method);
    const Point2d pp(c.cx, c.cy);
    const bool small = static_cast<size_t>(n) <= rcme_fuzz::kMaxPointsWithoutIterationCap;

    if (c.calls & rcme_fuzz::CALL_ESTIMATE_RELATIVE_MOTION)
        guarded([&] {
            const Report r = estimateRelativeMotion(p1.array(), p2.array(), K, params);
            FUZZ_REQUIRE(sameCount);
            checkEstimate(r.status, r.mask, n, r.F);
            if (!K.empty())
                checkModel(r.R, rotationStatus(r.status));
            FUZZ_REQUIRE(r.inlierCount == countNonZero(r.mask));
            if (r.status == STATUS_SUCCESS && !K.empty() && out.R.empty()) {
                out.E = r.E;
                out.R = r.R;
                out.t = r.t;
            }
        });
    if (c.calls & rcme_fuzz::CALL_FUNDAMENTAL_PARAMS)
        guardedEstimate(n, [&](Mat& mask, Status& status) {
            return cv::rcme::findFundamentalMat(p1.array(), p2.array(), params, mask, status);
        });
    if (c.calls & rcme_fuzz::CALL_FUNDAMENTAL_K_PARAMS)
        guardedEstimate(n, [&](Mat& mask, Status& status) {
            return cv::rcme::findFundamentalMat(p1.array(), p2.array(), K, params, mask, status);
        });
    // OpenCV's forms take any positive maxIters and rcme clamps it to 10^7: the large invalid
    // count of pickCount reaches them only on too few points (10^7 iterations took 35 s).
    const int dropInIters = params.maxIterations > 16 && !small ? 16 : params.maxIterations;
    if (c.calls & rcme_fuzz::CALL_FUNDAMENTAL_DROP_IN)
        guarded([&] {
            Mat mask;
            cv::rcme::findFundamentalMat(p1.array(), p2.array(), methodFlag, params.threshold,
                                         params.confidence, dropInIters, mask);
            checkMask(mask, n, false);
        });
    if ((c.calls & rcme_fuzz::CALL_FUNDAMENTAL_DROP_IN_DEFAULT_ITERS) && small)
        guarded([&] {
            Mat mask;
            cv::rcme::findFundamentalMat(p1.array(), p2.array(), methodFlag, params.threshold,
                                         params.confidence, mask);
            checkMask(mask, n, false);
        });
    if (c.calls & rcme_fuzz::CALL_ESSENTIAL_PARAMS)
        guardedEstimate(n, [&](Mat& mask, Status& status) {
            return cv::rcme::findEssentialMat(p1.array(), p2.array(), K, params, mask, status);
        });
    if (c.calls & rcme_fuzz::CALL_ESSENTIAL_DROP_IN)
        guarded([&] {
            Mat mask;
            cv::rcme::findEssentialMat(p1.array(), p2.array(), K, methodFlag, params.confidence,
                                       params.threshold, dropInIters, mask);
            checkMask(mask, n, false);
        });
    if (c.calls & rcme_fuzz::CALL_ESSENTIAL_FOCAL)
        guarded([&] {
            Mat mask;
            cv::rcme::findEssentialMat(p1.array(), p2.array(), c.fx, pp, methodFlag,
                                       params.confidence, params.threshold, dropInIters, mask);
            checkMask(mask, n, false);
        });
    if ((c.calls & rcme_fuzz::CALL_FUNDAMENTAL_MASK_FIRST) && small)
        guarded([&] {
            Mat mask;
            const Mat F = cv::rcme::findFundamentalMat(p1.array(), p2.array(), mask, methodFlag,
                                                       params.threshold, params.confidence);
            checkMask(mask, n, F.empty());
        });
    const UsacParams usac = makeUsacParams(c);
    if (c.calls & rcme_fuzz::CALL_FUNDAMENTAL_USAC)
        guarded([&] {
            Mat mask;
            const Mat F = cv::rcme::findFundamentalMat(p1.array(), p2.array(), mask, usac);
            checkMask(mask, n, F.empty());
            checkModel(F, F.empty() ? STATUS_POOR_QUALITY_INPUT : STATUS_SUCCESS);
        });
    const Mat distortion(1, 5, CV_32F, const_cast<float*>(c.distortion));
    if ((c.calls & rcme_fuzz::CALL_ESSENTIAL_TWO_CAMERAS) && small)
        guarded([&] {
            Mat mask;
            const Mat E =
                cv::rcme::findEssentialMat(p1.array(), p2.array(), K, distortion, K, distortion,
                                           methodFlag, params.confidence, params.threshold, mask);
            checkMask(mask, n, E.empty());
        });
    if (c.calls & rcme_fuzz::CALL_ESSENTIAL_USAC)
        guarded([&] {
            Mat mask;
            const Mat E = cv::rcme::findEssentialMat(p1.array(), p2.array(), K, K, distortion,
                                                     distortion, mask, usac);
            checkMask(mask, n, E.empty());
        });
    if ((c.calls & rcme_fuzz::CALL_RECOVER_POSE_TWO_CAMERAS) && small)
        guarded([&] {
            Mat E, R, t, mask;
            const int inliers =
                cv::rcme::recoverPose(p1.array(), p2.array(), K, distortion, K, distortion, E, R, t,
                                      methodFlag, params.confidence, params.threshold, mask);
            checkMask(mask, n, inliers == 0);
            FUZZ_REQUIRE(inliers == countNonZero(mask));
            FUZZ_REQUIRE(R.rows == 3 && R.cols == 3 && checkRange(R) && checkRange(t));
        });
    if (c.calls & rcme_fuzz::CALL_RECOVER_POSE_PARAMS)
        guarded([&] {
            Mat E, R, t, mask, covariance;
            Status status;
            const int inliers = cv::rcme::recoverPose(p1.array(), p2.array(), K, E, R, t, params,
                                                      mask, status, covariance);
            checkEstimate(rotationStatus(status), mask, n, R);
            FUZZ_REQUIRE(inliers == countNonZero(mask));
            if (status == STATUS_SUCCESS && out.R.empty()) {
                out.E = E;
                out.R = R;
                out.t = t;
            }
        });
}

Mat makeEssential(const FuzzCase& c, const Outputs& out)
{
    if (c.essentialMode % 3 == 0 && !out.E.empty())
        return out.E;
    Mat E(3, 3, CV_32F);
    for (int i = 0; i < 9; ++i)
        E.at<float>(i) = c.essential[i];
    if (c.essentialMode % 3 == 2)
        E.convertTo(E, CV_64F);
    return E;
}

Mat makeMaskInput(const FuzzCase& c, int n)
{
    switch (c.maskMode % 4) {
    case 0:
        return Mat();
    case 1: { // a selection derived from the coordinates
        Mat m(n, 1, CV_8U);
        for (int i = 0; i < n; ++i)
            m.at<uchar>(i) = (c.coords1[2 * i + 1] > c.coords1[2 * i]) ? 1 : 0;
        return m;
    }
    case 2:
        return Mat(n + 1, 1, CV_8U, Scalar(1));
    default:
        return Mat(n, 1, CV_32S, Scalar(1));
    }
}

void callPoseFromEssential(const FuzzCase& c, const PointInput& p1, const PointInput& p2,
                           const Mat& K, const Outputs& out)
{
    const int n = static_cast<int>(c.coords1.size() / 2);
    const Mat E = makeEssential(c, out);
    if (c.calls & rcme_fuzz::CALL_RECOVER_POSE_FROM_E)
        guarded([&] {
            Mat R, t, mask = makeMaskInput(c, n);
            const int count = cv::rcme::recoverPose(E, p1.array(), p2.array(), K, R, t, mask);
            FUZZ_REQUIRE(count >= 0 && count <= n);
        });
    if (c.calls & rcme_fuzz::CALL_RECOVER_POSE_DISTANCE)
        guarded([&] {
            Mat R, t, points, mask = makeMaskInput(c, n);
            const int count = cv::rcme::recoverPose(E, p1.array(), p2.array(), K, R, t,
                                                    c.distanceThresh, mask, points);
            FUZZ_REQUIRE(count >= 0 && count <= n);
            FUZZ_REQUIRE(points.empty() || (points.rows == 4 && points.cols == n));
        });
    if (c.calls & rcme_fuzz::CALL_RECOVER_POSE_FROM_E_FOCAL)
        guarded([&] {
            Mat R, t, mask = makeMaskInput(c, n);
            const int count = cv::rcme::recoverPose(E, p1.array(), p2.array(), R, t, c.fx,
                                                    Point2d(c.cx, c.cy), mask);
            FUZZ_REQUIRE(count >= 0 && count <= n);
        });
}

void callSceneAndMotion(const FuzzCase& c, const Outputs& out)
{
    Mat fuzzR(3, 3, CV_32F), fuzzT(3, 1, CV_32F);
    for (int i = 0; i < 9; ++i)
        fuzzR.at<float>(i) = c.motion[i];
    for (int i = 0; i < 3; ++i)
        fuzzT.at<float>(i) = c.motion[9 + i];
    Mat refR = fuzzR, refT = fuzzT;
    if (c.calls & rcme_fuzz::CALL_GENERATE_SCENE)
        guarded([&] {
            SceneParams sp;
            sp.kind = static_cast<SceneKind>(c.sceneKind % 5); // 4: an invalid kind
            sp.numPoints = c.sceneNumPoints % 128;             // keeps an execution fast
            sp.inlierRatio = c.sceneInlierRatio;
            sp.sigma = c.sceneSigma;
            sp.seed = c.seed;
            sp.focalLength = c.sceneFocal;
            sp.imageWidth = c.sceneImageWidth;
            sp.imageHeight = c.sceneImageHeight;
            sp.baseline = c.sceneBaseline;
            sp.corridorDepth = c.sceneDepth;
            sp.corridorWidth = c.sceneWidth;
            sp.corridorHeight = c.sceneHeight;
            const SyntheticScene scene = generateScene(sp);
            FUZZ_REQUIRE(scene.points1.rows == sp.numPoints && scene.points2.rows == sp.numPoints);
            FUZZ_REQUIRE(checkRange(scene.points1) && checkRange(scene.points2));
            refR = scene.R;
            refT = scene.t;
        });
    guarded([&] { compareMotion(fuzzR, fuzzT, refR, refT); });
    if (!out.R.empty())
        guarded([&] {
            const MotionError e = compareMotion(out.R, out.t, refR, refT);
            FUZZ_REQUIRE(e.rotationDeg >= 0 && e.rotationDeg <= 180.0 + 1e-9);
        });
}

void callParamsFromUsac(const FuzzCase& c)
{
    if (!(c.calls & rcme_fuzz::CALL_PARAMS_FROM_USAC))
        return;
    UsacParams usac = makeUsacParams(c);
    usac.maxIterations = c.usacMaxIterations; // only copied here, never run
    // 1 and 2 (NAPSAC) have no counterpart in Params(UsacParams): StsBadArg.
    guarded([&] {
        const Params p(usac);
        FUZZ_REQUIRE(p.maxIterations == usac.maxIterations);
    });
    guarded([&] { Params::fromUsacParams(usac); });
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    // OpenCV's own thread pool would only add threads (and noise) to every execution.
    cv::setNumThreads(0);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    FuzzCase c;
    rcme_fuzz::ByteReader reader(data, size);
    rcme_fuzz::transfer(reader, c);
    c.calls &= rcme_fuzz::CALL_ALL;
    for (int kept = 0, bit = 0; bit < rcme_fuzz::kNumCalls; ++bit)
        if ((c.calls >> bit) & 1u) {
            if (kept == rcme_fuzz::kMaxCallsPerInput)
                c.calls &= ~(1u << bit);
            else
                ++kept;
        }

    const PointInput p1 = makePoints(c.coords1, c.scaleExponent, c.layouts & 0x0F);
    const PointInput p2 = (c.flags & rcme_fuzz::FLAG_SECOND_VIEW_IS_FIRST)
                              ? makePoints(c.coords1, c.scaleExponent, c.layouts >> 4)
                              : makePoints(c.coords2, c.scaleExponent, c.layouts >> 4);
    const Mat K = makeCameraMatrix(c);
    const Params params = makeParams(c, makeQuality(c, static_cast<int>(c.coords1.size() / 2)));

    Outputs out;
    callEstimators(c, p1, p2, K, params, out);
    callPoseFromEssential(c, p1, p2, K, out);
    callSceneAndMotion(c, out);
    callParamsFromUsac(c);
    FUZZ_REQUIRE(!statusToString(static_cast<Status>(c.statusValue)).empty());
    // The names' parser on the input's raw bytes: a Method or a named error, never a crash.
    try {
        const Method method = methodFromString(
            std::string(reinterpret_cast<const char*>(data), std::min<size_t>(size, 16)));
        FUZZ_REQUIRE(methodFromString(methodName(method)) == method);
    } catch (const cv::Exception& e) {
        FUZZ_REQUIRE(std::string(e.what()).find("name") != std::string::npos);
    }
    return 0;
}
