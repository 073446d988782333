#include "app/gl/glsl_predictor.h"

#include "app/gl/gl_state.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <glad/gl.h>

#include <tbb/parallel_for.h>

#include "core/predict/exact_direct.h"
#include "core/util/stopwatch.h"
#include "core/util/data_dir.h"

namespace rrf {

namespace {

// Vertex layout of the G-buffer pass (see shaders/gbuffer.vert): position 3, geometry 4, normal 3,
// info 2 (id, kind), emission 3, vertex shading normal 3 (zero: flat, the geometric normal).
constexpr int kFloatsPerVertex = 18;
constexpr float kKindPolygon = 0.f, kKindSphere = 1.f, kKindLightOneSided = 2.f, kKindLightTwoSided = 3.f;
constexpr float kLightId = float(GlGBuffer::kLightPixel);

struct DVec {
    double x, y, z;
};
DVec dv(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
DVec dsub(const DVec& a, const DVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
DVec dcross(const DVec& a, const DVec& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double ddot(const DVec& a, const DVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/// Appends one triangle whose fragments intersect the pixel ray with the triangle's own plane
/// (computed in double) and report `normal` (the CPU's normal of the whole primitive) and, for a
/// smooth mesh, the interpolation of its `vertexNormals` (a, b, c order; null: flat). A zero vector
/// interpolates to exactly zero, which is how the fragment stage tells flat triangles apart.
void addTriangle(std::vector<float>& out, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& normal, float id,
                 float kind, const Vec3& emission, const Vec3* vertexNormals = nullptr) {
    const DVec n = dcross(dsub(dv(b), dv(a)), dsub(dv(c), dv(a)));
    const double len = std::sqrt(ddot(n, n));
    if (!(len > 0.0) || !std::isfinite(len)) return;  // degenerate: a ray cannot hit it either
    const DVec u{n.x / len, n.y / len, n.z / len};
    const float plane[4] = {float(u.x), float(u.y), float(u.z), float(ddot(u, dv(a)))};
    const Vec3* corners[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
        const Vec3& p = *corners[k];
        const Vec3 s = vertexNormals ? vertexNormals[k] : Vec3(0.f);
        out.insert(out.end(), {p.x, p.y, p.z, plane[0], plane[1], plane[2], plane[3], normal.x, normal.y, normal.z, id,
                               kind, emission.x, emission.y, emission.z, s.x, s.y, s.z});
    }
}

/// A planar quad v0 v1 v2 v3 as Embree splits it: (v0, v1, v3) and (v2, v3, v1).
void addQuad(std::vector<float>& out, const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& v3, const Vec3& normal,
             float id, float kind, const Vec3& emission) {
    addTriangle(out, v0, v1, v3, normal, id, kind, emission);
    addTriangle(out, v2, v3, v1, normal, id, kind, emission);
}

/// The normal core/scene/accel.cpp stores for a primitive (float arithmetic, same expression).
Vec3 accelNormal(const Vec3* q, bool quad) {
    Vec3 n = quad ? cross(q[2] - q[0], q[3] - q[1]) : cross(q[1] - q[0], q[2] - q[0]);
    const float len = length(n);
    return len > 0.f ? n / len : Vec3(0, 0, 1);
}

/// A cube around the sphere; its fragments ray-cast the sphere itself (gbuffer.frag, kind 1). The
/// margin makes sure every pixel whose centre ray touches the sphere is covered.
void addSphereProxy(std::vector<float>& out, const Vec3& c, float r, float id) {
    static_assert(kFloatsPerVertex == 18, "the proxy's vertices below spell out every float of the layout");
    const float h = r * 1.05f + 1e-6f * (std::fabs(c.x) + std::fabs(c.y) + std::fabs(c.z) + r);
    Vec3 v[8];
    for (int i = 0; i < 8; ++i) v[i] = c + Vec3(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
    static const int faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (const auto& f : faces) {
        const int tris[2][3] = {{f[0], f[1], f[2]}, {f[0], f[2], f[3]}};
        for (const auto& tri : tris)
            for (int i : tri)
                out.insert(out.end(),
                           {v[i].x, v[i].y, v[i].z, c.x, c.y, c.z, r, 0.f, 0.f, 0.f, id, kKindSphere, 0.f, 0.f, 0.f, 0.f, 0.f, 0.f});
    }
}

int log2Exact(int v) {
    int k = 0;
    while ((1 << k) < v) ++k;
    return k;
}

}  // namespace

GlslPredictor::GlslPredictor(const Scene& scene, const ModelSet& models, const std::string& shaderDir) : scene_(scene) {
    // Resolved before any GL work, so a missing data directory is reported as such (with the places
    // looked in) rather than as a shader file that cannot be read.
    prediction_.direct = PredictionSettings::Direct::Network;  // until setPrediction()
    const std::string dirName = shaderDir.empty() ? rrf::shaderDir().string() : shaderDir;
    const std::string dir = dirName.back() == '/' ? dirName : dirName + "/";
    GlStateGuard guard;
    checkGl("state before GlslPredictor");
    GLint maxTex = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTex);
    maxTextureSize_ = maxTex;
    networks_ = packNetworkTexture(scene_, models, 256, std::max(1, maxTex));
    if (networks_.width > maxTex)
        throw GlError("network texture needs " + std::to_string(networks_.width) + " texels per row, GL_MAX_TEXTURE_SIZE is " +
                      std::to_string(maxTex));
    static_assert((kNetworkTextureWidth & (kNetworkTextureWidth - 1)) == 0, "the shader indexes with shifts and masks");

    gbufferProgram_ = GlProgram::fromFiles(dir + "gbuffer.vert", dir + "gbuffer.frag");
    std::string defines = "#define RRF_MAX_VEC4 " + std::to_string((networks_.maxLayerWidth + 3) / 4) +
                          "\n#define RRF_NET_WIDTH_LOG2 " + std::to_string(log2Exact(networks_.width)) + "\n";
    // Output location of each term = its index in core's Term, so read(term) and texture(term) can
    // use int(term) as the colour attachment.
    for (Term t : kTerms) {
        std::string name = termName(t);
        std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::toupper(c)); });
        defines += "#define RRF_TERM_" + name + " " + std::to_string(int(t)) + "\n";
    }
    // Exact direct light (shaders/direct_light.glsl) and the input encodings (shaders/encoding.glsl,
    // which calls functions predict.frag defines) go in front of predict.frag only; #line keeps the
    // driver's messages pointing at each file's own lines (source string 1, 2, then predict.frag's 0).
    const std::string inserted = "#line 1 1\n" + readShaderFile(dir + "direct_light.glsl") + "\n#line 1 2\n" +
                                 readShaderFile(dir + "encoding.glsl") + "\n#line 2 0\n";
    const std::string vert = dir + "fullscreen.vert", frag = dir + "predict.frag";
    predictProgram_ = GlProgram(vert, injectDefines(readShaderFile(vert), defines, vert), frag,
                                injectDefines(readShaderFile(frag), defines + inserted, frag));

    glUseProgram(predictProgram_.id());
    glUniform1i(predictProgram_.uniform("uGPosition"), 0);
    glUniform1i(predictProgram_.uniform("uGNormal"), 1);
    glUniform1i(predictProgram_.uniform("uGEmission"), 2);
    glUniform1i(predictProgram_.uniform("uNetworks"), 3);
    glUniform1i(predictProgram_.uniform("uDirectScene"), 4);
    glUniform1i(predictProgram_.uniform("uDirectHost"), 5);

    networkTex_ = makeFloatTexture(networks_.width, networks_.height, networks_.texels.data());
    checkGl("uploading the network texture");

    glGenVertexArrays(1, &vao_);
    glGenVertexArrays(1, &emptyVao_);  // core profile: drawing needs a bound VAO even without attributes
    glGenBuffers(1, &objectVbo_);
    glGenBuffers(1, &lightVbo_);
    glGenQueries(2, timerQueries_.data());
    buildStaticGeometry();
    checkGl("uploading the scene geometry");
    setCamera(scene_.camera);
}

GlslPredictor::~GlslPredictor() {
    releaseTargets();
    if (networkTex_) glDeleteTextures(1, &networkTex_);
    const GLuint directTextures[2] = {directBufferTex_, directHostTex_};
    glDeleteTextures(2, directTextures);
    glDeleteBuffers(1, &directBuffer_);
    const GLuint buffers[2] = {objectVbo_, lightVbo_};
    glDeleteBuffers(2, buffers);
    const GLuint vaos[2] = {vao_, emptyVao_};
    glDeleteVertexArrays(2, vaos);
    glDeleteQueries(2, timerQueries_.data());
}

double GlslPredictor::gpuSeconds() const {
    if (!timed_) return std::numeric_limits<double>::quiet_NaN();
    // GL_QUERY_RESULT waits until the passes have run (read() has already waited for them).
    GLuint64 total = 0;
    for (size_t i = gbufferTimed_ ? 0 : 1; i < timerQueries_.size(); ++i) {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(timerQueries_[i], GL_QUERY_RESULT, &ns);
        total += ns;
    }
    checkGl("reading the frame's timer queries");
    return double(total) * 1e-9;
}

void GlslPredictor::buildStaticGeometry() {
    std::vector<float> v;
    for (const Object& o : scene_.objects) {
        const float id = float(o.id);
        if (o.kind == Object::Kind::Sphere) {
            addSphereProxy(v, o.center, o.radius, id);
            continue;
        }
        const bool quad = o.kind == Object::Kind::Quads;
        // Vertex normals (triangles only, as core/scene/accel.cpp interpolates them).
        const bool smooth = o.smooth();
        const size_t nv = size_t(o.verticesPerPrimitive());
        for (size_t p = 0; p < o.primitiveCount(); ++p) {
            Vec3 q[4], vn[3];
            for (size_t k = 0; k < nv; ++k) q[k] = o.positions[o.indices[p * nv + k]];
            if (smooth)
                for (size_t k = 0; k < 3; ++k) vn[k] = o.normals[o.indices[p * nv + k]];
            const Vec3 n = accelNormal(q, quad);
            if (quad)
                addQuad(v, q[0], q[1], q[2], q[3], n, id, kKindPolygon, Vec3(0.f));
            else
                addTriangle(v, q[0], q[1], q[2], n, id, kKindPolygon, Vec3(0.f), smooth ? vn : nullptr);
        }
    }
    objectVertices_ = int(v.size() / kFloatsPerVertex);
    glBindBuffer(GL_ARRAY_BUFFER, objectVbo_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(v.size() * sizeof(float)), v.empty() ? nullptr : v.data(), GL_STATIC_DRAW);
}

void GlslPredictor::uploadLights() {
    std::vector<float> v;
    for (const Light& l : scene_.lights) {
        if (!l.isArea()) continue;  // point lights are invisible
        Vec3 q[4];
        const float kind = l.oneSided ? kKindLightOneSided : kKindLightTwoSided;
        if (l.vertices(q) == 4) addQuad(v, q[0], q[1], q[2], q[3], l.normal(), kLightId, kind, l.radiance);
        else addTriangle(v, q[0], q[1], q[2], l.normal(), kLightId, kind, l.radiance);
    }
    lightVertices_ = int(v.size() / kFloatsPerVertex);
    glBindBuffer(GL_ARRAY_BUFFER, lightVbo_);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(v.size() * sizeof(float)), v.empty() ? nullptr : v.data(), GL_DYNAMIC_DRAW);
    lightsDirty_ = false;
}

void GlslPredictor::setLightPosition(const Vec3& p) {
    scene_.setLightPosition(p);
    lightsDirty_ = true;
}

void GlslPredictor::setCamera(const Camera& camera) {
    GLint dims[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
    const int limit = std::min(maxTextureSize_, std::min(dims[0], dims[1]));
    if (camera.width <= 0 || camera.height <= 0 || camera.width > limit || camera.height > limit)
        throw std::invalid_argument("GLSL predictor: image size " + std::to_string(camera.width) + "x" +
                                    std::to_string(camera.height) + " outside 1.." + std::to_string(limit));
    scene_.camera = camera;
    if (camera.width != targetWidth_ || camera.height != targetHeight_) {
        GlStateGuard guard;
        releaseTargets();
        allocateTargets();
    }
}

void GlslPredictor::releaseTargets() {
    for (auto* texs : {&gbufferTex_, &outputTex_}) {
        for (GLuint& t : *texs)
            if (t) glDeleteTextures(1, &t), t = 0;
    }
    if (depthRb_) glDeleteRenderbuffers(1, &depthRb_), depthRb_ = 0;
    if (gbufferFbo_) glDeleteFramebuffers(1, &gbufferFbo_), gbufferFbo_ = 0;
    if (outputFbo_) glDeleteFramebuffers(1, &outputFbo_), outputFbo_ = 0;
    targetWidth_ = targetHeight_ = 0;
}

void GlslPredictor::allocateTargets() {
    const int w = scene_.camera.width, h = scene_.camera.height;
    const GLenum drawBuffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};

    glGenFramebuffers(1, &gbufferFbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, gbufferFbo_);
    for (int i = 0; i < 3; ++i) {
        gbufferTex_[size_t(i)] = makeFloatTexture(w, h, nullptr);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + i), GL_TEXTURE_2D, gbufferTex_[size_t(i)], 0);
    }
    // A float depth buffer holds the exact ray distance / far that gbuffer.frag writes.
    glGenRenderbuffers(1, &depthRb_);
    glBindRenderbuffer(GL_RENDERBUFFER, depthRb_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthRb_);
    glDrawBuffers(3, drawBuffers);
    checkFramebuffer("G-buffer");

    glGenFramebuffers(1, &outputFbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, outputFbo_);
    static_assert(kTermCount == 3, "one colour attachment per term");
    for (Term t : kTerms) {
        const int i = int(t);
        outputTex_[size_t(i)] = makeFloatTexture(w, h, nullptr);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + i), GL_TEXTURE_2D, outputTex_[size_t(i)], 0);
    }
    glDrawBuffers(kTermCount, drawBuffers);
    checkFramebuffer("prediction");
    checkGl("allocating render targets");
    targetWidth_ = w;
    targetHeight_ = h;
}

