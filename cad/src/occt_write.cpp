// Parts into Open CASCADE shapes, STEP and IGES files (freeform/cad/cad_file.h, docs/cad.md "Writing").
//
// Open CASCADE has no parameter maps: a face's surface is written as the B-spline surface of its
// NURBS, in the NURBS's parameters (s, r) = (mapU(u), mapV(v)), and an edge's curve in
// sigma = map(t) of its own map (its file parameter when it has no 3D curve). Every pcurve must then
// run on sigma and land in (s, r):
//     g(sigma) = (mapU(pu(t)), mapV(pv(t))),  t = map^-1(sigma),  (pu, pv) the trim in the file.
// Written exactly (the trim's own control points) when the face's maps are identities and the
// trim's map is the edge's; as a line when g is linear (a half-angle iso line on a face whose arcs
// line up with the edge's: the maps then differ by a shift); otherwise fitted (a cubic B-spline
// through samples of g, the samples doubled until the fit's 3D distance to g on the surface,
// measured between the samples, is within a tenth of the edge's tolerance or 1e-7 of the part),
// and the edge's tolerance raised to that distance when it is larger.

#include "freeform/cad/cad_file.h"

#include <filesystem>
#include <fstream>
#include <map>
#include <limits>
#include <optional>

#include <BRepCheck_Analyzer.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2dAPI_Interpolate.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TColgp_HArray1OfPnt2d.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_DataMapOfShapeInteger.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>

#include "freeform/cad/occt_bridge.h"
#include "freeform/core/error.h"
#include "occt_common.h"

namespace freeform {
namespace {

/// A flat knot vector as Open CASCADE's distinct knots and multiplicities.
void knotsAndMults(const std::vector<double>& flat, Handle(TColStd_HArray1OfReal)& knots,
                   Handle(TColStd_HArray1OfInteger)& mults)
{
    std::vector<double> k;
    std::vector<int> m;
    for (double x : flat) {
        if (!k.empty() && x == k.back()) ++m.back();
        else k.push_back(x), m.push_back(1);
    }
    knots = new TColStd_HArray1OfReal(1, static_cast<int>(k.size()));
    mults = new TColStd_HArray1OfInteger(1, static_cast<int>(m.size()));
    for (std::size_t i = 0; i < k.size(); ++i) {
        knots->SetValue(static_cast<int>(i) + 1, k[i]);
        mults->SetValue(static_cast<int>(i) + 1, m[i]);
    }
}

Handle(Geom_BSplineSurface) bsplineSurface(const NurbsSurface<double, 3>& s)
{
    const int nu = s.countU(), nv = s.countV();
    TColgp_Array2OfPnt poles(1, nu, 1, nv);
    TColStd_Array2OfReal weights(1, nu, 1, nv);
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const Eigen::Vector3d p = s.controlPoint(i, j);
            poles.SetValue(i + 1, j + 1, gp_Pnt(p.x(), p.y(), p.z()));
            weights.SetValue(i + 1, j + 1, s.weight(i, j));
        }
    Handle(TColStd_HArray1OfReal) ku, kv;
    Handle(TColStd_HArray1OfInteger) mu, mv;
    knotsAndMults(s.knotsU().knots(), ku, mu);
    knotsAndMults(s.knotsV().knots(), kv, mv);
    if (!s.isRational())
        return new Geom_BSplineSurface(poles, ku->Array1(), kv->Array1(), mu->Array1(), mv->Array1(), s.degreeU(),
                                       s.degreeV());
    return new Geom_BSplineSurface(poles, weights, ku->Array1(), kv->Array1(), mu->Array1(), mv->Array1(), s.degreeU(),
                                   s.degreeV());
}

Handle(Geom_BSplineCurve) bsplineCurve(const NurbsCurve<double, 3>& c)
{
    const int n = c.controlCount();
    TColgp_Array1OfPnt poles(1, n);
    TColStd_Array1OfReal weights(1, n);
    for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d p = c.controlPoint(i);
        poles.SetValue(i + 1, gp_Pnt(p.x(), p.y(), p.z()));
        weights.SetValue(i + 1, c.weight(i));
    }
    Handle(TColStd_HArray1OfReal) k;
    Handle(TColStd_HArray1OfInteger) m;
    knotsAndMults(c.knots(), k, m);
    if (!c.isRational()) return new Geom_BSplineCurve(poles, k->Array1(), m->Array1(), c.degree());
    return new Geom_BSplineCurve(poles, weights, k->Array1(), m->Array1(), c.degree());
}

