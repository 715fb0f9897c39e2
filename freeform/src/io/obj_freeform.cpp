// OBJ free-form Bézier geometry (see io/obj_freeform.h and docs/surfaces.md).

#include "freeform/core/format.h"
#include "freeform/io/obj_freeform.h"

#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include "freeform/core/bernstein.h"
#include "freeform/core/error.h"
#include "freeform/curve/knot_vector.h"
#include "freeform/io/file.h"

namespace freeform {

namespace {

/// One curve of a trim or hole statement: curv2 number `curve` (0-based) from `first` to `last`.
struct TrimRef {
    double first = 0, last = 0;
    int curve = 0;
    int line = 0;
};

struct Element {
    bool surface = false;
    bool curve2 = false;      // a curv2 (its indices are vp references)
    int line = 0;
    std::string name;
    int du = 0, dv = -1;
    bool rational = false, bspline = false;
    std::array<double, 4> range{}; // curv u0 u1 / surf s0 s1 t0 t1
    std::vector<int> indices; // 0-based
    std::vector<double> parmU, parmV;
    std::vector<std::vector<TrimRef>> loops; // trim (the outer loop) first, then each hole
    bool outer = false;                      // a trim statement was given (loops[0])
};

/// A curv2 element: a 2D NURBS curve in a surface's parameters, and the group name it was under.
struct Curve2 {
    NurbsCurveData curve;
    std::string group;
    bool used = false;
};

/// The knot vector of Bézier segments with the given ends: every break of multiplicity d, the
/// ends d + 1 times.
std::vector<double> bezierKnots(const std::vector<double>& ends, int d)
{
    std::vector<double> k(static_cast<std::size_t>(d + 1), ends.front());
    for (std::size_t i = 1; i + 1 < ends.size(); ++i) k.insert(k.end(), static_cast<std::size_t>(d), ends[i]);
    k.insert(k.end(), static_cast<std::size_t>(d + 1), ends.back());
    return k;
}

class ObjReader {
public:
    ObjReader(const std::string& source) : source_(source) {}

    [[noreturn]] void fail(int line, const std::string& message) const
    {
        throw Error(source_ + std::string(": line ") + std::to_string(line) + ": " + message);
    }

    double number(const std::string& text, int line) const
    {
        double v = 0;
        const char* first = text.data();
        const char* last = first + text.size();
        if (first != last && *first == '+') ++first;
        const auto [ptr, ec] = std::from_chars(first, last, v);
        if (ec == std::errc::result_out_of_range) fail(line, "\"" + text + "\" is out of range");
        if (ec != std::errc() || ptr != last || !std::isfinite(v)) fail(line, "\"" + text + "\" is not a finite number");
        return v;
    }

    int integer(const std::string& text, int line) const
    {
        int v = 0;
        const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || ptr != text.data() + text.size()) fail(line, "\"" + text + "\" is not an integer");
        return v;
    }

    /// A vertex reference "i", "i/t", "i/t/n" or "i//n" (1-based, negative: relative).
    int vertexIndex(const std::string& text, int line) const
    {
        const int i = integer(text.substr(0, text.find('/')), line);
        const int count = static_cast<int>(vertices_.size());
        const int resolved = i > 0 ? i - 1 : count + i;
        if (i == 0 || resolved < 0 || resolved >= count)
            fail(line, std::string("vertex index ") + std::to_string(i) + std::string(" is out of range (") + std::to_string(count) + " vertices so far)");
        return resolved;
    }

    /// A parameter vertex reference (1-based, negative: relative) of a curv2: a vp with u and v.
    int paramIndex(const std::string& text, int line) const
    {
        const int i = integer(text, line);
        const int count = static_cast<int>(params_.size());
        const int resolved = i > 0 ? i - 1 : count + i;
        if (i == 0 || resolved < 0 || resolved >= count)
            fail(line, "parameter vertex index " + std::to_string(i) + " is out of range (" + std::to_string(count) + " vp so far)");
        if (paramLines_[static_cast<std::size_t>(resolved)] < 0)
            fail(line, "parameter vertex " + std::to_string(i) + " (line " + std::to_string(-paramLines_[static_cast<std::size_t>(resolved)]) +
                           ") has u alone; a trimming curve needs u and v");
        return resolved;
    }

