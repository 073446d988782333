#pragma once
/// GLSL prediction (docs/design.md §13): rasterises the scene into a G-buffer and evaluates every object's
/// radiance regression networks in a fragment shader, producing direct, indirect and global images.
///
/// Two passes per frame, both into float framebuffer objects of the camera's size:
///   1. shaders/gbuffer.{vert,frag}: per pixel the hit point of the pixel-centre camera ray (the same
///      ray as rrf::CameraRays with jitter 0.5), the normal facing the viewer, the object id and the
///      emission of lights seen directly.
///   2. shaders/fullscreen.vert + predict.frag: the network inputs (RecordLayout order) are formed
///      from the G-buffer, the light position and the object's BRDF parameters, and the object's
///      networks are evaluated with weights and scalers from the RGBA32F texture of
///      core/predict/network_texture.h (how direct / indirect / global are formed is documented there);
///      networks with an input encoding (nn/encoding.h) encode the scaled inputs first
///      (shaders/encoding.glsl, hash tables in the same texture).
///      Each term t is written to colour output int(t) (core/render/term.h; the host passes the
///      locations to the shader as RRF_TERM_DIRECT/INDIRECT/GLOBAL).
/// The prediction equals NetworkModel::predict on the same inputs to float rounding.
///
/// Direct light: a new predictor takes it from the networks. setPrediction() with "direct": "exact"
/// (the project default, which the live view passes) computes it instead, as core/predict/predictor
/// does: shaders/direct_light.glsl runs core/predict/exact_direct.h's estimator with the same random
/// numbers and shadow rays cast by brute force against the scene's triangles, spheres and area lights
/// (uploaded to a texture buffer on texture unit 4). Scenes above kMaxShaderDirectTriangles triangles
/// or kMaxShaderDirectRectLights area lights (rect or triangle) get the CPU estimator (Embree) on the read-back
/// G-buffer each frame instead, uploaded on unit 5; directLightNote() says so.
///
/// Usage for live relighting (all calls on the thread whose GL 3.3 core context is current):
///
///     GlslPredictor gp(scene, models);      // once per scene + model set: compiles, uploads
///     gp.setLightPosition(p);               // when the user drags the light
///     gp.render();                          // ~ a few ms on a GPU
///     Image img = gp.read(Term::Global);    // or draw gp.texture(term) directly
///
/// render() saves and restores the GL state it touches (framebuffer bindings, viewport, program,
/// vertex array, texture bindings of units 0–3, depth/blend/cull/scissor state), so it can be called
/// in the middle of a GUI frame.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "app/gl/gl_program.h"
#include "core/util/image.h"
#include "core/nn/model_set.h"
#include "core/predict/network_texture.h"
#include "core/predict/prediction_settings.h"
#include "core/render/path_tracer.h"
#include "core/render/term.h"
#include "core/scene/scene.h"

namespace rrf {

/// The G-buffer of the last render(), read back (top row first, like rrf::Image).
struct GlGBuffer {
    int width = 0, height = 0;
    std::vector<float> position;  ///< 3 floats per pixel: hit point (0 where nothing was hit)
    std::vector<float> normal;    ///< 3 floats per pixel: geometric normal facing the viewer
    std::vector<int> objectId;    ///< object id ≥ 0; kLightPixel for a light; kBackgroundPixel
    Image emission;               ///< radiance of lights seen directly, towards the eye

    static constexpr int kBackgroundPixel = -1;
    static constexpr int kLightPixel = -2;
    size_t pixelCount() const { return size_t(width) * size_t(height); }
};

class GlslPredictor {
public:
    /// Uploads the scene's geometry and the packed networks and compiles the shaders from
    /// `shaderDir` (empty: rrf::shaderDir(), the data directory's shaders/, core/util/data_dir.h).
    /// Needs a current OpenGL 3.3 core context with glad loaded (see GlContext).
    /// Throws std::invalid_argument for models that do not fit the scene (packNetworkTexture),
    /// GlError for a shader that does not compile (message names the file) or any GL failure,
    /// std::runtime_error (naming where it looked) when there is no data directory.
    GlslPredictor(const Scene& scene, const ModelSet& models, const std::string& shaderDir = {});
    ~GlslPredictor();
    GlslPredictor(const GlslPredictor&) = delete;
    GlslPredictor& operator=(const GlslPredictor&) = delete;

