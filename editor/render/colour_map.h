#pragma once
// The scalar colour map (det J of a lattice, docs/editor.md "Lattices and FFD"): a perceptually
// ordered ramp, dark blue - teal - green - yellow, piecewise linear through five stops. The mesh
// shader (render/shaders.h, colorMap) uses the same stops; the legend the panels draw uses these.

#include <algorithm>
#include <array>

#include "render/render_types.h"

namespace freeform::editor {

/// The five stops at t = 0, 1/4, 1/2, 3/4, 1 (the same numbers as colorMap in render/shaders.h).
inline const std::array<Vec3f, 5>& colourMapStops()
{
    static const std::array<Vec3f, 5> stops{Vec3f(0.267f, 0.005f, 0.329f), Vec3f(0.231f, 0.322f, 0.545f),
                                            Vec3f(0.129f, 0.569f, 0.549f), Vec3f(0.369f, 0.788f, 0.384f),
                                            Vec3f(0.993f, 0.906f, 0.144f)};
    return stops;
}

/// The map's colour at t (clamped to [0, 1]), as the shader computes it.
inline Vec3f colourMap(float t)
{
    const auto& c = colourMapStops();
    t = std::clamp(t, 0.0f, 1.0f);
    const int k = std::min(static_cast<int>(t * 4.0f), 3);
    const float f = t * 4.0f - static_cast<float>(k);
    return c[static_cast<std::size_t>(k)] * (1.0f - f) + c[static_cast<std::size_t>(k) + 1] * f;
}

} // namespace freeform::editor
