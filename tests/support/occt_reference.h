#pragma once
// Open CASCADE as the CAD tests' independent reference (tests/test_cad_*.cpp): a part file read
// with its own readers, and its shape counts and closedness as it computes them.

#include <catch2/catch.hpp>

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Shape.hxx>

#include <string>

namespace freeform::test {

/// Open CASCADE's writers print statistics to stdout; the tests that write with them call this
/// first (freeform_cad removes the printer too, but only once it reads).
inline void quietOcct()
{
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
}

/// The shape of a .step, .iges or .brep file as Open CASCADE reads it (in millimetres, its default).
inline TopoDS_Shape occtRead(const std::string& path)
{
    if (path.ends_with(".step") || path.ends_with(".stp")) {
        STEPControl_Reader r;
        REQUIRE(r.ReadFile(path.c_str()) == IFSelect_RetDone);
        r.TransferRoots();
        return r.OneShape();
    }
    if (path.ends_with(".iges") || path.ends_with(".igs")) {
        IGESControl_Reader r;
        REQUIRE(r.ReadFile(path.c_str()) == IFSelect_RetDone);
        r.TransferRoots();
        return r.OneShape();
    }
    TopoDS_Shape s;
    BRep_Builder b;
    REQUIRE(BRepTools::Read(s, path.c_str(), b));
    return s;
}

/// The number of distinct sub-shapes of a type (TopExp::MapShapes, as freeform numbers them).
inline int occtCount(const TopoDS_Shape& s, TopAbs_ShapeEnum type)
{
    TopTools_IndexedMapOfShape m;
    TopExp::MapShapes(s, type, m);
    return m.Extent();
}

/// There is a shell and every shell is closed (BRep_Tool::IsClosed: each edge in two faces).
inline bool occtClosed(const TopoDS_Shape& s)
{
    TopTools_IndexedMapOfShape shells;
    TopExp::MapShapes(s, TopAbs_SHELL, shells);
    if (shells.IsEmpty()) return false;
    for (int i = 1; i <= shells.Extent(); ++i)
        if (!BRep_Tool::IsClosed(shells(i))) return false;
    return true;
}

} // namespace freeform::test
