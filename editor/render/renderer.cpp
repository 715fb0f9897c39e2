// The parts of the renderer interface (render/renderer.h) that need no graphics API.

#include "render/renderer.h"

#include <algorithm>
#include <cctype>

namespace freeform::editor {

bool Renderer::software() const
{
    return isSoftwareRenderer(name());
}

bool isSoftwareRenderer(const std::string& glRenderer)
{
    std::string lower = glRenderer;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const char* word : {"llvmpipe", "softpipe", "swrast", "software rasterizer"})
        if (lower.find(word) != std::string::npos) return true;
    return false;
}

} // namespace freeform::editor
