#pragma once
// The NURBS tool: rational Bézier curves and patches, NURBS curves and surfaces (docs/nurbs.md,
// docs/editor.md "Rational and NURBS objects").
//   - weights: typed in the panel for the selected control points, or Alt + vertical drag on a
//     control point (up: heavier; the weights of the selected points scale by exp(-dy / 100), so
//     they stay > 0);
//   - knots: dots at the knots of the selected NURBS curve (one tick across the curve per unit of
//     multiplicity), isoparametric lines at the knots of a NURBS surface; Boehm insertion at the
//     slider's parameter (K, or the panel's field and button), the shape unchanged;
//   - exact circles and arcs from clicks (Shift+O: centre, radius; Shift+U: centre, start, end);
//   - the de Boor construction at the slider's parameter (T), the rational one drawn as the
//     central projection of the homogeneous construction.
// Every edit is one undo step through Scene::replaceObject / addObject.

#include <Eigen/Core>

#include <string>
#include <vector>

#include "tools/curve_tools.h"
#include "tools/tool.h"

namespace freeform::editor {

class NurbsTool final : public Tool {
public:
    using Tool::Tool;

    KeyContext keyContext() const override { return KeyContext::Nurbs; }
    bool onKey(ToolContext& context, KeyAction action) override;
    bool onPointer(ToolContext& context, const PointerEvent& event) override;
    void update(ToolContext& context, Overlay& overlay) override;
    void reset() override;

    /// Whether the type is one of the four rational/NURBS document types.
    static bool handles(const KindInfo* kind);
    /// The weights of item i's control points (1 for each when the object stores none; empty for
    /// other types).
    static std::vector<double> weightsOf(const Scene& scene, int item);

    // ---- operations (true on success; else the status line says why), each one undo step
    /// Sets the weights of control points ks of item i to w (w > 0, finite).
    bool setWeights(ToolContext& context, int item, const std::vector<int>& ks, double w);
    /// Multiplies the weights of control points ks of item i by factor, from `start` (the weights
    /// when the gesture began); within a merged gesture the steps are one.
    bool scaleWeights(ToolContext& context, int item, const std::vector<int>& ks, const std::vector<double>& start,
                      double factor);
    /// Inserts the knot u once into the selected nurbs_curve (direction ignored) or into the
    /// selected nurbs_surface's u (direction 0) or v (1) knots, by Boehm's algorithm (Oslo for
    /// surfaces): the shape does not change.
    bool insertKnot(ToolContext& context, double u, int direction = 0);
    /// The parameter of the slider on the selected object's domain (curve, or the chosen direction
    /// of a surface); 0 when there is none.
    double sliderParameter(const ToolContext& context) const;
    /// Starts creating a full circle (arc = false) or an arc by clicking.
    void startCreating(bool arc);
    /// One creation click at world point p (in the view plane); creates the object at the last.
    bool creationClick(ToolContext& context, const Eigen::Vector3d& p, const Eigen::Vector3d& normal);
    bool creating() const { return creating_; }
    /// Creating an arc (else a full circle), while creating().
    bool arc() const { return arc_; }
    void cancelCreating();
    /// The panel's weight field follows the selection: when point k of item is newly the last
    /// selected one, typedWeight becomes its weight (else the typed value stays).
    void followTypedWeight(int item, int k, double weight)
    {
        if (item == typedItem_ && k == typedPoint_) return;
        typedWeight = weight;
        typedItem_ = item, typedPoint_ = k;
    }

    // ---- settings the panel and the tests change
    double t = 0.5;            // the slider: fraction of the domain (knot insertion, de Boor at t)
    int direction = 0;         // surfaces: insert in u (0) or v (1)
    bool construction = false; // the de Boor construction at t (NURBS and rational Bézier curves)
    bool comb = false;         // the curvature comb of a curve (V)
    double combScale = 1;      // its teeth's length per unit of curvature, relative
    bool showKnots = true;     // knot dots and ticks, isoparametric lines at the knots
    double typedWeight = 1;    // the panel's weight field

private:
    bool creating_ = false;
    bool arc_ = false;
    std::vector<Eigen::Vector3d> clicks_;
    Eigen::Vector3d hover_ = Eigen::Vector3d::Zero();
    bool hasHover_ = false;
    Eigen::Vector3d normal_ = Eigen::Vector3d::UnitZ();
    int typedItem_ = -1, typedPoint_ = -1; // the point typedWeight was last filled from
    // The Alt + drag on a weight.
    int dragItem_ = -1;
    std::vector<int> dragPoints_;
    std::vector<double> dragStart_;
    double dragY_ = 0;
};

/// The exact circle of `radius` about `centre` in the plane spanned by the orthonormal a, b, as
/// nurbs_curve data (degree 2, four quarter arcs, knots 0,0,0, 1/4,1/4, ..., 1,1,1, weights 1 and
/// sqrt(2)/2, the first point c + r a).
NurbsCurveData circleData(const Eigen::Vector3d& centre, double radius, const Eigen::Vector3d& a, const Eigen::Vector3d& b);
/// The exact arc from angle 0 (c + r a) counter-clockwise about a x b by `sweep` (0 < sweep <
/// 2 pi): one quadratic rational_bezier_curve when sweep <= pi / 2, else a nurbs_curve of
/// ceil(sweep / (pi / 2)) equal quadratic pieces (interior knots doubled, knots 0..n).
ObjectData arcData(const Eigen::Vector3d& centre, double radius, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                   double sweep);

} // namespace freeform::editor
