// The byte encodings of glTF 2.0 files (gltf_internal.h): base64 (data: URIs), percent-encoding
// (the URIs of external buffers), and the GLB container's little-endian words and layout.

#include <cctype>
#include <cstdint>
#include <cstring>
#include <string>

#include "gltf_internal.h"

namespace freeform::meshio::gltf_detail {

namespace {

const char kBase64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

void appendU32(std::string& out, std::uint32_t v)
{
    char buffer[4];
    writeBinary(buffer, BinaryType::UInt32, false, v, "glb");
    out.append(buffer, 4);
}

} // namespace

// ---------------------------------------------------------------- base64 and URIs

std::string encodeBase64(const std::string& bytes)
{
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const std::uint32_t v = (static_cast<std::uint8_t>(bytes[i]) << 16) | (static_cast<std::uint8_t>(bytes[i + 1]) << 8) |
                                static_cast<std::uint8_t>(bytes[i + 2]);
        for (int k = 3; k >= 0; --k) out.push_back(kBase64[(v >> (6 * k)) & 63]);
    }
    if (i < bytes.size()) {
        std::uint32_t v = static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes[i + 1])) << 8;
        out.push_back(kBase64[(v >> 18) & 63]);
        out.push_back(kBase64[(v >> 12) & 63]);
        out.push_back(i + 1 < bytes.size() ? kBase64[(v >> 6) & 63] : '=');
        out.push_back('=');
    }
    return out;
}

bool decodeBase64(std::string_view text, std::string& out)
{
    std::uint32_t acc = 0;
    int bits = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '=') {
            for (std::size_t j = i; j < text.size(); ++j)
                if (text[j] != '=') return false;
            break;
        }
        const char* p = std::strchr(kBase64, c);
        if (c == '\0' || p == nullptr) return false;
        acc = (acc << 6) | static_cast<std::uint32_t>(p - kBase64);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(static_cast<char>((acc >> bits) & 0xFF));
        }
    }
    return true;
}

std::string percentDecode(const std::string& uri)
{
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out.push_back(static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16)));
            i += 2;
        } else {
            out.push_back(uri[i]);
        }
    }
    return out;
}

std::string percentEncode(const std::string& name)
{
    static const char* const hex = "0123456789ABCDEF";
    std::string out;
    for (const char ch : name) {
        const auto c = static_cast<unsigned char>(ch);
        if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') {
            out.push_back(ch);
        } else {
            out.push_back('%');
            out.push_back(hex[c >> 4]);
            out.push_back(hex[c & 15]);
        }
    }
    return out;
}

// ---------------------------------------------------------------- GLB

std::uint32_t readU32(const std::string& b, std::size_t at) { return static_cast<std::uint32_t>(readBinary(b.data() + at, BinaryType::UInt32, false)); }

std::string assembleGlb(std::string jsonChunk, bool jsonPadded, const std::string* bin, const std::string& trailing)
{
    if (!jsonPadded)
        while (jsonChunk.size() % 4 != 0) jsonChunk.push_back(' ');
    std::string binChunk;
    if (bin != nullptr) {
        binChunk = *bin;
        while (binChunk.size() % 4 != 0) binChunk.push_back('\0');
    }
    std::string out;
    appendU32(out, kGlbMagic);
    appendU32(out, 2);
    const std::size_t total = 12 + 8 + jsonChunk.size() + (bin != nullptr ? 8 + binChunk.size() : 0) + trailing.size();
    appendU32(out, static_cast<std::uint32_t>(total));
    appendU32(out, static_cast<std::uint32_t>(jsonChunk.size()));
    appendU32(out, kChunkJson);
    out += jsonChunk;
    if (bin != nullptr) {
        appendU32(out, static_cast<std::uint32_t>(binChunk.size()));
        appendU32(out, kChunkBin);
        out += binChunk;
    }
    out += trailing;
    return out;
}

} // namespace freeform::meshio::gltf_detail
