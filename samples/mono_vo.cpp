// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

/*
Monocular visual odometry over a KITTI image sequence with cv::rcme, next to OpenCV's estimator.

Keyframe policy (the same for both estimators): SIFT features, brute-force matching with Lowe's
ratio test between the current keyframe and each following frame; the first frame whose median
image displacement reaches --min-parallax pixels becomes the candidate second keyframe, and the
motion of the pair is estimated.

- rcme (cv::rcme::recoverPose, RCME by default): when the status is "poor quality input" (PQI)
  or degenerate, the motion is NOT accepted; the sample re-selects the second keyframe (the next
  frame, up to --max-reselect times) and counts the re-selection. This is the paper's argument
  for failure detection: a VO front end that is told "do not trust this pair" can pick another.
- OpenCV (cv::findEssentialMat with RANSAC, then cv::recoverPose): there is no failure signal, so
  every pair with an essential matrix is accepted.

--bad-frames simulates frames whose matches are all wrong (a glare, motion blur, a duplicated or
dropped frame): every match of a pair that involves such a frame is re-paired at random. On the
clean KITTI frames rcme never reports PQI (doc/results.md); with bad frames it does, and
re-selects, while OpenCV accepts the wrong motion. The degenerate status (Params::degeneracyTest,
--no-degeneracy-test turns it off) fires on some highway pairs of KITTI 01.

--front-end klt is the classic front end of OpenCV-based VO programs instead: every frame, FAST
corners of the reference frame tracked into it by pyramidal KLT (kept when the backward track
returns within 1 px), no parallax gate. The reference is the last frame whose motion was
accepted: when rcme flags a pair (any status but success) the frame is held, the reference is
kept and the next frame is tried against it, so the held frame's motion is not lost but
absorbed by the next pair. The held frames are listed and marked on the ground truth in the
picture; OpenCV, without a failure signal, accepts every pair.

If no candidate of the window can be accepted (or the matches run out), the track is bridged:
the first keyframe moves to the last tried frame with the previous accepted rotation and
translation direction (constant motion) and the gap is counted.

Monocular VO cannot observe scale: each accepted pair's unit translation is scaled by the
ground-truth distance between its two frames, for display only. The errors printed therefore
measure the rotations and the translation directions.

Input: a folder with calib.txt (first line: the 3x4 projection matrix P0, optionally labelled
"P0:"), poses.txt (one camera-to-world 3x4 pose per frame, KITTI format) and image_l/ (PNG images).
The default is the KITTI sequences in ../shared/data next to the repository
(see their PROVENANCE.md).

Exit codes: 0 success; 1 no keyframe pair could be estimated, or rcme's median rotation error
exceeds --max-median-rotation-error-deg; 2 usage or input/output error (e.g. a missing data
folder); 3 error raised by the library.
*/

#include "sample_common.hpp"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/rcme.hpp>
#include <opencv2/rcme/opencv_geometry.hpp> // cv::findEssentialMat & co.
#include <opencv2/video/tracking.hpp>       // calcOpticalFlowPyrLK

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#ifndef RCME_DEFAULT_DATA_DIR
#define RCME_DEFAULT_DATA_DIR "../shared/data"
#endif

