// The kind table (document/kinds.h): its names are the format's type strings, and every claim a
// row makes (what the kind is, its parameters, dimension, weights and knots, and each operation it
// supports or not) is checked against the document layer's operations on real objects of that kind:
// data/ffd_every_type.json, examples/data/nurbs.json and data/parts/ hold all thirteen.

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>

#include "freeform/document/document.h"
#include "freeform/document/object_data.h"
#include "freeform/io/geometry_data.h"

namespace test_kinds {

using namespace freeform;

namespace {

TypedDocument everyKind()
{
    TypedDocument doc = TypedDocument::read(std::string(FREEFORM_SOURCE_DIR) + "/data/ffd_every_type.json");
    const TypedDocument nurbs = TypedDocument::read(std::string(FREEFORM_SOURCE_DIR) + "/examples/data/nurbs.json");
    for (const TypedObject& o : nurbs.objects()) doc.add(o.name(), o.data());
    for (const char* file : {"/data/parts/plate.json", "/data/parts/trimmed_square.json"}) {
        const TypedDocument part = TypedDocument::read(std::string(FREEFORM_SOURCE_DIR) + file);
        for (const TypedObject& o : part.objects()) doc.add(o.name(), o.data());
    }
    // Objects every conversion applies to: a C2 cubic bezier_spline (the A-frame of a de Boor
    // spline) and NURBS forms of a polynomial spline and patch (one object of Bézier pieces each).
    doc.add("c2", toBezierSplineData(doc, doc.object("deboor3")));
    doc.add("nurbs_spline", toNurbsData(doc, doc.object("spline3")));
    doc.add("nurbs_patch", toNurbsData(doc, doc.object("patch")));
    return doc;
}

bool succeeds(const std::function<void()>& f)
{
    try {
        f();
        return true;
    } catch (const Error&) {
        return false;
    }
}

/// A parameter inside the object's domain, with the count its kind's parameters say.
std::vector<double> inside(const TypedObject& o)
{
    const std::vector<double> domain = parameterDomain(o);
    // A trimmed surface's domain is its parameter box (u0, u1, v0, v1); a part's face 0 has one.
    if (const auto* t = std::get_if<TrimmedSurface>(&o.geometry())) return {t->domain().center().x(), t->domain().center().y()};
    if (const auto* p = std::get_if<Part>(&o.geometry()))
        return {0, p->faces[0].surface.domain().center().x(), p->faces[0].surface.domain().center().y()};
    switch (o.info().parameters) {
    case KindParameters::T: return {0.5 * domain.at(0)};
    case KindParameters::UV: return {0.5 * domain.at(0), 0.5 * domain.at(1)};
    case KindParameters::STU: return {0.5, 0.25, 0.75};
    case KindParameters::FaceUV: return {0, 0.5, 0.5};
    }
    return {};
}

bool hasMember(const ObjectData& data, bool knots)
{
    return std::visit(
        [&](const auto& d) {
            // A trimmed surface's and a part's NURBS hold them (every face's, every trim's).
            using T = std::decay_t<decltype(d)>;
            if constexpr (std::is_same_v<T, TrimmedSurfaceData> || std::is_same_v<T, PartData>) return true;
            if (knots) return requires { d.knots; };
            return requires { d.weights; };
        },
        data);
}

} // namespace

TEST_CASE("the kind table names every kind as the format does, in ObjectData's order", "[kinds]")
{
    const ObjectData samples[] = {BezierCurveData{},         BezierSplineData{},      DeBoorSplineData{},
                                  BezierSurfaceData{},       DeBoorSurfaceData{},     LatticeData{},
                                  SubdivisionSurfaceData{},  RationalBezierCurveData{}, RationalBezierSurfaceData{},
                                  NurbsCurveData{},          NurbsSurfaceData{},      TrimmedSurfaceData{},
                                  PartData{}};
    REQUIRE(std::size(samples) == objectKinds().size());
    std::set<std::string_view> names;
    for (std::size_t k = 0; k < objectKinds().size(); ++k) {
        const KindInfo& info = objectKinds()[k];
        CHECK(static_cast<std::size_t>(info.kind) == k);
        CHECK(info.name == objectType(samples[k]));
        CHECK(&kindInfo(samples[k]) == &info);
        CHECK(findKind(info.name) == &info);
        CHECK(kindNamed(info.name) == info.kind);
        CHECK(!info.summary.empty());
        names.insert(info.name);
    }
    CHECK(names.size() == objectKinds().size());
    CHECK(findKind("bezier_curves") == nullptr);
    CHECK(findKind("") == nullptr);
    CHECK(findKind("mesh") == nullptr);
    // The parser's list of known types is the table's.
    try {
        parseDocument(R"({"format": "freeform", "version": 1, "objects": [{"name": "x", "type": "spline"}]})");
        FAIL("an unknown type was accepted");
    } catch (const Error& e) {
        const std::string what = e.what();
        for (const KindInfo& info : objectKinds()) CHECK(what.find(std::string(info.name)) != std::string::npos);
    }
}

TEST_CASE("every claim of a row holds for real objects of that kind", "[kinds]")
{
    const TypedDocument doc = everyKind();
    std::set<ObjectKind> seen;
    for (const TypedObject& o : doc.objects()) {
        const KindInfo& info = o.info();
        INFO(o.name() << " (" << info.name << ")");
        seen.insert(info.kind);
        CHECK(o.type() == info.name);
        CHECK(o.kind() == info.kind);
        if (info.dimension != 0) CHECK(o.dimension() == info.dimension);
        CHECK(hasMember(o.data(), false) == info.rational);
        CHECK(hasMember(o.data(), true) == info.knots);

        // Evaluate: the row's parameter count is the one evaluate takes, and one fewer is refused.
        std::vector<double> at = inside(o);
        CHECK(succeeds([&] { evaluate(doc, o, at, 0); }) == info.supports(KindOperation::Evaluate));
        at.pop_back();
        CHECK_FALSE(succeeds([&] { evaluate(doc, o, at, 0); }));
        CHECK((info.nature == KindNature::Curve) == (info.parameters == KindParameters::T));
        CHECK((info.nature == KindNature::Volume) == (info.parameters == KindParameters::STU));

        CHECK(objectPolyline(o, 1e-3).has_value() == info.supports(KindOperation::Polyline));
        CHECK(info.supports(KindOperation::Polyline) == info.isCurve());
        ObjectTessellation coarse;
        coarse.segments = 2;
        CHECK(tessellateObject(o, coarse).has_value() == info.supports(KindOperation::Tessellate));
        CHECK(info.supports(KindOperation::Tessellate) == (info.isSurface() || info.nature == KindNature::Part));
        CHECK(succeeds([&] { continuity(doc, o); }) == info.supports(KindOperation::Continuity));
        CHECK(succeeds([&] { toNurbsData(doc, o); }) == info.supports(KindOperation::ToNurbs));
        if (!info.supports(KindOperation::FromNurbs)) CHECK_FALSE(succeeds([&] { fromNurbsData(doc, o); }));
        if (!info.supports(KindOperation::ConvertSpline))
            for (ObjectKind form : {ObjectKind::BezierSpline, ObjectKind::DeBoorSpline}) {
                TypedDocument copy = doc;
                CHECK_FALSE(succeeds([&] { convertSpline(copy, o.id(), std::string(kindName(form))); }));
            }
    }
    CHECK(seen.size() == objectKinds().size()); // the documents hold every kind
    // Where a row claims a conversion, some object of the kind converts (not every one: a
    // bezier_spline that is not C2, a NURBS object of several rational pieces cannot).
    for (const KindInfo& info : objectKinds()) {
        INFO(info.name);
        bool spline = false, fromNurbs = false;
        for (const TypedObject& o : doc.objects()) {
            if (o.kind() != info.kind) continue;
            const ObjectKind other = info.kind == ObjectKind::BezierSpline ? ObjectKind::DeBoorSpline : ObjectKind::BezierSpline;
            TypedDocument copy = doc;
            spline = spline || succeeds([&] { convertSpline(copy, o.id(), std::string(kindName(other))); });
            fromNurbs = fromNurbs || succeeds([&] { fromNurbsData(doc, o); });
        }
        CHECK(spline == info.supports(KindOperation::ConvertSpline));
        CHECK(fromNurbs == info.supports(KindOperation::FromNurbs));
    }
}

TEST_CASE("deformDocument moves exactly the 3D objects whose kind says Deform", "[kinds]")
{
    TypedDocument doc = everyKind();
    // A lattice that is not affine: one corner moved.
    const Lattice& lattice = std::get<Lattice>(doc.object("L").geometry());
    Lattice::Points p = lattice.controlPoints();
    p.col(p.cols() - 1) += Eigen::Vector3d(0.3, -0.2, 0.1);
    const Lattice bent(lattice.degrees(), lattice.origin(), lattice.axes(), p, lattice.outside());
    REQUIRE_FALSE(isAffineLattice(bent));
    std::map<ObjectId, const KindInfo*> kinds;
    std::map<ObjectId, int> dims;
    for (const TypedObject& o : doc.objects()) kinds[o.id()] = &o.info(), dims[o.id()] = o.dimension();
    const DeformDocumentReport report = deformDocument(doc, bent);
    std::set<ObjectId> moved;
    for (const DeformedObject& d : report.objects) moved.insert(d.id);
    for (const auto& [id, info] : kinds) {
        INFO(doc.object(id).name());
        CHECK(moved.count(id) == (info->supports(KindOperation::Deform) && dims[id] == 3 ? 1u : 0u));
        CHECK(info->supports(KindOperation::DeformsOthers) == (info->kind == ObjectKind::Lattice));
    }
}

TEST_CASE("the kinds whose row says Part are those objectPart makes a part of", "[kinds]")
{
    const TypedDocument doc = everyKind();
    std::set<ObjectKind> parts;
    for (const TypedObject& o : doc.objects()) {
        INFO(o.name() << " (" << o.type() << ")");
        CHECK(o.info().supports(KindOperation::Part) == objectPart(o).has_value());
        if (objectPart(o)) parts.insert(o.info().kind);
    }
    CHECK(parts == std::set<ObjectKind>{ObjectKind::TrimmedSurface, ObjectKind::Part});
}

TEST_CASE("toData is the inverse of buildGeometry for every kind", "[kinds]")
{
    const TypedDocument doc = everyKind();
    auto text = [](const ObjectData& data) { return formatDocument(Document{{DocumentObject{"x", data, ""}}, "", ""}); };
    std::set<ObjectKind> seen;
    for (const TypedObject& o : doc.objects()) {
        INFO(o.name() << " (" << o.type() << ")");
        const ObjectData data = toData(o.geometry());
        CHECK(objectKind(data) == o.kind());
        const Geometry again = buildGeometry(data, doc.directory, o.name());
        CHECK(text(toData(again)) == text(data)); // a fixed point
        // The file's own data comes back, but where the format has two spellings of one geometry:
        // intervals left out (all 1) come back written, and a cage from a mesh file comes back inline.
        const bool canonical = std::visit(
            [](const auto& d) {
                if constexpr (requires { d.intervals; }) return !d.intervals.empty();
                else if constexpr (requires { d.mesh; }) return d.mesh.empty();
                else return true;
            },
            o.data());
        if (canonical) CHECK(text(data) == text(o.data()));
        seen.insert(o.kind());
    }
    CHECK(seen.size() == objectKinds().size());

    // A spline whose intervals were left out: the same geometry, the intervals written as 1.
    const TypedDocument one(parseDocument(R"({"format": "freeform", "version": 1, "objects": [
      {"name": "s", "type": "bezier_spline", "degree": 1, "closed": false, "points": [[0,0],[1,0],[1,2]]}]})"));
    const auto written = std::get<BezierSplineData>(toData(one.object("s").geometry()));
    CHECK(written.intervals == std::vector<double>{1, 1});