void GlslPredictor::render(int rowBegin, int rowEnd) {
    GlStateGuard guard;
    checkGl("state before GlslPredictor::render");
    rowBegin = std::max(0, rowBegin);
    rowEnd = std::min(height(), rowEnd);
    if (rowBegin >= rowEnd) return;
    const bool wholeGBuffer = rowBegin == 0;
    const bool lightMoved = lightsDirty_;
    if (lightMoved) uploadLights();
    if (lightMoved && directMode_ == 1) uploadDirectScene();
    const Camera& cam = scene_.camera;
    const int w = cam.width, h = cam.height;

    // Camera basis exactly as rrf::CameraRays builds it (float arithmetic, same expressions).
    const Vec3 forward = normalize(cam.target - cam.eye);
    const Vec3 rightUnit = normalize(cross(forward, cam.up));
    const Vec3 upUnit = cross(rightUnit, forward);
    const float tanHalf = std::tan(0.5f * cam.fovYDegrees * kPi / 180.f);
    const float tanX = tanHalf * float(w) / float(h);
    const Vec3 right = rightUnit * tanX, up = upUnit * tanHalf;

    // Far distance: beyond every corner of the scene's bounds (which include the lights at their
    // current positions); near: tiny, only clipping uses it.
    const Bounds3 b = scene_.bounds();
    double far = 0.0;
    for (int i = 0; i < 8; ++i) {
        const Vec3 corner(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
        far = std::max(far, double(length(corner - cam.eye)));
    }
    if (!(far > 0.0) || !std::isfinite(far)) far = 1.0;
    far *= 1.01;
    const float nearFar[2] = {float(far * 1e-6), float(far)};

    // ---- pass 1: G-buffer (the first band renders it for the whole frame; it is cheap beside the networks)
    gbufferTimed_ = wholeGBuffer;
    if (wholeGBuffer) {
        glBindFramebuffer(GL_FRAMEBUFFER, gbufferFbo_);
        glViewport(0, 0, w, h);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);  // surfaces are two-sided; the shader flips normals towards the viewer
        glDisable(GL_SCISSOR_TEST);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        const float background[4] = {0.f, 0.f, 0.f, float(GlGBuffer::kBackgroundPixel)};
        const float zero[4] = {0.f, 0.f, 0.f, 0.f};
        const float one = 1.f;
        glClearBufferfv(GL_COLOR, 0, background);
        glClearBufferfv(GL_COLOR, 1, zero);
        glClearBufferfv(GL_COLOR, 2, zero);
        glClearBufferfv(GL_DEPTH, 0, &one);

        // The passes' GPU time (gpuSeconds): one query per pass, so that the CPU's work between them
        // (mode 2's host direct light) is not counted as the GPU's.
        glBeginQuery(GL_TIME_ELAPSED, timerQueries_[0]);
        glUseProgram(gbufferProgram_.id());
        glUniform3f(gbufferProgram_.uniform("uEye"), cam.eye.x, cam.eye.y, cam.eye.z);
        glUniform3f(gbufferProgram_.uniform("uForward"), forward.x, forward.y, forward.z);
        glUniform3f(gbufferProgram_.uniform("uRightUnit"), rightUnit.x, rightUnit.y, rightUnit.z);
        glUniform3f(gbufferProgram_.uniform("uUpUnit"), upUnit.x, upUnit.y, upUnit.z);
        glUniform2f(gbufferProgram_.uniform("uTanHalf"), tanX, tanHalf);
        glUniform2f(gbufferProgram_.uniform("uNearFar"), nearFar[0], nearFar[1]);
        glUniform3f(gbufferProgram_.uniform("uRight"), right.x, right.y, right.z);
        glUniform3f(gbufferProgram_.uniform("uUp"), up.x, up.y, up.z);
        glUniform2f(gbufferProgram_.uniform("uViewport"), float(w), float(h));
        glUniform1f(gbufferProgram_.uniform("uFar"), nearFar[1]);

        glBindVertexArray(vao_);
        for (const auto& [vbo, count] : {std::pair<GLuint, int>{objectVbo_, objectVertices_}, {lightVbo_, lightVertices_}}) {
            if (count == 0) continue;
            glBindBuffer(GL_ARRAY_BUFFER, vbo);
            const GLsizei stride = kFloatsPerVertex * sizeof(float);
            const int sizes[6] = {3, 4, 3, 2, 3, 3};
            size_t offset = 0;
            for (GLuint a = 0; a < 6; ++a) {
                glEnableVertexAttribArray(a);
                glVertexAttribPointer(a, sizes[a], GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset));
                offset += size_t(sizes[a]) * sizeof(float);
            }
            glDrawArrays(GL_TRIANGLES, 0, count);
        }
        glEndQuery(GL_TIME_ELAPSED);
        checkGl("G-buffer pass");
    }

    // ---- pass 2: networks (a band after the first comes without pass 1's state: set its own)
    glBindFramebuffer(GL_FRAMEBUFFER, outputFbo_);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glUseProgram(predictProgram_.id());
    const Vec3 light = scene_.lightPosition();
    glUniform3f(predictProgram_.uniform("uEye"), cam.eye.x, cam.eye.y, cam.eye.z);
    glUniform3f(predictProgram_.uniform("uLight"), light.x, light.y, light.z);
    for (int i = 0; i < 3; ++i) {
        glActiveTexture(GLenum(GL_TEXTURE0 + i));
        glBindTexture(GL_TEXTURE_2D, gbufferTex_[size_t(i)]);
    }
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, networkTex_);
    hostDirectSeconds_ = 0.0;
    if (directMode_ != 0) {
        // Units 4 and 5 are the predictor's own (GlStateGuard restores units 0-3 only).
        if (directMode_ == 2 && wholeGBuffer) {
            const Stopwatch host;
            computeHostDirect();
            hostDirectSeconds_ = host.seconds();
        }
        glUseProgram(predictProgram_.id());
        glBindFramebuffer(GL_FRAMEBUFFER, outputFbo_);
        const uint64_t key = mix64(exactDirectSeed(prediction_.seed) + Rng::kGamma);  // Rng's first step
        const SampleGrid grid(prediction_.directSamples);
        glUniform2ui(predictProgram_.uniform("uDirectKey"), GLuint(key & 0xFFFFFFFFu), GLuint(key >> 32));
        glUniform3i(predictProgram_.uniform("uDirectGrid"), prediction_.directSamples, grid.cols, grid.rows);
        glUniform1f(predictProgram_.uniform("uSceneScale"), scene_.scale());
        glActiveTexture(GL_TEXTURE4);
        glBindTexture(GL_TEXTURE_BUFFER, directBufferTex_);
        glActiveTexture(GL_TEXTURE5);
        glBindTexture(GL_TEXTURE_2D, directHostTex_);
    }
    glUniform1i(predictProgram_.uniform("uDirectMode"), directMode_);
    glBindVertexArray(emptyVao_);
    // The band's rows only: the networks run per fragment, so the scissor is what limits the work.
    glViewport(0, 0, w, h);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, rowBegin, w, rowEnd - rowBegin);
    glBeginQuery(GL_TIME_ELAPSED, timerQueries_[1]);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEndQuery(GL_TIME_ELAPSED);
    glDisable(GL_SCISSOR_TEST);
    timed_ = true;
    checkGl("network pass");
}