namespace {

using namespace rcme_samples;
namespace fs = std::filesystem;

const char* const kDefaultSequence = "kitti_odometry_06_frames000-050";

void printUsage(const char* argv0)
{
    std::cout
        << "Usage: " << argv0 << " [options]\n"
        << "\n"
        << "Monocular visual odometry over a KITTI sequence: keyframe pairs estimated with\n"
        << "cv::rcme (re-selecting the keyframe when rcme reports poor quality input or a\n"
        << "degenerate configuration), then the same run with OpenCV's findEssentialMat +\n"
        << "recoverPose. Writes the top view of both trajectories against the ground truth as\n"
        << "a PNG.\n"
        << "\n"
        << "Options (--key value or --key=value):\n"
        << "  --data DIR          folder of the sequences (default " << RCME_DEFAULT_DATA_DIR
        << ")\n"
        << "  --sequence S        sequence folder inside --data, a path, or a KITTI number such\n"
        << "                      as 01 or 06 (default " << kDefaultSequence << ")\n"
        << "  --frames N          use only the first N frames (default: all)\n"
        << "  --method M          " << methodNames() << " (default rcme)\n"
        << "  --solver S          eight (default, the figures of doc/results.md), seven, five, "
           "auto\n"
        << "  --sigma S           rcme's noise sigma in pixels (default 1)\n"
        << "  --seed N            rcme's random generator state (default 0; OpenCV's RANSAC has\n"
        << "                      a fixed internal seed)\n"
        << "  --min-parallax PX   median displacement that makes a keyframe pair (default 30)\n"
        << "  --max-reselect N    later frames tried after a rejected pair (default 5)\n"
        << "  --min-matches N     fewer matches end the keyframe search (default 60)\n"
        << "  --features N        SIFT features per frame (default 3000)\n"
        << "  --front-end F       sift (keyframes, default) or klt: every frame, FAST corners of\n"
        << "                      the reference tracked by KLT; a flagged frame is held and the\n"
        << "                      reference kept for the next one\n"
        << "  --bad-frames LIST   comma-separated frames whose matches are re-paired at random,\n"
        << "                      simulating unusable frames (default: none)\n"
        << "  --stale-frames LIST comma-separated frames delivered as a stale copy of the frame\n"
        << "                      before (a camera that repeated its last image: no motion)\n"
        << "  --opencv-threshold PX  findEssentialMat's threshold (default 1, OpenCV's default)\n"
        << "  --opencv-prob P     findEssentialMat's confidence (default 0.999)\n"
        << "  --no-degeneracy-test  accept pairs that a homography explains as well as F\n"
        << "                      (Params::degeneracyTest off)\n"
        << "  --no-opencv         skip the OpenCV run\n"
        << "  --out FILE          output PNG (default rcme_mono_vo.png)\n"
        << "  --max-wrong-pairs K exit with 1 when rcme accepts more than K pairs whose rotation\n"
        << "                      is more than 5 deg or translation direction more than 15 deg\n"
        << "                      wrong\n"
        << "  --max-median-rotation-error-deg X\n"
        << "                      exit with 1 when rcme's median rotation error per keyframe\n"
        << "                      pair exceeds X degrees\n"
        << "  -v, --verbose       print every keyframe pair\n"
        << "  -h, --help          this help\n"
        << "\n"
        << "Exit codes: 0 success; 1 nothing estimated or rotation error too large; 2 usage or\n"
        << "input/output error; 3 error raised by the library.\n";
}

struct Options
{
    std::string dataDir = RCME_DEFAULT_DATA_DIR;
    std::string sequence = kDefaultSequence;
    int frames = 0;
    std::string method = "rcme";
    std::string solver = "eight";
    double sigma = 1.0;
    int seed = 0;
    double minParallax = 30.0;
    int maxReselect = 5;
    int minMatches = 60;
    int features = 3000;
    bool klt = false; //!< --front-end klt
    int maxWrongPairs = -1;
    std::vector<int> badFrames;
    std::vector<int> staleFrames;
    double opencvThreshold = 1.0;
    double opencvProb = 0.999;
    bool runOpencv = true;
    bool degeneracyTest = true;
    std::string outPath = "rcme_mono_vo.png";
    double maxMedianRotationErrorDeg = -1.0;
    bool verbose = false;
    bool help = false;
};

Options parseArgs(int argc, char** argv)
{
    const CommandLine cmd(argc, argv,
                          {"data", "sequence", "frames", "method", "solver", "sigma", "seed",
                           "min-parallax", "max-reselect", "min-matches", "features",
                           "opencv-threshold", "opencv-prob", "out", "bad-frames",
                           "max-median-rotation-error-deg", "front-end", "max-wrong-pairs",
                           "stale-frames"},
                          {"no-opencv", "no-degeneracy-test", "verbose", "v"});
    Options opt;
    opt.help = cmd.help;
    if (!cmd.positional.empty())
        throw UsageError("unexpected argument '" + cmd.positional[0] + "' (see --help)");
    for (const auto& [key, value] : cmd.options) {
        if (key == "data")
            opt.dataDir = value;
        else if (key == "sequence")
            opt.sequence = value;
        else if (key == "frames")
            opt.frames = parseInt(key, value);
        else if (key == "method")
            opt.method = value;
        else if (key == "solver")
            opt.solver = value;
        else if (key == "sigma")
            opt.sigma = parseDouble(key, value);
        else if (key == "seed")
            opt.seed = parseInt(key, value);
        else if (key == "min-parallax")
            opt.minParallax = parseDouble(key, value);
        else if (key == "max-reselect")
            opt.maxReselect = parseInt(key, value);
        else if (key == "min-matches")
            opt.minMatches = parseInt(key, value);
        else if (key == "features")
            opt.features = parseInt(key, value);
        else if (key == "front-end") {
            if (value != "sift" && value != "klt")
                throw UsageError("--front-end must be sift or klt, not '" + value + "'");
            opt.klt = value == "klt";
        } else if (key == "max-wrong-pairs")
            opt.maxWrongPairs = parseInt(key, value);
        else if (key == "opencv-threshold")
            opt.opencvThreshold = parseDouble(key, value);
        else if (key == "opencv-prob")
            opt.opencvProb = parseDouble(key, value);
        else if (key == "bad-frames" || key == "stale-frames") {
            std::stringstream list(value);
            std::string item;
            while (std::getline(list, item, ','))
                if (!item.empty())
                    (key == "bad-frames" ? opt.badFrames : opt.staleFrames)
                        .push_back(parseInt(key, item));
        } else if (key == "no-opencv")
            opt.runOpencv = false;
        else if (key == "no-degeneracy-test")
            opt.degeneracyTest = false;
        else if (key == "out")
            opt.outPath = value;
        else if (key == "max-median-rotation-error-deg")
            opt.maxMedianRotationErrorDeg = parseDouble(key, value);
        else if (key == "verbose" || key == "v")
            opt.verbose = true;
    }
    if (opt.frames != 0 && opt.frames < 2)
        throw UsageError("--frames must be at least 2 (or 0 for all)");
    if (opt.minParallax < 0 || opt.maxReselect < 0 || opt.minMatches < 8 || opt.features < 0)
        throw UsageError("--min-parallax and --max-reselect must be >= 0, --min-matches >= 8, "
                         "--features >= 0");
    if (!(opt.opencvThreshold > 0) || !(opt.opencvProb > 0 && opt.opencvProb < 1))
        throw UsageError("--opencv-threshold must be > 0 and --opencv-prob in (0, 1)");
    return opt;
}

// ---------------------------------------------------------------------------------------------
// The sequence: camera matrix, ground-truth poses, images.

//! Rigid transform as 4x4: camera-to-world poses and relative motions.
using Pose = cv::Matx44d;

Pose rigid(const cv::Matx33d& R, const cv::Vec3d& t)
{
    Pose T = Pose::eye();
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c)
            T(r, c) = R(r, c);
        T(r, 3) = t[r];
    }
    return T;
}

cv::Matx33d rotationOf(const Pose& T)
{
    return T.get_minor<3, 3>(0, 0);
}

cv::Vec3d translationOf(const Pose& T)
{
    return cv::Vec3d(T(0, 3), T(1, 3), T(2, 3));
}

Pose inverseRigid(const Pose& T)
{
    const cv::Matx33d Rt = rotationOf(T).t();
    return rigid(Rt, -(Rt * translationOf(T)));
}

struct Sequence
{
    std::string folder;
    std::string name;
    cv::Matx33d K;
    std::vector<Pose> groundTruth; //!< camera-to-world, one per frame
    std::vector<std::string> images;
};

//! The sequence folder: a path, a name inside dataDir, or a KITTI number ("06").
fs::path resolveSequenceFolder(const Options& opt)
{
    const fs::path given(opt.sequence);
    if (fs::is_directory(given) && opt.sequence.find('/') != std::string::npos)
        return given;
    const fs::path dataDir(opt.dataDir);
    if (!fs::is_directory(dataDir))
        throw UsageError("data folder not found: '" + fs::absolute(dataDir).string() +
                         "' (the KITTI sequences are expected in ../shared/data next to the "
                         "repository; pass --data DIR)");
    const fs::path inData = dataDir / given;
    if (fs::is_directory(inData))
        return inData;
    if (opt.sequence.size() == 2 && std::isdigit(static_cast<unsigned char>(opt.sequence[0])) &&
        std::isdigit(static_cast<unsigned char>(opt.sequence[1]))) {
        std::vector<fs::path> found;
        for (const auto& entry : fs::directory_iterator(dataDir))
            if (entry.is_directory() && entry.path().filename().string().rfind(
                                            "kitti_odometry_" + opt.sequence + "_", 0) == 0)
                found.push_back(entry.path());
        if (!found.empty())
            return *std::min_element(found.begin(), found.end());
    }
    throw UsageError("sequence folder not found: '" + fs::absolute(inData).string() + "'");
}

