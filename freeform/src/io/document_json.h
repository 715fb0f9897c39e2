#pragma once
// The document reader's and writer's field helpers (src/io/document.cpp), shared with the part
// and trimmed surface objects' fields (src/io/document_part.cpp). Private to the io layer.

#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <initializer_list>
#include <string>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/io/document.h"

namespace freeform::document_json {

using Json = nlohmann::ordered_json;

/// Context for messages: "source: object \"name\": field \"points\"".
struct Where {
    std::string source;
    std::string object;

    [[noreturn]] void fail(const std::string& field, const std::string& message) const
    {
        std::string where = source + ": ";
        if (!object.empty()) where += object + ": ";
        if (!field.empty()) where += "field \"" + field + "\": ";
        throw Error(where + message);
    }
    /// The context of a member object: `object "p": faces[2]`.
    Where inside(const std::string& member) const { return {source, object + ": " + member}; }
};

std::string typeName(const Json& j);
const Json& member(const Json& obj, const char* key, const Where& w);
double number(const Json& j, const std::string& field, const Where& w);
int integer(const Json& j, const std::string& field, const Where& w);
std::string string(const Json& j, const std::string& field, const Where& w);
std::string oneOf(const Json& j, const std::string& field, std::initializer_list<const char*> allowed,
                  const Where& w);
/// A list of points (arrays of dim numbers); dim 0 means "any of 2 or 3, the same for all".
PointColumns pointList(const Json& j, const std::string& field, int dim, const Where& w);
/// Rejects members of obj not in allowed.
void onlyKnown(const Json& obj, std::initializer_list<const char*> allowed, const Where& w);
/// The fields of a nurbs_curve (degree, knots, points of dimension dim (0: 2 or 3), weights).
NurbsCurveData nurbsCurveFields(const Json& obj, int dim, const Where& w);
/// The fields of a nurbs_surface (degree, knots, points, weights).
NurbsSurfaceData nurbsSurfaceFields(const Json& obj, const Where& w);
void writeNurbsCurve(Json& j, const NurbsCurveData& d);
void writeNurbsSurface(Json& j, const NurbsSurfaceData& d);
Json pointsJson(const PointColumns& p);

template <std::size_t N>
std::array<int, N> degreeArray(const Json& j, const Where& w)
{
    if (!j.is_array() || j.size() != N)
        w.fail("degree", "expected an array of " + std::to_string(N) + " integers");
    std::array<int, N> out{};
    for (std::size_t i = 0; i < N; ++i) {
        out[i] = integer(j[i], "degree[" + std::to_string(i) + "]", w);
        if (out[i] < 1 || out[i] > 67) w.fail("degree[" + std::to_string(i) + "]", "must be in 1..67");
    }
    return out;
}

// src/io/document_part.cpp (docs/format.md, "Trimmed surfaces and parts")
TrimmedSurfaceData trimmedSurfaceObject(const Json& obj, const Where& w);
PartData partObject(const Json& obj, const Where& w);
void writeTrimmedSurface(Json& j, const TrimmedSurfaceData& d);
void writePart(Json& j, const PartData& d);

} // namespace freeform::document_json
