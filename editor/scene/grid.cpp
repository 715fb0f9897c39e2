#include "scene/grid.h"

#include <algorithm>
#include <cmath>

namespace freeform::editor {

double niceStep(double x)
{
    const double p = std::pow(10.0, std::floor(std::log10(x)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * p >= x) return m * p;
    return 10 * p;
}

double gridStep(const Eigen::AlignedBox3d& box)
{
    const double diameter = box.diagonal().norm();
    const double extent = std::max({std::abs(box.min().x()), std::abs(box.max().x()), std::abs(box.min().y()),
                                    std::abs(box.max().y()), 0.5 * diameter, 1e-6});
    return niceStep(extent / 8);
}

} // namespace freeform::editor