/// A 2D NURBS with every control point's u shifted by `shift` (a period).
Handle(Geom2d_BSplineCurve) bsplineCurve2d(const NurbsCurve<double, 2>& c, const Eigen::Vector2d& shift)
{
    const int n = c.controlCount();
    TColgp_Array1OfPnt2d poles(1, n);
    TColStd_Array1OfReal weights(1, n);
    for (int i = 0; i < n; ++i) {
        const Eigen::Vector2d p = c.controlPoint(i) + shift;
        poles.SetValue(i + 1, gp_Pnt2d(p.x(), p.y()));
        weights.SetValue(i + 1, c.weight(i));
    }
    Handle(TColStd_HArray1OfReal) k;
    Handle(TColStd_HArray1OfInteger) m;
    knotsAndMults(c.knots(), k, m);
    if (!c.isRational()) return new Geom2d_BSplineCurve(poles, k->Array1(), m->Array1(), c.degree());
    return new Geom2d_BSplineCurve(poles, weights, k->Array1(), m->Array1(), c.degree());
}

Handle(Geom2d_BSplineCurve) line2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double s0, double s1)
{
    TColgp_Array1OfPnt2d poles(1, 2);
    poles.SetValue(1, gp_Pnt2d(a.x(), a.y()));
    poles.SetValue(2, gp_Pnt2d(b.x(), b.y()));
    TColStd_Array1OfReal knots(1, 2);
    knots.SetValue(1, s0);
    knots.SetValue(2, s1);
    TColStd_Array1OfInteger mults(1, 2);
    mults.SetValue(1, 2);
    mults.SetValue(2, 2);
    return new Geom2d_BSplineCurve(poles, knots, mults, 1);
}

bool sameMap(const ParameterMap& a, const ParameterMap& b)
{
    return a.kind == b.kind && a.start == b.start && a.span == b.span && a.spans == b.spans && a.period == b.period;
}

/// A map that is the identity on [lo, hi] once the values are shifted by a whole number of periods:
/// the shift, or nothing.
/// Whether [lo, hi] lies on a periodic identity map's closed range [start, start + period] (to 1e-9
/// of the period). Such parameters stay as they are: a seam's use at start + period would
/// otherwise move onto the other use, at start, and leave its wire open.
bool onPeriod(const ParameterMap& map, double lo, double hi)
{
    const double slack = 1e-9 * map.period;
    return map.kind == ParameterMap::Kind::Identity && map.period > 0 && lo >= map.start - slack &&
           hi <= map.start + map.period + slack;
}

std::optional<double> identityShift(const ParameterMap& map, double lo, double hi)
{
    if (map.isIdentity()) return 0.0;
    if (map.kind != ParameterMap::Kind::Identity) return std::nullopt;
    const double slack = 1e-9 * map.period;
    if (onPeriod(map, lo, hi)) return 0.0;
    const double k = std::floor((0.5 * (lo + hi) - map.start) / map.period);
    const double shift = -k * map.period;
    if (lo + shift < map.start - slack || hi + shift > map.start + map.period + slack) return std::nullopt;
    return shift;
}

struct PcurveResult {
    Handle(Geom2d_Curve) curve;
    bool fitted = false;
    double gap = 0; // the measured 3D distance of a fitted pcurve
};

class Writer {
public:
    explicit Writer(const Part& part) : part_(part), size_(part.bounds().diagonal().norm()) {}

    TopoDS_Shape build(CadWriteReport& report);

private:
    const Part& part_;
    double size_;
    BRep_Builder builder_;
    std::vector<TopoDS_Vertex> vertices_;
    std::vector<TopoDS_Edge> edges_;
    std::vector<double> edgeTolerance_;
    std::vector<TopoDS_Face> faces_;

    /// The edge's written parameter sigma of its file parameter t, and back.
    double sigma(const PartEdge& e, double t) const { return e.curve ? e.curve->map(t) : t; }
    double fileParameter(const PartEdge& e, double s) const { return e.curve ? e.curve->map.inverse(s) : s; }

    PcurveResult pcurve(const PartFace& face, const TrimCurve& trim, const PartEdge& edge) const;
    void raiseTolerances(CadWriteReport& report);
};