Sequence readSequence(const Options& opt)
{
    Sequence seq;
    const fs::path folder = resolveSequenceFolder(opt);
    seq.folder = folder.string();
    seq.name = fs::absolute(folder).lexically_normal().filename().string();
    if (seq.name.empty())
        seq.name = fs::absolute(folder).lexically_normal().parent_path().filename().string();
    for (const char* required : {"calib.txt", "poses.txt", "image_l"})
        if (!fs::exists(folder / required))
            throw UsageError("'" + (folder / required).string() +
                             "' not found: a sequence folder holds calib.txt, poses.txt and "
                             "image_l/");

    const auto calib = readNumberRows((folder / "calib.txt").string(), "calibration");
    if (calib.empty() || calib[0].size() != 12)
        throw UsageError("the first line of '" + (folder / "calib.txt").string() +
                         "' must hold the 12 numbers of P0");
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            seq.K(r, c) = calib[0][4 * r + c];
    if (!(seq.K(0, 0) > 0 && seq.K(1, 1) > 0 && seq.K(2, 2) > 0))
        throw UsageError("P0 in '" + (folder / "calib.txt").string() +
                         "' does not hold a camera matrix");

    const auto poses = readNumberRows((folder / "poses.txt").string(), "poses");
    for (size_t i = 0; i < poses.size(); ++i) {
        if (poses[i].size() != 12)
            throw UsageError("line " + std::to_string(i + 1) + " of '" +
                             (folder / "poses.txt").string() + "' must hold 12 numbers");
        Pose T = Pose::eye();
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c)
                T(r, c) = poses[i][4 * r + c];
        seq.groundTruth.push_back(T);
    }

    for (const auto& entry : fs::directory_iterator(folder / "image_l"))
        if (entry.path().extension() == ".png")
            seq.images.push_back(entry.path().string());
    std::sort(seq.images.begin(), seq.images.end());
    if (seq.images.size() < 2)
        throw UsageError("fewer than two PNG images in '" + (folder / "image_l").string() + "'");
    if (seq.groundTruth.size() < seq.images.size())
        throw UsageError("'" + (folder / "poses.txt").string() + "' has " +
                         std::to_string(seq.groundTruth.size()) + " poses for " +
                         std::to_string(seq.images.size()) + " images");
    if (opt.frames > 0 && static_cast<size_t>(opt.frames) < seq.images.size())
        seq.images.resize(opt.frames);
    seq.groundTruth.resize(seq.images.size());
    return seq;
}

// ---------------------------------------------------------------------------------------------
// Features and matches, computed once and shared by both runs.

class FeatureCache
{
public:
    FeatureCache(const Sequence& seq, int features, const std::vector<int>& badFrames,
                 const std::vector<int>& staleFrames, bool klt)
        : seq_(seq), sift_(cv::SIFT::create(features)), frames_(seq.images.size()),
          badFrames_(badFrames), staleFrames_(staleFrames), klt_(klt)
    {
    }

    struct PairMatches
    {
        Matches matches;
        double medianParallax = 0; //!< median image displacement, pixels
    };

    const PairMatches& matches(int i, int j)
    {
        auto it = pairs_.find({i, j});
        if (it != pairs_.end())
            return it->second;
        const Frame &a = frame(i), &b = frame(j);
        PairMatches pm;
        pm.matches = klt_ ? trackCorners(a, b)
                          : matchRatioTest(a.keypoints, a.descriptors, b.keypoints, b.descriptors);
        if (isBad(i) || isBad(j)) {
            // an unusable frame: every point keeps its position but gets a random partner
            cv::RNG rng(static_cast<uint64>(1000003) * i + j);
            std::vector<cv::Point2f>& p2 = pm.matches.points2;
            for (int k = static_cast<int>(p2.size()) - 1; k > 0; --k)
                std::swap(p2[k], p2[rng.uniform(0, k + 1)]);
        }
        std::vector<double> flow;
        for (size_t k = 0; k < pm.matches.points1.size(); ++k)
            flow.push_back(cv::norm(pm.matches.points2[k] - pm.matches.points1[k]));
        if (!flow.empty()) {
            std::nth_element(flow.begin(), flow.begin() + flow.size() / 2, flow.end());
            pm.medianParallax = flow[flow.size() / 2];
        }
        return pairs_.emplace(std::make_pair(i, j), std::move(pm)).first->second;
    }

    double featureMilliseconds() const { return featureTime_.getTimeMilli(); }

private:
    bool isBad(int frame) const
    {
        return std::find(badFrames_.begin(), badFrames_.end(), frame) != badFrames_.end();
    }

    struct Frame
    {
        bool ready = false;
        std::vector<cv::KeyPoint> keypoints;
        cv::Mat descriptors;
        cv::Mat image; //!< KLT tracks from it
    };

