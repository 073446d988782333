#pragma once
// A bare ImGui context for panel tests: no window, no GL, no renderer backend. The font atlas is
// built on the CPU so NewFrame() works; Render() produces draw lists that nobody draws.

#include <functional>

#include <gtest/gtest.h>
#include <imgui.h>

namespace rrf::test {

class ImGuiFixture : public ::testing::Test {
protected:
    void SetUp() override {
        ctx_ = ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(1600, 1000);
        io.DeltaTime = 1.f / 60.f;
        io.IniFilename = nullptr;  // tests must not write imgui.ini anywhere
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
        io.Fonts->SetTexID(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(1)));
    }
    void TearDown() override { ImGui::DestroyContext(ctx_); }

    /// One frame with `body` inside a full-screen window without padding at (0, 0), so tests
    /// know where widgets are.
    void frame(const std::function<void()>& body) {
        ImGui::NewFrame();
        ImGui::SetNextWindowPos(ImVec2(0, 0));
        ImGui::SetNextWindowSize(ImGui::GetIO().DisplaySize);
        ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
        ImGui::Begin("##test-host", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings);
        ImGui::PopStyleVar();
        body();
        ImGui::End();
        ImGui::Render();
    }

    void mouse(float x, float y, bool down, float wheel = 0.f) {
        ImGuiIO& io = ImGui::GetIO();
        io.MousePos = ImVec2(x, y);
        io.MouseDown[0] = down;
        io.MouseWheel = wheel;
    }

private:
    ImGuiContext* ctx_ = nullptr;
};

}  // namespace rrf::test
