// The A-frame as a picture: a C2 cubic spline from seven de Boor points (open, uniform), drawn as
// SVG with its de Boor polygon, the A-frames (each de Boor point a with the inner Bézier points
// c_2 and d_1 on its two legs, and the joint on the crossbar c_2 d_1) and the Bézier segments.
// The curve is written as SVG cubic path segments straight from the Bézier points, so the picture
// is exact. docs/images/aframe.svg is this program's output.
//
//   build/bin/example_02_aframe_svg docs/images/aframe.svg

#include <freeform/curve/aframe.h>
#include <freeform/curve/bezier_spline.h>
#include <freeform/curve/continuity.h>
#include <freeform/io/file.h>

#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

namespace {

using Points = freeform::PointMatrix<double, 2>;

// Drawing coordinates: x to the right, y up in the model, flipped for SVG.
constexpr double kScale = 60, kMarginX = 40, kTop = 330;

std::string xy(const Eigen::Vector2d& p)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2f,%.2f", kMarginX + kScale * p.x(), kTop - kScale * p.y());
    return buf;
}

std::string at(const Eigen::Vector2d& p, const char* a, const char* b)
{
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s=\"%.2f\" %s=\"%.2f\"", a, kMarginX + kScale * p.x(), b, kTop - kScale * p.y());
    return buf;
}

} // namespace

int main(int argc, char** argv)
{
    const std::string path = argc > 1 ? argv[1] : "aframe.svg";
    Points deboor(2, 7);
    deboor << 0, 1.5, 3.5, 5, 7, 9, 10, 0.5, 4.5, 5, 0.5, 0, 4.5, 1.5;
    const Points b = freeform::aframeBezierPoints<double, 2>(deboor, freeform::EndCondition::Open);
    const auto spline = freeform::BezierSpline<double, 2>(3, false, b);

    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"700\" height=\"380\" viewBox=\"0 0 700 380\" "
           "font-family=\"sans-serif\" font-size=\"14\">\n"
        << "<rect width=\"700\" height=\"380\" fill=\"white\"/>\n";
    // The de Boor polygon.
    svg << "<polyline fill=\"none\" stroke=\"#999\" stroke-dasharray=\"6 4\" points=\"";
    for (int i = 0; i < deboor.cols(); ++i) svg << xy(deboor.col(i)) << ' ';
    svg << "\"/>\n";
    // The A-frames at the inner joints: c_2 - a - d_1 and the crossbar c_2 d_1 through the joint.
    for (int j = 1; j < spline.segmentCount(); ++j) {
        const Eigen::Vector2d c2 = b.col(3 * j - 1), d1 = b.col(3 * j + 1);
        svg << "<line " << at(c2, "x1", "y1") << ' ' << at(d1, "x2", "y2")
            << " stroke=\"#2a7\" stroke-width=\"1.5\"/>\n";
    }
    // The Bézier control polygons of the segments.
    for (int i = 0; i < spline.segmentCount(); ++i) {
        svg << "<polyline fill=\"none\" stroke=\"#6af\" stroke-width=\"1\" points=\"";
        for (int k = 0; k <= 3; ++k) svg << xy(b.col(3 * i + k)) << ' ';
        svg << "\"/>\n";
    }
    // The curve, exact: one SVG cubic per segment.
    svg << "<path fill=\"none\" stroke=\"#c22\" stroke-width=\"3\" d=\"M " << xy(b.col(0));
    for (int i = 0; i < spline.segmentCount(); ++i)
        svg << " C " << xy(b.col(3 * i + 1)) << ' ' << xy(b.col(3 * i + 2)) << ' ' << xy(b.col(3 * i + 3));
    svg << "\"/>\n";
    // Points: de Boor (black squares, labelled), inner Bézier points (blue), joints (red).
    for (int i = 0; i < b.cols(); ++i) {
        const bool joint = i % 3 == 0;
        svg << "<circle " << at(b.col(i), "cx", "cy") << " r=\"" << (joint ? 5 : 3.5) << "\" fill=\""
            << (joint ? "#c22" : "#36c") << "\"/>\n";
    }
    for (int i = 0; i < deboor.cols(); ++i) {
        const Eigen::Vector2d p = deboor.col(i);
        const Eigen::Vector2d corner = p + Eigen::Vector2d(-5.0 / kScale, 5.0 / kScale);
        svg << "<rect " << at(corner, "x", "y") << " width=\"10\" height=\"10\" fill=\"black\"/>\n";
        svg << "<text " << at(p + Eigen::Vector2d(0.12, 0.12), "x", "y") << ">d" << i << "</text>\n";
    }
    svg << "<text x=\"20\" y=\"370\" fill=\"#444\">de Boor points d0..d6 (squares, dashed polygon), Bezier "
           "points (blue: inner, red: joints on the green crossbars), the C2 spline (red)</text>\n";
    svg << "</svg>\n";
    freeform::writeFileAtomically(path, svg.str());

    // The same numbers the picture shows, and the proof that the result is C2.
    std::cout << "wrote " << path << ": " << spline.segmentCount() << " cubic segments from " << deboor.cols()
              << " de Boor points\n";
    for (const auto& j : freeform::continuityReport(spline))
        std::cout << "joint " << j.joint << " at T = " << j.t << ": C" << j.C << ", G" << j.G
                  << ", third-derivative jump " << j.jumps[3] << "\n";
    return 0;
}