/// Every edge's tolerance raised to the largest distance, over 8 samples per knot span of its
/// curve and pcurves (at least 64), between its 3D curve and each face's surface at its pcurve,
/// times 1.05 (a file's tolerances often understate its gaps; Open CASCADE's check samples too).
void Writer::raiseTolerances(CadWriteReport& report)
{
    std::vector<double> measured(edges_.size(), 0.0);
    TopTools_DataMapOfShapeInteger index; // keyed like IsSame: orientation ignored
    for (std::size_t i = 0; i < edges_.size(); ++i) index.Bind(edges_[i], static_cast<int>(i));
    for (const TopoDS_Face& face : faces_) {
        const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
        for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
            const TopoDS_Edge& edge = TopoDS::Edge(ex.Current());
            double f = 0, l = 0, f2 = 0, l2 = 0;
            const Handle(Geom_Curve) curve = BRep_Tool::Curve(edge, f, l);
            const Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(edge, face, f2, l2);
            if (curve.IsNull() || pcurve.IsNull()) continue;
            int spans = 1;
            if (const auto b = Handle(Geom_BSplineCurve)::DownCast(curve)) spans += b->NbKnots();
            if (const auto b = Handle(Geom2d_BSplineCurve)::DownCast(pcurve)) spans += b->NbKnots();
            const int n = std::max(64, 8 * spans);
            double gap = 0;
            for (int k = 0; k <= n; ++k) {
                const double t = f + (l - f) * k / n;
                const gp_Pnt2d uv = pcurve->Value(t);
                gap = std::max(gap, surface->Value(uv.X(), uv.Y()).Distance(curve->Value(t)));
            }
            double& m = measured[static_cast<std::size_t>(index.Find(edge))];
            m = std::max(m, gap);
        }
    }
    for (std::size_t i = 0; i < edges_.size(); ++i) {
        const double needed = 1.05 * measured[i];
        if (needed > edgeTolerance_[i]) {
            ++report.raisedTolerances;
            edgeTolerance_[i] = needed;
        }
        report.maxTolerance = std::max(report.maxTolerance, edgeTolerance_[i]);
        builder_.UpdateEdge(edges_[i], edgeTolerance_[i]);
        // A vertex holds the tolerances of its edges.
        for (TopoDS_Iterator it(edges_[i]); it.More(); it.Next()) {
            const TopoDS_Vertex& v = TopoDS::Vertex(it.Value());
            if (BRep_Tool::Tolerance(v) < edgeTolerance_[i]) builder_.UpdateVertex(v, edgeTolerance_[i]);
        }
    }
}

