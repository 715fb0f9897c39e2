#pragma once
// PNG loading and image comparison for the render tests.

#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace freeform::test {

struct RgbImage {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb; // top row first
    bool empty() const { return rgb.empty(); }
    const unsigned char* at(int x, int y) const { return rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x); }
};

inline RgbImage loadPng(const std::string& path)
{
    RgbImage image;
    int channels = 0;
    unsigned char* data = stbi_load(path.c_str(), &image.width, &image.height, &channels, 3);
    if (!data) return {};
    image.rgb.assign(data, data + static_cast<std::size_t>(image.width) * image.height * 3);
    stbi_image_free(data);
    return image;
}

struct Difference {
    double meanAbs = 1e9;      // mean |a - b| over all channels of all pixels (0..255)
    double badFraction = 1.0;  // fraction of pixels whose largest channel difference exceeds 32
    long changedPixels = 0;    // pixels whose largest channel difference exceeds 8
};

inline Difference compare(const RgbImage& a, const RgbImage& b)
{
    Difference d;
    if (a.width != b.width || a.height != b.height || a.empty()) return d;
    double sum = 0;
    long bad = 0, changed = 0;
    for (std::size_t p = 0; p < a.rgb.size() / 3; ++p) {
        int largest = 0;
        for (int c = 0; c < 3; ++c) {
            const int diff = std::abs(int(a.rgb[3 * p + c]) - int(b.rgb[3 * p + c]));
            sum += diff;
            largest = std::max(largest, diff);
        }
        if (largest > 32) ++bad;
        if (largest > 8) ++changed;
    }
    d.meanAbs = sum / double(a.rgb.size());
    d.badFraction = double(bad) / double(a.rgb.size() / 3);
    d.changedPixels = changed;
    return d;
}

/// The tolerance that survives Mesa's rounding (llvmpipe versions, multisample resolve: a level or
/// two here and there, a few edge pixels) but not a wrong lighting: on average under 1 level of
/// 255 per channel, and under 0.25% of the pixels off by more than 32 levels.
inline bool matches(const Difference& d)
{
    return d.meanAbs < 1.0 && d.badFraction < 0.0025;
}

} // namespace freeform::test
