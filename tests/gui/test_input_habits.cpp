// Input habits of the workbench window, driven through the same code the window uses: a numeric
// drag field opens for typing on a single click (panels/input_habits.h), and a key tap whose press
// and release arrive between two frames is still seen (app/gui/key_taps.h).
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "app/gui/key_taps.h"
#include "panels/input_habits.h"
#include "tests/gui/imgui_fixture.h"

namespace rrf::test {
namespace {

class InputHabits : public ImGuiFixture {
protected:
    int value = 7;
    ImVec2 centre{0, 0};

    /// One frame with the drag field the panels use for counts (ImGui::DragInt, 0 … 100).
    void field() {
        frame([&] {
            ImGui::SetNextItemWidth(200);
            ImGui::DragInt("count", &value, 1.f, 0, 100);
            const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
            centre = ImVec2((a.x + b.x) / 2, (a.y + b.y) / 2);
        });
    }
    void click(float dx) {
        mouse(centre.x, centre.y, false);
        field();
        mouse(centre.x, centre.y, true);
        field();
        for (int i = 1; i <= 4; ++i) {
            mouse(centre.x + dx * float(i) / 4, centre.y, true);
            field();
        }
        mouse(centre.x + dx, centre.y, false);
        field();
        field();
    }
    /// Types `text` and presses Enter, a frame per event, as a user's keyboard would.
    void type(const char* text) {
        ImGuiIO& io = ImGui::GetIO();
        io.KeyMap[ImGuiKey_Enter] = GLFW_KEY_ENTER;
        for (const char* c = text; *c; ++c) {
            io.AddInputCharacter(static_cast<unsigned>(*c));
            field();
        }
        io.KeysDown[GLFW_KEY_ENTER] = true;
        field();
        io.KeysDown[GLFW_KEY_ENTER] = false;
        field();
    }
};

TEST_F(InputHabits, SingleClickOpensADragFieldForTyping) {
    panels::configureInput(ImGui::GetIO());
    field();
    click(0.f);
    type("42");
    EXPECT_EQ(value, 42);
}

TEST_F(InputHabits, WithoutTheHabitASingleClickDoesNotOpenTheField) {
    // ImGui's own default: the same click and keys leave the value alone (double-click or
    // Ctrl+click would be needed), which is what the habit changes.
    field();
    click(0.f);
    type("42");
    EXPECT_EQ(value, 7);
}

TEST_F(InputHabits, DraggingStillChangesTheValueAndDoesNotOpenTheField) {
    panels::configureInput(ImGui::GetIO());
    field();
    click(40.f);
    const int dragged = value;
    EXPECT_GT(dragged, 7);
    type("3");
    EXPECT_EQ(value, dragged);
}

class KeyTapsTest : public ImGuiFixture {
protected:
    bool pressed = false, down = false, ctrl = false;
    /// A frame as the window runs one: NewFrame, the panels (reading keys and modifiers), Render,
    /// then KeyTaps::frameEnded.
    void frameWith(KeyTaps* taps, int key) {
        frame([&] {
            pressed = ImGui::IsKeyPressed(key, false);
            down = ImGui::IsKeyDown(key);
            ctrl = ImGui::GetIO().KeyCtrl;
        });
        if (taps) taps->frameEnded();
    }
    /// What ImGui 1.86's GLFW backend does with a key event: the key's down state, and the
    /// modifiers recomputed from the keys at once.
    static void backend(int key, int, int action, int) {
        ImGuiIO& io = ImGui::GetIO();
        io.KeysDown[key] = action != GLFW_RELEASE;
        io.KeyCtrl = io.KeysDown[GLFW_KEY_LEFT_CONTROL] || io.KeysDown[GLFW_KEY_RIGHT_CONTROL];
    }
};

TEST_F(KeyTapsTest, ATapWithinOneFrameIsSeenPressedThenReleased) {
    KeyTaps taps(backend);
    frameWith(&taps, GLFW_KEY_F1);
    taps.event(GLFW_KEY_F1, 0, GLFW_PRESS, 0);
    taps.event(GLFW_KEY_F1, 0, GLFW_RELEASE, 0);
    EXPECT_EQ(taps.heldReleases(), 1u);
    frameWith(&taps, GLFW_KEY_F1);
    EXPECT_TRUE(pressed);
    EXPECT_EQ(taps.heldReleases(), 0u);
    frameWith(&taps, GLFW_KEY_F1);
    EXPECT_FALSE(down);
    EXPECT_FALSE(pressed);
}

TEST_F(KeyTapsTest, AShortcutTappedWithinOneFrameKeepsItsModifier) {
    // Ctrl+S pressed and let go between two frames: the frame's UI sees S pressed with Ctrl down,
    // as the shortcut table asks (workbench.cpp compares io.KeyCtrl while the UI runs).
    KeyTaps taps(backend);
    frameWith(&taps, GLFW_KEY_S);
    taps.event(GLFW_KEY_LEFT_CONTROL, 0, GLFW_PRESS, 0);
    taps.event(GLFW_KEY_S, 0, GLFW_PRESS, GLFW_MOD_CONTROL);
    taps.event(GLFW_KEY_S, 0, GLFW_RELEASE, GLFW_MOD_CONTROL);
    taps.event(GLFW_KEY_LEFT_CONTROL, 0, GLFW_RELEASE, 0);
    frameWith(&taps, GLFW_KEY_S);
    EXPECT_TRUE(pressed);
    EXPECT_TRUE(ctrl);
    frameWith(&taps, GLFW_KEY_S);
    EXPECT_FALSE(down);
    EXPECT_FALSE(ctrl);
}

TEST_F(KeyTapsTest, WithoutItTheSameTapIsLost) {
    // The backend alone: press and release before the frame leave the key up at NewFrame.
    frameWith(nullptr, GLFW_KEY_F1);
    backend(GLFW_KEY_F1, 0, GLFW_PRESS, 0);
    backend(GLFW_KEY_F1, 0, GLFW_RELEASE, 0);
    frameWith(nullptr, GLFW_KEY_F1);
    EXPECT_FALSE(pressed);
}

TEST_F(KeyTapsTest, AHeldKeyIsReleasedAtOnce) {
    KeyTaps taps(backend);
    taps.event(GLFW_KEY_Z, 0, GLFW_PRESS, 0);
    frameWith(&taps, GLFW_KEY_Z);
    EXPECT_TRUE(pressed);
    frameWith(&taps, GLFW_KEY_Z);
    EXPECT_TRUE(down);
    // Pressed in an earlier frame: its release is not held.
    taps.event(GLFW_KEY_Z, 0, GLFW_RELEASE, 0);
    EXPECT_EQ(taps.heldReleases(), 0u);
    frameWith(&taps, GLFW_KEY_Z);
    EXPECT_FALSE(down);
}

TEST_F(KeyTapsTest, TwoTapsWithinOneFrameEndReleased) {
    KeyTaps taps(backend);
    frameWith(&taps, GLFW_KEY_A);
    for (int i = 0; i < 2; ++i) {
        taps.event(GLFW_KEY_A, 0, GLFW_PRESS, 0);
        taps.event(GLFW_KEY_A, 0, GLFW_RELEASE, 0);
    }
    frameWith(&taps, GLFW_KEY_A);
    EXPECT_TRUE(pressed);
    frameWith(&taps, GLFW_KEY_A);
    EXPECT_FALSE(down);
}

}  // namespace
}  // namespace rrf::test
