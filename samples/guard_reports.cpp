// Prints every field of the Report of many estimator configurations as exact hex floats, one
// line per field, for a before-and-after diff of a change that must not alter results (a
// refactoring, a speed-up): `rcme_guard_reports > before.txt`, change, rebuild,
// `rcme_guard_reports > after.txt`, `diff before.txt after.txt`. The configurations cover every
// method, every solver, with and without a camera matrix, serial and parallel, exactly N and
// adaptive, on synthetic scenes of every kind (corridor, generic, plane, pure rotation, forward
// motion, few points, many outliers) and on the bundled real pair. Time is left out.
//
// Usage: rcme_guard_reports [--quick]   (--quick: one seed and serial runs only)

#include <opencv2/rcme.hpp>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

void printMat(const char* name, const cv::Mat& m)
{
    std::printf("  %s %dx%d t%d", name, m.rows, m.cols, m.empty() ? -1 : m.type());
    if (!m.empty()) {
        cv::Mat d;
        m.convertTo(d, CV_64F);
        for (int r = 0; r < d.rows; ++r)
            for (int c = 0; c < d.cols * d.channels(); ++c)
                std::printf(" %a", d.ptr<double>(r)[c]);
    }
    std::printf("\n");
}

// The mask as a short fingerprint (FNV-1a of its bytes) and its count: N bytes per report would
// bury the other fields.
void printMask(const cv::Mat& mask)
{
    unsigned long long h = 1469598103934665603ull;
    int ones = 0;
    const cv::Mat m = mask.isContinuous() ? mask : mask.clone();
    for (size_t i = 0; i < m.total() * m.elemSize(); ++i) {
        h = (h ^ m.data[i]) * 1099511628211ull;
        ones += m.data[i] != 0;
    }
    std::printf("  mask %dx%d t%d ones %d fnv %016llx\n", mask.rows, mask.cols,
                mask.empty() ? -1 : mask.type(), ones, h);
}

void printReport(const std::string& label, const cv::rcme::Report& r)
{
    std::printf("%s\n", label.c_str());
    std::printf("  status %d message %s\n", static_cast<int>(r.status), r.message.c_str());
    printMat("F", r.F);
    printMat("E", r.E);
    printMat("R", r.R);
    printMat("t", r.t);
    printMask(r.mask);
    std::printf("  inliers %d iterations %d pointsPerHypothesis %a meanEntropy %a\n", r.inlierCount,
                r.iterations, r.pointsPerHypothesis, r.meanEntropy);
    printMat("covariance", r.covariance);
    std::printf("  noiseSigma %a translationStdDeg %a rivalCostGap %a\n", r.noiseSigma,
                r.translationStdDeg, r.rivalCostGap);
    printMat("rotationStdDeg", r.rotationStdDeg);
    printMat("rejectedF", r.rejectedF);
    printMat("rejectedR", r.rejectedR);
    printMat("rejectedT", r.rejectedT);
}

struct Scene
{
    std::string name;
    cv::Mat points1, points2, K;
};

std::vector<Scene> syntheticScenes(int seeds)
{
    struct Kind
    {
        const char* name;
        cv::rcme::SceneParams params;
    };
    std::vector<Kind> kinds;
    auto add = [&kinds](const char* name, cv::rcme::SceneKind kind, int n, double w) {
        cv::rcme::SceneParams p;
        p.kind = kind;
        p.numPoints = n;
        p.inlierRatio = w;
        kinds.push_back({name, p});
        return &kinds.back().params;
    };
    add("corridor w0.5", cv::rcme::SCENE_CORRIDOR, 300, 0.5);
    add("corridor w0.3", cv::rcme::SCENE_CORRIDOR, 300, 0.3);
    add("generic w0.7", cv::rcme::SCENE_GENERIC, 200, 0.7);
    add("generic 40 points", cv::rcme::SCENE_GENERIC, 40, 0.8);
    add("generic w0.2", cv::rcme::SCENE_GENERIC, 400, 0.2);
    add("plane", cv::rcme::SCENE_PLANE, 200, 0.6);
    add("pure rotation", cv::rcme::SCENE_PURE_ROTATION, 200, 0.6);
    add("forward motion", cv::rcme::SCENE_GENERIC, 200, 0.6)->forwardMotion = true;
    add("near plane", cv::rcme::SCENE_PLANE, 200, 0.6)->planeRelief = 0.5;
    add("one quadrant", cv::rcme::SCENE_GENERIC, 300, 0.5)->inlierRegion = 0.5;

    std::vector<Scene> scenes;
    for (const Kind& kind : kinds) {
        for (int seed = 0; seed < seeds; ++seed) {
            cv::rcme::SceneParams p = kind.params;
            p.seed = seed;
            const cv::rcme::SyntheticScene s = cv::rcme::generateScene(p);
            scenes.push_back({std::string(kind.name) + " seed " + std::to_string(seed), s.points1,
                              s.points2, s.cameraMatrix});
        }
    }
    return scenes;
}

