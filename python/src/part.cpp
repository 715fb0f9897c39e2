// freeform.Part, Face and Edge: STEP and IGES parts (docs/python.md "CAD parts", docs/cad.md). The
// faces' surfaces and the edges' curves come out as the existing NurbsSurface and NurbsCurve (in
// their NURBS parameters); points(), normals() and classify() take the file's parameters.

#include <filesystem>
#include <memory>
#include <optional>

#include "freeform/brep/part_deform.h"
#include "freeform/brep/part_mesh.h"
#include "freeform/cad/cad_file.h"
#include "freeform/document/model.h"
#include "freeform/document/operations.h"
#include "freeform/document/object_data.h"
#include "lattice.h"
#include "nurbs.h"

namespace ffpy {
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

} // namespace

py::object partObject(const Part& part) { return py::cast(PyPart{std::make_shared<const Part>(part)}); }

std::optional<freeform::ObjectData> partData(py::handle h)
{
    if (!py::isinstance<PyPart>(h)) return std::nullopt;
    return freeform::ObjectData(freeform::toData(*h.cast<const PyPart&>().part));
}

void bindPart(py::module_& m)
{
    py::class_<PyPart>(m, "Part", R"doc(
A CAD part read from a STEP (.step .stp) or IGES (.iges .igs) file through Open CASCADE (docs/cad.md):
faces (trimmed NURBS surfaces in their exact forms), edges, vertices, shells and solids, in the
file's length unit. Faces and edges are numbered as Open CASCADE numbers them, from 0.)doc")
        .def_static(
            "load",
            [](const std::string& path) {
                const bool document = std::filesystem::path(path).extension() == ".json";
                return PyPart{std::make_shared<const Part>(document ? documentPart(path) : freeform::readCadFile(path))};
            },
            py::arg("path"),
            "Reads a STEP or IGES file, or the part object of a document (.json; docs/format.md) (freeform.Error "
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
            [](const PyPart& p, double tolerance, long long maxTriangles, bool withReport) -> py::tuple {
                freeform::PartMeshOptions o;
                o.tolerance = tolerance;
                o.maxTriangles = maxTriangles;
                const freeform::PartMesh m = freeform::tessellatePart(*p.part, o);
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
            [](const PyPart& p, PyLattice& lattice, double strength, int maxDegree, double tolerance) {
                freeform::PartDeformOptions o;
                o.strength = strength;
                o.maxDegree = maxDegree;
                o.tolerance = tolerance;
                const freeform::Lattice l = lattice.snapshot();
                freeform::DeformedPart d;
                {
                    py::gil_scoped_release release;
                    d = freeform::deformPart(*p.part, freeform::RationalLattice(l), o);
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
                return py::make_tuple(PyPart{std::make_shared<const Part>(std::move(d.part))}, report);
            },
            py::arg("lattice"), py::arg("strength") = 1.0, py::arg("max_degree") = 0, py::arg("tolerance") = 0.0,
            "The part through the lattice, exactly (docs/cad.md, Deformation): (Part, report). Every face's surface "
            "and edge's curve composed with the lattice, trims kept, vertices mapped. max_degree > 0 (25 for save()) "
            "reduces faces and edges above it within tolerance (<= 0: 1e-6 of the part's size), certified. The "
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
            "Writes the part as STEP (.step .stp) or IGES (.iges .igs) through Open CASCADE (docs/cad.md, Writing), or "
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
