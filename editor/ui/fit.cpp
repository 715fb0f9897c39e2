#include "ui/fit.h"

#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>

namespace freeform::editor {

namespace {

std::vector<Overflow>* records = nullptr;
constexpr std::size_t kMaxRecords = 200;
/// Rounding of glyph positions: a text that needs at most this much more is not cut.
constexpr float kSlack = 0.5f;

std::string panelName()
{
    const ImGuiWindow* w = ImGui::GetCurrentWindowRead();
    if (!w) return "?";
    return w->RootWindow ? w->RootWindow->Name : w->Name;
}

void record(const std::string& label, float needed, float available)
{
    if (!records || !(needed > available + kSlack)) return;
    const std::string panel = panelName();
    for (Overflow& o : *records)
        if (o.panel == panel && o.label == label) {
            if (needed - available > o.needed - o.available) o.needed = needed, o.available = available;
            return;
        }
    if (records->size() < kMaxRecords) records->push_back({panel, label, needed, available});
}

} // namespace

void recordOverflowsInto(std::vector<Overflow>* list)
{
    records = list;
}

void fitItem(const char* label)
{
    if (!records) return;
    const ImVec2 min = ImGui::GetItemRectMin(), max = ImGui::GetItemRectMax();
    // The draw list's clip rectangle is the panel's visible inner area, or inside a table the
    // cell's column (clipped to the table).
    const float right = ImGui::GetWindowDrawList()->GetClipRectMax().x;
    record(label, max.x - min.x, right - min.x);
}

void fitValue(const char* text)
{
    if (!records) return;
    const float width = ImGui::GetItemRectSize().x;
    record(text, fieldWidthFor(text), width);
    fitItem(text);
}

void fitPanel()
{
    if (!records) return;
    const ImGuiWindow* w = ImGui::GetCurrentWindowRead();
    if (!w || w->ScrollbarX || w->SkipItems) return;
    // IdealMaxPos: the right edge of everything laid out this frame, a table at its natural width.
    const float left = w->DC.CursorStartPos.x;
    record("(widest row)", w->DC.IdealMaxPos.x - left, w->InnerClipRect.Max.x - left);
}

void fitWidth(const char* label, float needed, float available)
{
    record(label, needed, available);
}

float fieldWidthFor(const char* text)
{
    return ImGui::CalcTextSize(text).x + 2 * ImGui::GetStyle().FramePadding.x;
}

} // namespace freeform::editor