    // A cage with holes from its mesh file has no inline form: refused, nothing half written.
    SubdivisionCage cage;
    cage.mesh = std::get<SubdivisionObject>(doc.object("cage").geometry()).cage().mesh;
    cage.holes = {0};
    const SubdivisionObject holed{SubdivisionSurface(cage, SubdivisionScheme::Catmark)};
    CHECK_THROWS_WITH(toData(holed), Catch::Contains("holes"));
}

TEST_CASE("a cage file with holes has no inline form: deformDocument and inlineCage refuse it, nothing changed", "[kinds]")
{
    const std::string dir = std::string(FREEFORM_TEST_TMP) + "/kinds_holes";
    std::filesystem::create_directories(dir);
    {
        std::ifstream in(std::string(FREEFORM_SOURCE_DIR) + "/data/cages/cube.obj");
        std::ofstream out(dir + "/holed.obj");
        out << in.rdbuf() << "t hole 1/0/0 0\n";
    }
    const Document data = parseDocument(R"({"format": "freeform", "version": 1, "objects": [
      {"name": "cage", "type": "subdivision_surface", "mesh": "holed.obj"},
      {"name": "L", "type": "lattice", "degree": [1, 1, 1], "origin": [-2, -2, -2],
       "axes": [[4,0,0],[0,4,0],[0,0,4]],
       "points": [[-2,-2,-2],[-2,-2,2],[-2,2,-2],[-2,2,2],[2,-2,-2],[2,-2,2],[2,2,-2],[3,3,3]]}]})",
                                        "holes.json");
    TypedDocument doc(data, dir);
    REQUIRE(std::get<SubdivisionObject>(doc.object("cage").geometry()).cage().holes == std::vector<int>{0});
    const std::string before = formatDocument(doc.toDocument());
    const Lattice lattice = std::get<Lattice>(doc.object("L").geometry());
    CHECK_THROWS_WITH(deformDocument(doc, lattice), Catch::Contains("object \"cage\"") && Catch::Contains("holes"));
    CHECK(formatDocument(doc.toDocument()) == before);
    CHECK_THROWS_WITH(inlineCage(std::get<SubdivisionSurfaceData>(data.object("cage").data), dir, "\"cage\""),
                      Catch::Contains("\"cage\"") && Catch::Contains("holes"));
}