struct Config
{
    std::string name;
    cv::rcme::Params params;
};

std::vector<Config> configs()
{
    using namespace cv::rcme;
    std::vector<Config> out;
    out.push_back({"default", Params()});
    const Method methods[] = {METHOD_RCME, METHOD_PRCME, METHOD_STANDARD, METHOD_MLESAC,
                              METHOD_COV_RANSAC};
    for (Method m : methods) {
        out.push_back({std::string(methodName(m)) + " as published", Params::asPublished(m)});
        for (MinimalSolverKind solver : {SOLVER_SEVEN_POINT, SOLVER_FIVE_POINT}) {
            Params p;
            p.method = m;
            p.solver = solver;
            out.push_back(
                {std::string(methodName(m)) + " solver " + std::to_string(static_cast<int>(solver)),
                 p});
        }
    }
    Params prosac;
    prosac.sampler = SAMPLER_PROSAC;
    out.push_back({"default PROSAC", prosac});
    Params sprt;
    sprt.verification = VERIFICATION_SPRT;
    out.push_back({"default SPRT", sprt});
    Params stated;
    stated.useEstimatedNoise = false;
    out.push_back({"default stated sigma", stated});
    return out;
}

} // namespace

int main(int argc, char** argv)
{
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    std::vector<Scene> scenes = syntheticScenes(quick ? 1 : 2);
    // The bundled real pair's matches are made by the demo from images; a synthetic scene in
    // normalized coordinates (K = I) stands for the VO programs that pass such points.
    {
        cv::rcme::SceneParams p;
        p.kind = cv::rcme::SCENE_GENERIC;
        p.numPoints = 120;
        p.inlierRatio = 0.8;
        const cv::rcme::SyntheticScene s = cv::rcme::generateScene(p);
        cv::Mat Kinv = s.cameraMatrix.inv();
        cv::Mat n1(s.points1.rows, 2, CV_64F), n2(s.points2.rows, 2, CV_64F);
        for (int i = 0; i < s.points1.rows; ++i) {
            for (int v = 0; v < 2; ++v) {
                const cv::Mat& src = v == 0 ? s.points1 : s.points2;
                cv::Mat& dst = v == 0 ? n1 : n2;
                cv::Mat x = cv::Mat(cv::Vec3d(src.at<double>(i, 0), src.at<double>(i, 1), 1.0));
                cv::Mat y = Kinv * x;
                dst.at<double>(i, 0) = y.at<double>(0) / y.at<double>(2);
                dst.at<double>(i, 1) = y.at<double>(1) / y.at<double>(2);
            }
        }
        scenes.push_back({"normalized K=I", n1, n2, cv::Mat::eye(3, 3, CV_64F)});
    }

    int runs = 0;
    for (const Scene& scene : scenes) {
        for (const Config& config : configs()) {
            for (int withK = 0; withK < 2; ++withK) {
                if (!withK && config.params.solver == cv::rcme::SOLVER_FIVE_POINT)
                    continue; // needs the camera matrix (a status, tested elsewhere)
                for (int exact = 0; exact < 2; ++exact) {
                    for (int parallel = 0; parallel < (quick ? 1 : 2); ++parallel) {
                        cv::rcme::Params p = config.params;
                        p.exactIterations = exact != 0;
                        p.isParallel = parallel != 0;
                        if (scene.name == "normalized K=I")
                            p.sigma = 1.0 / 500.0;
                        const cv::Mat K = withK ? scene.K : cv::Mat();
                        const std::string label = scene.name + " | " + config.name +
                                                  (withK ? " | K" : " | no K") +
                                                  (exact ? " | exact" : " | adaptive") +
                                                  (parallel ? " | parallel" : " | serial");
                        try {
                            printReport(label, cv::rcme::estimateRelativeMotion(
                                                   scene.points1, scene.points2, K, p));
                        } catch (const cv::Exception& e) {
                            std::printf("%s\n  exception %s\n", label.c_str(), e.err.c_str());
                        }
                        ++runs;
                    }
                }
            }
        }
    }
    std::fprintf(stderr, "%d reports\n", runs);
    return 0;
}
