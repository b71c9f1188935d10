// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Many threads calling every public function at once give exactly the serial results: the
// module keeps no shared mutable state. Also run under TSan (test/hardening/run_sanitizers.sh
// --tsan) and ASan.

#include "test_precomp.hpp"

#include <atomic>
#include <cmath>
#include <cstring>
#include <thread>

namespace opencv_test {
namespace {

// Every result of one task, in call order: matrices as they are, numbers as 1x1 matrices.
using Results = std::vector<Mat>;

Mat number(double value)
{
    return Mat(1, 1, CV_64F, Scalar(value));
}

Mat text(const String& s)
{
    return Mat(std::vector<uchar>(s.begin(), s.end()), /*copyData=*/true);
}

const Method kMethods[] = {METHOD_STANDARD, METHOD_RCME, METHOD_PRCME, METHOD_MLESAC,
                           METHOD_COV_RANSAC};

// One task: every public function once, on a scene and with a seed of its own.
Results callEveryFunction(int task)
{
    Results out;
    SceneParams sp;
    sp.kind = task % 2 ? SCENE_GENERIC : SCENE_CORRIDOR;
    sp.numPoints = 120;
    sp.inlierRatio = 0.7;
    sp.seed = 1000 + task;
    const SyntheticScene scene = generateScene(sp);
    out.push_back(scene.points1);
    out.push_back(scene.R);
    const Mat& K = scene.cameraMatrix;
    const Mat& p1 = scene.points1;
    const Mat& p2 = scene.points2;

    Params params;
    params.method = kMethods[task % 5];
    params.solver = static_cast<MinimalSolverKind>(task / 5 % 3);
    params.sampler = task % 4 == 3 ? SAMPLER_PROSAC : SAMPLER_UNIFORM;
    params.localOptimization = task % 3 == 1;
    params.randomGeneratorState = task;
    params.maxIterations = 100;

    // Without a camera matrix the 5-point solver is not available.
    Params uncalibrated = params;
    if (uncalibrated.solver == SOLVER_FIVE_POINT)
        uncalibrated.solver = SOLVER_EIGHT_POINT;

    const Report report = estimateRelativeMotion(p1, p2, K, params);
    out.push_back(number(report.status));
    out.push_back(report.F);
    out.push_back(report.R);
    out.push_back(report.t);
    out.push_back(report.mask);
    out.push_back(report.covariance);
    out.push_back(number(report.meanEntropy));
    out.push_back(number(report.iterations));

    Mat mask;
    Status status;
    out.push_back(cv::rcme::findFundamentalMat(p1, p2, uncalibrated, mask, status));
    out.push_back(mask.clone());
    out.push_back(cv::rcme::findFundamentalMat(p1, p2, K, params, mask, status));
    out.push_back(mask.clone());
    out.push_back(cv::rcme::findFundamentalMat(p1, p2, FM_RANSAC, 2.0, 0.99, 100 + task, mask));
    out.push_back(mask.clone());
    out.push_back(cv::rcme::findFundamentalMat(p1, p2, params.method, 2.0, 0.99, mask));
    out.push_back(mask.clone());
    out.push_back(cv::rcme::findEssentialMat(p1, p2, K, params, mask, status));
    out.push_back(mask.clone());
    out.push_back(cv::rcme::findEssentialMat(p1, p2, K, RANSAC, 0.99, 2.0, 100 + task, mask));
    out.push_back(mask.clone());
    const double focal = K.at<double>(0, 0);
    const Point2d pp(K.at<double>(0, 2), K.at<double>(1, 2));
    out.push_back(
        cv::rcme::findEssentialMat(p1, p2, focal, pp, params.method, 0.99, 2.0, 100, mask));
    out.push_back(mask.clone());

    Mat E, R, t, covariance;
    out.push_back(
        number(cv::rcme::recoverPose(p1, p2, K, E, R, t, params, mask, status, covariance)));
    out.push_back(number(status));
    out.push_back(E.clone());
    out.push_back(R.clone());
    out.push_back(t.clone());
    out.push_back(mask.clone());
    out.push_back(covariance.clone());
    out.push_back(number(cv::rcme::recoverPose(scene.E, p1, p2, K, R, t)));
    out.push_back(R.clone());
    out.push_back(t.clone());
    Mat selection = scene.inlierMask.clone();
    out.push_back(number(cv::rcme::recoverPose(scene.E, p1, p2, R, t, focal, pp, selection)));
    out.push_back(selection);

    if (report.status == STATUS_SUCCESS) {
        const MotionError e = compareMotion(report.R, report.t, scene.R, scene.t);
        out.push_back(Mat(Vec4d(e.dq, e.dt, e.rotationDeg, e.translationDeg)));
    }
    out.push_back(text(statusToString(report.status)));

    UsacParams usac;
    usac.randomGeneratorState = task;
    usac.sampler = task % 2 ? SAMPLING_PROSAC : SAMPLING_UNIFORM;
    const Params fromUsac(usac);
    out.push_back(number(fromUsac.sampler + 10 * fromUsac.randomGeneratorState));
    return out;
}

// Exactly equal, NaN included (meanEntropy is NaN for the methods other than RCME).
void expectIdentical(const Results& a, const Results& b, int task)
{
    ASSERT_EQ(a.size(), b.size()) << "task " << task;
    for (size_t i = 0; i < a.size(); ++i) {
        SCOPED_TRACE(cv::format("task %d, result %d", task, static_cast<int>(i)));
        ASSERT_EQ(a[i].size(), b[i].size());
        ASSERT_EQ(a[i].type(), b[i].type());
        if (a[i].empty())
            continue;
        const size_t bytes = a[i].total() * a[i].elemSize();
        ASSERT_TRUE(a[i].isContinuous() && b[i].isContinuous());
        EXPECT_EQ(std::memcmp(a[i].data, b[i].data, bytes), 0);
    }
}

TEST(Rcme_Concurrency, threads_calling_every_function_give_the_serial_results)
{
    const int numThreads = 8, tasksPerThread = 3;
    const int numTasks = numThreads * tasksPerThread;
    std::vector<Results> serial(numTasks), parallel(numTasks);
    for (int task = 0; task < numTasks; ++task)
        serial[task] = callEveryFunction(task);

    // All threads start together so that the calls really overlap.
    std::atomic<int> ready(0);
    std::vector<std::thread> threads;
    for (int thread = 0; thread < numThreads; ++thread)
        threads.emplace_back([&, thread] {
            ready.fetch_add(1);
            while (ready.load() < numThreads)
                std::this_thread::yield();
            // Interleaved: neighbouring tasks (different methods) run on different threads.
            for (int task = thread; task < numTasks; task += numThreads)
                parallel[task] = callEveryFunction(task);
        });
    for (auto& thread : threads)
        thread.join();
    for (int task = 0; task < numTasks; ++task)
        expectIdentical(serial[task], parallel[task], task);
}

TEST(Rcme_Concurrency, one_estimate_from_many_threads_is_always_the_same)
{
    // The same call (same data, same seed) from every thread at once: no thread may see
    // another's state.
    const SyntheticScene scene = [] {
        SceneParams sp;
        sp.kind = SCENE_GENERIC;
        sp.numPoints = 200;
        sp.seed = 77;
        return generateScene(sp);
    }();
    Params params;
    params.method = METHOD_RCME;
    params.randomGeneratorState = 5;
    const Report reference =
        estimateRelativeMotion(scene.points1, scene.points2, scene.cameraMatrix, params);
    ASSERT_EQ(reference.status, STATUS_SUCCESS);
    const int numThreads = 8;
    std::vector<Report> reports(numThreads);
    std::vector<std::thread> threads;
    for (int i = 0; i < numThreads; ++i)
        threads.emplace_back([&, i] {
            reports[i] =
                estimateRelativeMotion(scene.points1, scene.points2, scene.cameraMatrix, params);
        });
    for (auto& thread : threads)
        thread.join();
    for (const Report& r : reports) {
        ASSERT_EQ(r.status, reference.status);
        EXPECT_EQ(cv::norm(r.R, reference.R, NORM_INF), 0.0);
        EXPECT_EQ(cv::norm(r.t, reference.t, NORM_INF), 0.0);
        EXPECT_EQ(cv::norm(r.mask, reference.mask, NORM_INF), 0.0);
        EXPECT_EQ(r.meanEntropy, reference.meanEntropy);
    }
}

// estimateRelativeMotionBatch: every Report equal to the serial call's (timeSeconds aside), for
// any thread count, with per-pair camera matrices (empty ones uncalibrated) or a shared one.
void expectSameReport(const Report& a, const Report& b, size_t pair)
{
    SCOPED_TRACE(cv::format("pair %d", static_cast<int>(pair)));
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.message, b.message);
    EXPECT_EQ(a.inlierCount, b.inlierCount);
    EXPECT_EQ(a.iterations, b.iterations);
    EXPECT_EQ(a.pointsPerHypothesis, b.pointsPerHypothesis);
    EXPECT_TRUE(a.meanEntropy == b.meanEntropy ||
                (std::isnan(a.meanEntropy) && std::isnan(b.meanEntropy)));
    expectIdentical({a.F, a.E, a.R, a.t, a.mask, a.covariance},
                    {b.F, b.E, b.R, b.t, b.mask, b.covariance}, static_cast<int>(pair));
}

TEST(Rcme_Concurrency, batch_gives_the_serial_reports_on_any_thread_count)
{
    std::vector<Mat> points1, points2, cameras;
    for (int i = 0; i < 10; ++i) {
        const SyntheticScene s =
            testScene(i % 2 ? SCENE_GENERIC : SCENE_CORRIDOR, 300 + i, 0.6, 1.0, 120);
        points1.push_back(s.points1);
        points2.push_back(s.points2);
        cameras.push_back(i % 3 == 2 ? Mat() : s.cameraMatrix);
    }
    Params params;
    params.method = METHOD_RCME;
    params.maxIterations = 100;
    params.randomGeneratorState = 9;
    std::vector<Report> serial;
    for (size_t i = 0; i < points1.size(); ++i)
        serial.push_back(estimateRelativeMotion(points1[i], points2[i], cameras[i], params));
    for (int threads : {1, 3, 0}) {
        SCOPED_TRACE(cv::format("threads %d", threads));
        const std::vector<Report> batch =
            estimateRelativeMotionBatch(points1, points2, cameras, params, threads);
        ASSERT_EQ(batch.size(), serial.size());
        for (size_t i = 0; i < batch.size(); ++i)
            expectSameReport(batch[i], serial[i], i);
    }
    // One shared camera matrix is the same as that matrix repeated.
    const std::vector<Report> shared =
        estimateRelativeMotionBatch(points1, points2, {cameras[0]}, params, 2);
    const std::vector<Report> repeated = estimateRelativeMotionBatch(
        points1, points2, std::vector<Mat>(points1.size(), cameras[0]), params, 1);
    for (size_t i = 0; i < shared.size(); ++i)
        expectSameReport(shared[i], repeated[i], i);
    EXPECT_TRUE(estimateRelativeMotionBatch({}, {}, {}, params).empty());
}

TEST(Rcme_Concurrency, batch_errors_name_the_argument_and_the_pair)
{
    const SyntheticScene s = genericTestScene(5, 0.6, 100);
    const Params params;
    try {
        estimateRelativeMotionBatch({s.points1, s.points1}, {s.points2}, {}, params);
        ADD_FAILURE() << "no exception for points2's size";
    } catch (const cv::Exception& e) {
        EXPECT_NE(e.err.find("points2"), std::string::npos) << e.err;
    }
    try {
        estimateRelativeMotionBatch({s.points1, s.points1}, {s.points2, s.points2},
                                    {s.cameraMatrix, s.cameraMatrix, s.cameraMatrix}, params);
        ADD_FAILURE() << "no exception for cameraMatrices' size";
    } catch (const cv::Exception& e) {
        EXPECT_NE(e.err.find("cameraMatrices"), std::string::npos) << e.err;
    }
    try {
        // pair 1 has mismatched point counts, pair 2 a camera matrix of the wrong size
        estimateRelativeMotionBatch(
            {s.points1, s.points1, s.points1}, {s.points2, s.points2.rowRange(0, 50), s.points2},
            {s.cameraMatrix, s.cameraMatrix, Mat::eye(2, 2, CV_64F)}, params, 2);
        ADD_FAILURE() << "no exception for a malformed pair";
    } catch (const cv::Exception& e) {
        EXPECT_EQ(e.err.rfind("pair 1: ", 0), 0u) << e.err;
    }
}

} // namespace
} // namespace opencv_test
