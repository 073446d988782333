#include "app/gl/gl_state.h"

#include <cstdio>
#include <string>

#include "app/gl/gl_program.h"

namespace rrf {

GLuint makeFloatTexture(int w, int h, const float* data) {
    GLuint t = 0;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, w, h, 0, GL_RGBA, GL_FLOAT, data);
    return t;
}

void checkFramebuffer(const char* what) {
    const GLenum s = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (s != GL_FRAMEBUFFER_COMPLETE)
        throw GlError(std::string(what) + " framebuffer incomplete (status 0x" + [&] {
                          char b[16];
                          std::snprintf(b, sizeof b, "%x", unsigned(s));
                          return std::string(b);
                      }() + "): RGBA32F render targets are required");
}

}  // namespace rrf
