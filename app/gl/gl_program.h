#pragma once
/// Small OpenGL helpers: error checks that throw, and shader programs compiled from files with the
/// file names in every compile or link message.

#include <stdexcept>
#include <string>

namespace rrf {

/// An OpenGL failure: a glGetError code, an incomplete framebuffer, a shader that does not compile.
class GlError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Throws GlError naming `what` and every pending glGetError code (there may be several).
void checkGl(const char* what);

/// "GL_INVALID_ENUM" etc. for a glGetError code.
std::string glErrorName(unsigned code);

/// Reads a shader file; throws GlError naming the file if it cannot be read.
std::string readShaderFile(const std::string& path);

/// Inserts `defines` (lines of "#define NAME value") directly after the "#version" line of `source`,
/// where GLSL requires the version directive to stay first. Throws GlError naming `name` if the
/// source has no #version line.
std::string injectDefines(const std::string& source, const std::string& defines, const std::string& name);

/// A linked program (owns the GL object; needs a current context to construct and destroy).
class GlProgram {
public:
    GlProgram() = default;
    /// Compiles and links. `vertexName`/`fragmentName` label the sources in messages (file paths).
    /// Throws GlError with the driver's info log and the name of the failing file.
    GlProgram(const std::string& vertexName, const std::string& vertexSource, const std::string& fragmentName,
              const std::string& fragmentSource);
    ~GlProgram();
    GlProgram(GlProgram&& o) noexcept : id_(o.id_) { o.id_ = 0; }
    GlProgram& operator=(GlProgram&& o) noexcept;
    GlProgram(const GlProgram&) = delete;
    GlProgram& operator=(const GlProgram&) = delete;

    /// Reads, injects `defines` and compiles the two files.
    static GlProgram fromFiles(const std::string& vertexPath, const std::string& fragmentPath,
                               const std::string& defines = "");

    unsigned id() const { return id_; }
    /// Location of a uniform; -1 if the linker removed it (unused), which glUniform* ignores.
    int uniform(const char* name) const;

private:
    unsigned id_ = 0;
};

}  // namespace rrf