    Document parse(const std::string& text)
    {
        std::istringstream in(text);
        std::string raw;
        int number = 0;
        while (std::getline(in, raw)) {
            ++number;
            const int line = number;
            // Continuation lines end with a backslash.
            while (!raw.empty() && (raw.back() == '\\' || raw.back() == '\r')) {
                if (raw.back() == '\r') {
                    raw.pop_back();
                    continue;
                }
                raw.pop_back();
                std::string next;
                if (!std::getline(in, next)) break;
                ++number;
                raw += ' ' + next;
            }
            const auto hash = raw.find('#');
            if (hash != std::string::npos) raw.erase(hash);
            std::istringstream words(raw);
            std::vector<std::string> t;
            for (std::string w; words >> w;) t.push_back(w);
            if (!t.empty()) statement(t, line);
        }
        if (open_) fail(open_->line, std::string(open_->surface ? "surf" : open_->curve2 ? "curv2" : "curv") + " element has no \"end\"");
        // A curv2 no surface trims with is kept as a 2D curve of its own (nothing is dropped).
        for (Curve2& c : curves2_)
            if (!c.used) {
                name_ = c.group;
                objects_.push_back(DocumentObject{nextName(false), std::move(c.curve), ""});
            }
        Document doc;
        doc.source = source_;
        doc.objects = std::move(objects_);
        return doc;
    }

private:
    void statement(const std::vector<std::string>& t, int line)
    {
        const std::string& key = t[0];
        if (key == "v") {
            if (t.size() < 4 || t.size() > 7) fail(line, "a vertex needs 3 coordinates (x y z [w])");
            vertices_.emplace_back(number(t[1], line), number(t[2], line), number(t[3], line));
            for (std::size_t k = 4; k < t.size(); ++k) number(t[k], line);
            // The 4th coordinate is the weight of rational curves and surfaces (default 1).
            weights_.push_back(t.size() >= 5 ? number(t[4], line) : 1.0);
            weightLines_.push_back(line);
        } else if (key == "vp") {
            // A point in a curve's or surface's parameters: u [v [w]] (curv2 needs u and v).
            if (t.size() < 2 || t.size() > 4) fail(line, "a parameter vertex has 1 to 3 coordinates (u [v [w]])");
            params_.emplace_back(number(t[1], line), t.size() >= 3 ? number(t[2], line) : 0.0);
            paramWeights_.push_back(t.size() == 4 ? number(t[3], line) : 1.0);
            paramLines_.push_back(t.size() >= 3 ? line : -line); // negative: u alone
        } else if (key == "o" || key == "g") {
            if (t.size() >= 2) name_ = t[1];
        } else if (key == "cstype") {
            const bool rat = t.size() == 3 && t[1] == "rat";
            if (t.size() != 2 && !rat) fail(line, "expected \"cstype [rat] bezier|bspline\"");
            const std::string& type = t.back();
            if (type != "bezier" && type != "bspline")
                fail(line, "curve type \"" + std::string(rat ? "rat " : "") + type +
                               "\" is not supported (bezier, rat bezier, bspline, rat bspline)");
            cstype_ = true;
            rational_ = rat;
            bspline_ = type == "bspline";
        } else if (key == "deg") {
            if (t.size() != 2 && t.size() != 3) fail(line, "expected \"deg du\" or \"deg du dv\"");
            du_ = integer(t[1], line);
            dv_ = t.size() == 3 ? integer(t[2], line) : -1;
            for (std::size_t k = 1; k < t.size(); ++k) {
                const int d = k == 1 ? du_ : dv_;
                if (d < 1 || d > kMaxDegree)
                    fail(line, std::string("degree ") + std::to_string(d) + std::string(" is outside 1..") + std::to_string(kMaxDegree));
            }
        } else if (key == "curv" || key == "surf" || key == "curv2") {
            if (open_) fail(line, key + std::string(" inside the element of line ") + std::to_string(open_->line) + " (missing \"end\")");
            if (!cstype_) fail(line, key + " before \"cstype bezier\"");
            if (du_ < 1) fail(line, key + " before \"deg\"");
            const bool surface = key == "surf", curve2 = key == "curv2";
            if (surface && dv_ < 1) fail(line, "surf needs two degrees (\"deg du dv\")");
            const std::size_t params = surface ? 4 : curve2 ? 0 : 2;
            if (t.size() < params + 3)
                fail(line, key + (curve2 ? ": expected at least two parameter vertices" : ": expected the parameter range and at least two control points"));
            Element e;
            for (std::size_t k = 1; k <= params; ++k) e.range[k - 1] = number(t[k], line);
            e.rational = rational_;
            e.bspline = bspline_;
            e.surface = surface;
            e.curve2 = curve2;
            e.line = line;
            e.du = du_;
            e.dv = dv_;
            for (std::size_t k = params + 1; k < t.size(); ++k) e.indices.push_back(curve2 ? paramIndex(t[k], line) : vertexIndex(t[k], line));
            e.name = curve2 ? name_ : nextName(surface); // a curv2 is named only if no surface takes it
            open_ = std::move(e);
        } else if (key == "parm") {
            if (!open_) fail(line, "parm outside a curv, curv2 or surf element");
            if (t.size() < 4 || (t[1] != "u" && t[1] != "v")) fail(line, "expected \"parm u|v p0 p1 ...\"");
            std::vector<double>& p = t[1] == "u" ? open_->parmU : open_->parmV;
            p.clear();
            for (std::size_t k = 2; k < t.size(); ++k) {
                p.push_back(number(t[k], line));
                // Bézier parm values are segment ends (increasing); B-spline ones are knots (non-decreasing).
                if (p.size() > 1 && (open_->bspline ? p.back() < p[p.size() - 2] : !(p.back() > p[p.size() - 2])))
                    fail(line, open_->bspline ? "parm knots must not decrease" : "parm values must increase");
            }
        } else if (key == "end") {
            if (!open_) fail(line, "end without a curv, curv2 or surf element");
            if (open_->curve2) finishCurve2(*open_, line);
            else finish(*open_, line);
            open_.reset();
        } else if (key == "trim" || key == "hole") {
            trimStatement(t, line);
        } else if (key == "scrv" || key == "sp") {
            fail(line, "special curves and points (" + key + ") are not supported");
        } else if (key == "bmat" || key == "step" || key == "con") {
            fail(line, "\"" + key + "\" is not supported (Bézier and B-spline curves and surfaces only)");
        } else if (key == "vt" || key == "vn" || key == "f" || key == "l" || key == "p" || key == "s" ||
                   key == "usemtl" || key == "mtllib" || key == "ctech" || key == "stech" || key == "mg" ||
                   key == "lod" || key == "bevel" || key == "c_interp" || key == "d_interp" || key == "shadow_obj" ||
                   key == "trace_obj") {
            // Polygonal data and display attributes: not free-form geometry, skipped.
        } else {
            fail(line, "unknown statement \"" + key + "\"");
        }
    }

