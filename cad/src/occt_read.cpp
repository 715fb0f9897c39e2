// STEP and IGES files into parts (freeform/cad/cad_file.h, docs/cad.md "Reading").

#include "freeform/cad/cad_file.h"

#include <filesystem>
#include <map>
#include <utility>

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Wire.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Vertex.hxx>

#include "freeform/cad/occt_bridge.h"
#include "freeform/core/error.h"
#include "freeform/core/warning.h"
#include "freeform/io/part_file.h"
#include "occt_common.h"
#include "occt_convert.h"

namespace freeform {
namespace {

using occt::CascadeUnit;
using occt::lower;
using occt::MessageScope;

/// Open CASCADE's name of a length unit ("xstep.cascade.unit") and freeform's.
struct Unit {
    const char* occt;
    const char* name;
};

Unit stepUnit(const std::string& name)
{
    static const std::map<std::string, Unit> units = {
        {"millimetre", {"MM", "mm"}}, {"millimeter", {"MM", "mm"}}, {"metre", {"M", "m"}},
        {"meter", {"M", "m"}},        {"centimetre", {"CM", "cm"}}, {"centimeter", {"CM", "cm"}},
        {"micrometre", {"UM", "um"}}, {"micrometer", {"UM", "um"}}, {"kilometre", {"KM", "km"}},
        {"kilometer", {"KM", "km"}},  {"inch", {"INCH", "in"}},     {"foot", {"FT", "ft"}},
        {"mile", {"MI", "mi"}}};
    const auto it = units.find(lower(name));
    return it == units.end() ? Unit{"MM", "mm"} : it->second;
}

Unit igesUnit(int flag)
{
    switch (flag) {
    case 1: return {"INCH", "in"};
    case 4: return {"FT", "ft"};
    case 5: return {"MI", "mi"};
    case 6: return {"M", "m"};
    case 7: return {"KM", "km"};
    case 8: return {"MIL", "mil"};
    case 9: return {"UM", "um"};
    case 10: return {"CM", "cm"};
    case 11: return {"UIN", "uin"};
    default: return {"MM", "mm"};
    }
}

std::pair<TopoDS_Shape, std::string> readShape(const std::string& path, const MessageScope& messages)
{
    const std::string ext = lower(std::filesystem::path(path).extension().string());
    if (!std::filesystem::exists(path)) throw Error(path + ": no such file");
    if (ext == ".step" || ext == ".stp") {
        STEPControl_Reader reader;
        if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) throw Error(path + ": not a readable STEP file" + messages.firstMessage());
        TColStd_SequenceOfAsciiString length, angle, solid;
        reader.FileUnits(length, angle, solid);
        const Unit unit = length.IsEmpty() ? Unit{"MM", "mm"} : stepUnit(length.First().ToCString());
        CascadeUnit scope(unit.occt);
        if (reader.TransferRoots() == 0) throw Error(path + ": the STEP file holds no shape Open CASCADE can transfer" + messages.firstMessage());
        return {reader.OneShape(), unit.name};
    }
    if (ext == ".iges" || ext == ".igs") {
        IGESControl_Reader reader;
        if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) throw Error(path + ": not a readable IGES file" + messages.firstMessage());
        const Unit unit = igesUnit(reader.IGESModel()->GlobalSection().UnitFlag());
        CascadeUnit scope(unit.occt);
        if (reader.TransferRoots() == 0) throw Error(path + ": the IGES file holds no shape Open CASCADE can transfer" + messages.firstMessage());
        return {reader.OneShape(), unit.name};
    }
    if (ext == ".brep") {
        // Open CASCADE's own format carries no unit: its default, millimetres (docs/cad.md).
        TopoDS_Shape shape;
        BRep_Builder builder;
        if (!BRepTools::Read(shape, path.c_str(), builder) || shape.IsNull())
            throw Error(path + ": not a readable BRep file" + messages.firstMessage());
        return {shape, "mm"};
    }
    throw Error(path + ": not a STEP (.step .stp), IGES (.iges .igs) or BRep (.brep) file");
}

/// The edges of a wire in order along it: BRepTools_WireExplorer, or the wire's own order when
/// the explorer cannot walk it (a wire that branches).
std::vector<TopoDS_Edge> wireEdges(const TopoDS_Wire& wire, const TopoDS_Face& face)
{
    std::vector<TopoDS_Edge> stored, walked;
    for (TopoDS_Iterator it(wire); it.More(); it.Next())
        if (it.Value().ShapeType() == TopAbs_EDGE) stored.push_back(TopoDS::Edge(it.Value()));
    for (BRepTools_WireExplorer we(wire, face); we.More(); we.Next()) walked.push_back(we.Current());
    return walked.size() == stored.size() ? walked : stored;
}

} // namespace