PcurveResult Writer::pcurve(const PartFace& face, const TrimCurve& trim, const PartEdge& edge) const
{
    const MappedSurface& surface = face.surface.surface();
    const MappedCurve<2>& pc = trim.curve;
    const double s0 = sigma(edge, edge.first), s1 = sigma(edge, edge.last);
    const ParameterMap edgeMap = edge.curve ? edge.curve->map : ParameterMap::identity();
    // g(sigma) in the surface's NURBS parameters.
    auto onSurface = [](const ParameterMap& map, double x) { return onPeriod(map, x, x) ? x : map(x); };
    auto g = [&](double s) {
        const Eigen::Vector2d uv = pc.point(fileParameter(edge, s));
        return Eigen::Vector2d(onSurface(surface.mapU, uv.x()), onSurface(surface.mapV, uv.y()));
    };
    const Box<double, 2> range = pc.nurbs.controlBox();
    const auto shiftU = identityShift(surface.mapU, range.min().x(), range.max().x());
    const auto shiftV = identityShift(surface.mapV, range.min().y(), range.max().y());
    if (shiftU && shiftV && sameMap(pc.map, edgeMap) && pc.first == edge.first && pc.last == edge.last)
        return {Handle(Geom2d_Curve)(bsplineCurve2d(pc.nurbs, Eigen::Vector2d(*shiftU, *shiftV)))};

    // Linear in sigma? Checked at 8 points per arc of the edge's map and of the face's maps: within
    // one arc of each the composition is a Möbius function, which is linear once it agrees with a
    // line at three points.
    const Eigen::Vector2d a = g(s0), b = g(s1);
    const int arcs = std::max({1, edgeMap.spans, surface.mapU.spans, surface.mapV.spans});
    const double scale = std::max(1.0, std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff()));
    bool linear = true;
    for (int k = 1; k < 8 * arcs && linear; ++k) {
        const double x = double(k) / (8 * arcs), s = s0 + (s1 - s0) * x;
        linear = (g(s) - (a + (b - a) * x)).cwiseAbs().maxCoeff() <= 1e-12 * scale;
    }
    if (linear) return {Handle(Geom2d_Curve)(line2d(a, b, s0, s1))};

    // Fitted: cubic interpolation of samples, doubled until the 3D distance between the samples is
    // small enough.
    const double target = std::max(0.1 * edge.tolerance, 1e-7 * size_);
    PcurveResult best;
    best.gap = std::numeric_limits<double>::infinity();
    for (int n = 16 * arcs; n <= 4096 * arcs; n *= 2) {
        Handle(TColgp_HArray1OfPnt2d) points = new TColgp_HArray1OfPnt2d(1, n + 1);
        Handle(TColStd_HArray1OfReal) params = new TColStd_HArray1OfReal(1, n + 1);
        for (int i = 0; i <= n; ++i) {
            const double s = i == n ? s1 : s0 + (s1 - s0) * i / n;
            const Eigen::Vector2d p = g(s);
            points->SetValue(i + 1, gp_Pnt2d(p.x(), p.y()));
            params->SetValue(i + 1, s);
        }
        Geom2dAPI_Interpolate fit(points, params, false, 1e-12);
        fit.Perform();
        if (!fit.IsDone()) break;
        const Handle(Geom2d_BSplineCurve) c = fit.Curve();
        double gap = 0;
        for (int i = 0; i < n; ++i)
            for (double h : {0.25, 0.5, 0.75}) {
                const double s = s0 + (s1 - s0) * (i + h) / n;
                const gp_Pnt2d q = c->Value(s);
                gap = std::max(gap, (surface.nurbs.evaluate(surface.nurbs.clampU(q.X()), surface.nurbs.clampV(q.Y())) -
                                     surface.nurbs.evaluate(g(s).x(), g(s).y()))
                                        .norm());
            }
        if (gap < best.gap) best = PcurveResult{Handle(Geom2d_Curve)(c), true, gap};
        if (gap <= target) break;
    }
    if (best.curve.IsNull()) throw Error("Open CASCADE could not fit the trim of edge " + std::to_string(trim.edge + 1));
    return best;
}

/// The signed area of a closed polygon (positive counter-clockwise).
double signedArea(const std::vector<Eigen::Vector2d>& polygon)
{
    double twice = 0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Eigen::Vector2d& a = polygon[i];
        const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
        twice += a.x() * b.y() - a.y() * b.x();
    }
    return 0.5 * twice;
}

