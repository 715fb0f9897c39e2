#pragma once
// Little helpers for tests that build binary files byte by byte (PLY, STL, glTF buffers), written
// independently of the library's own binary code.

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

namespace freeform::test {

/// Appends the bytes of a trivially copyable value, little-endian unless big is set.
template <typename T>
void putBytes(std::string& out, T value, bool big = false)
{
    char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    if (big) std::reverse(b, b + sizeof(T)); // the test machines are little-endian (x86-64)
    out.append(b, sizeof(T));
}

/// Reads a value at out[offset].
template <typename T>
T getBytes(const std::string& in, std::size_t offset, bool big = false)
{
    char b[sizeof(T)];
    std::memcpy(b, in.data() + offset, sizeof(T));
    if (big) std::reverse(b, b + sizeof(T));
    T value;
    std::memcpy(&value, b, sizeof(T));
    return value;
}

} // namespace freeform::test
