// The control points of any object's data (document/object_data.h), as its kind file says
// (kindPoints, src/document/kind_file.h).

#include "freeform/document/object_data.h"

#include <variant>

#include "kind_file.h"

namespace freeform {

PointColumns* dataPoints(ObjectData& data)
{
    return std::visit([](auto& d) { return detail::kindPoints(d); }, data);
}

const PointColumns* dataPoints(const ObjectData& data) { return dataPoints(const_cast<ObjectData&>(data)); }

} // namespace freeform
