// OBJ free-form geometry written from a document (see io/obj_freeform.h and docs/surfaces.md).

#include "freeform/core/format.h"
#include "freeform/io/obj_freeform.h"

#include <array>
#include <string>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/io/file.h"

namespace freeform {

namespace {

void writeVertices(std::string& out, const PointColumns& pts, const std::vector<double>& weights = {})
{
    for (Eigen::Index k = 0; k < pts.cols(); ++k) {
        out += "v";
        for (int c = 0; c < 3; ++c) {
            out += ' ';
            out += formatNumber(c < pts.rows() ? pts(c, k) : 0.0);
        }
        if (!weights.empty()) {
            out += ' ';
            out += formatNumber(weights[static_cast<std::size_t>(k)]);
        }
        out += "\n";
    }
}

/// " base+1 base+2 ... base+count": references to the next count vertices (v or vp).
std::string references(long base, long count)
{
    std::string r;
    for (long k = 1; k <= count; ++k) {
        r += ' ';
        r += std::to_string(base + k);
    }
    return r;
}

std::string numberList(const std::vector<double>& values)
{
    std::string r;
    for (double v : values) {
        r += ' ';
        r += formatNumber(v);
    }
    return r;
}

/// A NURBS surface's vertices and its element, over range (u0 u1 v0 v1), with `trims` (trim and
/// hole statements) before its end.
void writeNurbsSurface(std::string& out, long& base, const NurbsSurfaceData& ns, const std::array<double, 4>& range,
                       const std::string& trims)
{
    const int p = ns.degree[0], q = ns.degree[1], rows = ns.rows, cols = ns.cols;
    PointColumns ordered(3, rows * cols);
    std::vector<double> w(ns.weights.empty() ? 0 : static_cast<std::size_t>(rows * cols));
    for (int j = 0; j < cols; ++j)
        for (int i = 0; i < rows; ++i) {
            ordered.col(j * rows + i) = ns.points.col(i * cols + j);
            if (!w.empty()) w[static_cast<std::size_t>(j * rows + i)] = ns.weights[static_cast<std::size_t>(i * cols + j)];
        }
    writeVertices(out, ordered, w);
    out += std::string(w.empty() ? "cstype bspline" : "cstype rat bspline") + "\ndeg " + std::to_string(p) + " " + std::to_string(q) +
           "\nsurf" + numberList({range.begin(), range.end()}) + references(base, ordered.cols()) + "\nparm u" + numberList(ns.knots[0]) +
           "\nparm v" + numberList(ns.knots[1]) + "\n" + trims + "end\n";
    base += ordered.cols();
}

/// A trimmed surface: each trim curve as a curv2 on its own vp lines, then the surface with one
/// `trim` statement (the outer loop) and a `hole` per inner loop, each curve as "first last k"
/// (reversed: "last first k"). Parameter maps have no OBJ form: an Error names them.
void writeTrimmedSurface(std::string& out, long& base, long& curves2, long& vps, const TrimmedSurfaceData& ts, const std::string& where)
{
    if (!ts.map[0].isIdentity() || !ts.map[1].isIdentity())
        throw Error(where + ": field \"" + std::string(ts.map[0].isIdentity() ? "map_v" : "map_u") +
                    "\": OBJ has no parameter maps (a CAD face's angles; write the part as STEP or IGES, or the document as JSON)");
    std::string trims;
    for (std::size_t l = 0; l < ts.loops.size(); ++l) {
        trims += l == 0 ? "trim" : "hole";
        for (std::size_t k = 0; k < ts.loops[l].size(); ++k) {
            const TrimCurveData& t = ts.loops[l][k];
            const NurbsCurveData& c = t.curve.nurbs;
            if (!t.curve.map.isIdentity())
                throw Error(where + ": field \"loops[" + std::to_string(l) + "][" + std::to_string(k) +
                            "].map\": OBJ has no parameter maps (write the document as JSON)");
            for (Eigen::Index i = 0; i < c.points.cols(); ++i) {
                out += "vp";
                std::vector<double> values{c.points(0, i), c.points(1, i)};
                if (!c.weights.empty()) values.push_back(c.weights[static_cast<std::size_t>(i)]);
                out += numberList(values);
                out += '\n';
            }
            out += std::string(c.weights.empty() ? "cstype bspline" : "cstype rat bspline") + "\ndeg " + std::to_string(c.degree) +
                   "\ncurv2" + references(vps, c.points.cols()) + "\nparm u" + numberList(c.knots) + "\nend\n";
            vps += c.points.cols();
            ++curves2;
            trims += t.reversed ? numberList({t.curve.last, t.curve.first}) : numberList({t.curve.first, t.curve.last});
            trims += ' ';
            trims += std::to_string(curves2);
        }
        trims += "\n";
    }
    writeNurbsSurface(out, base, ts.surface, ts.domain, trims);
}

} // namespace

std::string formatObjFreeform(const Document& document, const std::string& objectName)
{
    std::string out = "# OBJ free-form geometry written by freeform\n";
    long base = 0;    // vertices written so far
    long vps = 0;     // parameter vertices (vp) written so far
    long curves2 = 0; // curv2 elements written so far
    bool any = false;
    for (const DocumentObject& o : document.objects) {
        if (!objectName.empty() && o.name != objectName) continue;
        any = true;
        const std::string where = document.source + ": object \"" + o.name + "\"";
        if (o.name.empty() || o.name.find_first_of(" \t\r\n#") != std::string::npos)
            throw Error(where + ": the name cannot be written as an OBJ object name (no spaces or #)");
        auto refs = [&](long count) { return references(base, count); };
        if (const auto* c = std::get_if<BezierCurveData>(&o.data)) {
            const long count = c->points.cols();
            out += "o " + o.name + "\n";
            writeVertices(out, c->points);
            out += std::string("cstype bezier\ndeg ") + std::to_string(count - 1) + "\ncurv 0 1" + refs(count) + "\nparm u 0 1\nend\n";
            base += count;
        } else if (const auto* s = std::get_if<BezierSplineData>(&o.data)) {
            if (s->closed)
                throw Error(where + ": a closed bezier_spline has no OBJ free-form form (OBJ Bézier curves are open)");
            const long count = s->points.cols();
            const long segments = (count - 1) / s->degree;
            std::string parm = "parm u 0";
            double t = 0;
            for (long k = 0; k < segments; ++k) {
                t += s->intervals.empty() ? 1.0 : s->intervals[static_cast<std::size_t>(k)];
                parm += ' ';
                parm += formatNumber(t);
            }
            out += "o " + o.name + "\n";
            writeVertices(out, s->points);
            out += std::string("cstype bezier\ndeg ") + std::to_string(s->degree) + std::string("\ncurv 0 ") + formatNumber(t) + refs(count) + "\n" +
                   parm + "\nend\n";
            base += count;
        } else if (const auto* p = std::get_if<BezierSurfaceData>(&o.data)) {
            const int m = p->degree[0], n = p->degree[1];
            // u varies fastest: reference k is point (k mod (m+1), k div (m+1)).
            PointColumns ordered(3, (m + 1) * (n + 1));
            for (int j = 0; j <= n; ++j)
                for (int i = 0; i <= m; ++i) ordered.col(j * (m + 1) + i) = p->points.col(i * (n + 1) + j);
            out += "o " + o.name + "\n";
            writeVertices(out, ordered);
            out += std::string("cstype bezier\ndeg ") + std::to_string(m) + std::string(" ") + std::to_string(n) + "\nsurf 0 1 0 1" +
                   refs(ordered.cols()) + "\nparm u 0 1\nparm v 0 1\nend\n";
            base += ordered.cols();
        } else if (const auto* rc = std::get_if<RationalBezierCurveData>(&o.data)) {
            const long count = rc->points.cols();
            out += "o " + o.name + "\n";
            writeVertices(out, rc->points, rc->weights);
            out += std::string("cstype rat bezier\ndeg ") + std::to_string(count - 1) + "\ncurv 0 1" + refs(count) + "\nparm u 0 1\nend\n";
            base += count;
        } else if (const auto* rp = std::get_if<RationalBezierSurfaceData>(&o.data)) {
            const int m = rp->degree[0], n = rp->degree[1];
            PointColumns ordered(3, (m + 1) * (n + 1));
            std::vector<double> w(static_cast<std::size_t>((m + 1) * (n + 1)));
            for (int j = 0; j <= n; ++j)
                for (int i = 0; i <= m; ++i) {
                    ordered.col(j * (m + 1) + i) = rp->points.col(i * (n + 1) + j);
                    w[static_cast<std::size_t>(j * (m + 1) + i)] = rp->weights[static_cast<std::size_t>(i * (n + 1) + j)];
                }
            out += "o " + o.name + "\n";
            writeVertices(out, ordered, w);
            out += std::string("cstype rat bezier\ndeg ") + std::to_string(m) + std::string(" ") + std::to_string(n) + "\nsurf 0 1 0 1" +
                   refs(ordered.cols()) + "\nparm u 0 1\nparm v 0 1\nend\n";
            base += ordered.cols();
        } else if (const auto* nc = std::get_if<NurbsCurveData>(&o.data)) {
            const long count = nc->points.cols();
            const int p = nc->degree;
            // curv gives the whole domain [knot p, knot count]; parm u the knot vector.
            out += "o " + o.name + "\n";
            writeVertices(out, nc->points, nc->weights);
            out += std::string(nc->weights.empty() ? "cstype bspline" : "cstype rat bspline") + "\ndeg " + std::to_string(p) +
                   "\ncurv " + formatNumber(nc->knots[static_cast<std::size_t>(p)]) + " " +
                   formatNumber(nc->knots[static_cast<std::size_t>(count)]) + refs(count) + "\nparm u" + numberList(nc->knots) +
                   "\nend\n";
            base += count;
        } else if (const auto* ns = std::get_if<NurbsSurfaceData>(&o.data)) {
            const auto& ku = ns->knots[0];
            const auto& kv = ns->knots[1];
            const auto p = static_cast<std::size_t>(ns->degree[0]), q = static_cast<std::size_t>(ns->degree[1]);
            out += "o " + o.name + "\n";
            writeNurbsSurface(out, base, *ns, {ku[p], ku[ku.size() - 1 - p], kv[q], kv[kv.size() - 1 - q]}, "");
        } else if (const auto* ts = std::get_if<TrimmedSurfaceData>(&o.data)) {
            out += "o " + o.name + "\n";
            writeTrimmedSurface(out, base, curves2, vps, *ts, where);
        } else {
            throw Error(where + ": type " + objectType(o.data) +
                        " has no OBJ free-form form (bezier_curve, open bezier_spline, bezier_surface, rational_bezier_curve, "
                        "rational_bezier_surface, nurbs_curve, nurbs_surface and trimmed_surface do)");
        }
    }
    if (!objectName.empty() && !any) document.object(objectName); // throws, listing the names
    return out;
}
void writeObjFreeform(const Document& document, const std::string& path, const std::string& objectName)
{
    const std::string text = formatObjFreeform(document, objectName);
    writeFileAtomically(path, text);
}

} // namespace freeform