    /* The front end of OpenCV-based VO examples (as samples/benchmark/vo_front_end.py): FAST
    corners (threshold 20, non-maximum suppression) of `a` tracked into `b` by pyramidal KLT
    (21x21, 3 levels, 30 iterations or 0.01 px) and back, kept when both tracks converge inside
    the image and the backward one ends within 1 px of the corner. */
    static Matches trackCorners(const Frame& a, const Frame& b)
    {
        constexpr double kMaxForwardBackwardPx = 1.0;
        Matches m;
        std::vector<cv::Point2f> corners, tracked, back;
        cv::KeyPoint::convert(a.keypoints, corners);
        if (corners.empty())
            return m;
        std::vector<uchar> found, foundBack;
        std::vector<float> error;
        const cv::Size window(21, 21);
        const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.01);
        cv::calcOpticalFlowPyrLK(a.image, b.image, corners, tracked, found, error, window, 3, stop);
        cv::calcOpticalFlowPyrLK(b.image, a.image, tracked, back, foundBack, error, window, 3,
                                 stop);
        const cv::Rect inside(0, 0, b.image.cols, b.image.rows);
        for (size_t k = 0; k < corners.size(); ++k)
            if (found[k] && foundBack[k] && inside.contains(tracked[k]) &&
                cv::norm(back[k] - corners[k]) < kMaxForwardBackwardPx) {
                m.points1.push_back(corners[k]);
                m.points2.push_back(tracked[k]);
            }
        return m;
    }

    const Frame& frame(int i)
    {
        Frame& f = frames_[i];
        if (!f.ready) {
            // a stale frame repeats the image before it
            const bool stale = i > 0 && std::find(staleFrames_.begin(), staleFrames_.end(), i) !=
                                            staleFrames_.end();
            const std::string& path = seq_.images[stale ? i - 1 : i];
            const cv::Mat img = cv::imread(path, cv::IMREAD_GRAYSCALE);
            if (img.empty())
                throw UsageError("cannot read image '" + path + "'");
            featureTime_.start();
            if (klt_) {
                cv::FastFeatureDetector::create(20, true)->detect(img, f.keypoints);
                f.image = img;
            } else {
                sift_->detectAndCompute(img, cv::noArray(), f.keypoints, f.descriptors);
            }
            featureTime_.stop();
            f.ready = true;
        }
        return f;
    }

    const Sequence& seq_;
    cv::Ptr<cv::SIFT> sift_;
    std::vector<Frame> frames_;
    std::map<std::pair<int, int>, PairMatches> pairs_;
    cv::TickMeter featureTime_;
    std::vector<int> badFrames_, staleFrames_;
    bool klt_;
};

// ---------------------------------------------------------------------------------------------
// The two estimators behind one interface.

struct PairEstimate
{
    bool accepted = false;
    std::string verdict; //!< why a pair was not accepted
    //! rcme's status when rcme rejected the pair (OpenCV has none)
    std::optional<cv::rcme::Status> status;
    cv::Matx33d R;
    cv::Vec3d t;
    int inliers = 0;
    double milliseconds = 0;
};

using PairEstimator = std::function<PairEstimate(const Matches&, const cv::Matx33d& K)>;

PairEstimator rcmeEstimator(const cv::rcme::Params& params)
{
    return [params](const Matches& m, const cv::Matx33d& K) {
        PairEstimate est;
        cv::Mat E, R, t, mask;
        cv::rcme::Status status = cv::rcme::STATUS_SUCCESS;
        cv::TickMeter tm;
        tm.start();
        est.inliers =
            cv::rcme::recoverPose(m.points1, m.points2, cv::Mat(K), E, R, t, params, mask, status);
        tm.stop();
        est.milliseconds = tm.getTimeMilli();
        est.accepted = status == cv::rcme::STATUS_SUCCESS;
        if (est.accepted) {
            est.R = cv::Matx33d(R);
            est.t = cv::Vec3d(t);
        } else {
            est.verdict = cv::rcme::statusToString(status);
            est.status = status;
        }
        return est;
    };
}

PairEstimator opencvEstimator(double threshold, double prob)
{
    return [threshold, prob](const Matches& m, const cv::Matx33d& K) {
        PairEstimate est;
        cv::Mat mask, R, t;
        cv::TickMeter tm;
        tm.start();
        const cv::Mat E = cv::findEssentialMat(m.points1, m.points2, cv::Mat(K), cv::RANSAC, prob,
                                               threshold, mask);
        if (E.rows >= 3 && E.cols == 3)
            est.inliers =
                cv::recoverPose(E.rowRange(0, 3), m.points1, m.points2, cv::Mat(K), R, t, mask);
        tm.stop();
        est.milliseconds = tm.getTimeMilli();
        // No failure signal: whatever E it returns is accepted, as a VO front end would.
        est.accepted = !R.empty();
        if (est.accepted) {
            est.R = cv::Matx33d(R);
            est.t = cv::Vec3d(t);
        } else {
            est.verdict = "no essential matrix";
        }
        return est;
    };
}

// ---------------------------------------------------------------------------------------------
// The keyframe loop.

struct KeyframePair
{
    int first, second;
    double rotationErrorDeg, translationErrorDeg;
    int inliers, matches;
};

struct Rejection
{
    int first, second;
    std::string verdict;
    std::optional<cv::rcme::Status> status;
};

struct VoRun
{
    std::string label;
    std::vector<int> keyframes;      //!< frame indices
    std::vector<Pose> keyframePoses; //!< estimated camera-to-world poses, GT scale
    std::vector<KeyframePair> pairs;
    std::vector<Rejection> rejections;
    int bridgedGaps = 0;
    std::vector<double> milliseconds;
};

Pose relativeGroundTruth(const Sequence& seq, int i, int j)
{
    // x_j = R_ji x_i + t_ji with T_ji = T_wj^-1 T_wi
    return inverseRigid(seq.groundTruth[j]) * seq.groundTruth[i];
}