    std::string nextName(bool surface)
    {
        std::string base = name_;
        if (base.empty()) base = std::string(surface ? "surface" : "curve") + std::to_string(++(surface ? surfaces_ : curves_));
        const int used = ++usedNames_[base];
        return used == 1 ? base : base + std::string("_") + std::to_string(used);
    }

    /// The weights of the element's points (rational types), checked positive.
    std::vector<double> weightsOf(const Element& e) const
    {
        std::vector<double> w;
        for (int i : e.indices) {
            const auto k = static_cast<std::size_t>(i);
            const double x = e.curve2 ? paramWeights_[k] : weights_[k];
            if (!(x > 0))
                fail(e.line, std::string(e.curve2 ? "parameter vertex " : "vertex ") + std::to_string(i + 1) + " (line " +
                                 std::to_string(e.curve2 ? paramLines_[k] : weightLines_[k]) + ") has weight " + formatNumber(x) +
                                 "; rational weights must be positive");
            w.push_back(x);
        }
        return w;
    }

    /// A B-spline knot vector from parm: count + degree + 1 knots, validated, and (whole) the curv/surf
    /// range must be the whole domain [knot p, knot count].
    std::vector<double> knotsOf(const Element& e, const std::vector<double>& parm, char dir, int degree, int count, int line,
                                double r0, double r1, bool whole = true) const
    {
        const std::string name = std::string("parm ") + dir;
        if (parm.empty()) fail(e.line, std::string("a bspline element needs \"") + name + "\" (its knot vector)");
        const std::size_t need = static_cast<std::size_t>(count + degree + 1);
        if (parm.size() != need)
            fail(line, name + " has " + std::to_string(parm.size()) + " knots, " + std::to_string(count) + " control points of degree " +
                           std::to_string(degree) + " need " + std::to_string(need));
        KnotVector<double>(parm, degree, source_ + ": line " + std::to_string(line) + ": " + name); // throws naming the knot
        const double a = parm[static_cast<std::size_t>(degree)], b = parm[static_cast<std::size_t>(count)];
        if (whole && (r0 != a || r1 != b))
            fail(e.line, std::string("the parameter range ") + formatNumber(r0) + " " + formatNumber(r1) + " in " + dir +
                             " is not the knot domain " + formatNumber(a) + " " + formatNumber(b) +
                             " (a part of a B-spline is not supported)");
        return parm;
    }

