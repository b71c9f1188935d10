// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

// Standalone Python bindings of the rcme module (pybind11): `import rcme`.
//
// They reproduce the surface that OpenCV's Python generator (4.6) gives `cv2.rcme` from the
// public headers, so that one Python test suite and one sample run against both:
// - functions keep their C++ names and overload order; required inputs are positional in
//   declaration order, output arrays are optional arguments placed before the first defaulted
//   input, and the result is `retval` followed by every output in declaration order;
// - enum values are module-level ints; enum-typed fields and outputs are ints;
// - CV_EXPORTS_W_SIMPLE structs are classes whose attributes have the C++ field names;
// - arrays come in as NumPy arrays (or None for an empty array); an empty output Mat comes back
//   as None, a non-empty one as a NumPy array (single-channel 2D -> (rows, cols));
// - an output array passed in by the caller is written in place when its size and type already
//   fit, and returned as the same object, as cv2 does;
// - cv::Exception becomes `rcme.error` (like cv2.error: message, code, err, func, file, line).
// Extensions over cv2: Params and SceneParams accept keyword arguments, points may be given as
// Python sequences, and integer point arrays are converted to float64.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <opencv2/rcme.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace py = pybind11;
using namespace cv::rcme;

namespace {

PyObject* g_error = nullptr; // rcme.error, created at import and kept for the process lifetime

[[noreturn]] void raiseBadArg(const std::string& message, const char* func)
{
    throw cv::Exception(cv::Error::StsBadArg, message, func, __FILE__, __LINE__);
}

// ------------------------------------------------------------------------------------------
// NumPy <-> cv::Mat

//! How an input array is converted.
enum class Conv
{
    Float, //!< coordinates and matrices: float32 and float64 kept, integers/bool -> float64
    Any    //!< masks: every dtype OpenCV knows kept as is (bool -> uint8, int64 -> int32)
};

//! An input Mat plus whatever keeps its memory alive when it wraps a NumPy buffer.
struct InMat
{
    cv::Mat mat;
    py::object keep;        //!< the contiguous array whose buffer mat wraps, if any
    bool isCallers = false; //!< keep is the caller's own array (so writes reach the caller)
};

// A dtype's kind and size read through Python: pybind11 before 2.12 (Debian 12 has 2.10) reads
// them from NumPy 1's descriptor struct, whose layout NumPy 2 changed (the size read garbage).
char dtypeKind(const py::dtype& dt)
{
    return py::cast<std::string>(dt.attr("kind"))[0];
}

py::ssize_t dtypeSize(const py::dtype& dt)
{
    return py::cast<py::ssize_t>(dt.attr("itemsize"));
}

int depthOf(const py::dtype& dt)
{
    const char kind = dtypeKind(dt);
    const auto size = dtypeSize(dt);
    if (kind == 'f')
        return size == 8 ? CV_64F : size == 4 ? CV_32F : size == 2 ? CV_16F : -1;
    if (kind == 'u')
        return size == 1 ? CV_8U : size == 2 ? CV_16U : -1;
    if (kind == 'i')
        return size == 1 ? CV_8S : size == 2 ? CV_16S : size == 4 ? CV_32S : -1;
    return -1;
}

py::dtype dtypeOf(int depth)
{
    static const std::pair<int, const char*> kNames[] = {
        {CV_8U, "uint8"},  {CV_8S, "int8"},     {CV_16U, "uint16"},  {CV_16S, "int16"},
        {CV_32S, "int32"}, {CV_32F, "float32"}, {CV_64F, "float64"}, {CV_16F, "float16"}};
    for (const auto& entry : kNames)
        if (entry.first == depth)
            return py::dtype(entry.second);
    CV_Error(cv::Error::StsUnsupportedFormat, "rcme: a result has an unsupported depth");
}

std::string dtypeName(const py::dtype& dt)
{
    return py::cast<std::string>(dt.attr("name"));
}

//! The dtype the array is converted to before wrapping, or an empty string when unsupported.
std::string targetDtype(const py::dtype& dt, Conv conv)
{
    const char kind = dtypeKind(dt);
    if (conv == Conv::Float) {
        const auto size = dtypeSize(dt);
        if (kind == 'f' && (size == 8 || size == 4))
            return size == 8 ? "float64" : "float32";
        if (kind == 'f' || kind == 'i' || kind == 'u' || kind == 'b')
            return "float64";
        return "";
    }
    if (kind == 'b')
        return "uint8";
    if (depthOf(dt) >= 0)
        return dtypeName(dt);
    if (kind == 'i' || kind == 'u')
        return "int32"; // as cv2 does for int64
    return "";
}

//! Wraps a C-contiguous array, with cv2's shape rules: (k,) -> k x 1; (r, c) -> r x c;
//! (r, c, n) with n <= CV_CN_MAX -> r x c with n channels; higher ranks -> N-d Mat.
cv::Mat wrapArray(const py::array& a)
{
    const int depth = depthOf(a.dtype());
    CV_Assert(depth >= 0);
    std::vector<int> sizes;
    for (py::ssize_t i = 0; i < a.ndim(); ++i)
        sizes.push_back(static_cast<int>(a.shape(i)));
    int channels = 1;
    if (sizes.size() == 3 && sizes[2] >= 1 && sizes[2] <= CV_CN_MAX) {
        channels = sizes[2];
        sizes.pop_back();
    }
    if (sizes.empty())
        sizes = {1, 1};
    else if (sizes.size() == 1)
        sizes.push_back(1);
    const int type = CV_MAKETYPE(depth, channels);
    if (a.size() == 0)
        return cv::Mat(static_cast<int>(sizes.size()), sizes.data(), type);
    return cv::Mat(static_cast<int>(sizes.size()), sizes.data(), type, const_cast<void*>(a.data()));
}

/** Converts a Python argument to a Mat: None -> empty; a number -> 4x1 CV_64F (as cv2 does for
scalars); a NumPy array or a nested sequence of numbers -> a Mat wrapping its buffer when it is
C-contiguous with a supported dtype, a converted copy otherwise. Errors name the argument. */
InMat toMat(py::handle obj, const char* name, Conv conv, const char* func)
{
    InMat r;
    if (!obj || obj.is_none())
        return r;
    if (!py::isinstance<py::array>(obj) && (PyFloat_Check(obj.ptr()) || PyLong_Check(obj.ptr()))) {
        const double v[4] = {py::cast<double>(obj), 0., 0., 0.};
        r.mat = cv::Mat(4, 1, CV_64F, const_cast<double*>(v)).clone();
        return r;
    }
    py::array arr;
    if (py::isinstance<py::array>(obj)) {
        arr = py::reinterpret_borrow<py::array>(obj);
    } else if (PySequence_Check(obj.ptr()) && !py::isinstance<py::str>(obj) &&
               !py::isinstance<py::bytes>(obj)) {
        try {
            arr = py::module_::import("numpy").attr("asarray")(obj);
        } catch (const py::error_already_set&) {
            raiseBadArg(std::string(name) + " is not a numpy array, neither a sequence of numbers",
                        func);
        }
    } else {
        raiseBadArg(std::string(name) + " is not a numpy array, neither a scalar", func);
    }
    const std::string target = targetDtype(arr.dtype(), conv);
    if (target.empty())
        raiseBadArg(std::string(name) + " has an unsupported data type '" + dtypeName(arr.dtype()) +
                        "'",
                    func);
    py::array c = py::module_::import("numpy").attr("ascontiguousarray")(arr, target);
    if (c.ndim() != arr.ndim()) // ascontiguousarray returns at least 1-D; keep cv2's 1x1
        c = c.attr("reshape")(arr.attr("shape"));
    r.isCallers = c.ptr() == obj.ptr();
    r.mat = wrapArray(c);
    r.keep = std::move(c);
    return r;
}

//! A Mat as a new NumPy array, or None when it has no data (what cv2 returns for empty Mats).
py::object fromMat(const cv::Mat& m)
{
    if (!m.data)
        return py::none();
    py::list shape;
    for (int i = 0; i < m.dims; ++i)
        shape.append(m.size[i]);
    if (m.channels() > 1)
        shape.append(m.channels());
    // Made by NumPy itself: pybind11 2.10's py::array(dtype, shape) computes the strides from
    // NumPy 1's descriptor layout, wrong under NumPy 2 (see dtypeKind).
    py::array out =
        py::module_::import("numpy").attr("empty")(py::tuple(shape), dtypeOf(m.depth()));
    cv::Mat dst(m.dims, m.size.p, m.type(), out.mutable_data());
    m.copyTo(dst);
    return std::move(out);
}

//! An output array argument: the Mat the C++ function writes, wrapping the caller's array when
//! it is a writeable C-contiguous array of a supported dtype (then writes land in place).
struct OutMat
{
    cv::Mat mat;
    py::object provided;
    const void* data = nullptr;
};

OutMat toOutMat(py::handle obj)
{
    OutMat o;
    if (!obj || obj.is_none() || !py::isinstance<py::array>(obj))
        return o;
    auto a = py::reinterpret_borrow<py::array>(obj);
    const bool contiguous = (a.flags() & py::array::c_style) != 0;
    const bool writeable = a.writeable();
    if (!contiguous || !writeable || depthOf(a.dtype()) < 0 || a.size() == 0)
        return o;
    o.mat = wrapArray(a);
    o.provided = py::reinterpret_borrow<py::object>(obj);
    o.data = o.mat.data;
    return o;
}

//! The Python value of an output: the caller's array when it was written in place, else a copy.
py::object finishOut(const OutMat& o)
{
    if (o.provided && o.mat.data && o.mat.data == o.data)
        return o.provided;
    return fromMat(o.mat);
}

//! An input/output array (recoverPose's mask): the input, wrapped in place when possible.
OutMat toInOutMat(py::handle obj, const char* name, const char* func)
{
    OutMat o;
    InMat in = toMat(obj, name, Conv::Any, func);
    if (in.isCallers && in.keep && py::reinterpret_borrow<py::array>(in.keep).writeable()) {
        o.mat = in.mat;
        o.provided = in.keep;
        o.data = o.mat.data;
    } else {
        o.mat = in.mat.clone(); // owns its data, so the C++ side may write it freely
    }
    return o;
}

cv::Point2d toPoint2d(py::handle obj, const char* name, const char* func)
{
    try {
        py::sequence s = py::reinterpret_borrow<py::sequence>(obj);
        if (PySequence_Check(obj.ptr()) && py::len(s) == 2)
            return cv::Point2d(py::cast<double>(s[0]), py::cast<double>(s[1]));
    } catch (const py::error_already_set&) {
    } catch (const py::cast_error&) {
    }
    raiseBadArg(std::string(name) + " must be a sequence of two numbers", func);
}

cv::Mat matField(py::handle value, const char* name)
{
    // Fields own their data: a copy, never a view of a Python buffer.
    return toMat(value, name, Conv::Any, "setattr").mat.clone();
}

// ------------------------------------------------------------------------------------------
// Struct classes

//! A value of a public enum: its constant's name (METHOD_RCME) and value.
struct EnumConstant
{
    const char* name;
    int value;
};

//! Adds the read/write attributes of a struct and remembers their names (for keyword
//! construction and repr). Each attribute's docstring is its header comment followed by its
//! value in a default-constructed T.
template <class T> class Fields
{
public:
    explicit Fields(py::class_<T>& cls) : cls_(cls) {}

    template <class M> Fields& plain(const char* name, M T::*member, const char* doc)
    {
        const std::string field = qualified(name);
        const std::string text = withDefault(doc, "", py::repr(py::cast(defaults_.*member)));
        cls_.def_property(
            name, [member](const T& self) { return self.*member; },
            [member, field](T& self, py::object v) { self.*member = castField<M>(v, field); },
            text.c_str());
        names_.emplace_back(name);
        return *this;
    }

    //! An enum field, an int in Python.
    template <class E>
    Fields& enumInt(const char* name, E T::*member, const std::vector<EnumConstant>& constants,
                    const char* doc)
    {
        const std::string field = qualified(name);
        std::string values, defaultName = std::to_string(static_cast<int>(defaults_.*member));
        for (const EnumConstant& c : constants) {
            values += std::string(values.empty() ? "one of " : ", ") + c.name;
            if (c.value == static_cast<int>(defaults_.*member))
                defaultName = c.name;
        }
        const std::string text = withDefault(doc, values + "; ", defaultName);
        cls_.def_property(
            name, [member](const T& self) { return static_cast<int>(self.*member); },
            [member, field](T& self, py::object v) {
                self.*member = static_cast<E>(castField<int>(v, field));
            },
            text.c_str());
        names_.emplace_back(name);
        return *this;
    }

    Fields& mat(const char* name, cv::Mat T::*member, const char* doc)
    {
        const std::string text = withDefault(doc, "", (defaults_.*member).empty() ? "None" : "");
        cls_.def_property(
            name, [member](const T& self) { return fromMat(self.*member); },
            [member, name](T& self, py::object v) { self.*member = matField(v, name); },
            text.c_str());
        names_.emplace_back(name);
        matNames_.emplace_back(name);
        return *this;
    }

    //! `__repr__` listing every field, e.g. Params(method=1026, sigma=1.0, ...).
    void addRepr(const std::string& className)
    {
        auto names = names_;
        auto matNames = matNames_;
        cls_.def("__repr__", [names, matNames, className](py::object self) {
            std::ostringstream s;
            s << className << "(";
            for (size_t i = 0; i < names.size(); ++i) {
                py::object v = self.attr(names[i].c_str());
                // By the field's kind, not isinstance<array>, which imports NumPy: the default
                // Params is printed at import (the signature of params=Params()), and the stub
                // generator's interpreter has no NumPy.
                const bool isMat =
                    std::find(matNames.begin(), matNames.end(), names[i]) != matNames.end();
                std::string text = isMat && !v.is_none()
                                       ? "<array " + std::string(py::str(v.attr("shape"))) + " " +
                                             std::string(py::str(v.attr("dtype"))) + ">"
                                       : std::string(py::repr(v));
                s << (i ? ", " : "") << names[i] << "=" << text;
            }
            s << ")";
            return s.str();
        });
    }

    //! Constructor from keyword arguments (a convenience over cv2, where structs take none).
    void addKeywordInit(const std::string& className)
    {
        auto names = names_;
        cls_.def(py::init([names, className](const py::kwargs& kwargs) {
                     py::object self = py::cast(T());
                     for (const auto& kv : kwargs) {
                         const std::string key = py::cast<std::string>(kv.first);
                         if (std::find(names.begin(), names.end(), key) == names.end())
                             throw py::type_error(className +
                                                  "() got an unexpected keyword "
                                                  "argument '" +
                                                  key + "'");
                         py::setattr(self, kv.first, kv.second);
                     }
                     return py::cast<T>(self);
                 }),
                 ("Keyword form: every field may be given by name, the others keep their "
                  "defaults, e.g. " +
                  className + "(" + names.front() + "=...).")
                     .c_str());
    }

    //! Pickling by field values (Dask, Ray and multiprocessing send Params and Reports).
    void addPickle()
    {
        auto names = names_;
        cls_.def(py::pickle(
            [names](py::object self) {
                py::dict state;
                for (const auto& name : names)
                    state[name.c_str()] = self.attr(name.c_str());
                return state;
            },
            [](const py::dict& state) {
                py::object self = py::cast(T());
                for (const auto& kv : state)
                    py::setattr(self, kv.first, kv.second);
                return py::cast<T>(self);
            }));
    }

private:
    //! "doc\nprefix default value": the header's comment and the default of this build.
    static std::string withDefault(const char* doc, const std::string& prefix,
                                   const std::string& value)
    {
        const std::string note = value.empty() ? "" : prefix + "default " + value;
        return std::string(doc) + (*doc && !note.empty() ? "\n" : "") + note;
    }

    std::string qualified(const char* name) const
    {
        return py::cast<std::string>(cls_.attr("__name__")) + "." + name;
    }

    /* A wrong type names the field and the type given (pybind11's own message would print the
    whole struct and every overload of the setter). */
    template <class V> static V castField(const py::object& value, const std::string& field)
    {
        try {
            return py::cast<V>(value);
        } catch (const py::cast_error&) {
            const char* expected = std::is_same<V, bool>::value          ? "a bool"
                                   : std::is_integral<V>::value          ? "an int"
                                   : std::is_floating_point<V>::value    ? "a float"
                                   : std::is_same<V, std::string>::value ? "a str"
                                                                         : "another type";
            throw py::type_error(field + " must be " + expected + ", got " +
                                 py::cast<std::string>(value.get_type().attr("__name__")) + " (" +
                                 std::string(py::repr(value)) + ")");
        }
    }

    py::class_<T>& cls_;
    const T defaults_{};
    std::vector<std::string> names_;
    std::vector<std::string> matNames_; //!< the cv::Mat fields (NumPy arrays or None)
};

// The enums' constants and the fields' chains, generated from the public headers.
#include "generated_bindings.inc"

//! The arrays of the forms with one camera matrix, converted in argument order.
struct CameraInputs
{
    InMat p1, p2, k;
};

CameraInputs cameraInputs(const char* function, py::handle points1, py::handle points2,
                          py::handle cameraMatrix)
{
    CameraInputs in;
    in.p1 = toMat(points1, "points1", Conv::Float, function);
    in.p2 = toMat(points2, "points2", Conv::Float, function);
    in.k = toMat(cameraMatrix, "cameraMatrix", Conv::Float, function);
    return in;
}

//! An array argument and its name in the signature (OpenCV's forms spell them differently).
struct NamedArray
{
    py::handle object;
    const char* name;
};

//! The arrays of the forms with two cameras and their distortion coefficients.
struct TwoCameraInputs
{
    InMat p1, p2, k1, d1, k2, d2;
};

TwoCameraInputs twoCameraInputs(const char* function, py::handle points1, py::handle points2,
                                NamedArray k1, NamedArray d1, NamedArray k2, NamedArray d2)
{
    TwoCameraInputs in;
    in.p1 = toMat(points1, "points1", Conv::Float, function);
    in.p2 = toMat(points2, "points2", Conv::Float, function);
    in.k1 = toMat(k1.object, k1.name, Conv::Float, function);
    in.d1 = toMat(d1.object, d1.name, Conv::Float, function);
    in.k2 = toMat(k2.object, k2.name, Conv::Float, function);
    in.d2 = toMat(d2.object, d2.name, Conv::Float, function);
    return in;
}

/* The Params forms of findFundamentalMat and findEssentialMat: the inputs converted, `call`
(points1, points2, cameraMatrix, mask, status) run without the GIL, (matrix, mask, status)
returned. */
template <class Call>
py::tuple runWithParams(const char* function, py::object points1, py::object points2,
                        py::object cameraMatrix, py::object mask, const Call& call)
{
    const CameraInputs in = cameraInputs(function, points1, points2, cameraMatrix);
    OutMat outMask = toOutMat(mask);
    cv::Mat model;
    Status status = STATUS_SUCCESS;
    {
        py::gil_scoped_release nogil;
        model = call(in.p1.mat, in.p2.mat, in.k.mat, outMask.mat, status);
    }
    return py::make_tuple(fromMat(model), finishOut(outMask), static_cast<int>(status));
}

//! A struct of the headers as a Python class: the default constructor, the generated fields,
//! repr and pickling, and keyword construction when `keywordInit`.
template <class T>
py::class_<T> bindStruct(py::module_& m, const char* name, const char* doc, const char* initDoc,
                         bool keywordInit)
{
    py::class_<T> cls(m, name, doc);
    cls.def(py::init<>(), initDoc);
    Fields<T> fields(cls);
    addFields(fields);
    if (keywordInit)
        fields.addKeywordInit(name);
    fields.addRepr(name);
    fields.addPickle();
    return cls;
}

//! A cv::UsacParams from any object with cv2.UsacParams' attributes (duck typing, so that a
//! cv2.UsacParams from the installed cv2 works without this module depending on cv2).
cv::UsacParams usacFromPython(const py::object& u, const char* func, const char* name)
{
    if (!py::hasattr(u, "confidence") || !py::hasattr(u, "maxIterations") ||
        !py::hasattr(u, "threshold"))
        throw py::type_error(std::string(func) + ": " + name + " must be a cv2.UsacParams");
    cv::UsacParams usac;
    auto get = [&u](const char* name, auto& field) {
        if (py::hasattr(u, name))
            field = py::cast<std::decay_t<decltype(field)>>(u.attr(name));
    };
    auto getEnum = [&u](const char* name, auto& field) {
        if (py::hasattr(u, name))
            field = static_cast<std::decay_t<decltype(field)>>(py::cast<int>(u.attr(name)));
    };
    get("confidence", usac.confidence);
    get("isParallel", usac.isParallel);
    get("loIterations", usac.loIterations);
    getEnum("loMethod", usac.loMethod);
    get("loSampleSize", usac.loSampleSize);
    get("maxIterations", usac.maxIterations);
    getEnum("neighborsSearch", usac.neighborsSearch);
    get("randomGeneratorState", usac.randomGeneratorState);
    getEnum("sampler", usac.sampler);
    getEnum("score", usac.score);
    get("threshold", usac.threshold);
    return usac;
}

//! Params.fromUsacParams(usacParams).
Params paramsFromUsac(const py::object& u)
{
    return Params(usacFromPython(u, "fromUsacParams", "usacParams"));
}

// ------------------------------------------------------------------------------------------
// Docstrings: first line as the OpenCV generator writes it.

const char* const kDocFindFundamentalParams =
    "findFundamentalMat(points1, points2, params[, mask]) -> retval, mask, status\n"
    ".   @brief Fundamental matrix with an explicit status (an int, see STATUS_*).\n"
    ".   retval is the 3x3 float64 F (None unless status == STATUS_SUCCESS); mask is the Nx1\n"
    ".   uint8 inlier mask, always sized N.";
const char* const kDocFindFundamentalCalibrated =
    "findFundamentalMat(points1, points2, cameraMatrix, params[, mask]) -> retval, mask, status\n"
    ".   @brief Fundamental matrix of a calibrated pair (hypotheses are essential matrices).";
const char* const kDocFindFundamentalDropIn =
    "findFundamentalMat(points1, points2, method, ransacReprojThreshold, confidence, maxIters"
    "[, mask]) -> retval, mask\n"
    ".   @brief Drop-in for cv2.findFundamentalMat; method: a cv2 flag or METHOD_*.";
const char* const kDocFindFundamentalDropInDefaults =
    "findFundamentalMat(points1, points2[, method[, ransacReprojThreshold[, confidence[, mask]]]])"
    " -> retval, mask\n"
    ".   @brief Drop-in for cv2.findFundamentalMat with its defaults (FM_RANSAC, 3 px, 0.99).";
const char* const kDocFindFundamentalUsac =
    "findFundamentalMat(points1, points2, params[, mask]) -> retval, mask\n"
    ".   @overload Drop-in for cv2.findFundamentalMat with a cv2.UsacParams.";
const char* const kDocFindEssentialParams =
    "findEssentialMat(points1, points2, cameraMatrix, params[, mask]) -> retval, mask, status\n"
    ".   @brief Essential matrix with an explicit status.";
const char* const kDocFindEssentialDropIn =
    "findEssentialMat(points1, points2, cameraMatrix[, method[, prob[, threshold[, maxIters"
    "[, mask]]]]]) -> retval, mask\n"
    ".   @brief Drop-in for cv2.findEssentialMat; method: a cv2 flag or METHOD_*.";
const char* const kDocFindEssentialFocal =
    "findEssentialMat(points1, points2[, focal[, pp[, method[, prob[, threshold[, maxIters"
    "[, mask]]]]]]]) -> retval, mask\n"
    ".   @overload Camera matrix given by focal length and principal point.";
const char* const kDocFindEssentialTwoCameras =
    "findEssentialMat(points1, points2, cameraMatrix1, distCoeffs1, cameraMatrix2, distCoeffs2"
    "[, method[, prob[, threshold[, mask]]]]) -> retval, mask\n"
    ".   @overload Two cameras with distortion (undistorted as cv2 does).";
const char* const kDocFindEssentialUsac =
    "findEssentialMat(points1, points2, cameraMatrix1, cameraMatrix2, dist_coeff1, dist_coeff2, "
    "params[, mask]) -> retval, mask\n"
    ".   @overload Two cameras with distortion and a cv2.UsacParams.";
const char* const kDocRecoverPoseTwoCameras =
    "recoverPose(points1, points2, cameraMatrix1, distCoeffs1, cameraMatrix2, distCoeffs2[, E[, "
    "R[, t[, method[, prob[, threshold[, mask]]]]]]]) -> retval, E, R, t, mask\n"
    ".   @brief Drop-in for cv2.recoverPose of two cameras with distortion.";
const char* const kDocRecoverPoseDistance =
    "recoverPose(E, points1, points2, cameraMatrix, distanceThresh[, R[, t[, mask[, "
    "triangulatedPoints]]]]) -> retval, R, t, mask, triangulatedPoints\n"
    ".   @overload Points count only closer than distanceThresh; returns the triangulated points.";
const char* const kDocRecoverPoseParams =
    "recoverPose(points1, points2, cameraMatrix, params[, E[, R[, t[, mask[, covariance]]]]]) "
    "-> retval, E, R, t, mask, status, covariance\n"
    ".   @brief Estimates E robustly and recovers the motion x2 = R x1 + t, |t| = 1.\n"
    ".   retval is the number of inliers that pass cheirality.";
const char* const kDocRecoverPoseE =
    "recoverPose(E, points1, points2, cameraMatrix[, R[, t[, mask]]]) -> retval, R, t, mask\n"
    ".   @brief Drop-in for cv2.recoverPose from a known essential matrix.";
const char* const kDocRecoverPoseFocal =
    "recoverPose(E, points1, points2[, R[, t[, focal[, pp[, mask]]]]]) -> retval, R, t, mask\n"
    ".   @overload Camera matrix given by focal length and principal point.";
const char* const kDocEstimate =
    "estimateRelativeMotion(points1, points2, cameraMatrix[, params]) -> retval\n"
    ".   @brief Estimates the two-view geometry and returns everything in one Report.\n"
    ".   cameraMatrix may be None (uncalibrated: only F).";
const char* const kDocGenerateScene =
    "generateScene([, params]) -> retval\n"
    ".   @brief Generates a SyntheticScene deterministically from its SceneParams.";
const char* const kDocCompareMotion =
    "compareMotion(R, t, Rgt, tgt) -> retval\n"
    ".   @brief Compares an estimated motion with the truth; returns a MotionError.";
const char* const kDocPoseCovariance =
    "poseCovariance(R, t, covariance[, scaleStd[, inverse]]) -> retval\n"
    ".   @brief The 6x6 covariance of the pose (rotation, translation), GTSAM Pose3 convention,\n"
    ".   from the 5x5 tangent covariance of Report.covariance; singular along the unknown scale\n"
    ".   unless scaleStd > 0. inverse: the covariance of the inverse pose.";
const char* const kDocStatusToString =
    "statusToString(status) -> retval\n"
    ".   @brief A short English name of a STATUS_* value, e.g. \"poor quality input\".";
const char* const kDocMethodName =
    "methodName(method) -> retval\n"
    ".   @brief The command-line name of a METHOD_* value: rcme, prcme, standard, mlesac,\n"
    ".   covransac.";
const char* const kDocMethodFromString =
    "methodFromString(name) -> retval\n"
    ".   @brief The METHOD_* value of a name (methodName's, any letter case; cov-ransac and\n"
    ".   cov_ransac too); an error naming `name` otherwise.";

} // namespace