VoRun runOdometry(const Sequence& seq, FeatureCache& cache, const Options& opt,
                  const std::string& label, const PairEstimator& estimate)
{
    VoRun run;
    run.label = label;
    const int n = static_cast<int>(seq.images.size());
    int keyframe = 0;
    Pose pose = seq.groundTruth[0];
    Pose lastMotion = rigid(cv::Matx33d::eye(), cv::Vec3d(0, 0, -1)); // forward, until known
    run.keyframes.push_back(keyframe);
    run.keyframePoses.push_back(pose);

    // Moves the keyframe to `to` with the motion `motion` (unit translation, x_to = R x_kf + t)
    // scaled by the ground-truth distance between the frames: for display only.
    auto advance = [&](int to, const Pose& motion) {
        const double baseline = cv::norm(translationOf(relativeGroundTruth(seq, keyframe, to)));
        const Pose scaled = rigid(rotationOf(motion), baseline * translationOf(motion));
        pose = pose * inverseRigid(scaled);
        keyframe = to;
        run.keyframes.push_back(keyframe);
        run.keyframePoses.push_back(pose);
    };

    // KLT: every frame is a candidate, the reference is the last accepted one
    const double minParallax = opt.klt ? 0.0 : opt.minParallax;
    while (keyframe < n - 1) {
        int candidate = keyframe + 1;
        // first frame with enough parallax (or the last frame)
        while (candidate < n - 1 &&
               cache.matches(keyframe, candidate).medianParallax < minParallax &&
               static_cast<int>(cache.matches(keyframe, candidate).matches.points1.size()) >=
                   opt.minMatches)
            ++candidate;
        const int lastCandidate = std::min(n - 1, candidate + opt.maxReselect);
        int lastTried = keyframe;
        bool accepted = false, endOfSequence = false;
        for (; candidate <= lastCandidate && !accepted; ++candidate) {
            const auto& pm = cache.matches(keyframe, candidate);
            const int numMatches = static_cast<int>(pm.matches.points1.size());
            if (numMatches < opt.minMatches) {
                std::cout << "  " << label << ": keyframe pair " << keyframe << " -> " << candidate
                          << " has " << numMatches << " matches, too few\n";
                break; // later frames only have fewer
            }
            if (pm.medianParallax < minParallax && lastTried == keyframe) {
                endOfSequence = true; // the sequence ended before there was enough parallax
                break;
            }
            lastTried = candidate;
            const PairEstimate est = estimate(pm.matches, seq.K);
            run.milliseconds.push_back(est.milliseconds);
            if (!est.accepted) {
                run.rejections.push_back({keyframe, candidate, est.verdict, est.status});
                std::cout << "  " << label << ": keyframe pair " << keyframe << " -> " << candidate
                          << " rejected (" << est.verdict << ", " << numMatches
                          << (opt.klt ? " tracks): frame " + std::to_string(candidate) +
                                            " held, reference " + std::to_string(keyframe) +
                                            " kept for the next frame\n"
                                      : std::string(" matches), re-selecting\n"));
                continue;
            }
            const Pose truth = relativeGroundTruth(seq, keyframe, candidate);
            const cv::rcme::MotionError err =
                cv::rcme::compareMotion(cv::Mat(est.R), cv::Mat(est.t), cv::Mat(rotationOf(truth)),
                                        cv::Mat(translationOf(truth)));
            run.pairs.push_back({keyframe, candidate, err.rotationDeg, err.translationDeg,
                                 est.inliers, numMatches});
            if (opt.verbose)
                std::cout << "  " << label << ": " << keyframe << " -> " << candidate << ": "
                          << est.inliers << " / " << numMatches << " inliers, parallax "
                          << fixed(pm.medianParallax, 1) << " px, rotation error "
                          << fixed(err.rotationDeg, 3) << " deg, translation direction "
                          << fixed(err.translationDeg, 2) << " deg\n";
            lastMotion = rigid(est.R, est.t);
            advance(candidate, lastMotion);
            accepted = true;
        }
        if (accepted)
            continue;
        if (endOfSequence)
            break; // stop at this keyframe
        // Nothing acceptable: bridge to the last frame tried with the previous motion.
        const int to = std::max(lastTried, keyframe + 1);
        std::cout << "  " << label << ": no acceptable pair from keyframe " << keyframe
                  << ", bridging to frame " << to << " with the previous motion\n";
        ++run.bridgedGaps;
        advance(to, lastMotion);
    }
    return run;
}

// ---------------------------------------------------------------------------------------------
// Figures and the picture.

double median(std::vector<double> v)
{
    if (v.empty())
        return std::nan("");
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
}

double mean(const std::vector<double>& v)
{
    if (v.empty())
        return std::nan("");
    double s = 0;
    for (double x : v)
        s += x;
    return s / v.size();
}

struct Summary
{
    double meanRotationDeg, medianRotationDeg, medianTranslationDeg;
    double finalPositionError, ateRmse, pathLength, medianMilliseconds;
    int finalFrame;
};

Summary summarize(const Sequence& seq, const VoRun& run)
{
    Summary s;
    std::vector<double> rot, trans;
    for (const auto& p : run.pairs) {
        rot.push_back(p.rotationErrorDeg);
        trans.push_back(p.translationErrorDeg);
    }
    s.meanRotationDeg = mean(rot);
    s.medianRotationDeg = median(rot);
    s.medianTranslationDeg = median(trans);
    s.medianMilliseconds = median(run.milliseconds);
    s.finalFrame = run.keyframes.back();
    s.finalPositionError = cv::norm(translationOf(run.keyframePoses.back()) -
                                    translationOf(seq.groundTruth[s.finalFrame]));
    double sq = 0;
    for (size_t k = 0; k < run.keyframes.size(); ++k) {
        const double e = cv::norm(translationOf(run.keyframePoses[k]) -
                                  translationOf(seq.groundTruth[run.keyframes[k]]));
        sq += e * e;
    }
    s.ateRmse = std::sqrt(sq / run.keyframes.size());
    s.pathLength = 0;
    for (int f = 1; f <= s.finalFrame; ++f)
        s.pathLength +=
            cv::norm(translationOf(seq.groundTruth[f]) - translationOf(seq.groundTruth[f - 1]));
    return s;
}

const cv::Scalar kGroundTruthColor(40, 40, 40);
const cv::Scalar kRejectionColor(0, 0, 220);
const cv::Scalar kHeldColor(180, 0, 180);

cv::Scalar runColor(size_t r)
{
    return r == 0 ? cv::Scalar(200, 60, 0) : cv::Scalar(0, 140, 255);
}

void putLabel(cv::Mat& canvas, const std::string& text, cv::Point at, double size = 0.45,
              const cv::Scalar& color = cv::Scalar::all(0))
{
    cv::putText(canvas, text, at, cv::FONT_HERSHEY_SIMPLEX, size, color, 1, cv::LINE_AA);
}

//! A round grid step (1, 2 or 5 times a power of ten) giving about `lines` lines over span.
double gridStep(double span, double lines)
{
    const double raw = span / lines;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (m * magnitude >= raw)
            return m * magnitude;
    return 10 * magnitude;
}