Part partFromShape(const TopoDS_Shape& shape, const std::string& units)
{
    TopTools_IndexedMapOfShape faces, edges, vertices, shells, solids;
    TopExp::MapShapes(shape, TopAbs_FACE, faces);
    TopExp::MapShapes(shape, TopAbs_EDGE, edges);
    TopExp::MapShapes(shape, TopAbs_VERTEX, vertices);
    TopExp::MapShapes(shape, TopAbs_SHELL, shells);
    TopExp::MapShapes(shape, TopAbs_SOLID, solids);

    Part part;
    part.units = units;
    part.vertices.reserve(static_cast<std::size_t>(vertices.Extent()));
    part.edges.reserve(static_cast<std::size_t>(edges.Extent()));
    part.faces.reserve(static_cast<std::size_t>(faces.Extent()));
    for (int i = 1; i <= vertices.Extent(); ++i) {
        const TopoDS_Vertex& v = TopoDS::Vertex(vertices(i));
        const gp_Pnt p = BRep_Tool::Pnt(v);
        part.vertices.push_back({Eigen::Vector3d(p.X(), p.Y(), p.Z()), BRep_Tool::Tolerance(v)});
    }
    for (int i = 1; i <= edges.Extent(); ++i) {
        const TopoDS_Edge e = TopoDS::Edge(edges(i).Oriented(TopAbs_FORWARD));
        PartEdge out;
        BRep_Tool::Range(e, out.first, out.last);
        out.tolerance = BRep_Tool::Tolerance(e);
        out.degenerate = BRep_Tool::Degenerated(e);
        TopoDS_Vertex v0, v1;
        TopExp::Vertices(e, v0, v1);
        if (!v0.IsNull()) out.start = vertices.FindIndex(v0) - 1;
        if (!v1.IsNull()) out.end = vertices.FindIndex(v1) - 1;
        double f = 0, l = 0;
        const Handle(Geom_Curve) curve = BRep_Tool::Curve(e, f, l);
        if (!curve.IsNull() && !out.degenerate) {
            try {
                out.curve = occt::exactCurve(curve, f, l);
            } catch (const Error& err) {
                throw Error("edge " + std::to_string(i) + ": " + err.what());
            }
        }
        part.edges.push_back(std::move(out));
    }
    for (int i = 1; i <= faces.Extent(); ++i) {
        const TopoDS_Face& face = TopoDS::Face(faces(i));
        const std::string where = "face " + std::to_string(i);
        try {
            double u0, u1, v0, v1;
            BRepTools::UVBounds(face, u0, u1, v0, v1);
            auto [surface, kind] = occt::exactSurface(BRep_Tool::Surface(face), u0, u1, v0, v1);
            std::vector<TrimLoop> loops;
            const TopoDS_Wire outer = BRepTools::OuterWire(face);
            std::vector<TopoDS_Wire> wires;
            if (!outer.IsNull()) wires.push_back(outer);
            for (TopoDS_Iterator it(face); it.More(); it.Next())
                if (it.Value().ShapeType() == TopAbs_WIRE && !it.Value().IsSame(outer)) wires.push_back(TopoDS::Wire(it.Value()));
            for (const TopoDS_Wire& wire : wires) {
                TrimLoop loop;
                for (const TopoDS_Edge& e : wireEdges(wire, face)) {
                    double f = 0, l = 0;
                    const Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(e, face, f, l);
                    const int index = edges.FindIndex(e) - 1;
                    if (pcurve.IsNull())
                        throw Error("edge " + std::to_string(index + 1) + " has no curve in the face's parameters");
                    TrimCurve trim{occt::exactCurve2d(pcurve, f, l), e.Orientation() == TopAbs_REVERSED, index};
                    loop.curves.push_back(std::move(trim));
                }
                if (!loop.curves.empty()) loops.push_back(std::move(loop));
            }
            const Box<double, 2> domain(Eigen::Vector2d(u0, v0), Eigen::Vector2d(u1, v1));
            part.faces.push_back({TrimmedSurface(std::move(surface), domain, std::move(loops)),
                                  face.Orientation() == TopAbs_REVERSED, kind, BRep_Tool::Tolerance(face)});
        } catch (const Error& err) {
            throw Error(where + ": " + err.what());
        } catch (const Standard_Failure& err) {
            throw Error(where + ": Open CASCADE failed: " + err.GetMessageString());
        }
    }
    for (int i = 1; i <= shells.Extent(); ++i) {
        TopTools_IndexedMapOfShape shellFaces;
        TopExp::MapShapes(shells(i), TopAbs_FACE, shellFaces);
        PartShell s;
        for (int k = 1; k <= shellFaces.Extent(); ++k) s.faces.push_back(faces.FindIndex(shellFaces(k)) - 1);
        part.shells.push_back(std::move(s));
    }
    for (int i = 1; i <= solids.Extent(); ++i) {
        PartSolid s;
        for (TopExp_Explorer ex(solids(i), TopAbs_SHELL); ex.More(); ex.Next()) s.shells.push_back(shells.FindIndex(ex.Current()) - 1);
        part.solids.push_back(std::move(s));
    }
    return part;
}

bool isCadFile(const std::string& path) { return isPartFileName(path); }

bool cadFilesSupported() { return true; }

void requireCadFiles(const std::string&) {}

Part readCadFile(const std::string& path, std::vector<std::string>* warnings)
{
    // Open CASCADE's messages of a read that fails go into the error; of one that succeeds, to the
    // caller's list or to freeform::warn.
    MessageScope messages;
    Part part;
    try {
        auto [shape, units] = readShape(path, messages);
        if (shape.IsNull()) throw Error(path + ": the file holds no shape" + messages.firstMessage());
        try {
            part = partFromShape(shape, units);
        } catch (const Error& e) {
            throw Error(path + ": " + e.what());
        }
    } catch (const Standard_Failure& e) {
        throw Error(path + ": Open CASCADE failed: " + e.GetMessageString());
    }
    for (const std::string& m : messages.messages) {
        if (warnings) warnings->push_back(m);
        else warn(path + ": " + m);
    }
    return part;
}

} // namespace freeform