    void finishBspline(const Element& e, int line, DocumentObject& object, bool whole = true)
    {
        const int count = static_cast<int>(e.indices.size());
        std::vector<double> w;
        if (e.rational) w = weightsOf(e);
        if (!e.surface) {
            if (!e.parmV.empty()) fail(line, "a curve has no parm v");
            const int p = e.du;
            if (count < p + 1)
                fail(e.line, std::to_string(count) + std::string(" control points are too few for degree ") + std::to_string(p));
            NurbsCurveData c;
            c.degree = p;
            c.knots = knotsOf(e, e.parmU, 'u', p, count, line, e.range[0], e.range[1]);
            c.points.resize(3, count);
            for (int k = 0; k < count; ++k) c.points.col(k) = vertices_[static_cast<std::size_t>(e.indices[static_cast<std::size_t>(k)])];
            c.weights = std::move(w);
            object.data = std::move(c);
            return;
        }
        const int p = e.du, q = e.dv;
        if (e.parmU.empty() || e.parmV.empty())
            fail(e.line, "a bspline surf needs \"parm u\" and \"parm v\" (its knot vectors)");
        // The grid size follows from the knot counts: rows = |parm u| - p - 1, cols = |parm v| - q - 1.
        const int rows = static_cast<int>(e.parmU.size()) - p - 1, cols = static_cast<int>(e.parmV.size()) - q - 1;
        if (rows < p + 1 || cols < q + 1 || rows * cols != count)
            fail(e.line, std::to_string(count) + std::string(" control points do not fit parm u (") + std::to_string(e.parmU.size()) +
                             " knots) and parm v (" + std::to_string(e.parmV.size()) + " knots) of degree (" + std::to_string(p) + ", " +
                             std::to_string(q) + "), which need (|parm u| - " + std::to_string(p + 1) + ")(|parm v| - " +
                             std::to_string(q + 1) + ") points, at least " + std::to_string(p + 1) + " by " + std::to_string(q + 1));
        NurbsSurfaceData s;
        s.degree = {p, q};
        s.knots[0] = knotsOf(e, e.parmU, 'u', p, rows, line, e.range[0], e.range[1], whole);
        s.knots[1] = knotsOf(e, e.parmV, 'v', q, cols, line, e.range[2], e.range[3], whole);
        s.rows = rows;
        s.cols = cols;
        s.points.resize(3, count);
        if (!w.empty()) s.weights.resize(static_cast<std::size_t>(count));
        for (int k = 0; k < count; ++k) {
            const int i = k % rows, j = k / rows; // u varies fastest
            s.points.col(i * cols + j) = vertices_[static_cast<std::size_t>(e.indices[static_cast<std::size_t>(k)])];
            if (!w.empty()) s.weights[static_cast<std::size_t>(i * cols + j)] = w[static_cast<std::size_t>(k)];
        }
        object.data = std::move(s);
    }