/** Top view (x right, z forward, metres, equal scale) of the ground truth and of the runs'
keyframes, with a cross on the keyframes whose next pair was rejected and re-selected. */
cv::Mat drawTopView(const Sequence& seq, const std::vector<const VoRun*>& runs, int size)
{
    cv::Mat panel(size, size, CV_8UC3, cv::Scalar::all(255));
    const int margin = 40;
    double minX = 1e300, maxX = -1e300, minZ = 1e300, maxZ = -1e300;
    auto extend = [&](const Pose& T) {
        minX = std::min(minX, T(0, 3));
        maxX = std::max(maxX, T(0, 3));
        minZ = std::min(minZ, T(2, 3));
        maxZ = std::max(maxZ, T(2, 3));
    };
    for (const Pose& T : seq.groundTruth)
        extend(T);
    for (const VoRun* run : runs)
        for (const Pose& T : run->keyframePoses)
            extend(T);
    const double span = std::max({maxX - minX, maxZ - minZ, 1.0});
    const double scale = (size - 2 * margin) / span;
    const double centerX = 0.5 * (minX + maxX), centerZ = 0.5 * (minZ + maxZ);
    auto toPixel = [&](double x, double z) {
        return cv::Point(cvRound(size / 2 + (x - centerX) * scale),
                         cvRound(size / 2 - (z - centerZ) * scale));
    };
    auto at = [&](const Pose& T) { return toPixel(T(0, 3), T(2, 3)); };

    const double step = gridStep(span, 6), half = 0.5 * size / scale;
    // integer multiples of the step: no drift, and no "-0" label
    for (int k = cvCeil((centerX - half) / step); k * step <= centerX + half; ++k) {
        const double x = k * step;
        const int px = toPixel(x, centerZ).x;
        cv::line(panel, cv::Point(px, 0), cv::Point(px, size), cv::Scalar::all(225));
        putLabel(panel, fixed(x, step < 1 ? 1 : 0), cv::Point(px + 2, size - 6), 0.35,
                 cv::Scalar::all(120));
    }
    for (int k = cvCeil((centerZ - half) / step); k * step <= centerZ + half; ++k) {
        const double z = k * step;
        const int py = toPixel(centerX, z).y;
        cv::line(panel, cv::Point(0, py), cv::Point(size, py), cv::Scalar::all(225));
        putLabel(panel, fixed(z, step < 1 ? 1 : 0), cv::Point(4, py - 3), 0.35,
                 cv::Scalar::all(120));
    }
    putLabel(panel, "top view: x (m) right, z (m) forward", cv::Point(8, 18), 0.45,
             cv::Scalar::all(80));

    for (size_t f = 1; f < seq.groundTruth.size(); ++f)
        cv::line(panel, at(seq.groundTruth[f - 1]), at(seq.groundTruth[f]), kGroundTruthColor, 2,
                 cv::LINE_AA);
    // the last run first, so that rcme's (thinner) line stays visible on top
    for (size_t r = runs.size(); r-- > 0;) {
        const VoRun& run = *runs[r];
        const int width = r == 0 ? 2 : 4;
        for (size_t k = 0; k < run.keyframePoses.size(); ++k) {
            if (k > 0)
                cv::line(panel, at(run.keyframePoses[k - 1]), at(run.keyframePoses[k]), runColor(r),
                         width, cv::LINE_AA);
            cv::circle(panel, at(run.keyframePoses[k]), width + 1, runColor(r), cv::FILLED,
                       cv::LINE_AA);
        }
        for (const Rejection& rej : run.rejections) {
            const auto it = std::find(run.keyframes.begin(), run.keyframes.end(), rej.first);
            if (it != run.keyframes.end())
                cv::drawMarker(panel, at(run.keyframePoses[it - run.keyframes.begin()]),
                               kRejectionColor, cv::MARKER_TILTED_CROSS, 14, 2, cv::LINE_AA);
            // the frame whose pair was turned down, on the ground truth: a held frame
            cv::drawMarker(panel, at(seq.groundTruth[rej.second]), kHeldColor, cv::MARKER_DIAMOND,
                           12, 2, cv::LINE_AA);
        }
    }
    cv::rectangle(panel, cv::Rect(0, 0, size, size), cv::Scalar::all(160));
    return panel;
}

//! Position error of each run's keyframes against the frame number, logarithmic in metres.
cv::Mat drawErrorPlot(const Sequence& seq, const std::vector<const VoRun*>& runs, int width,
                      int height)
{
    cv::Mat panel(height, width, CV_8UC3, cv::Scalar::all(255));
    const int left = 50, right = 15, top = 30, bottom = 30;
    const int lastFrame = static_cast<int>(seq.groundTruth.size()) - 1;
    std::vector<std::vector<double>> errors(runs.size());
    double maxError = 1.0;
    for (size_t r = 0; r < runs.size(); ++r)
        for (size_t k = 0; k < runs[r]->keyframes.size(); ++k) {
            const double e = cv::norm(translationOf(runs[r]->keyframePoses[k]) -
                                      translationOf(seq.groundTruth[runs[r]->keyframes[k]]));
            errors[r].push_back(e);
            maxError = std::max(maxError, e);
        }
    const double lowDecade = -2, highDecade = std::ceil(std::log10(maxError));
    auto toPixel = [&](int frame, double error) {
        const double y = (std::log10(std::max(error, 0.01)) - lowDecade) / (highDecade - lowDecade);
        return cv::Point(left + cvRound((width - left - right) * frame / double(lastFrame)),
                         cvRound(height - bottom - (height - top - bottom) * y));
    };
    for (double d = lowDecade; d <= highDecade; ++d) {
        const int y = toPixel(0, std::pow(10.0, d)).y;
        cv::line(panel, cv::Point(left, y), cv::Point(width - right, y), cv::Scalar::all(225));
        putLabel(panel, fixed(std::pow(10.0, d), d < 0 ? static_cast<int>(-d) : 0),
                 cv::Point(4, y + 4), 0.35, cv::Scalar::all(120));
    }
    const double frameStep = gridStep(lastFrame, 5);
    for (double f = 0; f <= lastFrame; f += frameStep) {
        const int x = toPixel(static_cast<int>(f), 1).x;
        cv::line(panel, cv::Point(x, top), cv::Point(x, height - bottom), cv::Scalar::all(225));
        putLabel(panel, fixed(f, 0), cv::Point(x - 6, height - 10), 0.35, cv::Scalar::all(120));
    }
    putLabel(panel, "position error (m, log scale, <= 0.01 at the bottom) vs frame",
             cv::Point(8, 18), 0.45, cv::Scalar::all(80));
    for (size_t r = runs.size(); r-- > 0;)
        for (size_t k = 0; k < errors[r].size(); ++k) {
            const cv::Point p = toPixel(runs[r]->keyframes[k], errors[r][k]);
            if (k > 0)
                cv::line(panel, toPixel(runs[r]->keyframes[k - 1], errors[r][k - 1]), p,
                         runColor(r), r == 0 ? 2 : 4, cv::LINE_AA);
            cv::circle(panel, p, r == 0 ? 3 : 5, runColor(r), cv::FILLED, cv::LINE_AA);
        }
    cv::rectangle(panel, cv::Rect(0, 0, width, height), cv::Scalar::all(160));
    return panel;
}