TEST_CASE("objectDetails words each kind's degrees and form as written by hand", "[kinds]")
{
    BezierCurveData curve;
    curve.points = PointColumns::Zero(2, 4);
    CHECK(objectDetails(curve) == "degree 3, 2D");
    BezierSplineData spline;
    spline.degree = 2;
    spline.closed = true;
    spline.points = PointColumns::Zero(3, 4);
    CHECK(objectDetails(spline) == "degree 2, closed");
    DeBoorSplineData deboor;
    deboor.end = "clamped";
    CHECK(objectDetails(deboor) == "degree 3, end clamped");
    LatticeData lattice;
    lattice.degree = {1, 2, 3};
    CHECK(objectDetails(lattice) == "degree 1 x 2 x 3");
    NurbsCurveData nurbs;
    nurbs.degree = 2;
    nurbs.knots = {0, 0, 0, 1, 1, 1};
    nurbs.points = PointColumns::Zero(3, 3);
    CHECK(objectDetails(nurbs) == "degree 2, 6 knots, 3D");
    NurbsSurfaceData surface;
    surface.degree = {2, 1};
    surface.rows = 3;
    surface.cols = 2;
    CHECK(objectDetails(surface) == "degree 2 x 1, 3 x 2 points");
    TrimmedSurfaceData trimmed;
    trimmed.surface = surface;
    trimmed.loops.resize(2);
    CHECK(objectDetails(trimmed) == "degree 2 x 1, 2 trim loops");
    PartData part;
    part.faces.resize(1);
    part.edges.resize(4);
    part.vertices.resize(4);
    part.shells.push_back({0});
    part.units = "inch";
    CHECK(objectDetails(part) == "1 face, 4 edges, 4 vertices, 1 shell, 0 solids, units inch");
    CHECK(objectDetails(SubdivisionSurfaceData{}).empty());
    // Every kind has words (the subdivision surface aside): a new kind without them fails here.
    const auto empty = []<std::size_t... I>(std::size_t k, std::index_sequence<I...>) {
        ObjectData out;
        ((k == I ? (out = std::variant_alternative_t<I, ObjectData>{}, 0) : 0), ...);
        return out;
    };
    for (const KindInfo& k : objectKinds()) {
        const ObjectData d = empty(static_cast<std::size_t>(k.kind), std::make_index_sequence<std::variant_size_v<ObjectData>>{});
        REQUIRE(objectKind(d) == k.kind);
        if (k.kind != ObjectKind::SubdivisionSurface) CHECK_FALSE(objectDetails(d).empty());
    }
}

} // namespace test_kinds