    void finish(const Element& e, int line)
    {
        if (e.surface && (!e.loops.empty() || (e.bspline && !wholeDomain(e)))) {
            finishTrimmed(e, line);
            return;
        }
        if (e.bspline) {
            DocumentObject object;
            object.name = e.name;
            finishBspline(e, line, object);
            objects_.push_back(std::move(object));
            return;
        }
        const int count = static_cast<int>(e.indices.size());
        auto pointsOf = [&](int k) { return vertices_[static_cast<std::size_t>(e.indices[static_cast<std::size_t>(k)])]; };
        DocumentObject object;
        object.name = e.name;
        if (!e.surface) {
            if (!e.parmV.empty()) fail(line, "a curve has no parm v");
            const int d = e.du;
            if (count < d + 1 || (count - 1) % d != 0)
                fail(e.line, std::to_string(count) + std::string(" control points do not fit degree ") + std::to_string(d) +
                                 " (a Bézier curve of L segments has L*degree + 1)");
            const int segments = (count - 1) / d;
            if (!e.parmU.empty() && static_cast<int>(e.parmU.size()) != segments + 1)
                fail(line, std::string("parm u has ") + std::to_string(e.parmU.size()) + std::string(" values, ") + std::to_string(segments) +
                               std::string(" segments need ") + std::to_string(segments + 1));
            PointColumns pts(3, count);
            for (int k = 0; k < count; ++k) pts.col(k) = pointsOf(k);
            if (e.rational && segments == 1) {
                object.data = RationalBezierCurveData{std::move(pts), weightsOf(e)};
            } else if (e.rational) {
                // Piecewise rational Bézier: a NURBS curve with every interior break of multiplicity d.
                NurbsCurveData c;
                c.degree = d;
                std::vector<double> ends = e.parmU;
                if (ends.empty())
                    for (int k = 0; k <= segments; ++k) ends.push_back(k);
                c.knots = bezierKnots(ends, d);
                c.points = std::move(pts);
                c.weights = weightsOf(e);
                object.data = std::move(c);
            } else if (segments == 1) {
                object.data = BezierCurveData{std::move(pts)};
            } else {
                BezierSplineData s;
                s.degree = d;
                s.closed = false;
                s.points = std::move(pts);
                bool unit = true;
                std::vector<double> h;
                for (std::size_t k = 1; k < e.parmU.size(); ++k) {
                    h.push_back(e.parmU[k] - e.parmU[k - 1]);
                    unit = unit && h.back() == 1.0;
                }
                if (!unit) s.intervals = std::move(h);
                object.data = std::move(s);
            }
        } else {
            const int m = e.du, n = e.dv;
            const int expected = (m + 1) * (n + 1);
            if (count > expected && e.parmU.size() >= 2 && e.parmV.size() >= 2) {
                finishPiecewiseSurface(e, object);
                objects_.push_back(std::move(object));
                return;
            }
            if (count != expected) {
                const bool piecewise = count > expected;
                fail(e.line, std::to_string(count) + std::string(" control points do not fit degree (") + std::to_string(m) + ", " +
                                 std::to_string(n) + std::string("), which needs ") + std::to_string(expected) +
                                 (piecewise ? " (a surface of several patches needs \"parm u\" and \"parm v\" with the patch ends)" : ""));
            }
            for (const auto* p : {&e.parmU, &e.parmV})
                if (!p->empty() && p->size() != 2) fail(line, "a single Bézier patch has two parm values per direction");
            PointColumns pts(3, expected);
            std::vector<double> w = e.rational ? weightsOf(e) : std::vector<double>();
            std::vector<double> ws(w.size());
            for (int k = 0; k < count; ++k) {
                const int i = k % (m + 1), j = k / (m + 1);
                pts.col(i * (n + 1) + j) = pointsOf(k);
                if (!w.empty()) ws[static_cast<std::size_t>(i * (n + 1) + j)] = w[static_cast<std::size_t>(k)];
            }
            if (e.rational) {
                RationalBezierSurfaceData s;
                s.degree = {m, n};
                s.points = std::move(pts);
                s.weights = std::move(ws);
                object.data = std::move(s);
            } else {
                BezierSurfaceData s;
                s.degree = {m, n};
                s.points = std::move(pts);
                object.data = std::move(s);
            }
        }
        objects_.push_back(std::move(object));
    }