//! The picture: title and legend, then the top view and the error plot side by side.
cv::Mat drawTrajectories(const Sequence& seq, const std::vector<const VoRun*>& runs,
                         const std::vector<std::string>& legend, const std::string& title)
{
    const int plotSize = 640, errorWidth = 520, lineHeight = 22;
    cv::Mat plots;
    cv::hconcat(drawTopView(seq, runs, plotSize), drawErrorPlot(seq, runs, errorWidth, plotSize),
                plots);
    const int header = lineHeight * static_cast<int>(legend.size() + 4) + 8;
    cv::Mat canvas(header + plots.rows, plots.cols, CV_8UC3, cv::Scalar::all(255));
    plots.copyTo(canvas(cv::Rect(0, header, plots.cols, plots.rows)));

    putLabel(canvas, title, cv::Point(10, 20), 0.5);
    auto rowY = [&](int row) { return lineHeight * (row + 1) + 20; };
    cv::line(canvas, cv::Point(10, rowY(0) - 4), cv::Point(40, rowY(0) - 4), kGroundTruthColor, 2,
             cv::LINE_AA);
    putLabel(canvas, "ground truth (KITTI poses.txt)", cv::Point(48, rowY(0)));
    for (size_t r = 0; r < legend.size(); ++r) {
        const int y = rowY(static_cast<int>(r) + 1) - 4;
        cv::line(canvas, cv::Point(10, y), cv::Point(40, y), runColor(r), r == 0 ? 2 : 4,
                 cv::LINE_AA);
        cv::circle(canvas, cv::Point(25, y), r == 0 ? 3 : 5, runColor(r), cv::FILLED, cv::LINE_AA);
        putLabel(canvas, legend[r], cv::Point(48, y + 4));
    }
    const int y = rowY(static_cast<int>(legend.size()) + 1);
    cv::drawMarker(canvas, cv::Point(25, y - 4), kRejectionColor, cv::MARKER_TILTED_CROSS, 12, 2,
                   cv::LINE_AA);
    putLabel(canvas, "keyframe whose next pair rcme rejected and re-selected; dots: keyframes",
             cv::Point(48, y));
    cv::drawMarker(canvas, cv::Point(25, y + lineHeight - 4), kHeldColor, cv::MARKER_DIAMOND, 12, 2,
                   cv::LINE_AA);
    putLabel(canvas,
             "held frame (on the ground truth): its pair was rejected, the next frame was "
             "tried from the same reference",
             cv::Point(48, y + lineHeight));
    return canvas;
}

//! Accepted pairs whose rotation is more than 5 deg or translation direction more than 15 deg
//! off the ground truth (wrong, as the benchmark counts them).
int countWrongPairs(const VoRun& run)
{
    int count = 0;
    for (const KeyframePair& p : run.pairs)
        count += p.rotationErrorDeg > 5.0 || p.translationErrorDeg > 15.0;
    return count;
}

//! The held frames of a run and the status that held each ("12 (undetermined motion)").
std::string heldFrames(const VoRun& run)
{
    std::string list;
    for (const Rejection& r : run.rejections)
        list += (list.empty() ? "" : ", ") + std::to_string(r.second) + " (" + r.verdict + ")";
    return list.empty() ? "none" : list;
}

//! Re-selections after rcme reported `status`; with no status, the re-selections for any other
//! reason (OpenCV without an essential matrix, too few points...).
int countRejections(const VoRun& run, std::optional<cv::rcme::Status> status)
{
    int count = 0;
    for (const Rejection& r : run.rejections) {
        const bool isTracked = r.status == cv::rcme::STATUS_POOR_QUALITY_INPUT ||
                               r.status == cv::rcme::STATUS_DEGENERATE_CONFIGURATION;
        count += status ? r.status == status : !isTracked;
    }
    return count;
}

