// Reading and writing the v1 document (docs/format.md). Strict: every member is checked for
// presence, type, shape and finiteness, and every message names the source, the object and the
// field.

#include "freeform/io/document.h"

#include <Eigen/LU>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "freeform/core/error.h"
#include "freeform/io/file.h"
#include "freeform/io/json_check.h"
#include "document_json.h"
#include "object_lookup.h"

namespace freeform {

namespace document_json {

std::string typeName(const Json& j)
{
    return j.is_number() ? "a number" : j.is_string() ? "a string" : j.is_array() ? "an array"
         : j.is_object() ? "an object" : j.is_boolean() ? "a boolean" : "null";
}

const Json& member(const Json& obj, const char* key, const Where& w)
{
    const auto it = obj.find(key);
    if (it == obj.end()) w.fail(key, "is missing");
    return *it;
}

double number(const Json& j, const std::string& field, const Where& w)
{
    if (!j.is_number()) w.fail(field, "expected a number, found " + typeName(j));
    const double v = j.get<double>();
    if (!std::isfinite(v)) w.fail(field, "number is not finite");
    return v;
}

int integer(const Json& j, const std::string& field, const Where& w)
{
    if (!j.is_number_integer()) w.fail(field, "expected an integer, found " + typeName(j));
    const auto v = j.get<long long>();
    if (v < -1000000000LL || v > 1000000000LL) w.fail(field, "integer out of range");
    return static_cast<int>(v);
}

std::string string(const Json& j, const std::string& field, const Where& w)
{
    if (!j.is_string()) w.fail(field, "expected a string, found " + typeName(j));
    return j.get<std::string>();
}

std::string oneOf(const Json& j, const std::string& field, std::initializer_list<const char*> allowed,
                  const Where& w)
{
    const std::string v = string(j, field, w);
    std::string list;
    for (const char* a : allowed) {
        if (v == a) return v;
        list += std::string(list.empty() ? "" : ", ") + "\"" + a + "\"";
    }
    w.fail(field, "\"" + v + "\" is not one of " + list);
}

/// A list of points (arrays of dim numbers); dim 0 means "any of 2 or 3, the same for all".
PointColumns pointList(const Json& j, const std::string& field, int dim, const Where& w)
{
    if (!j.is_array()) w.fail(field, "expected an array of points, found " + typeName(j));
    if (j.empty()) w.fail(field, "has no points");
    PointColumns out;
    for (std::size_t i = 0; i < j.size(); ++i) {
        const Json& p = j[i];
        const std::string f = field + "[" + std::to_string(i) + "]";
        if (!p.is_array()) w.fail(f, "expected a point (an array of numbers), found " + typeName(p));
        if (i == 0) {
            if (dim == 0) {
                if (p.size() != 2 && p.size() != 3)
                    w.fail(f, "a point has 2 or 3 coordinates, found " + std::to_string(p.size()));
                dim = static_cast<int>(p.size());
            }
            out.resize(dim, static_cast<Eigen::Index>(j.size()));
        }
        if (static_cast<int>(p.size()) != dim)
            w.fail(f, "expected " + std::to_string(dim) + " coordinates, found " + std::to_string(p.size()));
        for (int k = 0; k < dim; ++k)
            out(k, static_cast<Eigen::Index>(i)) = number(p[k], f + "[" + std::to_string(k) + "]", w);
    }
    return out;
}

/// An array of positive numbers (spline intervals, weights); `what` names one in the message
/// ("interval length must be positive"). `count`: the size it must have (npos: any).
std::vector<double> positiveNumbers(const Json& j, const std::string& field, const char* what, const Where& w,
                                    std::size_t count = std::string::npos)
{
    if (!j.is_array()) w.fail(field, "expected an array of numbers, found " + typeName(j));
    if (count != std::string::npos && j.size() != count)
        w.fail(field, "has " + std::to_string(j.size()) + " weights for " + std::to_string(count) + " points");
    std::vector<double> out;
    for (std::size_t i = 0; i < j.size(); ++i) {
        const std::string f = field + "[" + std::to_string(i) + "]";
        const double v = number(j[i], f, w);
        if (!(v > 0)) w.fail(f, std::string(what) + " must be positive");
        out.push_back(v);
    }
    return out;
}

std::vector<double> positiveList(const Json& j, const std::string& field, const Where& w)
{
    return positiveNumbers(j, field, "interval length", w);
}

/// Rejects members of obj not in allowed.
void onlyKnown(const Json& obj, std::initializer_list<const char*> allowed, const Where& w)
{
    for (auto it = obj.begin(); it != obj.end(); ++it) {
        bool ok = false;
        for (const char* a : allowed) ok = ok || it.key() == a;
        if (!ok) w.fail(it.key(), "unknown field");
    }
}

/// A grid of points [[p, p, ...], ...] (rows x cols), 3D.
PointColumns pointGrid(const Json& j, int& rows, int& cols, const Where& w)
{
    if (!j.is_array() || j.empty()) w.fail("points", "expected a non-empty array of rows of points");
    rows = static_cast<int>(j.size());
    cols = -1;
    PointColumns out;
    for (int r = 0; r < rows; ++r) {
        const std::string f = "points[" + std::to_string(r) + "]";
        const PointColumns row = pointList(j[r], f, 3, w);
        if (cols < 0) {
            cols = static_cast<int>(row.cols());
            out.resize(3, rows * cols);
        } else if (row.cols() != cols) {
            w.fail(f, "has " + std::to_string(row.cols()) + " points, row 0 has " + std::to_string(cols));
        }
        out.middleCols(r * cols, cols) = row;
    }
    return out;
}

/// Positive weights, one per point: a flat list (curves) of `count` numbers.
std::vector<double> weightList(const Json& j, const std::string& field, std::size_t count, const Where& w)
{
    return positiveNumbers(j, field, "weight", w, count);
}

/// Positive weights as a rows x cols grid [[w, ...], ...] (surfaces), flattened row by row.
std::vector<double> weightGrid(const Json& j, const std::string& field, int rows, int cols, const Where& w)
{
    if (!j.is_array()) w.fail(field, "expected an array of rows of weights, found " + typeName(j));
    if (static_cast<int>(j.size()) != rows)
        w.fail(field, "has " + std::to_string(j.size()) + " rows, the points have " + std::to_string(rows));
    std::vector<double> out;
    for (int r = 0; r < rows; ++r) {
        const std::string f = field + "[" + std::to_string(r) + "]";
        const std::vector<double> row = weightList(j[static_cast<std::size_t>(r)], f, static_cast<std::size_t>(cols), w);
        out.insert(out.end(), row.begin(), row.end());
    }
    return out;
}

/// The "weights" of a rational curve or surface in the shape of its points, one positive weight
/// per point: a flat list of `cols` numbers for a curve (rows 0), a rows x cols grid for a surface
/// (flattened row by row). Empty when absent and not `required` (NURBS: all weights 1).
std::vector<double> weightsOf(const Json& obj, int rows, int cols, bool required, const Where& w)
{
    if (!required && !obj.contains("weights")) return {};
    const Json& j = member(obj, "weights", w);
    return rows == 0 ? weightList(j, "weights", static_cast<std::size_t>(cols), w) : weightGrid(j, "weights", rows, cols, w);
}

/// A knot vector for `count` control points of degree p: count + p + 1 finite non-decreasing
/// numbers, no knot of multiplicity above p + 1, and a non-empty domain [u_p, u_count].
std::vector<double> knotList(const Json& j, const std::string& field, int p, long count, const Where& w)
{
    if (!j.is_array()) w.fail(field, "expected an array of numbers, found " + typeName(j));
    const long expected = count + p + 1;
    if (static_cast<long>(j.size()) != expected)
        w.fail(field, "has " + std::to_string(j.size()) + " knots, " + std::to_string(count) + " points of degree " +
                          std::to_string(p) + " need " + std::to_string(expected));
    std::vector<double> out;
    int run = 0;
    for (std::size_t i = 0; i < j.size(); ++i) {
        const std::string f = field + "[" + std::to_string(i) + "]";
        const double v = number(j[i], f, w);
        if (!out.empty() && v < out.back())
            w.fail(f, "knot " + std::to_string(i) + " decreases (knots must be non-decreasing)");
        run = !out.empty() && v == out.back() ? run + 1 : 1;
        if (run > p + 1)
            w.fail(f, "knot " + std::to_string(i) + " has multiplicity above degree + 1 = " + std::to_string(p + 1));
        out.push_back(v);
    }
    if (!(out[static_cast<std::size_t>(p)] < out[static_cast<std::size_t>(count)]))
        w.fail(field, "the domain [knot " + std::to_string(p) + ", knot " + std::to_string(count) + "] is empty");
    return out;
}

/// The "degree" of a Bézier spline or NURBS curve: an integer in 1..67.
int curveDegree(const Json& obj, const Where& w)
{
    const int degree = integer(member(obj, "degree", w), "degree", w);
    if (degree < 1 || degree > 67) w.fail("degree", "must be in 1..67");
    return degree;
}

/// The "points" of a Bézier curve, rational or not (degree + 1 of them, degree at most 67).
PointColumns bezierPoints(const Json& obj, const Where& w)
{
    PointColumns points = pointList(member(obj, "points", w), "points", 0, w);
    if (points.cols() - 1 > 67) w.fail("points", "degree above the maximum 67");
    return points;
}

/// The "degree" [m, n] and "points" of a Bézier patch, rational or not: an (m+1) x (n+1) grid.
void patchGrid(const Json& obj, std::array<int, 2>& degree, PointColumns& points, const Where& w)
{
    degree = degreeArray<2>(member(obj, "degree", w), w);
    int rows = 0, cols = 0;
    points = pointGrid(member(obj, "points", w), rows, cols, w);
    if (rows != degree[0] + 1 || cols != degree[1] + 1)
        w.fail("points", "grid is " + std::to_string(rows) + " x " + std::to_string(cols) + ", degree [" +
                             std::to_string(degree[0]) + ", " + std::to_string(degree[1]) + "] needs " +
                             std::to_string(degree[0] + 1) + " x " + std::to_string(degree[1] + 1));
}

NurbsCurveData nurbsCurveFields(const Json& obj, int dim, const Where& w)
{
    NurbsCurveData d;
    d.degree = curveDegree(obj, w);
    d.points = pointList(member(obj, "points", w), "points", dim, w);
    const long count = static_cast<long>(d.points.cols());
    if (count < d.degree + 1)
        w.fail("points", std::to_string(count) + " points are too few for degree " + std::to_string(d.degree) +
                             " (needs at least " + std::to_string(d.degree + 1) + ")");
    d.knots = knotList(member(obj, "knots", w), "knots", d.degree, count, w);
    d.weights = weightsOf(obj, 0, static_cast<int>(count), false, w);
    return d;
}

NurbsSurfaceData nurbsSurfaceFields(const Json& obj, const Where& w)
{
    NurbsSurfaceData d;
    d.degree = degreeArray<2>(member(obj, "degree", w), w);
    d.points = pointGrid(member(obj, "points", w), d.rows, d.cols, w);
    if (d.rows < d.degree[0] + 1)
        w.fail("points", std::to_string(d.rows) + " rows are too few for degree " + std::to_string(d.degree[0]) +
                             " in u (needs at least " + std::to_string(d.degree[0] + 1) + ")");
    if (d.cols < d.degree[1] + 1)
        w.fail("points", std::to_string(d.cols) + " points per row are too few for degree " +
                             std::to_string(d.degree[1]) + " in v (needs at least " + std::to_string(d.degree[1] + 1) + ")");
    const Json& knots = member(obj, "knots", w);
    if (!knots.is_array() || knots.size() != 2) w.fail("knots", "expected an array of two knot vectors (u, v)");
    d.knots[0] = knotList(knots[0], "knots[0]", d.degree[0], d.rows, w);
    d.knots[1] = knotList(knots[1], "knots[1]", d.degree[1], d.cols, w);
    d.weights = weightsOf(obj, d.rows, d.cols, false, w);
    return d;
}

ObjectData parseObject(const Json& obj, const std::string& type, const Where& w)
{
    const std::optional<ObjectKind> kind = kindNamed(type);
    if (kind) switch (*kind) {
    case ObjectKind::RationalBezierCurve: {
        onlyKnown(obj, {"name", "type", "points", "weights", "editor"}, w);
        RationalBezierCurveData d;
        d.points = bezierPoints(obj, w);
        d.weights = weightsOf(obj, 0, static_cast<int>(d.points.cols()), true, w);
        return d;
    }
    case ObjectKind::RationalBezierSurface: {
        onlyKnown(obj, {"name", "type", "degree", "points", "weights", "editor"}, w);
        RationalBezierSurfaceData d;
        patchGrid(obj, d.degree, d.points, w);
        d.weights = weightsOf(obj, d.degree[0] + 1, d.degree[1] + 1, true, w);
        return d;
    }
    case ObjectKind::NurbsCurve:
        onlyKnown(obj, {"name", "type", "degree", "knots", "points", "weights", "editor"}, w);
        return nurbsCurveFields(obj, 0, w);
    case ObjectKind::NurbsSurface:
        onlyKnown(obj, {"name", "type", "degree", "knots", "points", "weights", "editor"}, w);
        return nurbsSurfaceFields(obj, w);
    case ObjectKind::TrimmedSurface:
        return trimmedSurfaceObject(obj, w);
    case ObjectKind::Part:
        return partObject(obj, w);
    case ObjectKind::BezierCurve: {
        onlyKnown(obj, {"name", "type", "points", "editor"}, w);
        BezierCurveData d;
        d.points = bezierPoints(obj, w);
        return d;
    }
    case ObjectKind::BezierSpline: {
        onlyKnown(obj, {"name", "type", "degree", "closed", "points", "intervals", "editor"}, w);
        BezierSplineData d;
        d.degree = curveDegree(obj, w);
        if (obj.contains("closed")) {
            if (!obj["closed"].is_boolean()) w.fail("closed", "expected true or false");
            d.closed = obj["closed"].get<bool>();
        }
        d.points = pointList(member(obj, "points", w), "points", 0, w);
        const long count = static_cast<long>(d.points.cols());
        const long segments = d.closed ? count / d.degree : (count - 1) / d.degree;
        const bool fits = d.closed ? (count % d.degree == 0 && segments >= 1)
                                   : ((count - 1) % d.degree == 0 && segments >= 1);
        if (!fits) {
            w.fail("points", std::to_string(count) + " points do not fit degree " + std::to_string(d.degree) +
                                 (d.closed ? ": a closed spline of L segments has L*degree points"
                                           : ": an open spline of L segments has L*degree + 1 points"));
        }
        if (obj.contains("intervals")) {
            d.intervals = positiveList(obj["intervals"], "intervals", w);
            if (static_cast<long>(d.intervals.size()) != segments)
                w.fail("intervals", "has " + std::to_string(d.intervals.size()) + " lengths for " +
                                        std::to_string(segments) + " segments");
        }
        return d;
    }
    case ObjectKind::DeBoorSpline: {
        onlyKnown(obj, {"name", "type", "degree", "end", "points", "intervals", "editor"}, w);
        DeBoorSplineData d;
        d.degree = integer(member(obj, "degree", w), "degree", w);
        if (d.degree != 3) w.fail("degree", "de Boor splines are cubic: degree must be 3");
        d.end = oneOf(member(obj, "end", w), "end", {"open", "clamped", "closed"}, w);
        d.points = pointList(member(obj, "points", w), "points", 0, w);
        // Open and clamped: L = count - 3 segments (at least 4 points); closed: L = count (at least 3).
        const bool closed = d.end == "closed";
        const long count = static_cast<long>(d.points.cols());
        const long minimum = closed ? 3 : 4;
        if (count < minimum)
            w.fail("points", std::to_string(count) + " de Boor points are too few for end \"" + d.end +
                                 "\" (needs at least " + std::to_string(minimum) + ")");
        const long segments = closed ? count : count - 3;
        if (obj.contains("intervals")) {
            d.intervals = positiveList(obj["intervals"], "intervals", w);
            if (static_cast<long>(d.intervals.size()) != segments)
                w.fail("intervals", "has " + std::to_string(d.intervals.size()) + " lengths for " +
                                        std::to_string(segments) + " segments (" + std::to_string(count) +
                                        " de Boor points, end \"" + d.end + "\")");
        }
        return d;
    }
    case ObjectKind::BezierSurface: {
        onlyKnown(obj, {"name", "type", "degree", "points", "editor"}, w);
        BezierSurfaceData d;
        patchGrid(obj, d.degree, d.points, w);
        return d;
    }
    case ObjectKind::DeBoorSurface: {
        onlyKnown(obj, {"name", "type", "degree", "end", "points", "editor"}, w);
        DeBoorSurfaceData d;
        d.degree = degreeArray<2>(member(obj, "degree", w), w);
        if (d.degree[0] != 3 || d.degree[1] != 3) w.fail("degree", "de Boor surfaces are bicubic: degree must be [3, 3]");
        const Json& end = member(obj, "end", w);
        if (!end.is_array() || end.size() != 2) w.fail("end", "expected an array of two end conditions");
        for (int i = 0; i < 2; ++i)
            d.end[i] = oneOf(end[i], "end[" + std::to_string(i) + "]", {"open", "clamped", "closed"}, w);
        d.points = pointGrid(member(obj, "points", w), d.rows, d.cols, w);
        // The A-frame needs 4 de Boor points per direction (open, clamped), 3 when closed.
        const int need[2] = {d.end[0] == "closed" ? 3 : 4, d.end[1] == "closed" ? 3 : 4};
        if (d.rows < need[0])
            w.fail("points", std::to_string(d.rows) + " rows are too few for end condition \"" + d.end[0] +
                                 "\" in u (needs at least " + std::to_string(need[0]) + ")");
        if (d.cols < need[1])
            w.fail("points", std::to_string(d.cols) + " points per row are too few for end condition \"" + d.end[1] +
                                 "\" in v (needs at least " + std::to_string(need[1]) + ")");
        return d;
    }
    case ObjectKind::Lattice: {
        onlyKnown(obj, {"name", "type", "degree", "origin", "axes", "points", "outside", "editor"}, w);
        LatticeData d;
        d.degree = degreeArray<3>(member(obj, "degree", w), w);
        d.origin = pointList(Json::array({member(obj, "origin", w)}), "origin", 3, w).col(0);
        const PointColumns axes = pointList(member(obj, "axes", w), "axes", 3, w);
        if (axes.cols() != 3) w.fail("axes", "expected three edge vectors S, T, U");
        d.axes = axes;
        if (std::abs(d.axes.determinant()) <= 1e-300) w.fail("axes", "edge vectors are linearly dependent");
        d.points = pointList(member(obj, "points", w), "points", 3, w);
        const long expected = static_cast<long>(d.degree[0] + 1) * (d.degree[1] + 1) * (d.degree[2] + 1);
        if (d.points.cols() != expected)
            w.fail("points", "has " + std::to_string(d.points.cols()) + " points, degree needs " + std::to_string(expected));
        if (obj.contains("outside"))
            d.outside = parseOutsidePolicy(oneOf(obj["outside"], "outside", {"keep", "clamp", "extrapolate"}, w), "outside");
        return d;
    }
    case ObjectKind::SubdivisionSurface: {
        onlyKnown(obj, {"name", "type", "mesh", "vertices", "faces", "scheme", "creases", "corners", "boundary", "editor"}, w);
        SubdivisionSurfaceData d;
        if (obj.contains("scheme")) d.scheme = oneOf(obj["scheme"], "scheme", {"catmark", "loop"}, w);
        if (obj.contains("boundary"))
            d.boundary = oneOf(obj["boundary"], "boundary", {"edge_only", "edge_and_corner", "none"}, w);
        // creases [[v0, v1, sharpness], ...] and corners [[v, sharpness], ...]: integer vertex indices
        // (checked against the cage when the surface is built), sharpness finite and >= 0.
        auto sharpList = [&](const char* field, std::size_t ints, auto& out) {
            if (!obj.contains(field)) return;
            const Json& list = obj[field];
            if (!list.is_array()) w.fail(field, "expected an array, found " + typeName(list));
            for (std::size_t i = 0; i < list.size(); ++i) {
                const std::string f = std::string(field) + "[" + std::to_string(i) + "]";
                if (!list[i].is_array() || list[i].size() != ints + 1)
                    w.fail(f, "expected " + std::to_string(ints) + " vertex indices and a sharpness");
                typename std::decay_t<decltype(out)>::value_type item{};
                for (std::size_t k = 0; k < ints; ++k) {
                    const int v = integer(list[i][k], f, w);
                    if (v < 0) w.fail(f, "vertex index " + std::to_string(v) + " is negative");
                    item[k] = v;
                }
                item[ints] = number(list[i][ints], f, w);
                if (item[ints] < 0) w.fail(f, "sharpness must be >= 0");
                out.push_back(item);
            }
        };
        sharpList("creases", 2, d.creases);
        sharpList("corners", 1, d.corners);
        if (obj.contains("mesh")) {
            if (obj.contains("vertices") || obj.contains("faces"))
                w.fail("mesh", "give either a mesh file or inline vertices and faces, not both");
            d.mesh = string(obj["mesh"], "mesh", w);
            return d;
        }
        d.vertices = pointList(member(obj, "vertices", w), "vertices", 3, w);
        const Json& faces = member(obj, "faces", w);
        if (!faces.is_array() || faces.empty()) w.fail("faces", "expected a non-empty array of faces");
        for (std::size_t f = 0; f < faces.size(); ++f) {
            const std::string field = "faces[" + std::to_string(f) + "]";
            if (!faces[f].is_array() || faces[f].size() < 3) w.fail(field, "a face needs at least 3 vertex indices");
            std::vector<int> face;
            for (std::size_t k = 0; k < faces[f].size(); ++k) {
                const int v = integer(faces[f][k], field, w);
                if (v < 0 || v >= d.vertices.cols())
                    w.fail(field, "vertex index " + std::to_string(v) + " is out of range 0.." +
                                      std::to_string(d.vertices.cols() - 1));
                face.push_back(v);
            }
            d.faces.push_back(std::move(face));
        }
        return d;
    }
    }
    std::string known;
    for (int k = 0; k < objectKindCount; ++k) known += (k ? ", " : "") + std::string(kindName(static_cast<ObjectKind>(k)));
    w.fail("type", "unknown object type \"" + type + "\" (known: " + known + ")");
}

Json pointsJson(const PointColumns& p)
{
    Json arr = Json::array();
    for (Eigen::Index i = 0; i < p.cols(); ++i) {
        Json q = Json::array();
        for (Eigen::Index k = 0; k < p.rows(); ++k) q.push_back(p(k, i));
        arr.push_back(std::move(q));
    }
    return arr;
}

Json gridJson(const PointColumns& p, int rows, int cols)
{
    Json arr = Json::array();
    for (int r = 0; r < rows; ++r) arr.push_back(pointsJson(p.middleCols(r * cols, cols)));
    return arr;
}

Json weightsGridJson(const std::vector<double>& w, int rows, int cols)
{
    Json arr = Json::array();
    for (int r = 0; r < rows; ++r)
        arr.push_back(std::vector<double>(w.begin() + r * cols, w.begin() + (r + 1) * cols));
    return arr;
}

struct ObjectWriter {
    Json& j;
    /// A spline's points and its interval lengths (written only when not all 1).
    void splinePoints(const PointColumns& points, const std::vector<double>& intervals) const
    {
        j["points"] = pointsJson(points);
        if (!intervals.empty()) j["intervals"] = intervals;
    }
    /// A Bézier patch's degrees and its (m+1) x (n+1) grid of points, rational or not.
    void patch(const std::array<int, 2>& degree, const PointColumns& points) const
    {
        j["degree"] = degree;
        j["points"] = gridJson(points, degree[0] + 1, degree[1] + 1);
    }
    void operator()(const BezierCurveData& d) const { j["points"] = pointsJson(d.points); }
    void operator()(const BezierSplineData& d) const
    {
        j["degree"] = d.degree;
        j["closed"] = d.closed;
        splinePoints(d.points, d.intervals);
    }
    void operator()(const DeBoorSplineData& d) const
    {
        j["degree"] = d.degree;
        j["end"] = d.end;
        splinePoints(d.points, d.intervals);
    }
    void operator()(const BezierSurfaceData& d) const
    {
        patch(d.degree, d.points);
    }
    void operator()(const DeBoorSurfaceData& d) const
    {
        j["degree"] = d.degree;
        j["end"] = d.end;
        j["points"] = gridJson(d.points, d.rows, d.cols);
    }
    void operator()(const LatticeData& d) const
    {
        j["degree"] = d.degree;
        j["origin"] = pointsJson(d.origin)[0];
        j["axes"] = pointsJson(d.axes);
        j["points"] = pointsJson(d.points);
        j["outside"] = toString(d.outside);
    }
    void operator()(const SubdivisionSurfaceData& d) const
    {
        if (!d.mesh.empty()) {
            j["mesh"] = d.mesh;
        } else {
            j["vertices"] = pointsJson(d.vertices);
            j["faces"] = d.faces;
        }
        j["scheme"] = d.scheme;
        if (!d.creases.empty()) {
            Json list = Json::array();
            for (const auto& c : d.creases)
                list.push_back(Json::array({static_cast<int>(c[0]), static_cast<int>(c[1]), c[2]}));
            j["creases"] = std::move(list);
        }
        if (!d.corners.empty()) {
            Json list = Json::array();
            for (const auto& c : d.corners) list.push_back(Json::array({static_cast<int>(c[0]), c[1]}));
            j["corners"] = std::move(list);
        }
        if (d.boundary != "edge_only") j["boundary"] = d.boundary;
    }
    void operator()(const RationalBezierCurveData& d) const
    {
        j["points"] = pointsJson(d.points);
        j["weights"] = d.weights;
    }
    void operator()(const RationalBezierSurfaceData& d) const
    {
        patch(d.degree, d.points);
        j["weights"] = weightsGridJson(d.weights, d.degree[0] + 1, d.degree[1] + 1);
    }
    void operator()(const NurbsCurveData& d) const { writeNurbsCurve(j, d); }
    void operator()(const NurbsSurfaceData& d) const { writeNurbsSurface(j, d); }
    void operator()(const TrimmedSurfaceData& d) const { writeTrimmedSurface(j, d); }
    void operator()(const PartData& d) const { writePart(j, d); }
};

void writeNurbsCurve(Json& j, const NurbsCurveData& d)
{
    j["degree"] = d.degree;
    j["knots"] = d.knots;
    j["points"] = pointsJson(d.points);
    if (!d.weights.empty()) j["weights"] = d.weights;
}

void writeNurbsSurface(Json& j, const NurbsSurfaceData& d)
{
    j["degree"] = d.degree;
    j["knots"] = Json::array({Json(d.knots[0]), Json(d.knots[1])});
    j["points"] = gridJson(d.points, d.rows, d.cols);
    if (!d.weights.empty()) j["weights"] = weightsGridJson(d.weights, d.rows, d.cols);
}

} // namespace document_json

namespace {
#define FREEFORM_KIND_NAME(Kind, Data, name) name,
constexpr std::string_view kindNames[] = {FREEFORM_OBJECT_KINDS(FREEFORM_KIND_NAME)};
#undef FREEFORM_KIND_NAME
static_assert(std::variant_size_v<ObjectData> == std::size(kindNames));
static_assert(objectKindCount == std::size(kindNames));
} // namespace

std::string_view kindName(ObjectKind kind) { return kindNames[static_cast<int>(kind)]; }

std::optional<ObjectKind> kindNamed(std::string_view name)
{
    for (int k = 0; k < objectKindCount; ++k)
        if (kindNames[k] == name) return static_cast<ObjectKind>(k);
    return std::nullopt;
}

std::string objectType(const ObjectData& data) { return std::string(kindName(objectKind(data))); }

const DocumentObject& findLattice(const Document& doc, const std::optional<std::string>& name, const std::string& choose)
{
    if (name) {
        const DocumentObject& o = doc.object(*name);
        if (!std::holds_alternative<LatticeData>(o.data))
            throw Error(doc.source + ": object \"" + *name + "\" is a " + objectType(o.data) + ", not a lattice");
        return o;
    }
    std::vector<const DocumentObject*> found;
    for (const DocumentObject& o : doc.objects)
        if (std::holds_alternative<LatticeData>(o.data)) found.push_back(&o);
    if (found.empty()) throw Error(doc.source + ": has no lattice object");
    if (found.size() > 1) {
        std::string list;
        for (const DocumentObject* o : found) list += (list.empty() ? "" : ", ") + o->name;
        throw Error(doc.source + ": has several lattices (" + list + "); " + choose);
    }
    return *found.front();
}

const DocumentObject& Document::object(const std::string& name) const
{
    if (const DocumentObject* o = find(name)) return *o;
    std::vector<std::string> names;
    for (const auto& o : objects) names.push_back(o.name);
    throw Error(noObjectMessage(source, name, names));
}

std::string noObjectMessage(const std::string& source, const std::string& name, const std::vector<std::string>& names)
{
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    return source + ": no object named \"" + name + "\"" +
           (list.empty() ? std::string(" (the document has no objects)") : " (objects: " + list + ")");
}

DocumentObject* Document::find(const std::string& name)
{
    for (auto& o : objects)
        if (o.name == name) return &o;
    return nullptr;
}

const DocumentObject* Document::find(const std::string& name) const
{
    return const_cast<Document*>(this)->find(name);
}

Document parseDocument(const std::string& text, const std::string& sourceName)
{
    using namespace document_json;
    checkJsonText(text, sourceName); // depth limit and duplicate keys (docs/mesh-io.md, "Hostile input")
    Json root;
    try {
        root = Json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        // e.byte is the offset; turn it into a line number for the message.
        std::size_t line = 1;
        for (std::size_t i = 0; i < std::min<std::size_t>(e.byte, text.size()); ++i) line += text[i] == '\n';
        throw Error(sourceName + ": line " + std::to_string(line) + ": not valid JSON");
    } catch (const nlohmann::json::exception& e) {
        // Out-of-range numbers (1e999) are the only other parse failure.
        std::string what = e.what();
        what = what.substr(what.find(']') + 2);
        throw Error(sourceName + ": a number is out of range (" + what + ")");
    }
    const Where top{sourceName, ""};
    if (!root.is_object()) top.fail("", "expected a JSON object at the top level, found " + typeName(root));
    onlyKnown(root, {"format", "version", "objects", "editor"}, top);
    if (string(member(root, "format", top), "format", top) != "freeform")
        top.fail("format", "expected \"freeform\"");
    const int version = integer(member(root, "version", top), "version", top);
    if (version != 1) top.fail("version", "version " + std::to_string(version) + " is not supported (this library reads 1)");
    const Json& objects = member(root, "objects", top);
    if (!objects.is_array()) top.fail("objects", "expected an array, found " + typeName(objects));

    Document doc;
    doc.source = sourceName;
    if (root.contains("editor")) {
        if (!root["editor"].is_object()) top.fail("editor", "expected an object");
        doc.editor = root["editor"].dump();
    }
    std::set<std::string> names;
    for (std::size_t i = 0; i < objects.size(); ++i) {
        const Json& obj = objects[i];
        Where w{sourceName, "object " + std::to_string(i)};
        if (!obj.is_object()) w.fail("", "expected a JSON object, found " + typeName(obj));
        const std::string name = string(member(obj, "name", w), "name", w);
        if (name.empty()) w.fail("name", "is empty");
        w.object = "object \"" + name + "\"";
        if (!names.insert(name).second) w.fail("name", "the name is used by an earlier object");
        const std::string type = string(member(obj, "type", w), "type", w);
        DocumentObject o{name, parseObject(obj, type, w), {}};
        if (obj.contains("editor")) {
            if (!obj["editor"].is_object()) w.fail("editor", "expected an object");
            o.editor = obj["editor"].dump();
        }
        doc.objects.push_back(std::move(o));
    }
    return doc;
}

Document readDocument(const std::string& path)
{
    return parseDocument(readFile(path), path);
}

namespace {

// An editor member held as text (a Document built in memory need not come from readDocument)
// passes the one JSON gate before it becomes a tree: nlohmann's dump below recurses on depth.
document_json::Json editorJson(const std::string& text, const std::string& source)
{
    checkJsonText(text, source);
    try {
        return document_json::Json::parse(text);
    } catch (const document_json::Json::exception& e) {
        throw Error(source + ": not valid JSON: " + e.what());
    }
}

} // namespace

std::string formatDocument(const Document& document)
{
    using namespace document_json;
    Json root;
    root["format"] = "freeform";
    root["version"] = 1;
    root["objects"] = Json::array();
    for (const auto& o : document.objects) {
        Json j;
        j["name"] = o.name;
        j["type"] = objectType(o.data);
        std::visit(ObjectWriter{j}, o.data);
        if (!o.editor.empty()) j["editor"] = editorJson(o.editor, "object \"" + o.name + "\".editor");
        root["objects"].push_back(std::move(j));
    }
    if (!document.editor.empty()) root["editor"] = editorJson(document.editor, "editor");
    return root.dump(2) + "\n";
}

void writeDocument(const Document& document, const std::string& path)
{
    writeFileAtomically(path, formatDocument(document));
}

} // namespace freeform