    /// A Bézier surf of several patches: parm u (v) holds the Lu + 1 (Lv + 1) increasing patch ends,
    /// the (Lu m + 1) x (Lv n + 1) control points run u fastest, neighbouring patches share their
    /// boundary row. Read as a nurbs_surface whose interior knots have multiplicity m (n): the same
    /// surface, patch (a, b) on [parm u a, a+1] x [parm v b, b+1].
    void finishPiecewiseSurface(const Element& e, DocumentObject& object)
    {
        const int m = e.du, n = e.dv;
        const int lu = static_cast<int>(e.parmU.size()) - 1, lv = static_cast<int>(e.parmV.size()) - 1;
        const int rows = lu * m + 1, cols = lv * n + 1;
        const int count = static_cast<int>(e.indices.size());
        if (count != rows * cols)
            fail(e.line, std::to_string(count) + " control points do not fit " + std::to_string(lu) + " x " + std::to_string(lv) +
                             " patches of degree (" + std::to_string(m) + ", " + std::to_string(n) + ") (parm u and parm v), which need (" +
                             std::to_string(lu) + "*" + std::to_string(m) + " + 1)(" + std::to_string(lv) + "*" + std::to_string(n) +
                             " + 1) = " + std::to_string(rows * cols));
        NurbsSurfaceData s;
        s.degree = {m, n};
        s.knots = {bezierKnots(e.parmU, m), bezierKnots(e.parmV, n)};
        s.rows = rows;
        s.cols = cols;
        s.points.resize(3, rows * cols);
        const std::vector<double> w = e.rational ? weightsOf(e) : std::vector<double>();
        if (!w.empty()) s.weights.resize(w.size());
        for (int k = 0; k < count; ++k) {
            const int i = k % rows, j = k / rows;
            s.points.col(i * cols + j) = vertices_[static_cast<std::size_t>(e.indices[static_cast<std::size_t>(k)])];
            if (!w.empty()) s.weights[static_cast<std::size_t>(i * cols + j)] = w[static_cast<std::size_t>(k)];
        }
        object.data = std::move(s);
    }

    /// trim u0 u1 k u0 u1 k ... (the outer loop) or hole ... (an inner one), inside a surf element:
    /// curv2 number k (1-based, negative: relative; defined before) from u0 to u1 (u0 > u1: run from
    /// u1 back to u0).
    void trimStatement(const std::vector<std::string>& t, int line)
    {
        const std::string& key = t[0];
        if (!open_ || !open_->surface) fail(line, key + " outside a surf element");
        if (t.size() < 4 || (t.size() - 1) % 3 != 0) fail(line, "expected \"" + key + " u0 u1 curv2 [u0 u1 curv2 ...]\"");
        if (key == "trim" && open_->outer)
            fail(line, "a second trim loop: a freeform trimmed surface has one outer boundary (holes are \"hole\" statements)");
        std::vector<TrimRef> loop;
        for (std::size_t k = 1; k < t.size(); k += 3) {
            TrimRef r{number(t[k], line), number(t[k + 1], line), 0, line};
            const int i = integer(t[k + 2], line);
            const int count = static_cast<int>(curves2_.size());
            r.curve = i > 0 ? i - 1 : count + i;
            if (i == 0 || r.curve < 0 || r.curve >= count)
                fail(line, "curv2 " + std::to_string(i) + " is not defined (" + std::to_string(count) + " curv2 so far)");
            if (r.first == r.last) fail(line, "the trim range " + formatNumber(r.first) + " " + formatNumber(r.last) + " is empty");
            curves2_[static_cast<std::size_t>(r.curve)].used = true;
            loop.push_back(r);
        }
        if (key == "trim") {
            open_->loops.insert(open_->loops.begin(), std::move(loop));
            open_->outer = true;
        } else {
            open_->loops.push_back(std::move(loop));
        }
    }

