// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// The byte format of the fuzzer's inputs. One function, transfer(), lists the fields in order
// and is run with a ByteReader (the fuzzer decodes bytes into a FuzzCase) or a ByteWriter (the
// seed generator encodes a FuzzCase into bytes), so the two can never disagree on the layout.
#ifndef OPENCV_RCME_FUZZ_INPUT_HPP
#define OPENCV_RCME_FUZZ_INPUT_HPP

#include "opencv2/rcme/opencv_geometry.hpp"
#include <opencv2/rcme/params.hpp>

// The library's list of the Method values (src/ is on the fuzz targets' include path).
#include "generated/enum_tables.inc"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

namespace rcme_fuzz {

//! At most this many correspondences per view, so that one execution stays in milliseconds.
constexpr size_t kMaxPoints = 32;

constexpr int kNumCalls = 19;

enum Call : uint32_t
{
    CALL_ESTIMATE_RELATIVE_MOTION = 1 << 0,
    CALL_FUNDAMENTAL_PARAMS = 1 << 1,
    CALL_FUNDAMENTAL_K_PARAMS = 1 << 2,
    CALL_FUNDAMENTAL_DROP_IN = 1 << 3,
    CALL_FUNDAMENTAL_DROP_IN_DEFAULT_ITERS = 1 << 4,
    CALL_ESSENTIAL_PARAMS = 1 << 5,
    CALL_ESSENTIAL_DROP_IN = 1 << 6,
    CALL_ESSENTIAL_FOCAL = 1 << 7,
    CALL_RECOVER_POSE_PARAMS = 1 << 8,
    CALL_RECOVER_POSE_FROM_E = 1 << 9,
    CALL_RECOVER_POSE_FROM_E_FOCAL = 1 << 10,
    CALL_GENERATE_SCENE = 1 << 11,
    CALL_PARAMS_FROM_USAC = 1 << 12,
    CALL_FUNDAMENTAL_MASK_FIRST = 1 << 13,
    CALL_FUNDAMENTAL_USAC = 1 << 14,
    CALL_ESSENTIAL_TWO_CAMERAS = 1 << 15,
    CALL_ESSENTIAL_USAC = 1 << 16,
    CALL_RECOVER_POSE_TWO_CAMERAS = 1 << 17,
    CALL_RECOVER_POSE_DISTANCE = 1 << 18,
    CALL_ALL = (1 << kNumCalls) - 1
};

//! OpenCV's forms without maxIters run 1000 iterations whenever no hypothesis passes (on any
//! number of points): they took half of the fuzzer's time. They are called on fewer points than
//! any minimal sample, so that they check and convert their arguments (undistortion included)
//! and stop at "not enough points"; the estimation behind them is the one the forms with an
//! iteration cap run on every input.
constexpr size_t kMaxPointsWithoutIterationCap = 4;
constexpr uint32_t kCallsWithoutIterationCap =
    CALL_FUNDAMENTAL_DROP_IN_DEFAULT_ITERS | CALL_FUNDAMENTAL_MASK_FIRST |
    CALL_ESSENTIAL_TWO_CAMERAS | CALL_RECOVER_POSE_TWO_CAMERAS;

//! At most this many of the requested calls run per input (the lowest set bits), so that one
//! execution stays cheap whatever the mutation does to the call bits.
constexpr int kMaxCallsPerInput = 2;

//! What the method byte (FuzzCase::method) picks, by its value modulo kNumMethodCodes: every
//! cv::rcme::Method in declaration order (the library's generated list, so a new method is
//! fuzzed too), then three values that are none: 0, -1 and an OpenCV flag. The drop-ins take the
//! first of those three (code % kNumMethodCodes == kNumMethods) as one of OpenCV's flags instead.
#define RCME_FUZZ_METHOD_CODE(value, name) cv::rcme::value,
constexpr int kMethodCodes[] = {RCME_METHOD_VALUES(RCME_FUZZ_METHOD_CODE) 0, -1, cv::FM_LMEDS};
#undef RCME_FUZZ_METHOD_CODE
constexpr int kNumMethodCodes = static_cast<int>(sizeof(kMethodCodes) / sizeof(kMethodCodes[0]));
constexpr int kNumMethods = kNumMethodCodes - 3;

enum Flag : uint8_t
{
    FLAG_EXACT_ITERATIONS = 1 << 0,
    FLAG_REFINE = 1 << 1,
    FLAG_LOCAL_OPTIMIZATION = 1 << 2,
    FLAG_SAMPLE_LEVERAGE = 1 << 3,
    FLAG_SECOND_VIEW_IS_FIRST = 1 << 4, //!< points2 = points1 (no motion at all)
    FLAG_K_SINGLE_PRECISION = 1 << 5,
    FLAG_NO_MOTION_TESTS = 1 << 6 //!< the ambiguity and uncertainty tests off (on by default)
};

//! One fuzz input, decoded. Small fields are raw bytes that fuzz_public_api.cpp maps to valid
//! values most of the time and to invalid ones (to exercise the argument checks) otherwise.
struct FuzzCase
{
    uint32_t calls = 0;
    uint8_t flags = 0;
    uint8_t layouts = 0;       //!< low nibble: layout of points1, high nibble: of points2
    uint8_t method = 0;        //!< Params::method (and the drop-ins' method flag)
    uint8_t sampler = 0;       //!< Params::sampler
    uint8_t solver = 0;        //!< Params::solver
    uint8_t maxIterations = 0; //!< small iteration caps, a few invalid values
    uint8_t refineIterations = 0;
    uint8_t sampleFitIterations = 0;
    uint8_t consistencyDof = 0;
    uint8_t cameraMatrixMode = 0; //!< none, from the five numbers below, malformed
    uint8_t qualityMode = 0;      //!< Params::matchQuality: empty, valid, malformed
    uint8_t essentialMode = 0;    //!< E of recoverPose(E, ...): estimated, fuzzed
    uint8_t maskMode = 0;         //!< input mask of recoverPose(E, ...)
    uint8_t sceneKind = 0;
    int8_t scaleExponent = 0; //!< every coordinate is multiplied by 2^scaleExponent
    int32_t seed = 0;
    int32_t statusValue = 0; //!< passed to statusToString as is
    int32_t usacSampler = 0;
    int32_t usacMaxIterations = 0;
    int16_t sceneNumPoints = 0;
    int16_t sceneImageWidth = 0;
    int16_t sceneImageHeight = 0;
    double sigma = 0, threshold = 0, confidence = 0, alpha = 0, entropyThreshold = 0;
    double inlierRatioFactor = 0, priorInlierRatio = 0, earlyTerminationEntropy = 0;
    double fx = 0, fy = 0, cx = 0, cy = 0, skew = 0;
    double sceneInlierRatio = 0, sceneSigma = 0, sceneFocal = 0, sceneBaseline = 0;
    double sceneDepth = 0, sceneWidth = 0, sceneHeight = 0;
    double usacConfidence = 0, usacThreshold = 0;
    float essential[9] = {};
    float distortion[5] = {}; //!< distortion coefficients of the two-camera forms
    double distanceThresh = 0;
    float motion[12] = {}; //!< a rotation (row-major) and a translation for compareMotion
    uint16_t numPoints1 = 0, numPoints2 = 0;
    std::vector<float> coords1, coords2; //!< x, y interleaved
};

//! Reads fields from the front of the bytes; past the end every field reads as zero, so every
//! byte string is a valid input.
class ByteReader
{
public:
    ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