TopoDS_Shape Writer::build(CadWriteReport& report)
{
    for (const PartVertex& v : part_.vertices) {
        TopoDS_Vertex out;
        builder_.MakeVertex(out, gp_Pnt(v.point.x(), v.point.y(), v.point.z()), std::max(v.tolerance, 1e-7));
        vertices_.push_back(out);
    }
    for (std::size_t i = 0; i < part_.edges.size(); ++i) {
        const PartEdge& e = part_.edges[i];
        TopoDS_Edge out;
        if (e.curve) {
            if (e.curve->nurbs.degree() > Geom_BSplineCurve::MaxDegree())
                throw Error("edge " + std::to_string(i + 1) + ": degree " + std::to_string(e.curve->nurbs.degree()) +
                            " is over Open CASCADE's " + std::to_string(Geom_BSplineCurve::MaxDegree()));
            builder_.MakeEdge(out, bsplineCurve(e.curve->nurbs), std::max(e.tolerance, 1e-7));
        } else {
            builder_.MakeEdge(out);
            builder_.UpdateEdge(out, std::max(e.tolerance, 1e-7));
        }
        builder_.Degenerated(out, e.degenerate);
        if (e.start >= 0) builder_.Add(out, vertices_[static_cast<std::size_t>(e.start)].Oriented(TopAbs_FORWARD));
        if (e.end >= 0) builder_.Add(out, vertices_[static_cast<std::size_t>(e.end)].Oriented(TopAbs_REVERSED));
        builder_.Range(out, sigma(e, e.first), sigma(e, e.last));
        edges_.push_back(out);
        edgeTolerance_.push_back(std::max(e.tolerance, 1e-7));
    }
    for (std::size_t f = 0; f < part_.faces.size(); ++f) {
        const PartFace& face = part_.faces[f];
        const NurbsSurface<double, 3>& nurbs = face.surface.surface().nurbs;
        const std::string where = "face " + std::to_string(f + 1);
        if (std::max(nurbs.degreeU(), nurbs.degreeV()) > Geom_BSplineSurface::MaxDegree())
            throw Error(where + ": degree " + std::to_string(nurbs.degreeU()) + " x " + std::to_string(nurbs.degreeV()) +
                        " is over Open CASCADE's " + std::to_string(Geom_BSplineSurface::MaxDegree()));
        TopoDS_Face out;
        builder_.MakeFace(out, bsplineSurface(nurbs), std::max(face.tolerance, 1e-7));
        // A seam (an edge twice in the face) gets both pcurves at once: the forward use's first.
        std::map<int, std::pair<Handle(Geom2d_Curve), Handle(Geom2d_Curve)>> seams;
        std::map<int, int> uses;
        for (const TrimLoop& loop : face.surface.loops())
            for (const TrimCurve& c : loop.curves) ++uses[c.edge];
        const auto& loops = face.surface.loops();
        const Box<double, 2>& domain = face.surface.domain();
        const double domainArea = domain.sizes().prod();
        for (std::size_t l = 0; l < loops.size(); ++l) {
            const TrimLoop& loop = loops[l];
            // Open CASCADE wants the outer loop counter-clockwise in the forward face's parameters
            // and the holes clockwise; a part's loops may run either way (a trimmed surface written
            // by hand: TrimmedSurface's classification does not depend on it). A loop that
            // encloses no area (a circle around a periodic direction) keeps its direction.
            const double area = signedArea(face.surface.polygons()[l]) * (face.reversed ? -1 : 1);
            const bool flip = std::abs(area) > 1e-9 * domainArea && (area > 0) != (l == 0);
            TopoDS_Wire wire;
            builder_.MakeWire(wire);
            for (const TrimCurve& c : loop.curves) {
                if (c.edge < 0) throw Error(where + ": a trim lies on no edge");
                const auto e = static_cast<std::size_t>(c.edge);
                PcurveResult pc = pcurve(face, c, part_.edges[e]);
                if (pc.fitted) {
                    ++report.fittedPcurves;
                    report.maxPcurveGap = std::max(report.maxPcurveGap, pc.gap);
                    edgeTolerance_[e] = std::max(edgeTolerance_[e], pc.gap);
                }
                // The part's orientations are as seen from the oriented face (Open CASCADE's
                // explorers compose them); the face is built forward, so a reversed face's edges
                // flip back.
                const bool reversed = (c.reversed != face.reversed) != flip;
                if (uses[c.edge] == 2) {
                    auto& pair = seams[c.edge];
                    (reversed ? pair.second : pair.first) = pc.curve;
                    if (!pair.first.IsNull() && !pair.second.IsNull())
                        builder_.UpdateEdge(edges_[e], pair.first, pair.second, out, edgeTolerance_[e]);
                } else {
                    builder_.UpdateEdge(edges_[e], pc.curve, out, edgeTolerance_[e]);
                }
                builder_.Add(wire, edges_[e].Oriented(reversed ? TopAbs_REVERSED : TopAbs_FORWARD));
            }
            builder_.Add(out, wire);
        }
        faces_.push_back(TopoDS::Face(out.Oriented(face.reversed ? TopAbs_REVERSED : TopAbs_FORWARD)));
    }
    raiseTolerances(report);
    // An edge the file gave only pcurves for gets its 3D curve from them.
    for (std::size_t i = 0; i < edges_.size(); ++i)
        if (!part_.edges[i].curve && !part_.edges[i].degenerate) BRepLib::BuildCurve3d(edges_[i], edgeTolerance_[i]);
    std::vector<TopoDS_Shell> shells;
    for (const PartShell& s : part_.shells) {
        TopoDS_Shell shell;
        builder_.MakeShell(shell);
        for (int f : s.faces) builder_.Add(shell, faces_[static_cast<std::size_t>(f)]);
        shells.push_back(shell);
    }
    std::vector<char> shellUsed(shells.size(), 0);
    TopoDS_Compound compound;
    builder_.MakeCompound(compound);
    std::vector<TopoDS_Shape> roots;
    for (const PartSolid& s : part_.solids) {
        TopoDS_Solid solid;
        builder_.MakeSolid(solid);
        for (int sh : s.shells) {
            builder_.Add(solid, shells[static_cast<std::size_t>(sh)]);
            shellUsed[static_cast<std::size_t>(sh)] = 1;
        }
        roots.push_back(solid);
    }
    for (std::size_t i = 0; i < shells.size(); ++i)
        if (!shellUsed[i]) roots.push_back(shells[i]);
    for (int f : part_.looseFaces()) roots.push_back(faces_[static_cast<std::size_t>(f)]);
    if (roots.size() == 1) return roots.front();
    for (const TopoDS_Shape& r : roots) builder_.Add(compound, r);
    return compound;
}