    /// A curv2: a 2D NURBS curve over its parm u (a B-spline's knots, Bézier segment ends, or 0 1 ...).
    void finishCurve2(const Element& e, int line)
    {
        if (!e.parmV.empty()) fail(line, "a curve has no parm v");
        const int count = static_cast<int>(e.indices.size());
        const int d = e.du;
        NurbsCurveData c;
        c.degree = d;
        if (e.bspline) {
            if (count < d + 1) fail(e.line, std::to_string(count) + " parameter vertices are too few for degree " + std::to_string(d));
            c.knots = knotsOf(e, e.parmU, 'u', d, count, line, 0, 0, false);
        } else {
            if ((count - 1) % d != 0)
                fail(e.line, std::to_string(count) + " parameter vertices do not fit degree " + std::to_string(d) +
                                 " (a Bézier curve of L segments has L*degree + 1)");
            const int segments = (count - 1) / d;
            std::vector<double> ends = e.parmU;
            if (ends.empty())
                for (int k = 0; k <= segments; ++k) ends.push_back(k);
            if (static_cast<int>(ends.size()) != segments + 1)
                fail(line, "parm u has " + std::to_string(ends.size()) + " values, " + std::to_string(segments) + " segments need " +
                               std::to_string(segments + 1));
            c.knots = bezierKnots(ends, d);
        }
        c.points.resize(2, count);
        for (int k = 0; k < count; ++k) c.points.col(k) = params_[static_cast<std::size_t>(e.indices[static_cast<std::size_t>(k)])];
        if (e.rational) c.weights = weightsOf(e);
        curves2_.push_back(Curve2{std::move(c), e.name, false});
    }

    /// Whether a B-spline surf's range is its whole knot domain (else it is a trimmed_surface).
    bool wholeDomain(const Element& e) const
    {
        const int rows = static_cast<int>(e.parmU.size()) - e.du - 1, cols = static_cast<int>(e.parmV.size()) - e.dv - 1;
        if (rows < 1 || cols < 1) return true; // finishBspline names what is wrong
        return e.range[0] == e.parmU[static_cast<std::size_t>(e.du)] && e.range[1] == e.parmU[static_cast<std::size_t>(rows)] &&
               e.range[2] == e.parmV[static_cast<std::size_t>(e.dv)] && e.range[3] == e.parmV[static_cast<std::size_t>(cols)];
    }