std::vector<float> GlslPredictor::readAttachment(unsigned fbo, int attachment) const {
    GlStateGuard guard;
    const int w = targetWidth_, h = targetHeight_;
    std::vector<float> rgba(size_t(w) * size_t(h) * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glReadBuffer(GLenum(GL_COLOR_ATTACHMENT0 + attachment));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, rgba.data());
    checkGl("reading back a render target");
    return rgba;
}

Image GlslPredictor::read(Term term) const {
    const std::vector<float> rgba = readAttachment(outputFbo_, int(term));
    Image img(targetWidth_, targetHeight_);
    for (int y = 0; y < img.height; ++y) {
        const float* row = &rgba[4 * size_t(img.height - 1 - y) * size_t(img.width)];  // GL rows: bottom first
        for (int x = 0; x < img.width; ++x) img.set(x, y, Vec3(row[4 * x], row[4 * x + 1], row[4 * x + 2]));
    }
    return img;
}

GlGBuffer GlslPredictor::readGBuffer() const {
    GlGBuffer g;
    g.width = targetWidth_;
    g.height = targetHeight_;
    const std::vector<float> pos = readAttachment(gbufferFbo_, 0), nrm = readAttachment(gbufferFbo_, 1),
                             emi = readAttachment(gbufferFbo_, 2);
    g.position.resize(3 * g.pixelCount());
    g.normal.resize(3 * g.pixelCount());
    g.objectId.resize(g.pixelCount());
    g.emission = Image(g.width, g.height);
    for (int y = 0; y < g.height; ++y) {
        for (int x = 0; x < g.width; ++x) {
            const size_t src = 4 * (size_t(g.height - 1 - y) * size_t(g.width) + size_t(x));
            const size_t dst = size_t(y) * size_t(g.width) + size_t(x);
            for (int c = 0; c < 3; ++c) {
                g.position[3 * dst + size_t(c)] = pos[src + size_t(c)];
                g.normal[3 * dst + size_t(c)] = nrm[src + size_t(c)];
            }
            g.objectId[dst] = int(std::lround(pos[src + 3]));
            g.emission.set(x, y, Vec3(emi[src], emi[src + 1], emi[src + 2]));
        }
    }
    return g;
}

}  // namespace rrf
