// The .bpt reader and writer (io/bpt.h).

#include "freeform/io/bpt.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/io/file.h"

namespace freeform {

namespace {

std::vector<std::string> tokens(const std::string& line)
{
    std::vector<std::string> out;
    std::istringstream in(line);
    std::string t;
    while (in >> t) out.push_back(t);
    return out;
}

double bptNumber(const std::string& text, const std::string& where)
{
    double v = 0;
    const char* first = text.data();
    const char* last = first + text.size();
    if (first != last && *first == '+') ++first;
    const auto [ptr, ec] = std::from_chars(first, last, v);
    if (ec == std::errc::result_out_of_range) throw Error(where + ": \"" + text + "\" is out of range");
    if (ec != std::errc() || ptr != last || !std::isfinite(v)) throw Error(where + ": \"" + text + "\" is not a finite number");
    return v;
}

int bptInteger(const std::string& text, const std::string& where)
{
    int v = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || ptr != text.data() + text.size()) throw Error(where + ": \"" + text + "\" is not an integer");
    return v;
}

} // namespace

PatchComplex parseBpt(const std::string& text, const std::string& source)
{
    // Lines with their numbers, blank ones skipped.
    std::vector<std::pair<int, std::vector<std::string>>> lines;
    {
        std::istringstream in(text);
        std::string line;
        int number = 0;
        while (std::getline(in, line)) {
            ++number;
            auto t = tokens(line);
            if (!t.empty()) lines.emplace_back(number, std::move(t));
        }
    }
    std::size_t at = 0;
    auto where = [&](std::size_t k) { return source + ": line " + std::to_string(lines[k].first); };
    if (lines.empty()) throw Error(source + ": empty file (expected the number of patches on the first line)");
    if (lines[0].second.size() != 1) throw Error(where(0) + ": expected the number of patches alone on the line");
    const int count = bptInteger(lines[0].second[0], where(0));
    if (count < 1) throw Error(where(0) + ": the number of patches must be at least 1, found " + std::to_string(count));
    at = 1;
    PatchComplex complex;
    for (int p = 0; p < count; ++p) {
        const std::string what = "patch " + std::to_string(p);
        if (at >= lines.size())
            throw Error(source + ": ends after " + std::to_string(p) + " of " + std::to_string(count) + " patches");
        const auto& head = lines[at].second;
        if (head.size() != 2) throw Error(where(at) + ": " + what + ": expected the degrees \"m n\", found " + std::to_string(head.size()) + " fields");
        const int m = bptInteger(head[0], where(at)), n = bptInteger(head[1], where(at));
        for (int d : {m, n})
            if (d < 1 || d > kMaxDegree)
                throw Error(where(at) + ": " + what + ": degree " + std::to_string(d) + " is outside 1.." + std::to_string(kMaxDegree));
        ++at;
        const int points = (m + 1) * (n + 1);
        PointMatrix<double, 3> pts(3, points);
        for (int k = 0; k < points; ++k, ++at) {
            if (at >= lines.size())
                throw Error(source + ": " + what + " ends after " + std::to_string(k) + " of " + std::to_string(points) + " points");
            const auto& t = lines[at].second;
            if (t.size() != 3) throw Error(where(at) + ": " + what + " point " + std::to_string(k) + ": expected 3 coordinates, found " + std::to_string(t.size()));
            for (int c = 0; c < 3; ++c) pts(c, k) = bptNumber(t[c], where(at));
        }
        complex.patches.emplace_back(m, n, std::move(pts));
    }
    if (at < lines.size())
        throw Error(where(at) + ": unexpected content after the " + std::to_string(count) + " announced patches");
    return complex;
}

PatchComplex readBpt(const std::string& path)
{
    return parseBpt(readFile(path), path);
}

std::string formatBpt(const PatchComplex& complex)
{
    std::string out = std::to_string(complex.patches.size()) + "\n";
    char buf[64];
    for (const Patch& p : complex.patches) {
        out += std::to_string(p.degreeU()) + " " + std::to_string(p.degreeV()) + "\n";
        for (Eigen::Index k = 0; k < p.controlPoints().cols(); ++k) {
            for (int c = 0; c < 3; ++c) {
                const auto r = std::to_chars(buf, buf + sizeof buf, p.controlPoints()(c, k));
                out.append(buf, r.ptr);
                out += c < 2 ? ' ' : '\n';
            }
        }
    }
    return out;
}

} // namespace freeform