// Runs `call` (the mask's cv::Mat to write) without the GIL and returns (model or None, mask), as
// the cv2 forms that give no status do.
template <class Call> py::tuple modelAndMask(py::object mask, const Call& call)
{
    OutMat outMask = toOutMat(mask);
    cv::Mat model;
    {
        py::gil_scoped_release nogil;
        model = call(outMask.mat);
    }
    return py::make_tuple(fromMat(model), finishOut(outMask));
}

// Runs a drop-in findFundamentalMat overload, which returns F (empty on failure) and writes the
// mask; returns (F or None, mask) as cv2 does.
template <class Call>
py::tuple runFundamentalDropIn(py::object points1, py::object points2, py::object mask, Call call)
{
    const char* f = "findFundamentalMat";
    InMat p1 = toMat(points1, "points1", Conv::Float, f);
    InMat p2 = toMat(points2, "points2", Conv::Float, f);
    return modelAndMask(mask, [&](cv::Mat& maskOut) { return call(p1.mat, p2.mat, maskOut); });
}

// ------------------------------------------------------------------------------------------
// Batch: many pairs on every core (an extension over cv2.rcme, see opencv2/rcme/batch.hpp).

const char* const kDocEstimateBatch =
    "estimateRelativeMotionBatch(pairs, cameraMatrix[, params[, threads]]) -> retval\n"
    ".   @brief estimateRelativeMotion on every (points1, points2) of pairs, spread over\n"
    ".   C++ threads with the GIL released; retval is a list of one Report per pair, in order,\n"
    ".   each the same as the single call's. cameraMatrix: None (uncalibrated), one 3x3\n"
    ".   matrix for every pair, or a list with one matrix (or None) per pair. threads <= 0:\n"
    ".   every core. A malformed pair raises rcme.error naming it (\"pair i: ...\").";