/// Open CASCADE's name of freeform's unit.
const char* occtUnit(const std::string& units)
{
    static const std::map<std::string, const char*> names = {
        {"mm", "MM"}, {"m", "M"},       {"cm", "CM"},   {"um", "UM"},  {"km", "KM"},
        {"in", "INCH"}, {"ft", "FT"}, {"mi", "MI"}, {"mil", "MIL"}, {"uin", "UIN"}};
    const auto it = names.find(units);
    return it == names.end() ? "MM" : it->second;
}

} // namespace

int cadMaxDegree()
{
    return std::min(Geom_BSplineCurve::MaxDegree(), Geom_BSplineSurface::MaxDegree());
}

TopoDS_Shape shapeFromPart(const Part& part, CadWriteReport* report)
{
    CadWriteReport local;
    CadWriteReport& r = report ? *report : local;
    r = {};
    try {
        TopoDS_Shape shape = Writer(part).build(r);
        r.valid = BRepCheck_Analyzer(shape).IsValid();
        return shape;
    } catch (const Standard_Failure& e) {
        throw Error(std::string("Open CASCADE failed: ") + e.GetMessageString());
    }
}

CadWriteReport writeCadFile(const Part& part, const std::string& path)
{
    const std::string ext = occt::lower(std::filesystem::path(path).extension().string());
    const bool step = ext == ".step" || ext == ".stp", iges = ext == ".iges" || ext == ".igs", brep = ext == ".brep";
    if (!step && !iges && !brep) throw Error(path + ": not a STEP (.step .stp), IGES (.iges .igs) or BRep (.brep) file name");
    // A BRep file has no unit (it is read as millimetres): a part in another unit would come back
    // scaled, so it is refused rather than written.
    if (brep && part.units != "mm")
        throw Error(path + ": a BRep file has no unit and is read as millimetres; the part is in " + part.units +
                    ": write it as STEP or IGES, which keep the unit");
    occt::MessageScope messages;
    CadWriteReport report;
    TopoDS_Shape shape;
    try {
        shape = shapeFromPart(part, &report);
    } catch (const Error& e) {
        throw Error(path + ": " + e.what());
    }
    // Written beside the target and renamed into place, so a failure leaves nothing behind.
    const std::filesystem::path target(path);
    std::string name = target.filename().string();
    name.insert(0, 1, '.');
    name.append(".writing");
    name.append(ext);
    const std::filesystem::path temporary = target.parent_path() / name;
    const char* unit = occtUnit(part.units);
    try {
        occt::CascadeUnit scope(unit);
        bool written = false;
        if (brep) {
            written = BRepTools::Write(shape, temporary.string().c_str());
        } else if (step) {
            STEPControl_Writer writer;
            Interface_Static::SetCVal("write.step.unit", unit);
            written = writer.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone &&
                      writer.Write(temporary.string().c_str()) == IFSelect_RetDone;
        } else {
            IGESControl_Controller::Init();
            IGESControl_Writer writer(unit, 1); // 1: B-rep entities (shells and solids), not trimmed surfaces only
            written = writer.AddShape(shape);
            if (written) {
                // IGESControl_Writer::Write keeps 10 significant digits of every real; the model is
                // printed here with 17, so that every double reads back as itself.
                writer.ComputeModel();
                IGESData_IGESWriter printer(writer.Model());
                printer.FloatWriter().SetFormat("%.17E");
                printer.SendModel(IGESSelect_WorkLibrary::DefineProtocol());
                std::ofstream file(temporary, std::ios::binary);
                written = printer.Print(file) && file.flush().good();
            }
        }
        if (!written) {
            std::filesystem::remove(temporary);
            throw Error(path + ": Open CASCADE could not write the part" + messages.firstMessage());
        }
        std::filesystem::rename(temporary, target);
    } catch (const Standard_Failure& e) {
        std::filesystem::remove(temporary);
        throw Error(path + ": Open CASCADE failed: " + e.GetMessageString());
    } catch (const std::filesystem::filesystem_error& e) {
        std::filesystem::remove(temporary);
        throw Error(path + ": " + e.what());
    }
    return report;
}

} // namespace freeform
