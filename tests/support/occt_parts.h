#pragma once
// Parts the CAD tests build with Open CASCADE's modelling algorithms (tests/test_cad_*.cpp), and a
// shape written to STEP by Open CASCADE's writer.

#include <catch2/catch.hpp>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <Geom_BSplineCurve.hxx>
#include <STEPControl_Writer.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Ax2.hxx>

#include <string>

#include "occt_reference.h"

namespace freeform::test {

inline std::string writeStep(const TopoDS_Shape& shape, const std::string& name)
{
    const std::string path = std::string(FREEFORM_TEST_TMP) + "/cad_" + name + ".step";
    quietOcct();
    STEPControl_Writer w;
    REQUIRE(w.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone);
    REQUIRE(w.Write(path.c_str()) == IFSelect_RetDone);
    return path;
}

/// A solid whose side is a surface of revolution of a B-spline meridian, and a prism whose sides
/// are extrusions of a B-spline curve (their faces are B-spline-based, not elementary).
inline TopoDS_Shape bsplineRevolution()
{
    TColgp_Array1OfPnt poles(1, 5);
    poles(1) = gp_Pnt(2, 0, 0);
    poles(2) = gp_Pnt(3, 0, 1);
    poles(3) = gp_Pnt(1.5, 0, 2);
    poles(4) = gp_Pnt(2.5, 0, 3);
    poles(5) = gp_Pnt(2, 0, 4);
    TColStd_Array1OfReal knots(1, 3);
    knots(1) = 0;
    knots(2) = 0.4;
    knots(3) = 1;
    TColStd_Array1OfInteger mults(1, 3);
    mults(1) = 4;
    mults(2) = 1;
    mults(3) = 4;
    Handle(Geom_BSplineCurve) meridian = new Geom_BSplineCurve(poles, knots, mults, 3);
    const TopoDS_Edge e0 = BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 0), gp_Pnt(2, 0, 0));
    const TopoDS_Edge e1 = BRepBuilderAPI_MakeEdge(meridian);
    const TopoDS_Edge e2 = BRepBuilderAPI_MakeEdge(gp_Pnt(2, 0, 4), gp_Pnt(0, 0, 4));
    const TopoDS_Edge e3 = BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 4), gp_Pnt(0, 0, 0));
    const TopoDS_Face profile = BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakeWire(e0, e1, e2, e3).Wire());
    return BRepPrimAPI_MakeRevol(profile, gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 5.0).Shape();
}

inline TopoDS_Shape bsplinePrism()
{
    TColgp_Array1OfPnt poles(1, 4);
    poles(1) = gp_Pnt(0, 0, 0);
    poles(2) = gp_Pnt(1, 2, 0);
    poles(3) = gp_Pnt(3, -1, 0);
    poles(4) = gp_Pnt(4, 1, 0);
    TColStd_Array1OfReal knots(1, 2);
    knots(1) = 0;
    knots(2) = 1;
    TColStd_Array1OfInteger mults(1, 2);
    mults(1) = 4;
    mults(2) = 4;
    Handle(Geom_BSplineCurve) curve = new Geom_BSplineCurve(poles, knots, mults, 3);
    const TopoDS_Edge e0 = BRepBuilderAPI_MakeEdge(curve);
    const TopoDS_Edge e1 = BRepBuilderAPI_MakeEdge(gp_Pnt(4, 1, 0), gp_Pnt(4, -3, 0));
    const TopoDS_Edge e2 = BRepBuilderAPI_MakeEdge(gp_Pnt(4, -3, 0), gp_Pnt(0, -3, 0));
    const TopoDS_Edge e3 = BRepBuilderAPI_MakeEdge(gp_Pnt(0, -3, 0), gp_Pnt(0, 0, 0));
    const TopoDS_Face base = BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakeWire(e0, e1, e2, e3).Wire());
    return BRepPrimAPI_MakePrism(base, gp_Vec(0.5, 0.25, 2)).Shape();
}

inline TopoDS_Shape boxWithHoles()
{
    TopoDS_Shape s = BRepPrimAPI_MakeBox(10, 8, 4).Shape();
    s = BRepAlgoAPI_Cut(s, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(3, 4, -1), gp_Dir(0, 0, 1)), 1.5, 6).Shape()).Shape();
    s = BRepAlgoAPI_Cut(s, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-1, 4, 2), gp_Dir(1, 0, 0)), 1, 12).Shape()).Shape();
    return s;
}

inline TopoDS_Shape filletedBox()
{
    const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(-2, -3, -1), 6, 5, 3).Shape();
    BRepFilletAPI_MakeFillet fillet(box);
    for (TopExp_Explorer ex(box, TopAbs_EDGE); ex.More(); ex.Next()) fillet.Add(0.6, TopoDS::Edge(ex.Current()));
    return fillet.Shape();
}

} // namespace freeform::test
