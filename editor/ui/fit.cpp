#include "ui/fit.h"

#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <cmath>

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

/// Inside a window or table that scrolls sideways (its scroll bar shown) everything can be reached;
/// a table's column still measuring its content (its first frames) has no width yet.
bool measuring()
{
    const ImGuiTable* t = ImGui::GetCurrentTable();
    return t && (t->IsInitializing || (t->CurrentColumn >= 0 && t->Columns[t->CurrentColumn].AutoFitQueue != 0));
}

bool scrollsSideways()
{
    const ImGuiWindow* w = ImGui::GetCurrentWindowRead();
    return (w && w->ScrollbarX) || measuring();
}

} // namespace

void recordOverflowsInto(std::vector<Overflow>* list)
{
    records = list;
}

void fitItem(const char* label)
{
    if (!records || scrollsSideways()) return;
    const ImVec2 min = ImGui::GetItemRectMin(), max = ImGui::GetItemRectMax();
    // The draw list's clip rectangle is the panel's visible inner area, or inside a table the
    // cell's column (clipped to the table).
    const float right = ImGui::GetWindowDrawList()->GetClipRectMax().x;
    record(label, max.x - min.x, right - min.x);
}

void fitText(const char* text)
{
    if (!records || scrollsSideways()) return;
    const float x = ImGui::GetCursorScreenPos().x;
    const float right = std::min(ImGui::GetWindowDrawList()->GetClipRectMax().x, x + ImGui::GetContentRegionAvail().x);
    record(text, ImGui::CalcTextSize(text).x, right - x);
}

void fitValue(const char* text)
{
    if (!records || measuring()) return;
    const float width = ImGui::GetItemRectSize().x;
    record(text, fieldWidthFor(text), width);
    fitItem(text);
}

void fitPanel(const std::string& what)
{
    if (!records) return;
    const ImGuiWindow* w = ImGui::GetCurrentWindowRead();
    if (!w || w->ScrollbarX || w->SkipItems) return;
    // CursorMaxPos: the right edge of everything laid out this frame; IdealMaxPos: the same with a
    // table at its natural width.
    const float left = w->DC.CursorStartPos.x, right = std::max(w->DC.CursorMaxPos.x, w->DC.IdealMaxPos.x);
    record(what.empty() ? std::string("(widest row)") : "(widest row, " + what + ")", right - left, w->InnerClipRect.Max.x - left);
}

void fitWindow(const std::string& what)
{
    if (!records) return;
    const ImGuiWindow* w = ImGui::GetCurrentWindowRead();
    if (!w || w->Appearing || w->HiddenFramesCannotSkipItems > 0 || w->HiddenFramesCanSkipItems > 0) return;
    fitPanel(what);
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    const ImRect screen(vp->Pos, ImVec2(vp->Pos.x + vp->Size.x, vp->Pos.y + vp->Size.y));
    ImRect shown = w->Rect();
    shown.ClipWithFull(screen);
    const std::string suffix = what.empty() ? std::string() : ", " + what;
    record("(cut by the screen, width" + suffix + ")", w->Size.x, std::max(shown.GetWidth(), 0.0f));
    record("(cut by the screen, height" + suffix + ")", w->Size.y, std::max(shown.GetHeight(), 0.0f));
}

void fitFields(const char* const texts[], int n, float reserve, bool centred)
{
    if (!records || n < 1 || measuring()) return;
    const float spacing = ImGui::GetStyle().ItemInnerSpacing.x;
    const float full = ImGui::CalcItemWidth() - reserve;
    // ImGui's PushMultiItemsWidths: n - 1 fields of this width, the last one the rest.
    const float one = std::max(1.0f, std::floor((full - spacing * float(n - 1)) / float(n)));
    const float last = std::max(1.0f, std::floor(full - (one + spacing) * float(n - 1)));
    for (int k = 0; k < n; ++k)
        record(texts[k], centred ? ImGui::CalcTextSize(texts[k]).x + 2 : fieldWidthFor(texts[k]), k + 1 < n ? one : last);
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
