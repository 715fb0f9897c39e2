// freeform.Part, Face and Edge: STEP, IGES and BRep parts (docs/python.md "CAD parts", docs/cad.md). The
// faces' surfaces and the edges' curves come out as the existing NurbsSurface and NurbsCurve (in
// their NURBS parameters); points(), normals() and classify() take the file's parameters.

#include <array>
#include <filesystem>
#include <memory>
#include <optional>

#include "freeform/brep/part_deform.h"
#include "freeform/brep/part_mesh.h"
#include "freeform/cad/cad_file.h"
#include "freeform/core/format.h"
#include "freeform/document/model.h"
#include "freeform/document/operations.h"
#include "freeform/document/object_data.h"
#include "lattice.h"
#include "nurbs.h"

namespace ffpy {

/// The lattice of a RationalLattice argument, or nullopt for anything else (nurbs_surface.cpp).
std::optional<freeform::RationalLattice> rationalLatticeArg(py::handle h);

namespace {

using freeform::Part;

struct PyPart {
    std::shared_ptr<const Part> part;
};
struct PyFace {
    std::shared_ptr<const Part> part;
    int index;
    const freeform::PartFace& face() const { return part->faces[static_cast<std::size_t>(index)]; }
};
/// A trimmed_surface object: the surface itself (document data without edges) and the part of one
/// face it is (singleFacePart) for what a Face, tessellate and deform read.
struct PyTrimmed : PyFace {
    std::shared_ptr<const freeform::TrimmedSurface> surface;
};
struct PyEdge {
    std::shared_ptr<const Part> part;
    int index;
    const freeform::PartEdge& edge() const { return part->edges[static_cast<std::size_t>(index)]; }
};

/// An (N, 2) parameter array as rows (checked finite).
std::vector<Eigen::Vector2d> uvRows(py::handle h)
{
    const py::array a = rows(h, "uv", 2, false);
    const auto n = static_cast<std::size_t>(a.shape(0));
    const double* p = static_cast<const double*>(a.data());
    requireFiniteRows(p, n, 2, "uv");
    std::vector<Eigen::Vector2d> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = Eigen::Vector2d(p[2 * i], p[2 * i + 1]);
    return out;
}

/// ((u0, u1), (v0, v1)) as a box (checked u0 < u1, v0 < v1).
freeform::Box<double, 2> domainBox(py::handle h)
{
    const py::sequence d = py::reinterpret_borrow<py::sequence>(h);
    if (d.size() != 2) throw freeform::Error("domain: expected ((u0, u1), (v0, v1))");
    const auto u = numberList(d[0], "domain[0]"), v = numberList(d[1], "domain[1]");
    if (u.size() != 2 || v.size() != 2 || !(u[0] < u[1]) || !(v[0] < v[1]))
        throw freeform::Error("domain: expected ((u0, u1), (v0, v1)) with u0 < u1 and v0 < v1");
    return freeform::Box<double, 2>(Eigen::Vector2d(u[0], v[0]), Eigen::Vector2d(u[1], v[1]));
}

py::list indexLists(const std::vector<std::vector<int>>& lists)
{
    py::list out;
    for (const auto& l : lists) out.append(py::cast(l));
    return out;
}

/// The document's part (its only part or trimmed surface), for Part.load of a .json file.
Part documentPart(const std::string& path)
{
    const freeform::TypedDocument doc = freeform::TypedDocument::read(path);
    return *freeform::objectPart(freeform::documentPart(doc));
}

PyTrimmed trimmedObject(freeform::TrimmedSurface surface)
{
    auto s = std::make_shared<const freeform::TrimmedSurface>(std::move(surface));
    return PyTrimmed{{std::make_shared<const Part>(freeform::singleFacePart(*s)), 0}, s};
}

/// A part's certified mesh as (V, F) or (V, F, report) (Part.tessellate, TrimmedSurface.tessellate).
py::tuple meshTuple(const Part& part, double tolerance, long long maxTriangles, bool withReport)
{
    freeform::PartMeshOptions o;
    o.tolerance = tolerance;
    o.maxTriangles = maxTriangles;
    const freeform::PartMesh m = freeform::tessellatePart(part, o);
    py::array_t<double> V({static_cast<py::ssize_t>(m.mesh.vertexCount()), py::ssize_t{3}});
    std::copy(m.mesh.positions.data(), m.mesh.positions.data() + m.mesh.positions.size(), V.mutable_data());
    py::array_t<int> F({static_cast<py::ssize_t>(m.mesh.faceCount()), py::ssize_t{3}});
    std::copy(m.mesh.faceVertices.begin(), m.mesh.faceVertices.end(), F.mutable_data());
    if (!withReport) return py::make_tuple(V, F);
    const freeform::PartMeshReport& r = m.report;
    py::dict d;
    d["faces"] = r.faces;
    d["triangles"] = m.mesh.faceCount();
    d["vertices"] = m.mesh.vertexCount();
    d["watertight"] = r.watertight;
    d["error_bound"] = r.errorBound;
    d["certified"] = r.certified;
    d["closed_shells"] = r.closedShells;
    d["open_mesh_edges"] = r.openMeshEdges;
    d["max_vertex_gap"] = r.maxVertexGap;
    d["max_trim_deviation"] = r.maxTrimDeviation;
    d["face_bounds"] = r.faceBound;
    py::array_t<int> faceOf(static_cast<py::ssize_t>(m.triangleFace.size()));
    std::copy(m.triangleFace.begin(), m.triangleFace.end(), faceOf.mutable_data());
    d["triangle_faces"] = faceOf;
    return py::make_tuple(V, F, d);
}

/// A part through a Lattice or RationalLattice (Part.deform, TrimmedSurface.deform): the deformed
/// part and the report.
std::pair<Part, py::dict> deformed(const Part& part, py::handle lattice, double strength, int maxDegree, double tolerance)
{
    freeform::PartDeformOptions o;
    o.strength = strength;
    o.maxDegree = maxDegree;
    o.tolerance = tolerance;
    std::optional<freeform::RationalLattice> rational = rationalLatticeArg(lattice);
    if (!rational && py::isinstance<PyLattice>(lattice)) rational.emplace(lattice.cast<PyLattice&>().snapshot());
    if (!rational)
        throw py::type_error("lattice: expected a Lattice or RationalLattice, got " + std::string(py::str(py::type::handle_of(lattice).attr("__name__"))));
    freeform::DeformedPart d;
    {
        py::gil_scoped_release release;
        d = freeform::deformPart(part, *rational, o);
    }
    const freeform::PartDeformReport& r = d.report;
    py::dict report;
    report["faces"] = r.faces;
    report["exact_faces"] = r.exactFaces;
    report["approximated_faces"] = r.approximatedFaces;
    report["face_errors"] = r.faceErrors;
    report["max_approximation_error"] = r.maxApproximationError;
    report["max_degree"] = r.maxDegree;
    report["max_gap"] = r.maxGap;
    report["outside_faces"] = r.outsideFaces;
    report["approximated_edges"] = r.approximatedEdges;
    report["affine"] = r.affine;
    report["lipschitz"] = r.lipschitz;
    report["max_tolerance"] = r.maxTolerance;
    return {std::move(d.part), std::move(report)};
}

/// A trim curve of TrimmedSurface(...): a 2D NurbsCurve (its whole domain, forward) or a tuple
/// (curve, first, last[, reversed]).
freeform::TrimCurve trimCurve(py::handle h, const std::string& where)
{
    py::handle curve = h;
    std::optional<std::array<double, 2>> range;
    bool reversed = false;
    if (py::isinstance<py::tuple>(h) || py::isinstance<py::list>(h)) {
        const py::sequence t = py::reinterpret_borrow<py::sequence>(h);
        if (t.size() != 3 && t.size() != 4)
            throw freeform::Error(where + ": expected a NurbsCurve or (curve, first, last[, reversed]), got " + std::to_string(t.size()) + " items");
        curve = t[0];
        range = std::array<double, 2>{t[1].cast<double>(), t[2].cast<double>()};
        if (t.size() == 4) reversed = t[3].cast<bool>();
    }
    if (!py::isinstance<PyNurbsCurve>(curve)) throw freeform::Error(where + ": expected a 2D NurbsCurve");
    const auto* c2 = std::get_if<freeform::NurbsCurve<double, 2>>(&curve.cast<const PyNurbsCurve&>().c);
    if (!c2) throw freeform::Error(where + ": a trim curve lies in the surface's parameters: expected a 2D NurbsCurve, got a 3D one");
    const freeform::TrimCurve t{{*c2, {}, range ? (*range)[0] : c2->domainStart(), range ? (*range)[1] : c2->domainEnd()}, reversed, -1};
    if (!(t.curve.first < t.curve.last) || t.curve.first < c2->domainStart() || t.curve.last > c2->domainEnd())
        throw freeform::Error(where + ": the range [" + freeform::formatNumber(t.curve.first) + ", " + freeform::formatNumber(t.curve.last) +
                              "] is not an increasing part of the curve's domain [" + freeform::formatNumber(c2->domainStart()) + ", " +
                              freeform::formatNumber(c2->domainEnd()) + "]");
    return t;
}

} // namespace

py::object partObject(const Part& part) { return py::cast(PyPart{std::make_shared<const Part>(part)}); }

py::object trimmedSurfaceObject(const freeform::TrimmedSurface& surface) { return py::cast(trimmedObject(surface)); }

std::optional<freeform::ObjectData> partData(py::handle h)
{
    if (py::isinstance<PyTrimmed>(h)) return freeform::ObjectData(freeform::toData(*h.cast<const PyTrimmed&>().surface));
    if (!py::isinstance<PyPart>(h)) return std::nullopt;
    return freeform::ObjectData(freeform::toData(*h.cast<const PyPart&>().part));
}

void bindPart(py::module_& m)
{
    py::class_<PyPart>(m, "Part", R"doc(
A CAD part read from a STEP (.step .stp), IGES (.iges .igs) or BRep (.brep) file through Open CASCADE (docs/cad.md),
or from a document's part object (.json): faces (trimmed NURBS surfaces in their exact forms), edges, vertices,
shells and solids, in the file's length unit. Faces and edges are numbered as Open CASCADE numbers them, from 0.
A module built without Open CASCADE has parts too, from documents and trimmed surfaces: Part.formats says
which files load and save take.)doc")
        .def_property_readonly_static(
            "formats",
            [](const py::object&) {
                py::tuple all = freeform::cadFilesSupported() ? py::make_tuple(".step", ".stp", ".iges", ".igs", ".brep", ".json")
                                                              : py::make_tuple(".json");
                return all;
            },
            "The file extensions load and save take: ('.step', '.stp', '.iges', '.igs', '.brep', '.json'), or "
            "('.json',) in a module built without Open CASCADE (FREEFORM_BUILD_CAD=OFF), whose load and save raise "
            "freeform.Error naming any other file.")
        .def_static(
            "load",
            [](const std::string& path) {
                const bool document = std::filesystem::path(path).extension() == ".json";
                return PyPart{std::make_shared<const Part>(document ? documentPart(path) : freeform::readCadFile(path))};
            },
            py::arg("path"),
            "Reads a STEP, IGES or BRep file (a BRep file has no unit: millimetres), or the part object of a document (.json; docs/format.md) (freeform.Error "
            "naming the file and the face or edge on bad input).")
        .def_property_readonly("faces",
                               [](const PyPart& p) {
                                   py::list out;
                                   for (std::size_t i = 0; i < p.part->faces.size(); ++i)
                                       out.append(PyFace{p.part, static_cast<int>(i)});
                                   return out;
                               })
        .def_property_readonly("edges",
                               [](const PyPart& p) {
                                   py::list out;
                                   for (std::size_t i = 0; i < p.part->edges.size(); ++i)
                                       out.append(PyEdge{p.part, static_cast<int>(i)});
                                   return out;
                               })
        .def_property_readonly("vertices",
                               [](const PyPart& p) {
                                   Points3 v(3, static_cast<Eigen::Index>(p.part->vertices.size()));
                                   for (std::size_t i = 0; i < p.part->vertices.size(); ++i)
                                       v.col(static_cast<Eigen::Index>(i)) = p.part->vertices[i].point;
                                   return fromColumns(v);
                               },
                               "The vertices' points, (V, 3).")
        .def_property_readonly("shells",
                               [](const PyPart& p) {
                                   std::vector<std::vector<int>> s;
                                   for (const auto& shell : p.part->shells) s.push_back(shell.faces);
                                   return indexLists(s);
                               },
                               "Each shell's face indices.")
        .def_property_readonly("solids",
                               [](const PyPart& p) {
                                   std::vector<std::vector<int>> s;
                                   for (const auto& solid : p.part->solids) s.push_back(solid.shells);
                                   return indexLists(s);
                               },
                               "Each solid's shell indices.")
        .def_property_readonly("units", [](const PyPart& p) { return p.part->units; }, "The file's length unit ('mm', 'm', 'in', ...).")
        .def_property_readonly("bounds", [](const PyPart& p) { return boxTuple<3>(p.part->bounds()); },
                               "(min, max): a box holding every face.")
        .def_property_readonly("area", [](const PyPart& p) { return p.part->area(); }, "The sum of the faces' areas.")
        .def(
            "tessellate",
            [](const PyPart& p, double tolerance, long long maxTriangles, bool withReport) {
                return meshTuple(*p.part, tolerance, maxTriangles, withReport);
            },
            py::arg("tolerance"), py::arg("max_triangles") = 10'000'000LL, py::arg("report") = false,
            "The certified watertight mesh (docs/cad.md, 'Tessellation'): (V (N, 3) float64, F (T, 3) int32), "
            "every triangle within the bound of its face (<= tolerance when certified), each edge sampled once "
            "for both of its faces. report=True adds a dict: the counts, watertight, error_bound, certified, "
            "face_bounds and triangle_faces (the face of each triangle).")
        .def(
            "check",
            [](const PyPart& p) {
                const freeform::PartCheck c = freeform::checkPart(*p.part);
                py::dict d;
                d["closed"] = c.closed;
                d["open_edges"] = c.openEdges;
                d["non_manifold_edges"] = c.nonManifoldEdges;
                d["max_gap"] = c.maxGap;
                d["gaps_over_tolerance"] = c.gapsOverTolerance;
                return d;
            },
            "The topology and gap check (as `freeform info`): closed, open_edges, non_manifold_edges, max_gap, "
            "gaps_over_tolerance.")
        .def(
            "deform",
            [](const PyPart& p, py::handle lattice, double strength, int maxDegree, double tolerance) {
                auto [part, report] = deformed(*p.part, lattice, strength, maxDegree, tolerance);
                return py::make_tuple(PyPart{std::make_shared<const Part>(std::move(part))}, report);
            },
            py::arg("lattice"), py::arg("strength") = 1.0, py::arg("max_degree") = 0, py::arg("tolerance") = 0.0,
            "The part through the lattice (a Lattice, or a RationalLattice: docs/nurbs.md 'Rational FFD'), exactly "
            "(docs/cad.md, Deformation): (Part, report); strength is this argument's. Every face's surface "
            "and edge's curve composed with the lattice, trims kept, vertices mapped. max_degree > 0 (25 for save()) "
            "reduces faces and edges above it within tolerance (<= 0: 1e-6 of the part's size), certified; "
            "without it, faces the composition takes over degree 67 are reduced to 67 the same way. The "
            "report: faces, exact_faces, approximated_faces (indices), face_errors, max_approximation_error, "
            "max_degree, max_gap, outside_faces, approximated_edges, affine, lipschitz, max_tolerance.")
        .def(
            "save",
            [](const PyPart& p, const std::string& path) {
                freeform::CadWriteReport w;
                if (std::filesystem::path(path).extension() == ".json") {
                    // A document of one part object named after the file (docs/format.md).
                    std::string name = std::filesystem::path(path).stem().string();
                    freeform::Document doc;
                    doc.objects.push_back({name.empty() ? std::string("unnamed") : name, freeform::toData(*p.part), {}});
                    freeform::writeDocument(doc, path);
                    const freeform::PartCheck check = freeform::checkPart(*p.part);
                    w.valid = check.gapsOverTolerance == 0;
                    for (const auto& e : p.part->edges) w.maxTolerance = std::max(w.maxTolerance, e.tolerance);
                    py::dict d;
                    d["valid"] = w.valid;
                    d["max_tolerance"] = w.maxTolerance;
                    return d;
                }
                {
                    py::gil_scoped_release release;
                    w = freeform::writeCadFile(*p.part, path);
                }
                py::dict d;
                d["valid"] = w.valid;
                d["fitted_trims"] = w.fittedPcurves;
                d["max_trim_gap"] = w.maxPcurveGap;
                d["raised_tolerances"] = w.raisedTolerances;
                d["max_tolerance"] = w.maxTolerance;
                return d;
            },
            py::arg("path"),
            "Writes the part as STEP (.step .stp), IGES (.iges .igs) or BRep (.brep, a part in millimetres only: the "
            "format has no unit) through Open CASCADE (docs/cad.md, Writing), or "
            "as a document of one part object named after the file (.json: every degree kept, up to 67; returns "
            "valid (every sampled gap within its edge's tolerance) and max_tolerance); "
            "returns valid (Open CASCADE's check), fitted_trims, max_trim_gap, raised_tolerances, max_tolerance. "
            "freeform.Error for a face or edge over degree 25 (deform with max_degree=25) or a bad path; nothing "
            "is written then.")
        .def("__repr__", [](const PyPart& p) {
            return "<freeform.Part: " + std::to_string(p.part->faces.size()) + " faces, " +
                   std::to_string(p.part->edges.size()) + " edges, " + std::to_string(p.part->solids.size()) + " solids, " +
                   p.part->units + ">";
        });

    py::class_<PyFace>(m, "Face", "A face of a Part: a trimmed NURBS surface in the file's parameters.")
        .def_property_readonly("index", [](const PyFace& f) { return f.index; })
        .def_property_readonly("kind", [](const PyFace& f) { return f.face().surfaceKind; },
                               "The surface kind the file gave: 'plane', 'cylinder', 'cone', 'sphere', 'torus', "
                               "'revolution', 'extrusion', 'bspline' or 'bezier'.")
        .def_property_readonly("reversed", [](const PyFace& f) { return f.face().reversed; },
                               "Whether the outward normal is -(S_u x S_v).")
        .def_property_readonly("domain",
                               [](const PyFace& f) {
                                   const auto& d = f.face().surface.domain();
                                   return py::make_tuple(py::make_tuple(d.min().x(), d.max().x()),
                                                         py::make_tuple(d.min().y(), d.max().y()));
                               },
                               "((u0, u1), (v0, v1)): the face's box in the file's parameters.")
        .def_property_readonly("surface", [](const PyFace& f) { return PyNurbsSurface{f.face().surface.surface().nurbs}; },
                               "The exact NURBS form (in its own parameters; points() maps the file's).")
        .def_property_readonly("loops",
                               [](const PyFace& f) {
                                   py::list out;
                                   for (const auto& loop : f.face().surface.loops()) {
                                       py::list l;
                                       for (const auto& c : loop.curves) l.append(py::make_tuple(c.edge, c.reversed));
                                       out.append(l);
                                   }
                                   return out;
                               },
                               "Per loop (the outer one first), its (edge index, reversed) in order.")
        .def(
            "boundary", [](const PyFace& f, int loop) {
                const auto& polys = f.face().surface.polygons();
                if (loop < 0 || static_cast<std::size_t>(loop) >= polys.size())
                    throw freeform::Error("Face.boundary: loop " + std::to_string(loop) + " of " +
                                          std::to_string(polys.size()));
                const auto& poly = polys[static_cast<std::size_t>(loop)];
                Eigen::Matrix2Xd p(2, static_cast<Eigen::Index>(poly.size()));
                for (std::size_t i = 0; i < poly.size(); ++i) p.col(static_cast<Eigen::Index>(i)) = poly[i];
                return fromColumns(p);
            },
            py::arg("loop"), "The loop's certified polygon in the face's parameters, (n, 2), within the face's flatness of the trims.")
        .def_property_readonly("flatness", [](const PyFace& f) { return f.face().surface.flatness(); })
        .def_property_readonly("area", [](const PyFace& f) { return f.face().surface.area(); },
                               "The face's area (Green's theorem over its trims; docs/cad.md, 'Area').")
        .def(
            "points",
            [](const PyFace& f, py::handle uv) {
                const auto ps = uvRows(uv);
                Points3 out(3, static_cast<Eigen::Index>(ps.size()));
                for (std::size_t i = 0; i < ps.size(); ++i)
                    out.col(static_cast<Eigen::Index>(i)) = f.face().surface.point(ps[i].x(), ps[i].y());
                return fromColumns(out);
            },
            py::arg("uv"), "Surface points (N, 3) at the file's parameters (N, 2).")
        .def(
            "surface_parameters",
            [](const PyFace& f, py::handle uv) {
                const auto ps = uvRows(uv);
                const auto& ms = f.face().surface.surface();
                Eigen::Matrix2Xd out(2, static_cast<Eigen::Index>(ps.size()));
                for (std::size_t i = 0; i < ps.size(); ++i)
                    out.col(static_cast<Eigen::Index>(i)) = Eigen::Vector2d(ms.mapU(ps[i].x()), ms.mapV(ps[i].y()));
                return fromColumns(out);
            },
            py::arg("uv"),
            "The surface's own parameters (N, 2) of the file's (N, 2): points(uv) == surface.evaluate(surface_parameters(uv)) "
            "(docs/cad.md, 'Exact forms and their parameters').")
        .def(
            "normals",
            [](const PyFace& f, py::handle uv) {
                const auto ps = uvRows(uv);
                Points3 out(3, static_cast<Eigen::Index>(ps.size()));
                const double sign = f.face().reversed ? -1 : 1;
                for (std::size_t i = 0; i < ps.size(); ++i)
                    out.col(static_cast<Eigen::Index>(i)) = sign * f.face().surface.normal(ps[i].x(), ps[i].y());
                return fromColumns(out);
            },
            py::arg("uv"), "Outward unit normals (N, 3) (the face's orientation applied; zero where degenerate).")
        .def(
            "classify",
            [](const PyFace& f, py::handle uv) {
                const auto ps = uvRows(uv);
                py::array_t<std::int8_t> out(static_cast<py::ssize_t>(ps.size()));
                for (std::size_t i = 0; i < ps.size(); ++i) {
                    const auto c = f.face().surface.classify(ps[i]);
                    out.mutable_data()[i] = c == freeform::TrimClass::Inside ? 1 : c == freeform::TrimClass::Outside ? -1 : 0;
                }
                return out;
            },
            py::arg("uv"), "Per parameter point: 1 inside the trims, -1 outside, 0 within twice the flatness of a trim.");

    py::class_<PyTrimmed, PyFace>(m, "TrimmedSurface", R"doc(
A NURBS surface trimmed by loops of 2D NURBS curves in its parameters (a document's
trimmed_surface; docs/cad.md): what a Face is, standing alone. The first loop is the outer
boundary, the others holes; no loops: the whole domain. Face's properties and methods apply
(points, normals, classify, area, boundary, ...); tessellate and deform work as a Part's of one face.)doc")
        .def(py::init([](const PyNurbsSurface& surface, py::handle domain, py::handle loops) {
                 const auto& n = surface.s;
                 const freeform::Box<double, 2> knotBox(Eigen::Vector2d(n.knotsU().front(), n.knotsV().front()),
                                                        Eigen::Vector2d(n.knotsU().back(), n.knotsV().back()));
                 const freeform::Box<double, 2> d = domain.is_none() ? knotBox : domainBox(domain);
                 if (!knotBox.contains(d)) throw freeform::Error("domain: the box must lie in the surface's knot domain");
                 std::vector<freeform::TrimLoop> trimLoops;
                 if (!loops.is_none())
                     for (std::size_t l = 0; l < py::len(loops); ++l) {
                         const py::sequence loop = py::reinterpret_borrow<py::sequence>(loops[py::int_(l)]);
                         freeform::TrimLoop tl;
                         for (std::size_t k = 0; k < loop.size(); ++k)
                             tl.curves.push_back(trimCurve(loop[k], "loops[" + std::to_string(l) + "][" + std::to_string(k) + "]"));
                         if (tl.curves.empty()) throw freeform::Error("loops[" + std::to_string(l) + "]: a loop needs a curve");
                         trimLoops.push_back(std::move(tl));
                     }
                 return trimmedObject(freeform::TrimmedSurface(freeform::MappedSurface{n, {}, {}}, d, std::move(trimLoops)));
             }),
             py::arg("surface"), py::arg("domain") = py::none(), py::arg("loops") = py::none(),
             "surface: a NurbsSurface; domain ((u0, u1), (v0, v1)) (None: the surface's knot domain); loops: a list "
             "of loops, each a list of trim curves, each a 2D NurbsCurve (its whole domain) or (curve, first, last[, "
             "reversed]) (None: no trims).")
        .def_property_readonly("trims",
                               [](const PyTrimmed& t) {
                                   py::list out;
                                   for (const auto& loop : t.surface->loops()) {
                                       py::list l;
                                       for (const auto& c : loop.curves)
                                           l.append(py::make_tuple(PyNurbsCurve{c.curve.nurbs}, c.curve.first, c.curve.last, c.reversed));
                                       out.append(l);
                                   }
                                   return out;
                               },
                               "Per loop (the outer one first), its trim curves as (NurbsCurve 2D, first, last, reversed).")
        .def("as_part", [](const PyTrimmed& t) { return PyPart{t.part}; },
             "The Part of one face it is: one edge per trim, no shell (save() writes it as STEP or IGES).")
        .def(
            "tessellate",
            [](const PyTrimmed& t, double tolerance, long long maxTriangles, bool withReport) {
                return meshTuple(*t.part, tolerance, maxTriangles, withReport);
            },
            py::arg("tolerance"), py::arg("max_triangles") = 10'000'000LL, py::arg("report") = false,
            "The certified mesh of the trimmed domain, as Part.tessellate: (V, F) or (V, F, report).")
        .def(
            "deform",
            [](const PyTrimmed& t, py::handle lattice, double strength, int maxDegree, double tolerance) {
                auto [part, report] = deformed(*t.part, lattice, strength, maxDegree, tolerance);
                // The face's new surface with the same domain and trims (the part's edges dropped).
                const freeform::TrimmedSurface& f = part.faces.front().surface;
                return py::make_tuple(trimmedObject(freeform::TrimmedSurface(f.surface(), f.domain(), t.surface->loops(), t.surface->flatness())),
                                      report);
            },
            py::arg("lattice"), py::arg("strength") = 1.0, py::arg("max_degree") = 0, py::arg("tolerance") = 0.0,
            "The surface through the lattice, exactly (as Part.deform, trims kept): (TrimmedSurface, report).")
        .def("__repr__", [](const PyTrimmed& t) {
            const auto& n = t.surface->surface().nurbs;
            return "<freeform.TrimmedSurface: degree (" + std::to_string(n.degreeU()) + ", " + std::to_string(n.degreeV()) + "), " +
                   std::to_string(t.surface->loops().size()) + " loops>";
        });

    py::class_<PyEdge>(m, "Edge", "An edge of a Part: a 3D curve in the file's parameter, shared by its faces.")
        .def_property_readonly("index", [](const PyEdge& e) { return e.index; })
        .def_property_readonly("range", [](const PyEdge& e) { return py::make_tuple(e.edge().first, e.edge().last); })
        .def_property_readonly("vertices", [](const PyEdge& e) { return py::make_tuple(e.edge().start, e.edge().end); })
        .def_property_readonly("tolerance", [](const PyEdge& e) { return e.edge().tolerance; })
        .def_property_readonly("degenerate", [](const PyEdge& e) { return e.edge().degenerate; })
        .def_property_readonly("curve",
                               [](const PyEdge& e) -> py::object {
                                   if (!e.edge().curve) return py::none();
                                   return py::cast(PyNurbsCurve{e.edge().curve->nurbs});
                               },
                               "The exact NURBS form (in its own parameter), or None (degenerate or no 3D curve).")
        .def(
            "points",
            [](const PyEdge& e, py::handle ts) {
                if (!e.edge().curve) throw freeform::Error("Edge " + std::to_string(e.index) + " has no 3D curve");
                const auto t = numberList(ts, "t");
                Points3 out(3, static_cast<Eigen::Index>(t.size()));
                for (std::size_t i = 0; i < t.size(); ++i) out.col(static_cast<Eigen::Index>(i)) = e.edge().curve->point(t[i]);
                return fromColumns(out);
            },
            py::arg("t"), "Curve points (N, 3) at the file's parameters.");
}

} // namespace ffpy
