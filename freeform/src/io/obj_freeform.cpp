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

struct Element {
    bool surface = false;
    int line = 0;
    std::string name;
    int du = 0, dv = -1;
    bool rational = false, bspline = false;
    std::array<double, 4> range{}; // curv u0 u1 / surf s0 s1 t0 t1
    std::vector<int> indices; // 0-based
    std::vector<double> parmU, parmV;
};

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
        if (open_) fail(open_->line, std::string(open_->surface ? "surf" : "curv") + " element has no \"end\"");
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
        } else if (key == "curv" || key == "surf") {
            if (open_) fail(line, key + std::string(" inside the element of line ") + std::to_string(open_->line) + " (missing \"end\")");
            if (!cstype_) fail(line, key + " before \"cstype bezier\"");
            if (du_ < 1) fail(line, key + " before \"deg\"");
            const bool surface = key == "surf";
            if (surface && dv_ < 1) fail(line, "surf needs two degrees (\"deg du dv\")");
            const std::size_t params = surface ? 4 : 2;
            if (t.size() < params + 2) fail(line, key + ": expected the parameter range and at least two control points");
            Element e;
            for (std::size_t k = 1; k <= params; ++k) e.range[k - 1] = number(t[k], line);
            e.rational = rational_;
            e.bspline = bspline_;
            e.surface = surface;
            e.line = line;
            e.du = du_;
            e.dv = dv_;
            for (std::size_t k = params + 1; k < t.size(); ++k) e.indices.push_back(vertexIndex(t[k], line));
            e.name = nextName(surface);
            open_ = std::move(e);
        } else if (key == "parm") {
            if (!open_) fail(line, "parm outside a curv or surf element");
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
            if (!open_) fail(line, "end without a curv or surf element");
            finish(*open_, line);
            open_.reset();
        } else if (key == "trim" || key == "hole" || key == "scrv" || key == "sp") {
            fail(line, "trimming and special curves (" + key + ") are not supported");
        } else if (key == "bmat" || key == "step" || key == "curv2" || key == "con") {
            fail(line, "\"" + key + "\" is not supported (Bézier and B-spline curves and surfaces only)");
        } else if (key == "vt" || key == "vn" || key == "vp" || key == "f" || key == "l" || key == "p" || key == "s" ||
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
            const double x = weights_[static_cast<std::size_t>(i)];
            if (!(x > 0))
                fail(e.line, std::string("vertex ") + std::to_string(i + 1) + " (line " +
                                 std::to_string(weightLines_[static_cast<std::size_t>(i)]) + ") has weight " + formatNumber(x) +
                                 "; rational weights must be positive");
            w.push_back(x);
        }
        return w;
    }

    /// A B-spline knot vector from parm: count + degree + 1 knots, validated, and the curv/surf range
    /// must be the whole domain [knot p, knot count].
    std::vector<double> knotsOf(const Element& e, const std::vector<double>& parm, char dir, int degree, int count, int line,
                                double r0, double r1) const
    {
        const std::string name = std::string("parm ") + dir;
        if (parm.empty()) fail(e.line, std::string("a bspline element needs \"") + name + "\" (its knot vector)");
        const std::size_t need = static_cast<std::size_t>(count + degree + 1);
        if (parm.size() != need)
            fail(line, name + " has " + std::to_string(parm.size()) + " knots, " + std::to_string(count) + " control points of degree " +
                           std::to_string(degree) + " need " + std::to_string(need));
        KnotVector<double>(parm, degree, source_ + ": line " + std::to_string(line) + ": " + name); // throws naming the knot
        const double a = parm[static_cast<std::size_t>(degree)], b = parm[static_cast<std::size_t>(count)];
        if (r0 != a || r1 != b)
            fail(e.line, std::string("the parameter range ") + formatNumber(r0) + " " + formatNumber(r1) + " in " + dir +
                             " is not the knot domain " + formatNumber(a) + " " + formatNumber(b) +
                             " (a part of a B-spline is not supported)");
        return parm;
    }

    void finishBspline(const Element& e, int line, DocumentObject& object)
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
        s.knots[0] = knotsOf(e, e.parmU, 'u', p, rows, line, e.range[0], e.range[1]);
        s.knots[1] = knotsOf(e, e.parmV, 'v', q, cols, line, e.range[2], e.range[3]);
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
                c.knots.push_back(ends.front());
                for (std::size_t k = 0; k < ends.size(); ++k)
                    for (int r = 0; r < d; ++r) c.knots.push_back(ends[k]);
                c.knots.push_back(ends.back());
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
        auto knots = [](const std::vector<double>& ends, int d) {
            std::vector<double> k(static_cast<std::size_t>(d + 1), ends.front());
            for (std::size_t i = 1; i + 1 < ends.size(); ++i) k.insert(k.end(), static_cast<std::size_t>(d), ends[i]);
            k.insert(k.end(), static_cast<std::size_t>(d + 1), ends.back());
            return k;
        };
        NurbsSurfaceData s;
        s.degree = {m, n};
        s.knots = {knots(e.parmU, m), knots(e.parmV, n)};
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

    std::string source_;
    std::vector<Eigen::Vector3d> vertices_;
    std::vector<double> weights_; // per vertex, 1 when not given
    std::vector<int> weightLines_;
    std::vector<DocumentObject> objects_;
    std::optional<Element> open_;
    std::string name_;
    std::map<std::string, int> usedNames_;
    int curves_ = 0, surfaces_ = 0;
    bool cstype_ = false, rational_ = false, bspline_ = false;
    int du_ = 0, dv_ = -1;
};

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

