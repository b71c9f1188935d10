// This file is part of the rcme module. It is subject to the license terms in the LICENSE file
// found in the top-level directory of this distribution.

#ifndef OPENCV_RCME_FRAMEWORK_MODEL_HPP
#define OPENCV_RCME_FRAMEWORK_MODEL_HPP

// The model space of the loop: a hypothesis (F, and with K its motion and covariance), its
// score, and what turns an essential matrix into a motion.

#include "framework/two_view_data.hpp"
#include "geometry/motion_parameterization.hpp"

#include <variant>

namespace cv {
namespace rcme {
namespace detail {

//! A camera motion: x2 = R x1 + t, |t| = 1.
struct Motion
{
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

/** The two kinds of model, each refined in its own parameters (estimation/model_fit.hpp): a
fundamental matrix (7 DoF, in Hartley-normalized coordinates) or a camera motion (5 DoF; E and F
follow from it). Which one a model is refined as is the model space's choice
(ModelSpace::formOf). */
enum class ModelForm
{
    kFundamental,
    kMotion
};

/** The first-order uncertainty of a model in P parameters theta of a tangent space at it: their
covariance and the directions dF/dtheta_k in pixels, so that a residual's variance can be
propagated without knowing the parameterization (components/residual_uncertainty.hpp). */
template <int P> struct TangentUncertainty
{
    static constexpr int kDof = P;
    Eigen::Matrix<double, P, P> covariance = Eigen::Matrix<double, P, P>::Zero();
    Eigen::Matrix3d directions[P];
};
//! A motion's, in MotionTangent's parameters (the rotation increment, then the translation's).
using MotionUncertainty = TangentUncertainty<MotionTangent::kDof>;
//! A fundamental matrix's, in FundamentalTangent's parameters.
using FundamentalUncertainty = TangentUncertainty<FundamentalTangent::kDof>;

/** What is known of a model's uncertainty: nothing (a solver's hypothesis, a fit whose
information matrix is ill-conditioned, an F replaced by another), its motion's or its F's, each
at its own size: a covariance is read as what it is the covariance of. */
class ModelUncertainty
{
public:
    bool isKnown() const { return !std::holds_alternative<std::monostate>(value_); }
    void reset() { value_ = std::monostate(); }
    //! Makes it `Tangent`'s (MotionUncertainty or FundamentalUncertainty), zero, and returns it.
    template <class Tangent> Tangent& emplace() { return value_.template emplace<Tangent>(); }
    //! It as `Tangent`'s; null when it is none or the other kind.
    template <class Tangent> const Tangent* as() const { return std::get_if<Tangent>(&value_); }
    template <class Tangent> Tangent* as() { return std::get_if<Tangent>(&value_); }
    //! visit(uncertainty) with whichever kind it is; not called when none is known.
    template <class Visit> void visitKnown(Visit&& visit) const
    {
        if (const MotionUncertainty* motion = as<MotionUncertainty>())
            visit(*motion);
        else if (const FundamentalUncertainty* fundamental = as<FundamentalUncertainty>())
            visit(*fundamental);
    }

private:
    std::variant<std::monostate, MotionUncertainty, FundamentalUncertainty> value_;
};

/** A model that is its fundamental matrix (refined as F). With a camera matrix, `essential` is the
essential matrix of the hypothesis it came from: F = K^-T E K^-1 up to scale until the model is
refined as F, which leaves E as the solver gave it, and the motion is decomposed from it. Zero
otherwise (a motion then comes from the E closest to F). */
struct FundamentalForm
{
    Eigen::Matrix3d essential = Eigen::Matrix3d::Zero();
};

//! One hypothesis (and, after selection, the estimate).
struct Model
{
    Eigen::Matrix3d F = Eigen::Matrix3d::Zero(); //!< pixel fundamental matrix, ||F|| = 1
    //! What the model is: a fundamental matrix, or, with K once the decomposition of E is
    //! decided, a camera motion (refined as a motion; F follows from it, setMotion).
    std::variant<FundamentalForm, Motion> form;
    //! First-order uncertainty of the model, in the parameters it is refined in (none until a
    //! fit gives it).
    ModelUncertainty uncertainty;
    //! Noise sigma estimated from the final inliers' residuals (Refiner::finalize), NaN if none.
    double noiseSigma = std::numeric_limits<double>::quiet_NaN();
    //! The scale (pixels) of the Cauchy loss the final polish fitted the motion with
    //! (polishFinalMotionOn); 0 for a least-squares fit.
    double polishLossScale = 0.0;

    //! The motion the model is; null while it is a fundamental matrix.
    const Motion* motion() const { return std::get_if<Motion>(&form); }
    Motion* motion() { return std::get_if<Motion>(&form); }
    //! Its essential matrix: the motion's [t]x R, or the hypothesis' (zero when it has none).
    Eigen::Matrix3d essential() const;
};

/** Makes `model` the motion (R, t), its F = K^-T [t]x R K^-1; F is not finite where the motion is
not (a fit that diverged). */
void setMotion(const TwoViewData& data, const Motion& motion, Model& model);

/** Gives a model of calibrated data its motion: E (from F when the hypothesis was not
essential) is decomposed with cheirality on `inliers`, and E, F are set from (R, t). False when
no decomposition puts any inlier in front of both cameras. */
bool recoverMotion(const TwoViewData& data, const std::vector<uchar>& inliers, Model& model);

/** The same from the points of a minimal sample alone (cheirality decided by them), with
`points1`, `points2` as buffers for the sample's points. */
bool recoverMotionFromSample(const TwoViewData& data, const std::vector<int>& sample, Model& model,
                             std::vector<Eigen::Vector2d>& points1,
                             std::vector<Eigen::Vector2d>& points2);

/** Whether two motions are different answers: their rotations differ by more than 5 deg or their
translation directions by more than 15 deg, the accuracy a right motion is held to
(doc/results.md). A model without a motion (a selection whose E no decomposition puts the inliers
in front of) differs from every motion. */
bool areDistinctMotions(const Model& a, const Model& b);

//! Quality of a hypothesis as a scorer sees it; lower value is better.
struct Score
{
    double value = std::numeric_limits<double>::infinity();
    int inlierCount = 0;
    double meanEntropy = std::numeric_limits<double>::quiet_NaN();
    //! Whether the hypothesis passed the method's acceptance tests (may become the estimate).
    bool isCandidate = false;
    //! What the hypothesis tells the run-wide tests (RCME: its ratio of points in the noise-only
    //! band when it passes the quality test, else 0); read by Scorer::commit().
    double runEvidence = 0;

    bool isBetterThan(const Score& other) const { return value < other.value; }
};

} // namespace detail
} // namespace rcme
} // namespace cv

#endif // OPENCV_RCME_FRAMEWORK_MODEL_HPP