    /// Moves the scene's movable light (its centre, as Scene::setLightPosition): the network input
    /// and the light's visible quad. Takes effect at the next render().
    void setLightPosition(const Vec3& p);
    Vec3 lightPosition() const { return scene_.lightPosition(); }
    /// Chooses where the direct term comes from ("direct": "network" | "exact", with
    /// "direct_samples" and "seed" as in the CPU predictor). Cheap when nothing changes.
    void setPrediction(const PredictionSettings& prediction);
    /// Empty, or one line saying that exact direct light is computed on the CPU and why.
    const std::string& directLightNote() const { return directNote_; }
    /// Brute-force shadow rays in the shader cost triangles × samples per pixel; above these sizes
    /// the CPU computes exact direct light.
    static constexpr int kMaxShaderDirectTriangles = 2048;
    static constexpr int kMaxShaderDirectRectLights = 8;  ///< shaders/direct_light.glsl's arrays

    /// Replaces the camera; the output size is camera.width × camera.height (textures are
    /// reallocated when it changes). Throws std::invalid_argument for a non-positive size or one
    /// above GL_MAX_TEXTURE_SIZE / GL_MAX_VIEWPORT_DIMS.
    void setCamera(const Camera& camera);
    const Camera& camera() const { return scene_.camera; }

    /// Renders the G-buffer and the three predictions. Asynchronous like any GL call: read() or
    /// glFinish() waits for the result. Throws GlError on a GL error.
    void render() { render(0, height()); }
    /// Renders the predictions of the rows [rowBegin, rowEnd) only (GL rows, bottom first), the
    /// rest of the outputs kept: a full frame in bands over several UI frames, so that one frame
    /// never waits for a whole prediction on a slow driver (issue 29: seconds under llvmpipe).
    /// A band starting at row 0 also renders the G-buffer (and, in mode 2, the CPU's direct light);
    /// later bands reuse them, so the light, camera and settings must not change within a frame.
    void render(int rowBegin, int rowEnd);

    /// The GPU time of the last render()'s G-buffer (when it rendered one) and network passes (GL
    /// timer queries), in seconds; waits for the passes to finish. NaN before the first render(). Excludes read-back
    /// and CPU work (uploads, mode 2's host direct light); on a software driver (llvmpipe) the
    /// "GPU" is the CPU's rasteriser threads.
    double gpuSeconds() const;
    /// What the last render() cost as a frame: gpuSeconds() plus, in mode 2, the CPU's exact direct
    /// light computed for it (the part of the frame the GPU does not do). NaN before the first render().
    double frameSeconds() const { return gpuSeconds() + hostDirectSeconds_; }

    /// The prediction of the last render() as an image (top row first).
    Image read(Term term) const;
    /// The G-buffer of the last render().
    GlGBuffer readGBuffer() const;

    /// RGBA32F texture holding a term of the last render(), GL convention (bottom row first); alpha
    /// is 1 where an object or a light was hit, 0 on background. Owned by the predictor.
    unsigned texture(Term term) const { return outputTex_[size_t(term)]; }
    int width() const { return scene_.camera.width; }
    int height() const { return scene_.camera.height; }
    /// The packed networks (which terms the models provide, network count, texture size).
    const NetworkTexture& networks() const { return networks_; }

private:
    void buildStaticGeometry();
    void uploadLights();
    void uploadDirectScene();
    void computeHostDirect();
    void allocateTargets();
    void releaseTargets();
    std::vector<float> readAttachment(unsigned fbo, int attachment) const;

    Scene scene_;
    NetworkTexture networks_;
    GlProgram gbufferProgram_, predictProgram_;
    unsigned vao_ = 0, objectVbo_ = 0, lightVbo_ = 0, emptyVao_ = 0;
    int objectVertices_ = 0, lightVertices_ = 0;
    bool lightsDirty_ = true;
    unsigned networkTex_ = 0;
    unsigned gbufferFbo_ = 0, depthRb_ = 0, outputFbo_ = 0;
    std::array<unsigned, 3> gbufferTex_{};
    std::array<unsigned, kTermCount> outputTex_{};  ///< index int(Term), attachment int(Term)
    int targetWidth_ = 0, targetHeight_ = 0;
    int maxTextureSize_ = 0;
    // Direct light (setPrediction): mode 0 networks, 1 shader, 2 CPU-computed and uploaded.
    PredictionSettings prediction_;
    int directMode_ = 0;
    std::string directNote_;
    unsigned directBuffer_ = 0, directBufferTex_ = 0, directHostTex_ = 0;
    std::unique_ptr<Accel> hostAccel_;         ///< mode 2 only
    std::unique_ptr<PathTracer> hostTracer_;   ///< mode 2 only
    std::array<unsigned, 2> timerQueries_{};   ///< GL_TIME_ELAPSED of the G-buffer and network passes
    bool timed_ = false;                       ///< a render() has issued the queries
    bool gbufferTimed_ = false;                ///< the last render() issued the G-buffer's query
    double hostDirectSeconds_ = 0.0;           ///< the last render()'s computeHostDirect (mode 2), else 0
};

}  // namespace rrf