//! cameraMatrix of the batch: None, one matrix, or a list/tuple of matrices or None, one per
//! pair. A list of numbers (a nested-list 3x3) is one matrix.
std::vector<InMat> batchCameras(py::handle cameraMatrix, size_t numPairs, const char* func)
{
    std::vector<InMat> cameras;
    if (cameraMatrix.is_none())
        return cameras;
    const bool perPair = (PyList_Check(cameraMatrix.ptr()) || PyTuple_Check(cameraMatrix.ptr())) &&
                         py::len(cameraMatrix) > 0 && [&] {
                             for (py::handle k : cameraMatrix)
                                 if (!k.is_none() && !py::isinstance<py::array>(k))
                                     return false;
                             return true;
                         }();
    if (!perPair) {
        cameras.push_back(toMat(cameraMatrix, "cameraMatrix", Conv::Float, func));
        return cameras;
    }
    if (py::len(cameraMatrix) != numPairs)
        raiseBadArg("cameraMatrix is a list of " + std::to_string(py::len(cameraMatrix)) +
                        " matrices; expected one per pair (" + std::to_string(numPairs) + ")",
                    func);
    size_t i = 0;
    for (py::handle k : cameraMatrix) {
        const std::string name = "cameraMatrix[" + std::to_string(i++) + "]";
        cameras.push_back(toMat(k, name.c_str(), Conv::Float, func));
    }
    return cameras;
}

