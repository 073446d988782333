#include "app/gl/gl_program.h"

#include <fstream>
#include <sstream>
#include <vector>

#include <glad/gl.h>

#include "app/gl/program_binary_cache.h"

namespace rrf {

std::string glErrorName(unsigned code) {
    switch (code) {
        case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
        default: return "GL error 0x" + [&] { std::ostringstream s; s << std::hex << code; return s.str(); }();
    }
}

void checkGl(const char* what) {
    std::string errors;
    // glGetError returns one flag per call; a lost context keeps returning errors, so bound the loop.
    for (int i = 0; i < 16; ++i) {
        const GLenum e = glGetError();
        if (e == GL_NO_ERROR) break;
        errors += (errors.empty() ? "" : ", ") + glErrorName(e);
    }
    if (!errors.empty()) throw GlError(std::string("OpenGL error in ") + what + ": " + errors);
}

std::string readShaderFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw GlError(path + ": cannot read shader file");
    std::ostringstream s;
    s << in.rdbuf();
    if (in.bad()) throw GlError(path + ": error while reading shader file");
    return s.str();
}

std::string injectDefines(const std::string& source, const std::string& defines, const std::string& name) {
    const size_t v = source.find("#version");
    if (v == std::string::npos) throw GlError(name + ": shader has no #version line");
    const size_t eol = source.find('\n', v);
    if (eol == std::string::npos) throw GlError(name + ": shader ends after its #version line");
    // "#line 2" keeps the driver's line numbers equal to the file's.
    return source.substr(0, eol + 1) + defines + (defines.empty() || defines.back() == '\n' ? "" : "\n") +
           "#line 2\n" + source.substr(eol + 1);
}

namespace {

std::string shaderLog(GLuint s) {
    GLint n = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &n);
    std::vector<char> log(size_t(std::max(n, 1)), '\0');
    glGetShaderInfoLog(s, GLsizei(log.size()), nullptr, log.data());
    return log.data();
}

std::string programLog(GLuint p) {
    GLint n = 0;
    glGetProgramiv(p, GL_INFO_LOG_LENGTH, &n);
    std::vector<char> log(size_t(std::max(n, 1)), '\0');
    glGetProgramInfoLog(p, GLsizei(log.size()), nullptr, log.data());
    return log.data();
}

GLuint compile(GLenum type, const std::string& name, const std::string& source) {
    const GLuint s = glCreateShader(type);
    if (!s) throw GlError(name + ": glCreateShader failed");
    const char* text = source.c_str();
    glShaderSource(s, 1, &text, nullptr);
    glCompileShader(s);
    GLint ok = GL_FALSE;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = shaderLog(s);
        glDeleteShader(s);
        throw GlError(name + ": shader does not compile:\n" + log);
    }
    return s;
}

}  // namespace

GlProgram::GlProgram(const std::string& vertexName, const std::string& vertexSource, const std::string& fragmentName,
                     const std::string& fragmentSource) {
    // A binary linked by an earlier run of the same sources and driver skips compiling and linking
    // (program_binary_cache.h); a miss or a refused file compiles as always.
    ProgramBinaryCache& cache = ProgramBinaryCache::shared();
    const uint64_t key = ProgramBinaryCache::key(vertexSource, fragmentSource);
    id_ = glCreateProgram();
    if (cache.load(key, id_)) {
        try {
            checkGl(("loading the cached program " + vertexName + " + " + fragmentName).c_str());
        } catch (...) {
            glDeleteProgram(id_);  // the constructor throws: no destructor will
            id_ = 0;
            throw;
        }
        return;
    }
    glDeleteProgram(id_);  // a refused binary may leave the object in a state a link does not clear
    id_ = 0;
    const GLuint vs = compile(GL_VERTEX_SHADER, vertexName, vertexSource);
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, fragmentName, fragmentSource);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    id_ = glCreateProgram();
    glAttachShader(id_, vs);
    glAttachShader(id_, fs);
    glProgramParameteri(id_, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
    glLinkProgram(id_);
    glDeleteShader(vs);  // flagged for deletion; freed with the program
    glDeleteShader(fs);
    GLint ok = GL_FALSE;
    glGetProgramiv(id_, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        const std::string log = programLog(id_);
        glDeleteProgram(id_);
        id_ = 0;
        throw GlError(vertexName + " + " + fragmentName + ": program does not link:\n" + log);
    }
    checkGl(("building program " + vertexName + " + " + fragmentName).c_str());
    cache.store(key, id_);
}

GlProgram::~GlProgram() {
    if (id_) glDeleteProgram(id_);
}

GlProgram& GlProgram::operator=(GlProgram&& o) noexcept {
    if (this != &o) {
        if (id_) glDeleteProgram(id_);
        id_ = o.id_;
        o.id_ = 0;
    }
    return *this;
}

GlProgram GlProgram::fromFiles(const std::string& vertexPath, const std::string& fragmentPath, const std::string& defines) {
    return GlProgram(vertexPath, injectDefines(readShaderFile(vertexPath), defines, vertexPath), fragmentPath,
                     injectDefines(readShaderFile(fragmentPath), defines, fragmentPath));
}

int GlProgram::uniform(const char* name) const { return glGetUniformLocation(id_, name); }

}  // namespace rrf
