#include "app/tooltip_audit.h"

#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <cfloat>
#include <map>

namespace freeform::editor {

namespace {

using Frame = std::function<void(const std::function<void()>&)>;

/// The IDs of window chrome: title bar buttons, scrollbars, resize grips and borders, the move
/// handle, and the column borders of every table.
bool isChrome(ImGuiID id)
{
    ImGuiContext& g = *GImGui;
    for (ImGuiWindow* w : g.Windows) {
        if (id == w->MoveId || id == ImHashStr("#COLLAPSE", 0, w->ID) || id == ImHashStr("#CLOSE", 0, w->ID) ||
            id == ImHashStr("#SCROLLX", 0, w->ID) || id == ImHashStr("#SCROLLY", 0, w->ID))
            return true;
        for (int n = 0; n < 4; ++n)
            if (id == ImGui::GetWindowResizeCornerID(w, n) || id == ImGui::GetWindowResizeBorderID(w, static_cast<ImGuiDir>(n)))
                return true;
    }
    for (int n = 0; n < g.Tables.GetMapSize(); ++n)
        if (const ImGuiTable* table = g.Tables.TryGetMapData(n))
            for (int c = 0; c < table->ColumnsCount; ++c)
                for (int instance = 0; instance <= table->InstanceCurrent; ++instance)
                    if (id == ImGui::TableGetColumnResizeID(table, c, instance)) return true;
    return false;
}

bool tooltipOpen()
{
    for (const ImGuiWindow* w : GImGui->Windows)
        if ((w->Flags & ImGuiWindowFlags_Tooltip) && w->Active) return true;
    return false;
}

/// The ID path of `id`, hovered now (the pointer stays): ImGui's stack tool protocol
/// (DebugHookIdInfo), driven from here so that an active text field does not take the query.
/// The first frame finds the ID stack the item's ID was made with, then one level is asked per
/// frame (up to 3 frames each) for the label or number that made it.
std::string idPath(ImGuiID id, const Frame& frame)
{
    ImGuiContext& g = *GImGui;
    ImGuiStackTool& tool = g.DebugStackTool;
    tool.Results.resize(0);
    tool.StackLevel = -1;
    tool.QueryId = id;
    frame([&] {
        tool.StackLevel = -1;
        g.DebugHookIdInfo = id;
    });
    for (int level = 0; level < tool.Results.Size; ++level)
        for (int attempt = 0; attempt < 3 && !tool.Results[level].QuerySuccess; ++attempt)
            frame([&] {
                tool.StackLevel = level;
                tool.Results[level].QueryFrameCount++;
                g.DebugHookIdInfo = tool.Results[level].ID;
            });
    std::string path;
    for (int level = 0; level < tool.Results.Size; ++level) {
        const ImGuiStackLevelInfo& info = tool.Results[level];
        std::string part;
        if (info.QuerySuccess) {
            part = info.Desc;
            // The stack tool's buffer is full: the label may go on beyond it. Say so rather than
            // report a cut label as if it were whole.
            if (part.size() + 1 >= sizeof info.Desc) part += "...";
        }
        else if (const ImGuiWindow* w = ImGui::FindWindowByID(info.ID)) part = w->Name;
        else {
            char hex[16];
            ImFormatString(hex, sizeof hex, "0x%08X", info.ID);
            part = hex;
        }
        path += (path.empty() ? "" : " > ") + part;
    }
    tool.Results.resize(0);
    tool.StackLevel = -1;
    if (path.empty()) {
        char hex[16];
        ImFormatString(hex, sizeof hex, "0x%08X", id);
        path = hex;
    }
    return path;
}

struct Sweep {
    const Frame& frame;
    const std::string& shownTooltip;
    float step;
    const std::vector<unsigned>* dropdowns; // the panels' dropdowns (may be null: none opened)
    TooltipAudit audit;
    std::map<std::pair<ImGuiID, ImGuiID>, std::size_t> index; // (open dropdown or 0, item id) -> audit.items
    std::vector<ImGuiID> ids;                                 // audit.items' ImGui IDs
    int scrolled = 0;                                         // > 0 while a panel is scrolled by the sweep
    ImGuiID dropdown = 0;                                     // the dropdown whose list is swept now (0: none)
    std::string dropdownPath, dropdownWindow;

