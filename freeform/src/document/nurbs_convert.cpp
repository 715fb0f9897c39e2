// The NURBS conversions of the document layer (document/operations.h: toNurbsData, fromNurbsData;
// docs/format.md): every curve and surface kind with an exact NURBS form into a nurbs_curve or
// nurbs_surface, and a NURBS of one piece back into its Bézier kind. Each kind's file says how
// (kindToNurbs, kindFromNurbs: src/document/kind_file.h); the kind table's ToNurbs and FromNurbs
// bits name the kinds in the messages.

#include <string>
#include <type_traits>

#include "freeform/core/error.h"
#include "freeform/document/operations.h"
#include "kind_file.h"

namespace freeform {
namespace {

/// The names of the kinds that support op, joined by sep.
std::string kindsSupporting(KindOperation op, const char* sep)
{
    std::string out;
    for (const KindInfo& k : objectKinds())
        if (k.supports(op)) out += (out.empty() ? "" : sep) + std::string(k.name);
    return out;
}

} // namespace

ObjectData toNurbsData(const TypedDocument& doc, const TypedObject& object)
{
    const std::string what = doc.what(object);
    std::optional<ObjectData> out =
        std::visit([&](const auto& d) { return detail::kindToNurbs(d, object.geometry(), what); }, object.data());
    if (out) return std::move(*out);
    if (object.info().supports(KindOperation::FromNurbs)) throw Error(what + " is already a " + object.type());
    throw Error(what + ": a " + object.type() + " has no NURBS form here (" + kindsSupporting(KindOperation::ToNurbs, ", ") +
                " convert)");
}

ObjectData fromNurbsData(const TypedDocument& doc, const TypedObject& object)
{
    const std::string what = doc.what(object);
    std::optional<ObjectData> out =
        std::visit([&](const auto& d) { return detail::kindFromNurbs(d, object.geometry(), what); }, object.data());
    if (out) return std::move(*out);
    throw Error(what + " is a " + object.type() + ", not a " + kindsSupporting(KindOperation::FromNurbs, " or "));
}

} // namespace freeform
