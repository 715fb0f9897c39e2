// The control points of any object's data (document/object_data.h).

#include "freeform/document/object_data.h"

#include <type_traits>
#include <variant>

namespace freeform {

PointColumns* dataPoints(ObjectData& data)
{
    return std::visit(
        [](auto& d) -> PointColumns* {
            using T = std::decay_t<decltype(d)>;
            if constexpr (std::is_same_v<T, SubdivisionSurfaceData>) return &d.vertices;
            else if constexpr (std::is_same_v<T, TrimmedSurfaceData>) return &d.surface.points;
            else if constexpr (std::is_same_v<T, PartData>) return nullptr;
            else return &d.points;
        },
        data);
}

const PointColumns* dataPoints(const ObjectData& data) { return dataPoints(const_cast<ObjectData&>(data)); }

} // namespace freeform