    /// A surf with trim or hole statements, or a B-spline surf over a part of its domain: a
    /// trimmed_surface whose domain is the surf range (docs/surfaces.md, "Trimmed surfaces in OBJ").
    void finishTrimmed(const Element& e, int line)
    {
        DocumentObject object;
        object.name = e.name;
        TrimmedSurfaceData ts;
        if (e.bspline) {
            finishBspline(e, line, object, false);
            ts.surface = std::get<NurbsSurfaceData>(std::move(object.data));
        } else {
            // A Bézier surf (one patch or several) as the NURBS surface it is, over its parm ends.
            Element whole = e;
            whole.loops.clear();
            for (std::vector<double>* parm : {&whole.parmU, &whole.parmV})
                if (parm->empty()) *parm = {0, 1};
            const std::size_t before = objects_.size();
            finish(whole, line);
            DocumentObject made = std::move(objects_.back());
            objects_.resize(before);
            if (auto* n = std::get_if<NurbsSurfaceData>(&made.data)) {
                ts.surface = std::move(*n);
            } else {
                const int m = e.du, n2 = e.dv;
                ts.surface.degree = {m, n2};
                ts.surface.knots = {bezierKnots(whole.parmU, m), bezierKnots(whole.parmV, n2)};
                ts.surface.rows = m + 1;
                ts.surface.cols = n2 + 1;
                if (auto* b = std::get_if<BezierSurfaceData>(&made.data)) {
                    ts.surface.points = std::move(b->points);
                } else {
                    auto& r = std::get<RationalBezierSurfaceData>(made.data);
                    ts.surface.points = std::move(r.points);
                    ts.surface.weights = std::move(r.weights);
                }
            }
        }
        const NurbsSurfaceData& s = ts.surface;
        for (int dir = 0; dir < 2; ++dir) {
            const auto& k = s.knots[static_cast<std::size_t>(dir)];
            const auto p = static_cast<std::size_t>(s.degree[static_cast<std::size_t>(dir)]);
            const double r0 = e.range[2 * static_cast<std::size_t>(dir)], r1 = e.range[2 * static_cast<std::size_t>(dir) + 1];
            const char* name = dir == 0 ? "u" : "v";
            if (!(r0 < r1)) fail(e.line, std::string("the parameter range in ") + name + " is empty (" + formatNumber(r0) + " " + formatNumber(r1) + ")");
            if (r0 < k[p] || r1 > k[k.size() - 1 - p])
                fail(e.line, std::string("the parameter range ") + formatNumber(r0) + " " + formatNumber(r1) + " in " + name +
                                 " is outside the surface's domain " + formatNumber(k[p]) + " " + formatNumber(k[k.size() - 1 - p]));
        }
        ts.domain = e.range;
        if (!e.loops.empty() && !e.outer) {
            // Holes alone: the outer boundary is the surf range, four lines around it.
            const double u0 = e.range[0], u1 = e.range[1], v0 = e.range[2], v1 = e.range[3];
            const std::array<Eigen::Vector2d, 5> c{Eigen::Vector2d(u0, v0), Eigen::Vector2d(u1, v0), Eigen::Vector2d(u1, v1),
                                                   Eigen::Vector2d(u0, v1), Eigen::Vector2d(u0, v0)};
            std::vector<TrimCurveData> box;
            for (int k = 0; k < 4; ++k) {
                TrimCurveData t;
                t.curve.nurbs.degree = 1;
                t.curve.nurbs.knots = {0, 0, 1, 1};
                t.curve.nurbs.points.resize(2, 2);
                t.curve.nurbs.points << c[static_cast<std::size_t>(k)], c[static_cast<std::size_t>(k) + 1];
                box.push_back(std::move(t));
            }
            ts.loops.push_back(std::move(box));
        }
        for (const std::vector<TrimRef>& loop : e.loops) {
            std::vector<TrimCurveData> curves;
            for (const TrimRef& r : loop) {
                TrimCurveData t;
                t.curve.nurbs = curves2_[static_cast<std::size_t>(r.curve)].curve;
                const auto& k = t.curve.nurbs.knots;
                const auto p = static_cast<std::size_t>(t.curve.nurbs.degree);
                t.curve.first = std::min(r.first, r.last);
                t.curve.last = std::max(r.first, r.last);
                t.reversed = r.first > r.last;
                if (t.curve.first < k[p] || t.curve.last > k[k.size() - 1 - p])
                    fail(r.line, "the trim range " + formatNumber(r.first) + " " + formatNumber(r.last) + " of curv2 " +
                                     std::to_string(r.curve + 1) + " is outside its domain " + formatNumber(k[p]) + " " +
                                     formatNumber(k[k.size() - 1 - p]));
                curves.push_back(std::move(t));
            }
            ts.loops.push_back(std::move(curves));
        }
        object.data = std::move(ts);
        objects_.push_back(std::move(object));
    }

    std::string source_;
    std::vector<Eigen::Vector3d> vertices_;
    std::vector<double> weights_; // per vertex, 1 when not given
    std::vector<int> weightLines_;
    std::vector<Eigen::Vector2d> params_; // vp (v = 0 when given u alone)
    std::vector<double> paramWeights_;
    std::vector<int> paramLines_;         // negative: a vp with u alone
    std::vector<Curve2> curves2_;
    std::vector<DocumentObject> objects_;
    std::optional<Element> open_;
    std::string name_;
    std::map<std::string, int> usedNames_;
    int curves_ = 0, surfaces_ = 0;
    bool cstype_ = false, rational_ = false, bspline_ = false;
    int du_ = 0, dv_ = -1;
};

} // namespace

Document parseObjFreeform(const std::string& text, const std::string& source)
{
    return ObjReader(source).parse(text);
}

Document readObjFreeform(const std::string& path)
{
    return parseObjFreeform(readFile(path), path);
}

} // namespace freeform
