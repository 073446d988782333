#include "app/gui/gl_texture.h"

#include <glad/gl.h>

namespace rrf {

GlTexture::~GlTexture() {
    if (texture_) glDeleteTextures(1, &texture_);
}

void GlTexture::upload(const panels::DisplayImage& image) {
    if (image.revision == revision_) return;
    revision_ = image.revision;
    empty_ = image.empty();
    if (empty_) return;
    if (!texture_) {
        glGenTextures(1, &texture_);
        glBindTexture(GL_TEXTURE_2D, texture_);
        // Nearest magnification: zoomed-in pixels stay square, as an inspection tool should show them.
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    glBindTexture(GL_TEXTURE_2D, texture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    if (image.width != width_ || image.height != height_) {
        width_ = image.width;
        height_ = image.height;
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width_, height_, 0, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
    } else {
        glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
    }
}

ImTextureID GlTexture::id() const {
    if (empty_ || !texture_) return nullptr;
    return reinterpret_cast<ImTextureID>(static_cast<intptr_t>(texture_));
}

}  // namespace rrf
