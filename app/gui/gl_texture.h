#pragma once
/// An RGBA8 OpenGL texture holding one view's display image (UI thread only).

#include <cstdint>

#include <imgui.h>

#include "panels/view_model.h"

namespace rrf {

class GlTexture {
public:
    GlTexture() = default;
    ~GlTexture();
    GlTexture(const GlTexture&) = delete;
    GlTexture& operator=(const GlTexture&) = delete;

    /// Uploads `image` unless its revision is already on the GPU.
    void upload(const panels::DisplayImage& image);
    /// The texture for ImGui::Image / ImDrawList::AddImage, null while empty.
    ImTextureID id() const;

private:
    unsigned int texture_ = 0;
    int width_ = 0, height_ = 0;
    uint64_t revision_ = ~0ull;
    bool empty_ = true;
};

}  // namespace rrf
