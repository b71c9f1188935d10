// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Writes the fuzzer's seed corpus: synthetic scenes (cv::rcme::generateScene) encoded in the
// fuzzer's byte format with sensible Params, one file per method, solver and calibration, so
// that the fuzzer starts from inputs that reach the estimation's successful paths.
// Usage: rcme_fuzz_seeds <output folder>

#include "fuzz_input.hpp"

#include <opencv2/rcme.hpp>

#include <cstdio>
#include <fstream>
#include <string>

namespace {

using rcme_fuzz::FuzzCase;

FuzzCase sceneCase(const cv::rcme::SceneParams& sp)
{
    const cv::rcme::SyntheticScene scene = cv::rcme::generateScene(sp);
    FuzzCase c;
    c.calls = rcme_fuzz::CALL_ALL;
    c.flags = rcme_fuzz::FLAG_REFINE;
    c.maxIterations = 15; // 16 iterations (pickCount in fuzz_public_api.cpp)
    c.refineIterations = 3;
    c.sampleFitIterations = 2;
    c.consistencyDof = 1;
    c.cameraMatrixMode = 1;
    c.qualityMode = 0;
    c.essentialMode = 0;
    c.seed = sp.seed;
    c.usacMaxIterations = 16;
    c.distanceThresh = 50.0;
    c.sceneKind = static_cast<uint8_t>(sp.kind);
    c.sceneNumPoints = 50;
    c.sceneImageWidth = 640;
    c.sceneImageHeight = 480;
    c.sigma = 1.0;
    c.threshold = 0.0;
    c.confidence = 0.99;
    c.alpha = 0.05;
    c.entropyThreshold = 1.27;
    c.inlierRatioFactor = 0.9;
    c.priorInlierRatio = 0.0;
    c.earlyTerminationEntropy = 0.0;
    const cv::Mat& K = scene.cameraMatrix;
    c.fx = K.at<double>(0, 0);
    c.fy = K.at<double>(1, 1);
    c.cx = K.at<double>(0, 2);
    c.cy = K.at<double>(1, 2);
    c.skew = 0.0;
    c.sceneInlierRatio = 0.5;
    c.sceneSigma = 1.0;
    c.sceneFocal = 500.0;
    c.sceneBaseline = 1.0;
    c.sceneDepth = 50.0;
    c.sceneWidth = 4.0;
    c.sceneHeight = 3.0;
    c.usacConfidence = 0.99;
    c.usacThreshold = 1.5;
    for (int i = 0; i < 9; ++i) {
        c.essential[i] = static_cast<float>(scene.E.at<double>(i));
        c.motion[i] = static_cast<float>(scene.R.at<double>(i));
    }
    for (int i = 0; i < 3; ++i)
        c.motion[9 + i] = static_cast<float>(scene.t.at<double>(i));
    c.numPoints1 = c.numPoints2 = static_cast<uint16_t>(scene.points1.rows);
    for (int i = 0; i < scene.points1.rows; ++i)
        for (int j = 0; j < 2; ++j) {
            c.coords1.push_back(static_cast<float>(scene.points1.at<double>(i, j)));
            c.coords2.push_back(static_cast<float>(scene.points2.at<double>(i, j)));
        }
    return c;
}

// The seed with no more points than its calls are run on (the forms without maxIters).
FuzzCase fitToCalls(FuzzCase c)
{
    if (!(c.calls & rcme_fuzz::kCallsWithoutIterationCap))
        return c;
    const size_t n = rcme_fuzz::kMaxPointsWithoutIterationCap;
    c.numPoints1 = c.numPoints2 = static_cast<uint16_t>(n);
    c.coords1.resize(2 * n);
    c.coords2.resize(2 * n);
    return c;
}

void write(const std::string& folder, const std::string& name, const FuzzCase& c)
{
    rcme_fuzz::ByteWriter writer;
    rcme_fuzz::transfer(writer, c);
    std::ofstream out(folder + "/" + name, std::ios::binary);
    out.write(reinterpret_cast<const char*>(writer.bytes.data()),
              static_cast<std::streamsize>(writer.bytes.size()));
    if (!out)
        throw std::runtime_error("cannot write " + folder + "/" + name);
}

} // namespace

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s <output folder>\n", argv[0]);
        return 2;
    }
    const std::string folder = argv[1];
    // The method bytes follow rcme_fuzz::kMethodCodes: every method, then an OpenCV flag.
    const auto seedName = [](int code) {
        return code < rcme_fuzz::kNumMethods ? cv::rcme::methodName(static_cast<cv::rcme::Method>(
                                                   rcme_fuzz::kMethodCodes[code]))
                                             : std::string("opencv_flag");
    };
    int files = 0;
    for (int kind = 0; kind < 2; ++kind)
        for (uint8_t method = 0; method <= rcme_fuzz::kNumMethods; ++method) {
            cv::rcme::SceneParams sp;
            sp.kind = static_cast<cv::rcme::SceneKind>(kind);
            sp.numPoints = 32;
            sp.inlierRatio = 0.7;
            sp.seed = 10 * kind + method;
            FuzzCase c = sceneCase(sp);
            c.method = method;
            c.solver = static_cast<uint8_t>(method % 3); // 8-, 7- and 5-point
            c.sampler = static_cast<uint8_t>(kind);      // uniform, PROSAC
            if (method == 2)
                c.flags |= rcme_fuzz::FLAG_LOCAL_OPTIMIZATION;
            // One function per seed (each one at least once over the 24 seeds): an execution stays
            // short, and mutating the call bits combines them.
            c.calls = static_cast<uint32_t>(1u << (files % rcme_fuzz::kNumCalls));
            write(folder, std::string(kind ? "generic_" : "corridor_") + seedName(method),
                  fitToCalls(c));
            ++files;

            // The same without a camera matrix, with float points in another layout.
            c.cameraMatrixMode = 0;
            c.solver = static_cast<uint8_t>(method % 2);
            c.layouts = static_cast<uint8_t>(0x10 * (method % 7) + (method + 1) % 7);
            c.calls = static_cast<uint32_t>(1u << (files % rcme_fuzz::kNumCalls));
            write(folder, std::string(kind ? "generic_" : "corridor_") + seedName(method) + "_nok",
                  fitToCalls(c));
            ++files;
        }
    std::printf("%d seeds written to %s\n", files, folder.c_str());
    return 0;
}