std::string numberList(const std::vector<double>& values)
{
    std::string r;
    for (double v : values) {
        r += ' ';
        r += formatNumber(v);
    }
    return r;
}

} // namespace

Document parseObjFreeform(const std::string& text, const std::string& source)
{
    return ObjReader(source).parse(text);
}

Document readObjFreeform(const std::string& path)
{
    return parseObjFreeform(readFile(path), path);
}

std::string formatObjFreeform(const Document& document, const std::string& objectName)
{
    std::string out = "# OBJ free-form geometry written by freeform (cstype bezier)\n";
    long base = 0; // vertices written so far
    bool any = false;
    for (const DocumentObject& o : document.objects) {
        if (!objectName.empty() && o.name != objectName) continue;
        any = true;
        const std::string where = document.source + ": object \"" + o.name + "\"";
        if (o.name.empty() || o.name.find_first_of(" \t\r\n#") != std::string::npos)
            throw Error(where + ": the name cannot be written as an OBJ object name (no spaces or #)");
        auto refs = [&](long count) {
            std::string r;
            for (long k = 1; k <= count; ++k) {
                r += ' ';
                r += std::to_string(base + k);
            }
            return r;
        };
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
            const int p = ns->degree[0], q = ns->degree[1], rows = ns->rows, cols = ns->cols;
            PointColumns ordered(3, rows * cols);
            std::vector<double> w(ns->weights.empty() ? 0 : static_cast<std::size_t>(rows * cols));
            for (int j = 0; j < cols; ++j)
                for (int i = 0; i < rows; ++i) {
                    ordered.col(j * rows + i) = ns->points.col(i * cols + j);
                    if (!w.empty()) w[static_cast<std::size_t>(j * rows + i)] = ns->weights[static_cast<std::size_t>(i * cols + j)];
                }
            const auto& ku = ns->knots[0];
            const auto& kv = ns->knots[1];
            out += "o " + o.name + "\n";
            writeVertices(out, ordered, w);
            out += std::string(w.empty() ? "cstype bspline" : "cstype rat bspline") + "\ndeg " + std::to_string(p) + " " +
                   std::to_string(q) + "\nsurf " + formatNumber(ku[static_cast<std::size_t>(p)]) + " " +
                   formatNumber(ku[static_cast<std::size_t>(rows)]) + " " + formatNumber(kv[static_cast<std::size_t>(q)]) + " " +
                   formatNumber(kv[static_cast<std::size_t>(cols)]) + refs(ordered.cols()) + "\nparm u" + numberList(ku) +
                   "\nparm v" + numberList(kv) + "\nend\n";
            base += ordered.cols();
        } else {
            throw Error(where + ": type " + objectType(o.data) +
                        " has no OBJ free-form form (bezier_curve, open bezier_spline, bezier_surface, rational_bezier_curve, "
                        "rational_bezier_surface, nurbs_curve and nurbs_surface do)");
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