void addBatch(py::module_& m)
{
    m.def(
        "estimateRelativeMotionBatch",
        [](py::iterable pairs, py::object cameraMatrix, const Params& p, int threads) {
            const char* f = "estimateRelativeMotionBatch";
            std::vector<InMat> kept; // the arrays the Mats wrap, alive until the call returns
            std::vector<cv::Mat> points1, points2;
            size_t i = 0;
            for (py::handle pair : pairs) {
                const std::string name = "pairs[" + std::to_string(i++) + "]";
                if (!PySequence_Check(pair.ptr()) || py::isinstance<py::array>(pair) ||
                    py::len(pair) != 2)
                    raiseBadArg(name + " must be a pair (points1, points2)", f);
                py::sequence pq = py::reinterpret_borrow<py::sequence>(pair);
                kept.push_back(toMat(pq[0], (name + "[0]").c_str(), Conv::Float, f));
                points1.push_back(kept.back().mat);
                kept.push_back(toMat(pq[1], (name + "[1]").c_str(), Conv::Float, f));
                points2.push_back(kept.back().mat);
            }
            const std::vector<InMat> cameraArrays = batchCameras(cameraMatrix, points1.size(), f);
            std::vector<cv::Mat> cameras;
            for (const InMat& k : cameraArrays)
                cameras.push_back(k.mat);
            std::vector<Report> reports;
            {
                py::gil_scoped_release nogil;
                reports =
                    cv::rcme::estimateRelativeMotionBatch(points1, points2, cameras, p, threads);
            }
            py::list out;
            for (Report& r : reports)
                out.append(py::cast(std::move(r)));
            return out;
        },
        py::arg("pairs"), py::arg("cameraMatrix"), py::arg("params") = Params(),
        py::arg("threads") = 0, kDocEstimateBatch);
}

