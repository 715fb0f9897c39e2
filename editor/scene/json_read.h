#pragma once
// Small strict readers for the editor's JSON settings: a missing member keeps the default, a member
// of the wrong type or out of range is a freeform::Error naming its path ("editor.camera.distance").

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <limits>
#include <string>

#include "freeform/core/error.h"

namespace freeform::editor::json {

using Json = nlohmann::ordered_json;

[[noreturn]] inline void fail(const std::string& path, const std::string& message)
{
    throw Error(path + ": " + message);
}

inline double number(const Json& j, const std::string& path)
{
    if (!j.is_number()) fail(path, "expected a number");
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(path, "number is not finite");
    return v;
}

/// v as a T, refused (not cast: a float cast out of range is undefined) when T cannot hold it.
template <typename T>
T narrow(double v, const std::string& path)
{
    if (std::abs(v) > static_cast<double>(std::numeric_limits<T>::max()))
        fail(path, "number is out of range (beyond single precision)");
    return static_cast<T>(v);
}

inline void read(const Json& obj, const char* key, const std::string& path, double& out)
{
    if (obj.contains(key)) out = number(obj[key], path + "." + key);
}

inline void read(const Json& obj, const char* key, const std::string& path, float& out)
{
    if (obj.contains(key)) out = narrow<float>(number(obj[key], path + "." + key), path + "." + key);
}

inline void read(const Json& obj, const char* key, const std::string& path, int& out)
{
    if (!obj.contains(key)) return;
    if (!obj[key].is_number_integer()) fail(path + "." + key, "expected an integer");
    out = obj[key].get<int>();
}

inline void read(const Json& obj, const char* key, const std::string& path, bool& out)
{
    if (!obj.contains(key)) return;
    if (!obj[key].is_boolean()) fail(path + "." + key, "expected true or false");
    out = obj[key].get<bool>();
}

template <typename Vector>
void readVector(const Json& obj, const char* key, const std::string& path, Vector& out)
{
    if (!obj.contains(key)) return;
    const Json& a = obj[key];
    const std::string where = path + "." + key;
    if (!a.is_array() || a.size() != static_cast<std::size_t>(out.size()))
        fail(where, "expected an array of " + std::to_string(out.size()) + " numbers");
    for (Eigen::Index i = 0; i < out.size(); ++i) {
        const std::string at = where + "[" + std::to_string(i) + "]";
        out[i] = narrow<typename Vector::Scalar>(number(a[static_cast<std::size_t>(i)], at), at);
    }
}

/// Reads a string member that must be one of `allowed`; returns its index in the list.
inline int choice(const Json& obj, const char* key, const std::string& path, std::initializer_list<const char*> allowed,
                  int current)
{
    if (!obj.contains(key)) return current;
    const std::string where = path + "." + key;
    if (!obj[key].is_string()) fail(where, "expected a string");
    const std::string v = obj[key].get<std::string>();
    int i = 0;
    std::string list;
    for (const char* a : allowed) {
        if (v == a) return i;
        list += (i ? ", " : "") + std::string(a);
        ++i;
    }
    fail(where, "\"" + v + "\" is not one of " + list);
}

inline void requireObject(const Json& j, const std::string& path)
{
    if (!j.is_object()) fail(path, "expected an object");
}

/// A float as the double with the same shortest decimal form (0.72f is written 0.72, not
/// 0.7200000286102295), so that the file reads back to the same float and writes back the same.
inline double tidy(float f)
{
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, f);
    return std::strtod(std::string(buffer, result.ptr).c_str(), nullptr);
}
inline double tidy(double d) { return d; }

template <typename Vector>
Json array(const Vector& v)
{
    Json a = Json::array();
    for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(tidy(v[i]));
    return a;
}

} // namespace freeform::editor::json
