// The typed document (document/model.h): TypedDocument, and the visits over an object's data that
// hand each kind to its document file (src/document/kinds/TYPE.cpp, declared in kind_file.h): its
// geometry (buildGeometry), its data (toData of any Geometry) and its control net (controlNet,
// document/operations.h). The facades AnyCurve and AnySurface are in any_geometry.cpp.

#include "freeform/document/model.h"

#include <filesystem>
#include <utility>

#include "freeform/core/error.h"
#include "freeform/document/object_data.h"
#include "../io/object_lookup.h"
#include "kind_file.h"

namespace freeform {
namespace {

Geometry build(const ObjectData& data, const std::string& directory, const std::string& what)
{
    const detail::KindBuild context{directory, what};
    return std::visit([&](const auto& d) { return detail::kindBuild(d, context); }, data);
}

} // namespace

Geometry buildGeometry(const ObjectData& data, const std::string& documentDirectory, const std::string& what)
{
    try {
        return build(data, documentDirectory, what);
    } catch (const Error& e) {
        const std::string message = e.what();
        if (message.rfind(what, 0) == 0) throw; // already prefixed (subdivision cages)
        throw Error(what + ": " + message);
    }
}

int TypedObject::dimension() const
{
    if (const int d = info().dimension; d != 0) return d;
    return static_cast<int>(dataPoints(data_)->rows()); // a curve: 2 or 3 as its points are
}

TypedDocument::TypedDocument(const Document& document, std::optional<std::string> documentDirectory)
    : source(document.source), editor(document.editor)
{
    directory = documentDirectory ? *documentDirectory : std::filesystem::path(document.source).parent_path().string();
    objects_.reserve(document.objects.size());
    for (const DocumentObject& o : document.objects) add(o.name, o.data, o.editor);
}

TypedDocument TypedDocument::read(const std::string& path) { return TypedDocument(readDocument(path)); }

Document TypedDocument::toDocument() const
{
    Document d;
    d.source = source;
    d.editor = editor;
    d.objects.reserve(objects_.size());
    for (const TypedObject& o : objects_) d.objects.push_back(DocumentObject{o.name(), o.data(), o.editor()});
    return d;
}

const TypedObject* TypedDocument::find(ObjectId id) const
{
    for (const TypedObject& o : objects_)
        if (o.id() == id) return &o;
    return nullptr;
}

const TypedObject* TypedDocument::find(const std::string& name) const
{
    for (const TypedObject& o : objects_)
        if (o.name() == name) return &o;
    return nullptr;
}

const TypedObject& TypedDocument::object(const std::string& name) const
{
    if (const TypedObject* o = find(name)) return *o;
    std::vector<std::string> names;
    for (const TypedObject& o : objects_) names.push_back(o.name());
    throw Error(noObjectMessage(source, name, names)); // the reader's message (src/io/object_lookup.h)
}

const TypedObject& TypedDocument::object(ObjectId id) const
{
    if (const TypedObject* o = find(id)) return *o;
    throw Error(source + ": no object with id " + std::to_string(id));
}

std::string TypedDocument::what(const TypedObject& object) const { return source + ": object \"" + object.name() + "\""; }

ObjectId TypedDocument::add(std::string name, ObjectData data, std::string editorText)
{
    Geometry geometry = buildGeometry(data, directory, source + ": object \"" + name + "\"");
    const ObjectId id = nextId_++;
    objects_.push_back(TypedObject(id, std::move(name), std::move(data), std::move(geometry), std::move(editorText)));
    return id;
}

void TypedDocument::replace(ObjectId id, ObjectData data)
{
    const TypedObject& current = object(id);
    Geometry geometry = buildGeometry(data, directory, what(current));
    for (TypedObject& o : objects_)
        if (o.id_ == id) {
            o.data_ = std::move(data);
            o.geometry_ = std::move(geometry);
        }
}

void TypedDocument::rename(ObjectId id, std::string name)
{
    object(id);
    for (TypedObject& o : objects_)
        if (o.id_ == id) o.name_ = std::move(name);
}

void TypedDocument::remove(ObjectId id)
{
    object(id);
    std::erase_if(objects_, [id](const TypedObject& o) { return o.id() == id; });
}

// ---------------------------------------------------------------- toData and the control net

ObjectData toData(const Geometry& geometry)
{
    return std::visit([](const auto& g) -> ObjectData { return toData(g); }, geometry);
}

ControlNet controlNet(const TypedObject& object)
{
    ControlNet net;
    std::visit([&](const auto& d) { detail::kindNet(d, object.geometry(), net); }, object.data());
    return net;
}

} // namespace freeform