    template <typename T> void operator()(T& value)
    {
        static_assert(std::is_trivially_copyable<T>::value, "plain data only");
        std::memset(&value, 0, sizeof(T));
        const size_t n = std::min(sizeof(T), size_ - pos_);
        std::memcpy(&value, data_ + pos_, n);
        pos_ += n;
    }

    void floats(std::vector<float>& values, size_t count)
    {
        values.resize(count);
        for (float& v : values)
            (*this)(v);
    }

private:
    const uint8_t* data_;
    size_t size_;
    size_t pos_ = 0;
};

//! Appends fields to a byte string (the seed generator).
class ByteWriter
{
public:
    template <typename T> void operator()(const T& value)
    {
        static_assert(std::is_trivially_copyable<T>::value, "plain data only");
        const auto* p = reinterpret_cast<const uint8_t*>(&value);
        bytes.insert(bytes.end(), p, p + sizeof(T));
    }

    void floats(const std::vector<float>& values, size_t count)
    {
        for (size_t i = 0; i < count; ++i)
            (*this)(i < values.size() ? values[i] : 0.0f);
    }

    std::vector<uint8_t> bytes;
};

//! The layout: the scalar fields first, then the coordinates, so that a short input still sets
//! every parameter.
template <typename Archive, typename Case> void transfer(Archive& a, Case& c)
{
    a(c.calls);
    a(c.flags);
    a(c.layouts);
    a(c.method);
    a(c.sampler);
    a(c.solver);
    a(c.maxIterations);
    a(c.refineIterations);
    a(c.sampleFitIterations);
    a(c.consistencyDof);
    a(c.cameraMatrixMode);
    a(c.qualityMode);
    a(c.essentialMode);
    a(c.maskMode);
    a(c.sceneKind);
    a(c.scaleExponent);
    a(c.seed);
    a(c.statusValue);
    a(c.usacSampler);
    a(c.usacMaxIterations);
    a(c.sceneNumPoints);
    a(c.sceneImageWidth);
    a(c.sceneImageHeight);
    for (auto* field : {&c.sigma,
                        &c.threshold,
                        &c.confidence,
                        &c.alpha,
                        &c.entropyThreshold,
                        &c.inlierRatioFactor,
                        &c.priorInlierRatio,
                        &c.earlyTerminationEntropy,
                        &c.fx,
                        &c.fy,
                        &c.cx,
                        &c.cy,
                        &c.skew,
                        &c.sceneInlierRatio,
                        &c.sceneSigma,
                        &c.sceneFocal,
                        &c.sceneBaseline,
                        &c.sceneDepth,
                        &c.sceneWidth,
                        &c.sceneHeight,
                        &c.usacConfidence,
                        &c.usacThreshold})
        a(*field);
    for (auto& v : c.essential)
        a(v);
    for (auto& v : c.motion)
        a(v);
    for (auto& v : c.distortion)
        a(v);
    a(c.distanceThresh);
    a(c.numPoints1);
    a(c.numPoints2);
    a.floats(c.coords1, 2 * std::min<size_t>(c.numPoints1, kMaxPoints));
    a.floats(c.coords2, 2 * std::min<size_t>(c.numPoints2, kMaxPoints));
}

} // namespace rcme_fuzz

#endif // OPENCV_RCME_FUZZ_INPUT_HPP
