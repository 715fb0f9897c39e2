// The kind table (document/kinds.h): one row per object kind, in ObjectKind's order, each from its
// kind's document file (kindRow, src/document/kinds/TYPE.cpp). The rows say what the document
// layer's operations accept (document/operations.h); test_kinds checks each claim against the
// operations themselves.

#include "freeform/document/kinds.h"

#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "kind_file.h"

namespace freeform {
namespace {

template <std::size_t K>
KindInfo tableRow()
{
    const ObjectKind kind = static_cast<ObjectKind>(K);
    const detail::KindRow r = detail::kindRow(std::type_identity<std::variant_alternative_t<K, ObjectData>>{});
    return KindInfo{kind, kindName(kind), r.summary, r.nature, r.parameters, r.dimension, r.rational, r.knots, r.pieces, r.operations};
}

template <std::size_t... K>
std::array<KindInfo, objectKindCount> makeTable(std::index_sequence<K...>)
{
    return {{tableRow<K>()...}};
}

} // namespace

const std::array<KindInfo, objectKindCount>& objectKinds()
{
    static const std::array<KindInfo, objectKindCount> table = makeTable(std::make_index_sequence<objectKindCount>{});
    return table;
}

const KindInfo& kindInfo(ObjectKind kind) { return objectKinds()[static_cast<std::size_t>(kind)]; }

const KindInfo* findKind(std::string_view name)
{
    const std::optional<ObjectKind> kind = kindNamed(name);
    return kind ? &kindInfo(*kind) : nullptr;
}

std::string objectDetails(const ObjectData& data)
{
    return std::visit([](const auto& d) { return detail::kindDetails(d); }, data);
}

} // namespace freeform
