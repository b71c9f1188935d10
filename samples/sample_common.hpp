// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Helpers shared by the C++ samples (two_view_demo.cpp, mono_vo.cpp): command-line parsing, the
// names of rcme's methods and solvers, exit codes, and writing the output picture.

#ifndef RCME_SAMPLES_SAMPLE_COMMON_HPP
#define RCME_SAMPLES_SAMPLE_COMMON_HPP

#include <opencv2/core.hpp>
// features2d became features in OpenCV 5 (opencv_modules.hpp, from core.hpp, says which).
#ifdef HAVE_OPENCV_FEATURES
#include <opencv2/features.hpp>
#else
#include <opencv2/features2d.hpp>
#endif
#include <opencv2/imgcodecs.hpp>
#include <opencv2/rcme.hpp>

// The library's list of its enums' values, generated from its public headers
// (modules/rcme/src/generated/, on the samples' include path).
#include "enum_tables.inc"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rcme_samples {

enum ExitCode
{
    EXIT_OK = 0,
    EXIT_NOT_SUCCESS = 1,
    EXIT_USAGE = 2,
    EXIT_LIBRARY_ERROR = 3
};

//! Usage or input/output error: reported with exit code 2.
struct UsageError : std::runtime_error
{
    explicit UsageError(const std::string& what) : std::runtime_error(what) {}
};

inline double parseDouble(const std::string& key, const std::string& value)
{
    try {
        size_t used = 0;
        double v = std::stod(value, &used);
        if (used == value.size() && std::isfinite(v))
            return v;
    } catch (const std::exception&) {
    }
    throw UsageError("--" + key + " expects a number, got '" + value + "'");
}

inline int parseInt(const std::string& key, const std::string& value)
{
    try {
        size_t used = 0;
        int v = std::stoi(value, &used);
        if (used == value.size())
            return v;
    } catch (const std::exception&) {
    }
    throw UsageError("--" + key + " expects an integer, got '" + value + "'");
}

//! The --method values every sample accepts, as listed in the usage texts: the library's name
//! (cv::rcme::methodName) of each Method, in the order of the library's generated list.
inline std::string methodNames()
{
    std::string names;
#define RCME_SAMPLE_METHOD_NAME(value, name)                                                       \
    names += (names.empty() ? "" : ", ") + cv::rcme::methodName(cv::rcme::value);
    RCME_METHOD_VALUES(RCME_SAMPLE_METHOD_NAME)
#undef RCME_SAMPLE_METHOD_NAME
    return names;
}

// The library's names (cv::rcme::methodFromString); a usage error for any other.
inline cv::rcme::Method parseMethod(const std::string& name)
{
    try {
        return cv::rcme::methodFromString(name);
    } catch (const cv::Exception&) {
        throw UsageError("unknown --method '" + name + "' (" + methodNames() + ")");
    }
}

inline cv::rcme::MinimalSolverKind parseSolver(const std::string& name)
{
    if (name == "eight" || name == "8")
        return cv::rcme::SOLVER_EIGHT_POINT;
    if (name == "seven" || name == "7")
        return cv::rcme::SOLVER_SEVEN_POINT;
    if (name == "five" || name == "5")
        return cv::rcme::SOLVER_FIVE_POINT;
    if (name == "auto")
        return cv::rcme::SOLVER_AUTO;
    throw UsageError("unknown --solver '" + name + "' (auto, eight, seven, five)");
}

inline std::string fixed(double v, int digits)
{
    std::ostringstream ss;
    ss.setf(std::ios::fixed);
    ss.precision(digits);
    ss << v;
    return ss.str();
}

/** Splits the command line into options and positional arguments. Options are `--key value`
or `--key=value` (a single dash works too); keys that take no value are listed in flagKeys. */
struct CommandLine
{
    std::vector<std::pair<std::string, std::string>> options;
    std::vector<std::string> positional;
    bool help = false;

