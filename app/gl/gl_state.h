#pragma once
/// Small GL helpers shared by the GLSL predictor's files (app/gl/glsl_predictor.cpp and
/// app/gl/glsl_direct_light.cpp): a scope guard for the GL state they change, float textures and
/// framebuffer checks. Need a current GL context.

#include <glad/gl.h>

namespace rrf {

/// Saves the GL state that render() and the read-backs change and restores it on scope exit, so the
/// predictor can run inside another renderer's frame (the GUI's ImGui pass).
class GlStateGuard {
public:
    GlStateGuard() {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFbo_);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFbo_);
        glGetIntegerv(GL_VIEWPORT, viewport_);
        glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao_);
        glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &arrayBuffer_);
        glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture_);
        for (int i = 0; i < 4; ++i) {
            glActiveTexture(GLenum(GL_TEXTURE0 + i));
            glGetIntegerv(GL_TEXTURE_BINDING_2D, &textures_[i]);
        }
        glGetIntegerv(GL_DEPTH_FUNC, &depthFunc_);
        glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask_);
        glGetIntegerv(GL_PACK_ALIGNMENT, &packAlignment_);
        glGetIntegerv(GL_UNPACK_ALIGNMENT, &unpackAlignment_);
        for (int i = 0; i < 4; ++i) enabled_[i] = glIsEnabled(kCaps[i]);
    }
    ~GlStateGuard() {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(drawFbo_));
        glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(readFbo_));
        glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
        glUseProgram(GLuint(program_));
        glBindVertexArray(GLuint(vao_));
        glBindBuffer(GL_ARRAY_BUFFER, GLuint(arrayBuffer_));
        for (int i = 0; i < 4; ++i) {
            glActiveTexture(GLenum(GL_TEXTURE0 + i));
            glBindTexture(GL_TEXTURE_2D, GLuint(textures_[i]));
        }
        glActiveTexture(GLenum(activeTexture_));
        glDepthFunc(GLenum(depthFunc_));
        glDepthMask(depthMask_);
        glPixelStorei(GL_PACK_ALIGNMENT, packAlignment_);
        glPixelStorei(GL_UNPACK_ALIGNMENT, unpackAlignment_);
        for (int i = 0; i < 4; ++i) (enabled_[i] ? glEnable : glDisable)(kCaps[i]);
    }

private:
    static constexpr GLenum kCaps[4] = {GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_SCISSOR_TEST};
    GLint drawFbo_ = 0, readFbo_ = 0, viewport_[4] = {0, 0, 0, 0}, program_ = 0, vao_ = 0, arrayBuffer_ = 0;
    GLint activeTexture_ = GL_TEXTURE0, textures_[4] = {0, 0, 0, 0}, depthFunc_ = GL_LESS;
    GLint packAlignment_ = 4, unpackAlignment_ = 4;
    GLboolean depthMask_ = GL_TRUE, enabled_[4] = {GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE};
};

/// A w × h RGBA32F texture with nearest filtering and clamped edges, filled from `data` (may be null).
GLuint makeFloatTexture(int w, int h, const float* data);

/// Throws GlError naming `what` when the bound framebuffer is incomplete.
void checkFramebuffer(const char* what);

}  // namespace rrf
