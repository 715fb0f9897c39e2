// The keymap (interaction/keymap.h): the one table key handling and the F1 help are made from.
// Checked: every entry with a help line appears in the F1 text as that line; no two entries of one
// context match the same key press (for every combination of Shift, Ctrl, Alt and Super); and the
// key handling of Interaction and the tools follows the table (a key rebound in the table would
// move with it: the checks below look the keys up in the table, not in GLFW constants).

#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <set>
#include <string>

#include "interaction/interaction.h"
#include "interaction/keymap.h"
#include "tools/tools.h"
#include "ui/ui.h"

namespace test_keymap {

using namespace freeform::editor;

namespace {

const int kAllMods[] = {0,
                        GLFW_MOD_SHIFT,
                        GLFW_MOD_CONTROL,
                        GLFW_MOD_ALT,
                        GLFW_MOD_SUPER,
                        GLFW_MOD_SHIFT | GLFW_MOD_CONTROL,
                        GLFW_MOD_SHIFT | GLFW_MOD_ALT,
                        GLFW_MOD_SHIFT | GLFW_MOD_SUPER,
                        GLFW_MOD_CONTROL | GLFW_MOD_ALT,
                        GLFW_MOD_CONTROL | GLFW_MOD_SUPER,
                        GLFW_MOD_ALT | GLFW_MOD_SUPER,
                        GLFW_MOD_SHIFT | GLFW_MOD_CONTROL | GLFW_MOD_ALT,
                        GLFW_MOD_SHIFT | GLFW_MOD_CONTROL | GLFW_MOD_SUPER,
                        GLFW_MOD_SHIFT | GLFW_MOD_ALT | GLFW_MOD_SUPER,
                        GLFW_MOD_CONTROL | GLFW_MOD_ALT | GLFW_MOD_SUPER,
                        GLFW_MOD_SHIFT | GLFW_MOD_CONTROL | GLFW_MOD_ALT | GLFW_MOD_SUPER};

/// The first entry for `action` (its key and the modifiers it needs).
const KeyBinding& entryOf(KeyAction action)
{
    for (const KeyBinding& b : keymap())
        if (b.action == action) return b;
    FAIL("no entry for an action");
    return keymap().front();
}

} // namespace

TEST_CASE("keymap: every entry's help line is in the F1 text", "[editor][keymap]")
{
    const std::string help = controlsHelp();
    int lines = 0;
    for (const KeyBinding& b : keymap()) {
        if (!b.help) continue;
        INFO(b.keys);
        CHECK(help.find(helpLine(b) + "\n") != std::string::npos);
        CHECK(help.find(contextTitle(b.context)) != std::string::npos);
        ++lines;
    }
    CHECK(lines > 40);
    // An entry without help is listed under an entry with help of its context before it (a keypad
    // twin under its key, Y and Z under "X / Y / Z").
    const auto& table = keymap();
    for (std::size_t i = 0; i < table.size(); ++i) {
        if (table[i].help) continue;
        INFO(table[i].keys);
        bool found = false;
        for (std::size_t j = 0; j < i; ++j)
            found |= table[j].help && table[j].context == table[i].context;
        CHECK(found);
    }
}

TEST_CASE("keymap: no two entries of one context match the same key press", "[editor][keymap]")
{
    const auto& table = keymap();
    for (std::size_t i = 0; i < table.size(); ++i)
        for (std::size_t j = i + 1; j < table.size(); ++j) {
            if (table[i].context != table[j].context || table[i].key != table[j].key) continue;
            for (int mods : kAllMods) {
                INFO(table[i].keys << " and " << table[j].keys << " with modifier bits " << mods);
                CHECK_FALSE((matches(table[i], table[i].key, mods) && matches(table[j], table[j].key, mods)));
            }
        }
    // Every entry matches its own key with its own modifiers, and findBinding finds it (or its
    // alias twin with the same action).
    for (const KeyBinding& b : table) {
        INFO(b.keys);
        CHECK(matches(b, b.key, b.mods));
        const KeyBinding* found = findBinding(b.context, b.key, b.mods);
        REQUIRE(found);
        CHECK(found->action == b.action);
    }
}

TEST_CASE("keymap: the modifier rules of a few entries, worked out by hand", "[editor][keymap]")
{
    // C creates a curve, Shift+C a spline; Ctrl+C is neither.
    REQUIRE(findBinding(KeyContext::Curve, GLFW_KEY_C, 0));
    CHECK(findBinding(KeyContext::Curve, GLFW_KEY_C, 0)->action == KeyAction::CreateCurve);
    CHECK(findBinding(KeyContext::Curve, GLFW_KEY_C, GLFW_MOD_SHIFT)->action == KeyAction::CreateSpline);
    CHECK_FALSE(findBinding(KeyContext::Curve, GLFW_KEY_C, GLFW_MOD_CONTROL));
    // Shift+1 is the front view like 1; Ctrl+1 the back view (another context).
    CHECK(findBinding(KeyContext::View, GLFW_KEY_1, GLFW_MOD_SHIFT)->action == KeyAction::ViewFront);
    CHECK_FALSE(findBinding(KeyContext::View, GLFW_KEY_1, GLFW_MOD_CONTROL));
    CHECK(findBinding(KeyContext::Files, GLFW_KEY_1, GLFW_MOD_CONTROL)->action == KeyAction::ViewBack);
    // Ctrl+Z undo, Ctrl+Shift+Z and Ctrl+Y redo.
    CHECK(findBinding(KeyContext::History, GLFW_KEY_Z, GLFW_MOD_CONTROL)->action == KeyAction::Undo);
    CHECK(findBinding(KeyContext::History, GLFW_KEY_Z, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT)->action == KeyAction::Redo);
    CHECK(findBinding(KeyContext::History, GLFW_KEY_Y, GLFW_MOD_CONTROL)->action == KeyAction::Redo);
    // Alt+A (with or without Shift) selects no point; Shift+A nothing; A all.
    CHECK(findBinding(KeyContext::Edit, GLFW_KEY_A, GLFW_MOD_ALT | GLFW_MOD_SHIFT)->action == KeyAction::SelectNone);
    CHECK_FALSE(findBinding(KeyContext::Edit, GLFW_KEY_A, GLFW_MOD_SHIFT));
    CHECK(findBinding(KeyContext::Edit, GLFW_KEY_A, 0)->action == KeyAction::SelectAll);
}

TEST_CASE("keymap: Interaction and the tools act on the table's keys", "[editor][keymap]")
{
    Scene scene;
    Selection selection;
    EditSettings settings;
    Interaction interaction(settings);
    const ViewTransform view{};
    // The snap toggle, the soft toggle and the gizmo toggle, pressed as the table says.
    for (KeyAction action : {KeyAction::ToggleSnap, KeyAction::ToggleSoft, KeyAction::ToggleGizmo}) {
        const KeyBinding& b = entryOf(action);
        const EditSettings before = settings;
        REQUIRE(interaction.key(scene, selection, view, b.key, b.mods, 0, 0));
        CHECK((settings.snap != before.snap || settings.soft != before.soft || settings.gizmo != before.gizmo));
    }
    CHECK(settings.snap);
    CHECK(settings.soft);
    CHECK_FALSE(settings.gizmo);
    // With Ctrl held no editing key is taken.
    CHECK_FALSE(interaction.key(scene, selection, view, entryOf(KeyAction::ToggleSoft).key, GLFW_MOD_CONTROL, 0, 0));

    // The curve tool: its creation key starts creating, the creation context's cancel ends it.
    Tools tools;
    ToolContext context{scene, selection};
    const KeyBinding& create = entryOf(KeyAction::CreateSpline);
    REQUIRE(tools.onKey(context, create.key, create.mods));
    CHECK(tools.curve().creating());
    CHECK(tools.curve().creatingSpline());
    const KeyBinding& cancel = entryOf(KeyAction::CreateCancel);
    REQUIRE(tools.onKey(context, cancel.key, cancel.mods));
    CHECK_FALSE(tools.curve().creating());
    // Direct manipulation toggles; a key of no tool context is not taken.
    const KeyBinding& direct = entryOf(KeyAction::DirectManipulation);
    REQUIRE(tools.onKey(context, direct.key, direct.mods));
    CHECK(tools.lattice().direct);
    CHECK_FALSE(tools.onKey(context, entryOf(KeyAction::NextShading).key, 0));
}

} // namespace test_keymap