// The native part of the package `rcme` (its __init__.py re-exports every name).
PYBIND11_MODULE(_rcme, m)
{
    py::options options;
    options.disable_function_signatures(); // the docstrings carry cv2-style signatures

    m.doc() = "Robust camera motion estimation (model quality aware RANSAC): the standalone "
              "twin of cv2.rcme.";

    // --- errors
    g_error = PyErr_NewException("rcme.error", PyExc_Exception, nullptr);
    if (!g_error)
        throw py::error_already_set();
    m.attr("error") = py::handle(g_error);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p)
                std::rethrow_exception(p);
        } catch (const cv::Exception& e) {
            try {
                py::object type = py::reinterpret_borrow<py::object>(g_error);
                py::object inst = type(e.what());
                inst.attr("code") = static_cast<int>(e.code); // an enum type in OpenCV 5
                inst.attr("err") = e.err;
                inst.attr("func") = e.func;
                inst.attr("file") = e.file;
                inst.attr("line") = e.line;
                PyErr_SetObject(g_error, inst.ptr());
            } catch (...) {
                PyErr_SetString(g_error, e.what());
            }
        }
    });

    // --- enum values: module-level ints, as the generator exports plain enums
    for (const std::vector<EnumConstant>* constants : kEnumConstants)
        for (const EnumConstant& c : *constants)
            m.attr(c.name) = c.value;

    // --- Params
    py::class_<Params> params = bindStruct<Params>(
        m, "Params", "Parameters of the robust estimators, shaped like cv2.UsacParams.",
        "Params() -> <rcme.Params object>\n.   Every field at its default.",
        /*keywordInit=*/true);
    // A static factory rather than a constructor, as in cv2.rcme: see params.hpp.
    const char* docFromUsac =
        "fromUsacParams(usacParams) -> retval\n"
        ".   Params with confidence, maxIterations, randomGeneratorState, "
        "threshold, isParallel and sampler carried over from a cv2.UsacParams.";
    params.def_static("fromUsacParams", &paramsFromUsac, py::arg("usacParams"), docFromUsac);
    m.def("Params_fromUsacParams", &paramsFromUsac, py::arg("usacParams"), docFromUsac);
    const char* docAsPublished =
        "asPublished(method) -> retval\n"
        ".   The paper's configuration of method: 8-point solver, no local optimisation, no "
        "ambiguity or uncertainty test, the classic adaptive bound (cleanSampleSuccessRate 1).";
    const auto asPublished = [](int method) {
        return Params::asPublished(static_cast<Method>(method));
    };
    params.def_static("asPublished", asPublished, py::arg("method"), docAsPublished);
    m.def("Params_asPublished", asPublished, py::arg("method"), docAsPublished);

    // --- Report, SceneParams, SyntheticScene, MotionError
    bindStruct<Report>(m, "Report", "Everything an estimation produced.",
                       "Report() -> <rcme.Report object>", /*keywordInit=*/false);
    bindStruct<SceneParams>(m, "SceneParams", "Parameters of the synthetic scene generator.",
                            "SceneParams() -> <rcme.SceneParams object>", /*keywordInit=*/true);
    bindStruct<SyntheticScene>(m, "SyntheticScene",
                               "A generated two-view scene with its ground truth.",
                               "SyntheticScene() -> <rcme.SyntheticScene object>",
                               /*keywordInit=*/false);
    bindStruct<MotionError>(m, "MotionError", "Differences between an estimated and a true motion.",
                            "MotionError() -> <rcme.MotionError object>", /*keywordInit=*/false);

    // --- functions, overloads in header order (cv2 tries them in that order too)
    m.def(
        "statusToString",
        [](int status) { return cv::rcme::statusToString(static_cast<Status>(status)); },
        py::arg("status"), kDocStatusToString);
    m.def(
        "methodName", [](int method) { return cv::rcme::methodName(static_cast<Method>(method)); },
        py::arg("method"), kDocMethodName);
    m.def(
        "methodFromString",
        [](const std::string& name) { return static_cast<int>(cv::rcme::methodFromString(name)); },
        py::arg("name"), kDocMethodFromString);

    m.def(
        "estimateRelativeMotion",
        [](py::object points1, py::object points2, py::object cameraMatrix, const Params& p) {
            const char* f = "estimateRelativeMotion";
            const CameraInputs in = cameraInputs(f, points1, points2, cameraMatrix);
            py::gil_scoped_release nogil;
            return cv::rcme::estimateRelativeMotion(in.p1.mat, in.p2.mat, in.k.mat, p);
        },
        py::arg("points1"), py::arg("points2"), py::arg("cameraMatrix"),
        py::arg("params") = Params(), kDocEstimate);

    // The calibrated form is the general one; without a camera matrix it is passed as None,
    // which converts to an empty array, as the C++ overload passes noArray().
    auto findFundamentalWithCamera = [](py::object points1, py::object points2,
                                        py::object cameraMatrix, const Params& p, py::object mask) {
        return runWithParams(
            "findFundamentalMat", points1, points2, cameraMatrix, mask,
            [&](const cv::Mat& a, const cv::Mat& b, const cv::Mat& k, cv::Mat& m, Status& status) {
                return cv::rcme::findFundamentalMat(a, b, k, p, m, status);
            });
    };
    m.def(
        "findFundamentalMat",
        [findFundamentalWithCamera](py::object points1, py::object points2, const Params& p,
                                    py::object mask) {
            return findFundamentalWithCamera(points1, points2, py::none(), p, mask);
        },
        py::arg("points1"), py::arg("points2"), py::arg("params"), py::arg("mask") = py::none(),
        kDocFindFundamentalParams);
    m.def("findFundamentalMat", findFundamentalWithCamera, py::arg("points1"), py::arg("points2"),
          py::arg("cameraMatrix"), py::arg("params"), py::arg("mask") = py::none(),
          kDocFindFundamentalCalibrated);

    m.def(
        "findFundamentalMat",
        [](py::object points1, py::object points2, int method, double ransacReprojThreshold,
           double confidence, int maxIters, py::object mask) {
            return runFundamentalDropIn(
                points1, points2, mask, [&](cv::Mat& a, cv::Mat& b, cv::Mat& m) {
                    return cv::rcme::findFundamentalMat(a, b, method, ransacReprojThreshold,
                                                        confidence, maxIters, m);
                });
        },
        py::arg("points1"), py::arg("points2"), py::arg("method"), py::arg("ransacReprojThreshold"),
        py::arg("confidence"), py::arg("maxIters"), py::arg("mask") = py::none(),
        kDocFindFundamentalDropIn);
    m.def(
        "findFundamentalMat",
        [](py::object points1, py::object points2, int method, double ransacReprojThreshold,
           double confidence, py::object mask) {
            return runFundamentalDropIn(points1, points2, mask,
                                        [&](cv::Mat& a, cv::Mat& b, cv::Mat& m) {
                                            return cv::rcme::findFundamentalMat(
                                                a, b, method, ransacReprojThreshold, confidence, m);
                                        });
        },
        py::arg("points1"), py::arg("points2"), py::arg("method") = static_cast<int>(cv::FM_RANSAC),
        py::arg("ransacReprojThreshold") = 3.0, py::arg("confidence") = 0.99,
        py::arg("mask") = py::none(), kDocFindFundamentalDropInDefaults);
    // Last of its name: it takes any object as params and rejects what is not a UsacParams.
    m.def(
        "findFundamentalMat",
        [](py::object points1, py::object points2, py::object params, py::object mask) {
            const cv::UsacParams usac = usacFromPython(params, "findFundamentalMat", "params");
            return runFundamentalDropIn(points1, points2, mask,
                                        [&](cv::Mat& a, cv::Mat& b, cv::Mat& m) {
                                            return cv::rcme::findFundamentalMat(a, b, m, usac);
                                        });
        },
        py::arg("points1"), py::arg("points2"), py::arg("params"), py::arg("mask") = py::none(),
        kDocFindFundamentalUsac);

    m.def(
        "findEssentialMat",
        [](py::object points1, py::object points2, py::object cameraMatrix, const Params& p,
           py::object mask) {
            return runWithParams(
                "findEssentialMat", points1, points2, cameraMatrix, mask,
                [&](const cv::Mat& a, const cv::Mat& b, const cv::Mat& k, cv::Mat& m,
                    Status& status) { return cv::rcme::findEssentialMat(a, b, k, p, m, status); });
        },
        py::arg("points1"), py::arg("points2"), py::arg("cameraMatrix"), py::arg("params"),
        py::arg("mask") = py::none(), kDocFindEssentialParams);

    m.def(
        "findEssentialMat",
        [](py::object points1, py::object points2, py::object cameraMatrix, int method, double prob,
           double threshold, int maxIters, py::object mask) {
            const char* f = "findEssentialMat";
            const CameraInputs in = cameraInputs(f, points1, points2, cameraMatrix);
            return modelAndMask(mask, [&](cv::Mat& maskOut) {
                return cv::rcme::findEssentialMat(in.p1.mat, in.p2.mat, in.k.mat, method, prob,
                                                  threshold, maxIters, maskOut);
            });
        },
        py::arg("points1"), py::arg("points2"), py::arg("cameraMatrix"),
        py::arg("method") = static_cast<int>(cv::RANSAC), py::arg("prob") = 0.999,
        py::arg("threshold") = 1.0, py::arg("maxIters") = 1000, py::arg("mask") = py::none(),
        kDocFindEssentialDropIn);

    m.def(
        "findEssentialMat",
        [](py::object points1, py::object points2, double focal, py::object pp, int method,
           double prob, double threshold, int maxIters, py::object mask) {
            const char* f = "findEssentialMat";
            InMat p1 = toMat(points1, "points1", Conv::Float, f);
            InMat p2 = toMat(points2, "points2", Conv::Float, f);
            const cv::Point2d principal = toPoint2d(pp, "pp", f);
            return modelAndMask(mask, [&](cv::Mat& maskOut) {
                return cv::rcme::findEssentialMat(p1.mat, p2.mat, focal, principal, method, prob,
                                                  threshold, maxIters, maskOut);
            });
        },
        py::arg("points1"), py::arg("points2"), py::arg("focal") = 1.0,
        py::arg("pp") = py::make_tuple(0.0, 0.0), py::arg("method") = static_cast<int>(cv::RANSAC),
        py::arg("prob") = 0.999, py::arg("threshold") = 1.0, py::arg("maxIters") = 1000,
        py::arg("mask") = py::none(), kDocFindEssentialFocal);

    m.def(
        "findEssentialMat",
        [](py::object points1, py::object points2, py::object cameraMatrix1, py::object distCoeffs1,
           py::object cameraMatrix2, py::object distCoeffs2, int method, double prob,
           double threshold, py::object mask) {
            const char* f = "findEssentialMat";
            const TwoCameraInputs in = twoCameraInputs(
                f, points1, points2, {cameraMatrix1, "cameraMatrix1"}, {distCoeffs1, "distCoeffs1"},
                {cameraMatrix2, "cameraMatrix2"}, {distCoeffs2, "distCoeffs2"});
            return modelAndMask(mask, [&](cv::Mat& maskOut) {
                return cv::rcme::findEssentialMat(in.p1.mat, in.p2.mat, in.k1.mat, in.d1.mat,
                                                  in.k2.mat, in.d2.mat, method, prob, threshold,
                                                  maskOut);
            });
        },
        py::arg("points1"), py::arg("points2"), py::arg("cameraMatrix1"), py::arg("distCoeffs1"),
        py::arg("cameraMatrix2"), py::arg("distCoeffs2"),
        py::arg("method") = static_cast<int>(cv::RANSAC), py::arg("prob") = 0.999,
        py::arg("threshold") = 1.0, py::arg("mask") = py::none(), kDocFindEssentialTwoCameras);

    m.def(
        "findEssentialMat",
        [](py::object points1, py::object points2, py::object cameraMatrix1,
           py::object cameraMatrix2, py::object distCoeff1, py::object distCoeff2,
           py::object params, py::object mask) {
            const char* f = "findEssentialMat";
            const cv::UsacParams usac = usacFromPython(params, f, "params");
            const TwoCameraInputs in = twoCameraInputs(
                f, points1, points2, {cameraMatrix1, "cameraMatrix1"}, {distCoeff1, "dist_coeff1"},
                {cameraMatrix2, "cameraMatrix2"}, {distCoeff2, "dist_coeff2"});
            return modelAndMask(mask, [&](cv::Mat& maskOut) {
                return cv::rcme::findEssentialMat(in.p1.mat, in.p2.mat, in.k1.mat, in.k2.mat,
                                                  in.d1.mat, in.d2.mat, maskOut, usac);
            });
        },
        py::arg("points1"), py::arg("points2"), py::arg("cameraMatrix1"), py::arg("cameraMatrix2"),
        py::arg("dist_coeff1"), py::arg("dist_coeff2"), py::arg("params"),
        py::arg("mask") = py::none(), kDocFindEssentialUsac);

    m.def(
        "recoverPose",
        [](py::object points1, py::object points2, py::object cameraMatrix, const Params& p,
           py::object E, py::object R, py::object t, py::object mask, py::object covariance) {
            const char* f = "recoverPose";
            const CameraInputs in = cameraInputs(f, points1, points2, cameraMatrix);
            OutMat outE = toOutMat(E), outR = toOutMat(R), outT = toOutMat(t);
            OutMat outMask = toOutMat(mask), outCov = toOutMat(covariance);
            Status status = STATUS_SUCCESS;
            int retval = 0;
            {
                py::gil_scoped_release nogil;
                retval = cv::rcme::recoverPose(in.p1.mat, in.p2.mat, in.k.mat, outE.mat, outR.mat,
                                               outT.mat, p, outMask.mat, status, outCov.mat);
            }
            return py::make_tuple(retval, finishOut(outE), finishOut(outR), finishOut(outT),
                                  finishOut(outMask), static_cast<int>(status), finishOut(outCov));
        },
        py::arg("points1"), py::arg("points2"), py::arg("cameraMatrix"), py::arg("params"),
        py::arg("E") = py::none(), py::arg("R") = py::none(), py::arg("t") = py::none(),
        py::arg("mask") = py::none(), py::arg("covariance") = py::none(), kDocRecoverPoseParams);

    m.def(
        "recoverPose",
        [](py::object points1, py::object points2, py::object cameraMatrix1, py::object distCoeffs1,
           py::object cameraMatrix2, py::object distCoeffs2, py::object E, py::object R,
           py::object t, int method, double prob, double threshold, py::object mask) {
            const char* f = "recoverPose";
            const TwoCameraInputs in = twoCameraInputs(
                f, points1, points2, {cameraMatrix1, "cameraMatrix1"}, {distCoeffs1, "distCoeffs1"},
                {cameraMatrix2, "cameraMatrix2"}, {distCoeffs2, "distCoeffs2"});
            OutMat outE = toOutMat(E), outR = toOutMat(R), outT = toOutMat(t);
            OutMat ioMask = toInOutMat(mask, "mask", f);
            int retval = 0;
            {
                py::gil_scoped_release nogil;
                retval = cv::rcme::recoverPose(in.p1.mat, in.p2.mat, in.k1.mat, in.d1.mat,
                                               in.k2.mat, in.d2.mat, outE.mat, outR.mat, outT.mat,
                                               method, prob, threshold, ioMask.mat);
            }
            return py::make_tuple(retval, finishOut(outE), finishOut(outR), finishOut(outT),
                                  finishOut(ioMask));
        },
        py::arg("points1"), py::arg("points2"), py::arg("cameraMatrix1"), py::arg("distCoeffs1"),
        py::arg("cameraMatrix2"), py::arg("distCoeffs2"), py::arg("E") = py::none(),
        py::arg("R") = py::none(), py::arg("t") = py::none(),
        py::arg("method") = static_cast<int>(cv::RANSAC), py::arg("prob") = 0.999,
        py::arg("threshold") = 1.0, py::arg("mask") = py::none(), kDocRecoverPoseTwoCameras);

    m.def(
        "recoverPose",
        [](py::object E, py::object points1, py::object points2, py::object cameraMatrix,
           py::object R, py::object t, py::object mask) {
            const char* f = "recoverPose";
            InMat e = toMat(E, "E", Conv::Float, f);
            const CameraInputs in = cameraInputs(f, points1, points2, cameraMatrix);
            OutMat outR = toOutMat(R), outT = toOutMat(t);
            OutMat ioMask = toInOutMat(mask, "mask", f);
            int retval = 0;
            {
                py::gil_scoped_release nogil;
                retval = cv::rcme::recoverPose(e.mat, in.p1.mat, in.p2.mat, in.k.mat, outR.mat,
                                               outT.mat, ioMask.mat);
            }
            return py::make_tuple(retval, finishOut(outR), finishOut(outT), finishOut(ioMask));
        },
        py::arg("E"), py::arg("points1"), py::arg("points2"), py::arg("cameraMatrix"),
        py::arg("R") = py::none(), py::arg("t") = py::none(), py::arg("mask") = py::none(),
        kDocRecoverPoseE);

    m.def(
        "recoverPose",
        [](py::object E, py::object points1, py::object points2, py::object R, py::object t,
           double focal, py::object pp, py::object mask) {
            const char* f = "recoverPose";
            InMat e = toMat(E, "E", Conv::Float, f);
            InMat p1 = toMat(points1, "points1", Conv::Float, f);
            InMat p2 = toMat(points2, "points2", Conv::Float, f);
            const cv::Point2d principal = toPoint2d(pp, "pp", f);
            OutMat outR = toOutMat(R), outT = toOutMat(t);
            OutMat ioMask = toInOutMat(mask, "mask", f);
            int retval = 0;
            {
                py::gil_scoped_release nogil;
                retval = cv::rcme::recoverPose(e.mat, p1.mat, p2.mat, outR.mat, outT.mat, focal,
                                               principal, ioMask.mat);
            }
            return py::make_tuple(retval, finishOut(outR), finishOut(outT), finishOut(ioMask));
        },
        py::arg("E"), py::arg("points1"), py::arg("points2"), py::arg("R") = py::none(),
        py::arg("t") = py::none(), py::arg("focal") = 1.0, py::arg("pp") = py::make_tuple(0.0, 0.0),
        py::arg("mask") = py::none(), kDocRecoverPoseFocal);

    m.def(
        "recoverPose",
        [](py::object E, py::object points1, py::object points2, py::object cameraMatrix,
           double distanceThresh, py::object R, py::object t, py::object mask,
           py::object triangulatedPoints) {
            const char* f = "recoverPose";
            InMat e = toMat(E, "E", Conv::Float, f);
            const CameraInputs in = cameraInputs(f, points1, points2, cameraMatrix);
            OutMat outR = toOutMat(R), outT = toOutMat(t), outPoints = toOutMat(triangulatedPoints);
            OutMat ioMask = toInOutMat(mask, "mask", f);
            int retval = 0;
            {
                py::gil_scoped_release nogil;
                retval = cv::rcme::recoverPose(e.mat, in.p1.mat, in.p2.mat, in.k.mat, outR.mat,
                                               outT.mat, distanceThresh, ioMask.mat, outPoints.mat);
            }
            return py::make_tuple(retval, finishOut(outR), finishOut(outT), finishOut(ioMask),
                                  finishOut(outPoints));
        },
        py::arg("E"), py::arg("points1"), py::arg("points2"), py::arg("cameraMatrix"),
        py::arg("distanceThresh"), py::arg("R") = py::none(), py::arg("t") = py::none(),
        py::arg("mask") = py::none(), py::arg("triangulatedPoints") = py::none(),
        kDocRecoverPoseDistance);

    m.def(
        "generateScene",
        [](const SceneParams& p) {
            py::gil_scoped_release nogil;
            return cv::rcme::generateScene(p);
        },
        py::arg("params") = SceneParams(), kDocGenerateScene);

    m.def(
        "compareMotion",
        [](py::object R, py::object t, py::object Rgt, py::object tgt) {
            const char* f = "compareMotion";
            InMat r = toMat(R, "R", Conv::Float, f);
            InMat tt = toMat(t, "t", Conv::Float, f);
            InMat rgt = toMat(Rgt, "Rgt", Conv::Float, f);
            InMat tgtm = toMat(tgt, "tgt", Conv::Float, f);
            py::gil_scoped_release nogil;
            return cv::rcme::compareMotion(r.mat, tt.mat, rgt.mat, tgtm.mat);
        },
        py::arg("R"), py::arg("t"), py::arg("Rgt"), py::arg("tgt"), kDocCompareMotion);

    m.def(
        "poseCovariance",
        [](py::object R, py::object t, py::object covariance, double scaleStd, bool inverse) {
            const char* f = "poseCovariance";
            InMat r = toMat(R, "R", Conv::Float, f);
            InMat tt = toMat(t, "t", Conv::Float, f);
            InMat c = toMat(covariance, "covariance", Conv::Float, f);
            cv::Mat out;
            {
                py::gil_scoped_release nogil;
                out = cv::rcme::poseCovariance(r.mat, tt.mat, c.mat, scaleStd, inverse);
            }
            return fromMat(out);
        },
        py::arg("R"), py::arg("t"), py::arg("covariance"), py::arg("scaleStd") = 0.0,
        py::arg("inverse") = false, kDocPoseCovariance);

    addBatch(m);
}