int run(int argc, char** argv)
{
    const Options opt = parseArgs(argc, argv);
    if (opt.help) {
        printUsage(argv[0]);
        return EXIT_OK;
    }
    cv::rcme::Params params;
    params.method = parseMethod(opt.method);
    params.solver = parseSolver(opt.solver);
    params.sigma = opt.sigma;
    params.randomGeneratorState = opt.seed;
    params.degeneracyTest = opt.degeneracyTest;

    const Sequence seq = readSequence(opt);
    const int n = static_cast<int>(seq.images.size());
    std::cout << "sequence: " << seq.name << " (" << seq.folder << "), frames 0-" << n - 1 << "\n"
              << "camera: fx " << fixed(seq.K(0, 0), 3) << ", cx " << fixed(seq.K(0, 2), 3)
              << ", cy " << fixed(seq.K(1, 2), 3) << "\n"
              << (opt.klt ? "frames: FAST corners of the reference tracked by KLT "
                            "(forward-backward <= 1 px), every frame; a rejected frame is held, "
                            "up to " +
                                std::to_string(opt.maxReselect) + " per reference\n"
                          : "keyframes: SIFT (" + std::to_string(opt.features) +
                                " per frame) + ratio test 0.8, median parallax >= " +
                                fixed(opt.minParallax, 1) + " px, up to " +
                                std::to_string(opt.maxReselect) + " re-selections per keyframe\n")
              << "rcme: method " << opt.method << ", solver " << opt.solver << ", sigma "
              << opt.sigma << " px, degeneracy test " << (opt.degeneracyTest ? "on" : "off")
              << "; OpenCV: findEssentialMat RANSAC (threshold " << opt.opencvThreshold
              << " px, prob " << opt.opencvProb << ") + recoverPose\n"
              << (opt.badFrames.empty() ? std::string()
                                        : "simulated unusable frames (matches re-paired at "
                                          "random): " +
                                              std::to_string(opt.badFrames.size()) + "\n")
              << (opt.staleFrames.empty() ? std::string()
                                          : "simulated stale frames (a repeat of the frame "
                                            "before): " +
                                                std::to_string(opt.staleFrames.size()) + "\n")
              << "scale: each pair's translation is scaled by the ground-truth distance between "
                 "its frames (display only: monocular VO has no scale)\n";

    FeatureCache cache(seq, opt.features, opt.badFrames, opt.staleFrames, opt.klt);
    const std::string rcmeLabel = "rcme " + opt.method;
    std::cout << "run 1: " << rcmeLabel << "\n";
    const VoRun rcmeRun = runOdometry(seq, cache, opt, rcmeLabel, rcmeEstimator(params));
    std::vector<const VoRun*> runs = {&rcmeRun};
    std::unique_ptr<VoRun> opencvRun;
    if (opt.runOpencv) {
        std::cout << "run 2: OpenCV\n";
        opencvRun = std::make_unique<VoRun>(runOdometry(
            seq, cache, opt, "OpenCV", opencvEstimator(opt.opencvThreshold, opt.opencvProb)));
        runs.push_back(opencvRun.get());
    }

    // side-by-side figures
    std::vector<Summary> summaries;
    for (const VoRun* r : runs)
        summaries.push_back(summarize(seq, *r));
    const int labelWidth = 48, columnWidth = 22;
    auto row = [&](const std::string& name, const std::function<std::string(size_t)>& cell) {
        std::cout << std::left << std::setw(labelWidth) << name;
        for (size_t r = 0; r < runs.size(); ++r)
            std::cout << std::left << std::setw(columnWidth) << cell(r);
        std::cout << "\n";
    };
    std::cout << "\n";
    row("", [&](size_t r) { return r == 0 ? rcmeLabel : std::string("OpenCV RANSAC"); });
    row("keyframes", [&](size_t r) { return std::to_string(runs[r]->keyframes.size()); });
    row("keyframe pairs estimated",
        [&](size_t r) { return std::to_string(runs[r]->pairs.size()); });
    const int pqiCount = countRejections(rcmeRun, cv::rcme::STATUS_POOR_QUALITY_INPUT);
    const int degenerateCount = countRejections(rcmeRun, cv::rcme::STATUS_DEGENERATE_CONFIGURATION);
    row("re-selected after PQI", [&](size_t r) {
        return r == 0 ? std::to_string(pqiCount) : std::string("- (no failure signal)");
    });
    row("re-selected after degenerate", [&](size_t r) {
        return r == 0 ? std::to_string(degenerateCount) : std::string("- (no failure signal)");
    });
    row("other re-selections (no E, ...)",
        [&](size_t r) { return std::to_string(countRejections(*runs[r], std::nullopt)); });
    row("accepted pairs wrong (R > 5, t > 15 deg)",
        [&](size_t r) { return std::to_string(countWrongPairs(*runs[r])); });
    row("gaps bridged with the previous motion",
        [&](size_t r) { return std::to_string(runs[r]->bridgedGaps); });
    row("rotation error per pair, mean (deg)",
        [&](size_t r) { return fixed(summaries[r].meanRotationDeg, 3); });
    row("rotation error per pair, median (deg)",
        [&](size_t r) { return fixed(summaries[r].medianRotationDeg, 3); });
    row("translation direction error, median (deg)",
        [&](size_t r) { return fixed(summaries[r].medianTranslationDeg, 2); });
    row("final position error (m, GT scale)", [&](size_t r) {
        return fixed(summaries[r].finalPositionError, 2) + " @ frame " +
               std::to_string(summaries[r].finalFrame);
    });
    row("ATE RMSE over keyframes (m, GT scale)",
        [&](size_t r) { return fixed(summaries[r].ateRmse, 2); });
    row("ground-truth path length (m)",
        [&](size_t r) { return fixed(summaries[r].pathLength, 1); });
    row("estimator time per pair, median (ms)",
        [&](size_t r) { return fixed(summaries[r].medianMilliseconds, 1); });
    std::cout << rcmeLabel << " re-selected after PQI: " << pqiCount
              << ", after degenerate: " << degenerateCount << "\n";
    std::cout << rcmeLabel << " held frames: " << rcmeRun.rejections.size() << ": "
              << heldFrames(rcmeRun) << "\n";
    std::cout << rcmeLabel << " accepted pairs more than 5 deg (rotation) or 15 deg (translation) "
              << "wrong: " << countWrongPairs(rcmeRun) << " of " << rcmeRun.pairs.size() << "\n";
    std::cout << "features: " << fixed(cache.featureMilliseconds(), 0) << " ms of "
              << (opt.klt ? "FAST" : "SIFT") << ", computed once for all runs\n";

    std::vector<std::string> legend;
    for (size_t r = 0; r < runs.size(); ++r) {
        std::string text = (r == 0 ? "rcme recoverPose, method " + opt.method
                                   : std::string("OpenCV findEssentialMat RANSAC + recoverPose")) +
                           ": " + std::to_string(runs[r]->keyframes.size()) + " keyframes, ";
        if (r == 0)
            text += "re-selected after PQI " + std::to_string(pqiCount) + ", after degenerate " +
                    std::to_string(degenerateCount) + ", ";
        text += "final error " + fixed(summaries[r].finalPositionError, 2) + " m";
        legend.push_back(text);
    }
    const cv::Mat picture = drawTrajectories(
        seq, runs, legend,
        seq.name + ", frames 0-" + std::to_string(n - 1) +
            ": monocular VO, each pair's translation scaled by the ground-truth distance (display "
            "only)");
    std::cout << "wrote " << writePicture(opt.outPath, picture) << "\n";

    if (rcmeRun.pairs.empty()) {
        std::cout << "FAILED: rcme estimated no keyframe pair\n";
        return EXIT_NOT_SUCCESS;
    }
    if (opt.maxWrongPairs >= 0 && countWrongPairs(rcmeRun) > opt.maxWrongPairs) {
        std::cout << "FAILED: rcme accepted " << countWrongPairs(rcmeRun)
                  << " wrong pairs, more than --max-wrong-pairs " << opt.maxWrongPairs << "\n";
        return EXIT_NOT_SUCCESS;
    }
    if (opt.maxMedianRotationErrorDeg >= 0 &&
        !(summaries[0].medianRotationDeg <= opt.maxMedianRotationErrorDeg)) {
        std::cout << "FAILED: rcme's median rotation error "
                  << fixed(summaries[0].medianRotationDeg, 3)
                  << " deg exceeds --max-median-rotation-error-deg "
                  << opt.maxMedianRotationErrorDeg << "\n";
        return EXIT_NOT_SUCCESS;
    }
    return EXIT_OK;
}

} // namespace

int main(int argc, char** argv)
{
    return runSample([&] { return run(argc, argv); });
}