    /// One point: the pointer there, a frame, the hovered item and the tooltip.
    void point(float x, float y, const std::string& window)
    {
        ImGuiContext& g = *GImGui;
        g.IO.MousePos = ImVec2(x, y);
        frame({});
        ++audit.points;
        const ImGuiID id = g.HoveredId;
        if (id == 0 || isChrome(id)) return;
        const bool shown = tooltipOpen();
        auto found = index.find({dropdown, id});
        if (found == index.end()) {
            TooltipAuditItem item;
            item.window = g.HoveredWindow ? g.HoveredWindow->RootWindow->Name : window; // a window on top may hide the one swept
            item.x = x;
            item.y = y;
            item.tooltip = shown;
            item.scrolled = scrolled > 0;
            item.text = shownTooltip;
            item.path = idPath(id, frame); // the pointer stays on it meanwhile
            if (dropdown != 0) {
                // A choice: named after its dropdown (the list's own window, "##Combo_00", left out).
                const std::size_t list = item.path.find(" > ");
                item.path = dropdownPath + " > (open) > " + (list == std::string::npos ? item.path : item.path.substr(list + 3));
                item.window = dropdownWindow;
                item.dropdown = dropdownPath;
            }
            found = index.emplace(std::make_pair(dropdown, id), audit.items.size()).first;
            audit.items.push_back(std::move(item));
            ids.push_back(id);
        }
        TooltipAuditItem& item = audit.items[found->second];
        ++item.hovered;
        item.tooltip = item.tooltip && shown;
    }

    void rect(const ImRect& r, const std::string& window)
    {
        for (float y = r.Min.y + 0.5f * step; y < r.Max.y; y += step)
            for (float x = r.Min.x + 0.5f * step; x < r.Max.x; x += step) point(x, y, window);
    }

    /// A frame with the pointer away from every window (scroll positions take effect).
    void settle()
    {
        GImGui->IO.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
        frame({});
    }

    /// Opens each dropdown among audit.items[from, end) (found at the scroll positions now in
    /// effect) by a click where it was hovered, sweeps its list, and closes it again.
    void openDropdowns(std::size_t from)
    {
        if (!dropdowns || dropdown != 0) return;
        ImGuiContext& g = *GImGui;
        const std::size_t end = audit.items.size();
        for (std::size_t i = from; i < end; ++i) {
            const ImGuiID id = ids[i];
            if (std::find(dropdowns->begin(), dropdowns->end(), id) == dropdowns->end()) continue;
            const TooltipAuditItem item = audit.items[i];
            TooltipAuditDropdown d;
            d.window = item.window;
            d.path = item.path;
            const int level = g.OpenPopupStack.Size;
            const ImGuiID popup = ImHashStr("##ComboPopup", 0, id);
            g.IO.MousePos = ImVec2(item.x, item.y);
            frame({});
            g.IO.MouseDown[0] = true;
            frame({});
            g.IO.MouseDown[0] = false;
            frame({});
            settle();
            ImGuiWindow* list = nullptr;
            if (g.OpenPopupStack.Size > level && g.OpenPopupStack[level].PopupId == popup) list = g.OpenPopupStack[level].Window;
            d.opened = list != nullptr && list->Active;
            if (d.opened) {
                const std::size_t before = audit.items.size();
                dropdown = id;
                dropdownPath = item.path;
                dropdownWindow = item.window;
                const ImGuiViewport* vp = ImGui::GetMainViewport();
                window(list, ImRect(vp->Pos, ImVec2(vp->Pos.x + vp->Size.x, vp->Pos.y + vp->Size.y)), true, list->Name);
                dropdown = 0;
                for (std::size_t k = before; k < audit.items.size(); ++k) d.choices += audit.items[k].dropdown == item.path;
            }
            // Closed without a choice (as Escape does), focus back where it was.
            frame([&] {
                if (GImGui->OpenPopupStack.Size > level) ImGui::ClosePopupToLevel(level, true);
            });
            settle();
            audit.dropdowns.push_back(std::move(d));
        }
    }