    CommandLine(int argc, char** argv, const std::vector<std::string>& valueKeys,
                const std::vector<std::string>& flagKeys = {})
    {
        auto known = [](const std::vector<std::string>& keys, const std::string& key) {
            return std::find(keys.begin(), keys.end(), key) != keys.end();
        };
        for (int i = 1; i < argc; ++i) {
            const std::string arg = argv[i];
            if (arg == "-h" || arg == "--help" || arg == "-help" || arg == "-?") {
                help = true;
                continue;
            }
            if (arg.size() < 2 || arg[0] != '-' || arg == "--") {
                positional.push_back(arg);
                continue;
            }
            std::string key = arg.substr(arg[1] == '-' ? 2 : 1), value;
            const size_t eq = key.find('=');
            if (eq != std::string::npos) {
                value = key.substr(eq + 1);
                key = key.substr(0, eq);
                if (!known(valueKeys, key))
                    throw UsageError("unknown option '" + arg + "' (see --help)");
            } else if (known(flagKeys, key)) {
                value = "1";
            } else {
                if (!known(valueKeys, key))
                    throw UsageError("unknown option '" + arg + "' (see --help)");
                if (i + 1 >= argc)
                    throw UsageError("option --" + key + " needs a value");
                value = argv[++i];
            }
            options.emplace_back(key, value);
        }
    }
};

/** Reads a text file of whitespace-separated numbers, one row per non-empty line; '#' starts a
comment that runs to the end of the line, and a leading label such as "P0:" is skipped. */
inline std::vector<std::vector<double>> readNumberRows(const std::string& path, const char* what)
{
    std::ifstream in(path);
    if (!in)
        throw UsageError(std::string("cannot open ") + what + " file '" + path + "'");
    std::vector<std::vector<double>> rows;
    std::string line;
    while (std::getline(in, line)) {
        const size_t hash = line.find('#');
        if (hash != std::string::npos)
            line.resize(hash);
        std::istringstream ss(line);
        std::vector<double> row;
        std::string token;
        while (ss >> token) {
            if (row.empty() && token.back() == ':')
                continue;
            try {
                size_t used = 0;
                double v = std::stod(token, &used);
                if (used != token.size() || !std::isfinite(v))
                    throw std::invalid_argument(token);
                row.push_back(v);
            } catch (const std::exception&) {
                throw UsageError(std::string("bad number '") + token + "' in " + what + " file '" +
                                 path + "'");
            }
        }
        if (!row.empty())
            rows.push_back(row);
    }
    return rows;
}

//! Matched point pairs of two images.
struct Matches
{
    std::vector<cv::Point2f> points1, points2;
};

/** Brute-force k = 2 matching of SIFT-like (float) descriptors with Lowe's ratio test. */
inline Matches matchRatioTest(const std::vector<cv::KeyPoint>& keypoints1, const cv::Mat& desc1,
                              const std::vector<cv::KeyPoint>& keypoints2, const cv::Mat& desc2,
                              float ratio = 0.8f)
{
    Matches matches;
    if (desc1.empty() || desc2.rows < 2)
        return matches;
    cv::BFMatcher matcher(cv::NORM_L2);
    std::vector<std::vector<cv::DMatch>> knn;
    matcher.knnMatch(desc1, desc2, knn, 2);
    for (const auto& m : knn)
        if (m.size() == 2 && m[0].distance < ratio * m[1].distance) {
            matches.points1.push_back(keypoints1[m[0].queryIdx].pt);
            matches.points2.push_back(keypoints2[m[0].trainIdx].pt);
        }
    return matches;
}

//! Writes a picture, creating its folder; an unwritable path is a usage/IO error.
inline std::string writePicture(const std::string& path, const cv::Mat& picture)
{
    if (path.empty())
        throw UsageError("--out needs a file name");
    const std::filesystem::path outPath = std::filesystem::absolute(path);
    std::error_code ec;
    if (outPath.has_parent_path())
        std::filesystem::create_directories(outPath.parent_path(), ec);
    bool written = false;
    try {
        // the smallest PNG, or a JPEG of moderate quality (pictures are committed to doc/samples/)
        written = cv::imwrite(outPath.string(), picture,
                              {cv::IMWRITE_PNG_COMPRESSION, 9, cv::IMWRITE_JPEG_QUALITY, 80});
    } catch (const cv::Exception& e) {
        throw UsageError("cannot write '" + outPath.string() + "': " + e.what());
    }
    if (!written)
        throw UsageError("cannot write '" + outPath.string() + "'");
    return outPath.string();
}

//! Runs a sample's body and maps its exceptions to the exit codes above.
inline int runSample(const std::function<int()>& body)
{
    try {
        return body();
    } catch (const UsageError& e) {
        std::cerr << "error: " << e.what() << "\n(run with --help for the usage)\n";
        return EXIT_USAGE;
    } catch (const cv::Exception& e) {
        std::cerr << "OpenCV error: " << e.what() << "\n";
        return EXIT_LIBRARY_ERROR;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return EXIT_LIBRARY_ERROR;
    }
}

} // namespace rcme_samples

#endif // RCME_SAMPLES_SAMPLE_COMMON_HPP
