// The fields of the trimmed_surface and part objects (docs/format.md, "Trimmed surfaces and
// parts"), read as strictly as every other object: each index is checked against what it names,
// each parameter map against its NURBS's knots, and every message names the member it is about
// (`object "p": faces[2]: loops[0][1]: field "range"`).

#include <cmath>
#include <string>

#include "document_json.h"

namespace freeform::document_json {

namespace {

std::string indexed(const std::string& name, std::size_t i) { return name + "[" + std::to_string(i) + "]"; }

/// An array of `count` finite numbers.
std::vector<double> numbers(const Json& j, const std::string& field, std::size_t count, const Where& w)
{
    if (!j.is_array() || j.size() != count)
        w.fail(field, "expected an array of " + std::to_string(count) + " numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < count; ++i) out.push_back(number(j[i], indexed(field, i), w));
    return out;
}

double tolerance(const Json& obj, const Where& w)
{
    if (!obj.contains("tolerance")) return 0;
    const double t = number(obj["tolerance"], "tolerance", w);
    if (t < 0) w.fail("tolerance", "must be >= 0");
    return t;
}

bool flag(const Json& obj, const char* field, const Where& w)
{
    if (!obj.contains(field)) return false;
    if (!obj[field].is_boolean()) w.fail(field, "expected true or false");
    return obj[field].get<bool>();
}

/// A parameter map (brep/parameter_map.h); absent: the identity.
ParameterMap parameterMap(const Json& obj, const char* field, const Where& w)
{
    if (!obj.contains(field)) return ParameterMap::identity();
    const Json& m = obj[field];
    if (!m.is_object()) w.fail(field, "expected an object, found " + typeName(m));
    const Where mw = w.inside(field);
    const std::string kind = oneOf(member(m, "kind", mw), "kind", {"identity", "periodic", "half_angle", "exponential"}, mw);
    if (kind == "identity") {
        onlyKnown(m, {"kind"}, mw);
        return ParameterMap::identity();
    }
    if (kind == "exponential") {
        onlyKnown(m, {"kind"}, mw);
        return ParameterMap::exponential();
    }
    if (kind == "periodic") {
        onlyKnown(m, {"kind", "start", "period"}, mw);
        const double start = number(member(m, "start", mw), "start", mw);
        const double period = number(member(m, "period", mw), "period", mw);
        if (!(period > 0)) mw.fail("period", "must be positive");
        return ParameterMap::periodic(start, period);
    }
    onlyKnown(m, {"kind", "start", "span", "spans"}, mw);
    ParameterMap map;
    map.kind = ParameterMap::Kind::HalfAngle;
    map.start = number(member(m, "start", mw), "start", mw);
    map.span = number(member(m, "span", mw), "span", mw);
    map.spans = integer(member(m, "spans", mw), "spans", mw);
    // Each arc's local parameter uses tan(span / 4): a span above a half turn has no exact arc.
    if (!(map.span > 0 && map.span <= std::acos(-1.0) * (1 + 1e-12))) mw.fail("span", "must be in (0, pi]");
    if (map.spans < 1 || map.spans > 1000000) mw.fail("spans", "must be in 1..1000000");
    return map;
}

Json mapJson(const ParameterMap& map)
{
    Json j;
    switch (map.kind) {
    case ParameterMap::Kind::Identity:
        j["kind"] = map.period > 0 ? "periodic" : "identity";
        if (map.period > 0) {
            j["start"] = map.start;
            j["period"] = map.period;
        }
        break;
    case ParameterMap::Kind::HalfAngle:
        j["kind"] = "half_angle";
        j["start"] = map.start;
        j["span"] = map.span;
        j["spans"] = map.spans;
        break;
    case ParameterMap::Kind::Exponential:
        j["kind"] = "exponential";
        break;
    }
    return j;
}

/// The NURBS parameters of the file's parameters t0 and t1 lie in [lo, hi] (a relative 1e-9 of
/// slack: the maps round).
void mapInside(const ParameterMap& map, double t0, double t1, double lo, double hi, const std::string& field,
               const Where& w)
{
    const double slack = 1e-9 * std::max({1.0, std::abs(lo), std::abs(hi)});
    for (const double t : {t0, t1}) {
        const double s = map(t);
        if (!(s >= lo - slack && s <= hi + slack))
            w.fail(field, "parameter " + std::to_string(t) + " maps to " + std::to_string(s) +
                              ", outside the knots' domain [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
}

/// A range [first, last] with first < last.
std::array<double, 2> range(const Json& obj, const Where& w)
{
    const std::vector<double> r = numbers(member(obj, "range", w), "range", 2, w);
    if (!(r[0] < r[1])) w.fail("range", "first must be below last");
    return {r[0], r[1]};
}

/// A mapped curve: the nurbs_curve fields, "map" and "range".
MappedCurveData mappedCurve(const Json& obj, int dim, const Where& w)
{
    MappedCurveData d;
    d.nurbs = nurbsCurveFields(obj, dim, w);
    d.map = parameterMap(obj, "map", w);
    const auto [first, last] = range(obj, w);
    d.first = first;
    d.last = last;
    const auto p = static_cast<std::size_t>(d.nurbs.degree);
    mapInside(d.map, first, last, d.nurbs.knots[p], d.nurbs.knots[d.nurbs.knots.size() - 1 - p], "range", w);
    return d;
}

void writeMappedCurve(Json& j, const MappedCurveData& d)
{
    writeNurbsCurve(j, d.nurbs);
    if (!d.map.isIdentity()) j["map"] = mapJson(d.map);
    j["range"] = Json::array({d.first, d.last});
}

/// The fields of a trimmed surface, as an object of its own or as a part's face (trims may then
/// name edges, below `edges`; otherwise an "edge" member is an unknown field).
TrimmedSurfaceData trimmedSurfaceFields(const Json& obj, int edges, const Where& w)
{
    TrimmedSurfaceData d;
    d.surface = nurbsSurfaceFields(obj, w);
    d.map[0] = parameterMap(obj, "map_u", w);
    d.map[1] = parameterMap(obj, "map_v", w);
    const std::vector<double> box = numbers(member(obj, "domain", w), "domain", 4, w);
    if (!(box[0] < box[1])) w.fail("domain", "u0 must be below u1");
    if (!(box[2] < box[3])) w.fail("domain", "v0 must be below v1");
    d.domain = {box[0], box[1], box[2], box[3]};
    for (int dir = 0; dir < 2; ++dir) {
        const std::vector<double>& k = d.surface.knots[static_cast<std::size_t>(dir)];
        const auto p = static_cast<std::size_t>(d.surface.degree[static_cast<std::size_t>(dir)]);
        mapInside(d.map[static_cast<std::size_t>(dir)], box[2 * static_cast<std::size_t>(dir)],
                  box[2 * static_cast<std::size_t>(dir) + 1], k[p], k[k.size() - 1 - p], "domain", w);
    }
    if (!obj.contains("loops")) return d;
    const Json& loops = obj["loops"];
    if (!loops.is_array()) w.fail("loops", "expected an array of loops, found " + typeName(loops));
    for (std::size_t l = 0; l < loops.size(); ++l) {
        const Json& loop = loops[l];
        if (!loop.is_array() || loop.empty()) w.fail(indexed("loops", l), "expected a non-empty array of trim curves");
        std::vector<TrimCurveData> curves;
        for (std::size_t c = 0; c < loop.size(); ++c) {
            const Where cw = w.inside(indexed(indexed("loops", l), c));
            const Json& t = loop[c];
            if (!t.is_object()) cw.fail("", "expected a trim curve object, found " + typeName(t));
            if (edges >= 0)
                onlyKnown(t, {"degree", "knots", "points", "weights", "map", "range", "reversed", "edge"}, cw);
            else
                onlyKnown(t, {"degree", "knots", "points", "weights", "map", "range", "reversed"}, cw);
            TrimCurveData trim;
            trim.curve = mappedCurve(t, 2, cw);
            trim.reversed = flag(t, "reversed", cw);
            if (t.contains("edge")) {
                trim.edge = integer(t["edge"], "edge", cw);
                if (trim.edge < 0 || trim.edge >= edges)
                    cw.fail("edge", "edge " + std::to_string(trim.edge) + " is out of range 0.." + std::to_string(edges - 1));
            }
            curves.push_back(std::move(trim));
        }
        d.loops.push_back(std::move(curves));
    }
    return d;
}

void writeTrimmedSurfaceFields(Json& j, const TrimmedSurfaceData& d)
{
    writeNurbsSurface(j, d.surface);
    if (!d.map[0].isIdentity()) j["map_u"] = mapJson(d.map[0]);
    if (!d.map[1].isIdentity()) j["map_v"] = mapJson(d.map[1]);
    j["domain"] = d.domain;
    if (d.loops.empty()) return;
    Json loops = Json::array();
    for (const auto& loop : d.loops) {
        Json curves = Json::array();
        for (const TrimCurveData& t : loop) {
            Json c;
            writeMappedCurve(c, t.curve);
            if (t.reversed) c["reversed"] = true;
            if (t.edge >= 0) c["edge"] = t.edge;
            curves.push_back(std::move(c));
        }
        loops.push_back(std::move(curves));
    }
    j["loops"] = std::move(loops);
}

/// An array of arrays of indices below `count` ("shells": faces, "solids": shells).
std::vector<std::vector<int>> indexLists(const Json& obj, const char* field, int count, const char* what,
                                         const Where& w)
{
    std::vector<std::vector<int>> out;
    if (!obj.contains(field)) return out;
    const Json& lists = obj[field];
    if (!lists.is_array()) w.fail(field, "expected an array of arrays of " + std::string(what) + " indices");
    for (std::size_t i = 0; i < lists.size(); ++i) {
        const std::string f = indexed(field, i);
        if (!lists[i].is_array() || lists[i].empty()) w.fail(f, "expected a non-empty array of " + std::string(what) + " indices");
        std::vector<int> list;
        for (std::size_t k = 0; k < lists[i].size(); ++k) {
            const int v = integer(lists[i][k], indexed(f, k), w);
            if (v < 0 || v >= count)
                w.fail(indexed(f, k), std::string(what) + " " + std::to_string(v) + " is out of range 0.." +
                                          std::to_string(count - 1));
            list.push_back(v);
        }
        out.push_back(std::move(list));
    }
    return out;
}

/// An array member that must be present (may be empty).
const Json& arrayMember(const Json& obj, const char* field, const Where& w)
{
    const Json& a = member(obj, field, w);
    if (!a.is_array()) w.fail(field, "expected an array, found " + typeName(a));
    return a;
}

} // namespace

TrimmedSurfaceData trimmedSurfaceObject(const Json& obj, const Where& w)
{
    onlyKnown(obj, {"name", "type", "degree", "knots", "points", "weights", "map_u", "map_v", "domain", "loops", "editor"}, w);
    return trimmedSurfaceFields(obj, -1, w);
}

PartData partObject(const Json& obj, const Where& w)
{
    onlyKnown(obj, {"name", "type", "units", "faces", "edges", "vertices", "shells", "solids", "editor"}, w);
    PartData d;
    if (obj.contains("units")) {
        d.units = string(obj["units"], "units", w);
        if (d.units.empty()) w.fail("units", "is empty");
    }
    const Json& vertices = arrayMember(obj, "vertices", w);
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        const Where vw = w.inside(indexed("vertices", i));
        const Json& v = vertices[i];
        if (!v.is_object()) vw.fail("", "expected a vertex object, found " + typeName(v));
        onlyKnown(v, {"point", "tolerance"}, vw);
        PartVertexData vertex;
        const std::vector<double> p = numbers(member(v, "point", vw), "point", 3, vw);
        vertex.point = {p[0], p[1], p[2]};
        vertex.tolerance = tolerance(v, vw);
        d.vertices.push_back(vertex);
    }
    const int vertexCount = static_cast<int>(d.vertices.size());
    const Json& edges = arrayMember(obj, "edges", w);
    for (std::size_t i = 0; i < edges.size(); ++i) {
        const Where ew = w.inside(indexed("edges", i));
        const Json& e = edges[i];
        if (!e.is_object()) ew.fail("", "expected an edge object, found " + typeName(e));
        onlyKnown(e, {"curve", "range", "vertices", "tolerance", "degenerate"}, ew);
        PartEdgeData edge;
        if (e.contains("curve")) {
            const Where cw = ew.inside("curve");
            const Json& c = e["curve"];
            if (!c.is_object()) ew.fail("curve", "expected a curve object, found " + typeName(c));
            onlyKnown(c, {"degree", "knots", "points", "weights", "map", "range"}, cw);
            edge.curve = mappedCurve(c, 3, cw);
        }
        const auto [first, last] = range(e, ew);
        edge.first = first;
        edge.last = last;
        const Json& ends = member(e, "vertices", ew);
        if (!ends.is_array() || ends.size() != 2) ew.fail("vertices", "expected [start, end] vertex indices");
        for (std::size_t k = 0; k < 2; ++k) {
            const int v = integer(ends[k], indexed("vertices", k), ew);
            if (v < -1 || v >= vertexCount)
                ew.fail(indexed("vertices", k), "vertex " + std::to_string(v) + " is out of range 0.." +
                                                    std::to_string(vertexCount - 1) + " (-1: none)");
            (k == 0 ? edge.start : edge.end) = v;
        }
        edge.tolerance = tolerance(e, ew);
        edge.degenerate = flag(e, "degenerate", ew);
        d.edges.push_back(std::move(edge));
    }
    const Json& faces = arrayMember(obj, "faces", w);
    if (faces.empty()) w.fail("faces", "a part needs at least one face");
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const Where fw = w.inside(indexed("faces", i));
        const Json& f = faces[i];
        if (!f.is_object()) fw.fail("", "expected a face object, found " + typeName(f));
        onlyKnown(f, {"degree", "knots", "points", "weights", "map_u", "map_v", "domain", "loops", "reversed", "surface",
                      "tolerance"},
                  fw);
        PartFaceData face;
        face.surface = trimmedSurfaceFields(f, static_cast<int>(d.edges.size()), fw);
        face.reversed = flag(f, "reversed", fw);
        if (f.contains("surface")) face.kind = string(f["surface"], "surface", fw);
        face.tolerance = tolerance(f, fw);
        d.faces.push_back(std::move(face));
    }
    d.shells = indexLists(obj, "shells", static_cast<int>(d.faces.size()), "face", w);
    d.solids = indexLists(obj, "solids", static_cast<int>(d.shells.size()), "shell", w);
    return d;
}

void writeTrimmedSurface(Json& j, const TrimmedSurfaceData& d) { writeTrimmedSurfaceFields(j, d); }

void writePart(Json& j, const PartData& d)
{
    j["units"] = d.units;
    Json faces = Json::array();
    for (const PartFaceData& f : d.faces) {
        Json face;
        writeTrimmedSurfaceFields(face, f.surface);
        if (f.reversed) face["reversed"] = true;
        if (!f.kind.empty()) face["surface"] = f.kind;
        face["tolerance"] = f.tolerance;
        faces.push_back(std::move(face));
    }
    j["faces"] = std::move(faces);
    Json edges = Json::array();
    for (const PartEdgeData& e : d.edges) {
        Json edge;
        if (e.curve) {
            Json curve;
            writeMappedCurve(curve, *e.curve);
            edge["curve"] = std::move(curve);
        }
        edge["range"] = Json::array({e.first, e.last});
        edge["vertices"] = Json::array({e.start, e.end});
        edge["tolerance"] = e.tolerance;
        if (e.degenerate) edge["degenerate"] = true;
        edges.push_back(std::move(edge));
    }
    j["edges"] = std::move(edges);
    Json vertices = Json::array();
    for (const PartVertexData& v : d.vertices)
        vertices.push_back(Json{{"point", Json::array({v.point.x(), v.point.y(), v.point.z()})}, {"tolerance", v.tolerance}});
    j["vertices"] = std::move(vertices);
    j["shells"] = d.shells;
    j["solids"] = d.solids;
}

} // namespace freeform::document_json
