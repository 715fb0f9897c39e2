// Shared pieces of the mesh I/O: numbers as text, binary values, slots.

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <ostream>

#include "freeform/core/format.h"
#include "source.h"

namespace freeform::meshio {

bool sameBits(double a, double b)
{
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

std::string formatDouble(double value) { return formatNumber(value); }

std::string formatFloat(float value) { return formatNumber(value); }

bool parseDouble(std::string_view token, double& value)
{
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty() || token.front() == '+') return false;
    const char* first = token.data();
    const char* last = token.data() + token.size();
    const auto result = std::from_chars(first, last, value, std::chars_format::general);
    if (result.ec == std::errc::result_out_of_range) {
        // from_chars reports overflow and underflow alike; strtod tells them apart (inf or 0).
        value = std::strtod(std::string(token).c_str(), nullptr);
        return true;
    }
    return result.ec == std::errc() && result.ptr == last;
}

bool parseInteger(std::string_view token, long long& value)
{
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty() || token.front() == '+') return false;
    const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
    return result.ec == std::errc() && result.ptr == token.data() + token.size();
}

void requireText(const std::string& path, const std::string& text, const char* format)
{
    const auto starts = [&](const char* bom, std::size_t n) { return text.size() >= n && text.compare(0, n, bom, n) == 0; };
    if (starts("\xFF\xFE", 2) || starts("\xFE\xFF", 2))
        throw Error(path + ": UTF-16 text (a byte order mark); the " + format + " reader reads ASCII / UTF-8: convert the file");
    const std::size_t nul = text.find('\0');
    if (nul != std::string::npos) {
        std::size_t line = 1;
        for (std::size_t i = 0; i < nul; ++i) line += text[i] == '\n';
        throw Error(path + ":" + std::to_string(line) + ": a NUL byte at byte " + std::to_string(nul) + ": binary data, not an " + format +
                    " text file");
    }
}

std::string extensionOf(const std::string& path)
{
    const std::size_t slash = path.find_last_of("/\\");
    const std::size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

void writeText(std::ostream& out, const std::string& text, const std::vector<TextSlot>& slots, const Values& now,
               const Values& was)
{
    std::size_t at = 0;
    for (const TextSlot& s : slots) {
        const double value = valueAt(now, s.field, s.column, s.row);
        if (sameBits(value, valueAt(was, s.field, s.column, s.row))) continue;
        out.write(text.data() + at, static_cast<std::streamsize>(s.begin - at));
        if (s.integer) {
            // An integer property keeps an integer: rounded, and an Error when out of its range
            // (the same rule as the binary writer).
            char scratch[8];
            const auto type = static_cast<BinaryType>(s.integerType);
            writeBinary(scratch, type, false, value, "an integer coordinate of the ASCII PLY file");
            out << formatDouble(readBinary(scratch, type, false));
        } else {
            out << (s.single ? formatFloat(static_cast<float>(value)) : formatDouble(value));
        }
        at = s.end;
    }
    out.write(text.data() + at, static_cast<std::streamsize>(text.size() - at));
}

int binarySize(BinaryType type)
{
    switch (type) {
    case BinaryType::Int8:
    case BinaryType::UInt8: return 1;
    case BinaryType::Int16:
    case BinaryType::UInt16: return 2;
    case BinaryType::Int32:
    case BinaryType::UInt32:
    case BinaryType::Float32: return 4;
    case BinaryType::Float64: return 8;
    }
    return 0;
}

namespace {

template <typename T>
T load(const char* bytes, bool bigEndian)
{
    char buffer[sizeof(T)];
    std::memcpy(buffer, bytes, sizeof(T));
    if (bigEndian != (std::endian::native == std::endian::big)) std::reverse(buffer, buffer + sizeof(T));
    T value;
    std::memcpy(&value, buffer, sizeof(T));
    return value;
}

template <typename T>
void store(char* bytes, bool bigEndian, T value)
{
    char buffer[sizeof(T)];
    std::memcpy(buffer, &value, sizeof(T));
    if (bigEndian != (std::endian::native == std::endian::big)) std::reverse(buffer, buffer + sizeof(T));
    std::memcpy(bytes, buffer, sizeof(T));
}

template <typename T>
void storeInteger(char* bytes, bool bigEndian, double value, const std::string& what)
{
    const double rounded = std::nearbyint(value);
    if (!(rounded >= static_cast<double>(std::numeric_limits<T>::min()) &&
          rounded <= static_cast<double>(std::numeric_limits<T>::max())))
        throw Error(what + ": the value " + formatDouble(value) + " does not fit the file's integer type");
    store<T>(bytes, bigEndian, static_cast<T>(rounded));
}

} // namespace

double readBinary(const char* bytes, BinaryType type, bool bigEndian)
{
    switch (type) {
    case BinaryType::Int8: return load<std::int8_t>(bytes, bigEndian);
    case BinaryType::UInt8: return load<std::uint8_t>(bytes, bigEndian);
    case BinaryType::Int16: return load<std::int16_t>(bytes, bigEndian);
    case BinaryType::UInt16: return load<std::uint16_t>(bytes, bigEndian);
    case BinaryType::Int32: return load<std::int32_t>(bytes, bigEndian);
    case BinaryType::UInt32: return load<std::uint32_t>(bytes, bigEndian);
    case BinaryType::Float32: return load<float>(bytes, bigEndian);
    case BinaryType::Float64: return load<double>(bytes, bigEndian);
    }
    return 0;
}

void writeBinary(char* bytes, BinaryType type, bool bigEndian, double value, const std::string& what)
{
    switch (type) {
    case BinaryType::Int8: storeInteger<std::int8_t>(bytes, bigEndian, value, what); break;
    case BinaryType::UInt8: storeInteger<std::uint8_t>(bytes, bigEndian, value, what); break;
    case BinaryType::Int16: storeInteger<std::int16_t>(bytes, bigEndian, value, what); break;
    case BinaryType::UInt16: storeInteger<std::uint16_t>(bytes, bigEndian, value, what); break;
    case BinaryType::Int32: storeInteger<std::int32_t>(bytes, bigEndian, value, what); break;
    case BinaryType::UInt32: storeInteger<std::uint32_t>(bytes, bigEndian, value, what); break;
    case BinaryType::Float32: {
        const float f = static_cast<float>(value);
        if (!std::isfinite(f)) throw Error(what + ": the value " + formatDouble(value) + " overflows float32");
        store<float>(bytes, bigEndian, f);
        break;
    }
    case BinaryType::Float64: store<double>(bytes, bigEndian, value); break;
    }
}

void patchBinary(std::string& bytes, const std::vector<BinarySlot>& slots, const Values& now, const Values& was,
                 const std::string& path)
{
    for (const BinarySlot& s : slots) {
        const double value = valueAt(now, s.field, s.column, s.row);
        if (sameBits(value, valueAt(was, s.field, s.column, s.row))) continue;
        const char* kind = s.field == Field::Position ? "position " : s.field == Field::Normal ? "normal " : "tangent ";
        writeBinary(bytes.data() + s.offset, s.type, s.bigEndian, value, path + ": " + kind + std::to_string(s.column));
    }
}

} // namespace freeform::meshio