    /// Sweeps `w` within `clip` at each of its scroll positions (`whole`: at the first one its
    /// whole rectangle, title bar included; else only what scrolling brings in), and the scrolling
    /// children inside it likewise.
    void window(ImGuiWindow* w, ImRect clip, bool whole, const std::string& name)
    {
        const float original = w->Scroll.y;
        const float page = std::max(w->InnerRect.GetHeight() - ImGui::GetTextLineHeightWithSpacing(), step);
        std::vector<float> positions = {0};
        for (float s = page; s < w->ScrollMax.y + page; s += page) positions.push_back(std::min(s, w->ScrollMax.y));
        for (std::size_t k = 0; k < positions.size(); ++k) {
            ImGui::SetScrollY(w, positions[k]);
            scrolled += k > 0;
            settle();
            ImRect r = whole && k == 0 ? w->Rect() : w->InnerClipRect;
            r.ClipWithFull(clip);
            const std::size_t found = audit.items.size();
            if (whole || k > 0) rect(r, name);
            openDropdowns(found);
            ImRect inner = w->InnerClipRect;
            inner.ClipWithFull(clip);
            std::vector<ImGuiWindow*> children;
            for (ImGuiWindow* c : GImGui->Windows)
                if ((c->Flags & ImGuiWindowFlags_ChildWindow) && c->ParentWindow == w && c->Active && c->ScrollMax.y > 0 &&
                    c->Rect().Overlaps(inner))
                    children.push_back(c);
            for (ImGuiWindow* c : children) window(c, inner, false, name);
            scrolled -= k > 0;
        }
        ImGui::SetScrollY(w, original);
        settle();
    }
};

} // namespace

TooltipAudit auditTooltips(const Frame& frame, const std::string& shownTooltip, float step, const std::vector<std::string>& windows,
                           const std::vector<unsigned>* dropdowns)
{
    ImGuiContext& g = *GImGui;
    const ImVec2 mouse = g.IO.MousePos;
    if (!(step > 0)) step = 0.5f * ImGui::GetTextLineHeightWithSpacing();
    Sweep sweep{frame, shownTooltip, step, dropdowns, {}, {}, {}, 0, 0, {}, {}};
    sweep.audit.step = step;
    sweep.settle();
    // The windows shown now (ImGui keeps them back to front). While a popup (a menu, a dialog)
    // is open only the popups: hovering another menu title would open that menu instead.
    const bool popupOpen = g.OpenPopupStack.Size > 0;
    // A submenu (a menu inside a menu) is a child window of its menu, swept as a window of its own;
    // front to back, so that a submenu is swept before hovering its menu's other items closes it.
    std::vector<ImGuiWindow*> roots;
    for (int n = g.Windows.Size - 1; n >= 0; --n) {
        ImGuiWindow* w = g.Windows[n];
        const bool childMenu = (w->Flags & ImGuiWindowFlags_ChildMenu) != 0;
        if (!w->Active || (w->Flags & ImGuiWindowFlags_Tooltip) || ((w->Flags & ImGuiWindowFlags_ChildWindow) && !childMenu)) continue;
        if (popupOpen && !(w->Flags & ImGuiWindowFlags_Popup)) continue;
        if (!windows.empty() && std::find(windows.begin(), windows.end(), std::string(w->Name)) == windows.end()) continue;
        roots.push_back(w);
    }
    const ImGuiViewport* vp = ImGui::GetMainViewport();
    const ImRect screen(vp->Pos, ImVec2(vp->Pos.x + vp->Size.x, vp->Pos.y + vp->Size.y));
    for (ImGuiWindow* w : roots) {
        sweep.audit.windows.push_back(w->Name);
        sweep.window(w, screen, true, w->Name);
    }
    g.IO.MousePos = mouse;
    frame({});
    return std::move(sweep.audit);
}

} // namespace freeform::editor
