// bench_glsl: milliseconds per frame of the GLSL predictor (G-buffer + network pass), the number the
// GUI's live relighting costs, on whatever OpenGL driver the context gets (Mesa llvmpipe under Xvfb,
// or a GPU).
//
//   xvfb-run -a -s "-screen 0 1280x1024x24" bench_glsl [--size 256] [--frames 50]
//                                                       [--project P --models DIR]
//                                                       [--encoding NAME|JSON] [--encodings-only]
//
// Without --models: the Cornell box with untrained networks of several sizes (weights from
// initialParams; speed does not depend on their values), one row per (hidden sizes, targets),
// then encoded networks (issue 16, nn/encoding.h) beside the raw network of the same hidden sizes:
// every named encoding (nn/encoding_presets.h), or the one --encoding names (a name or an
// "encoding" JSON array).
// With --models: the trained model directory of the project (`rrf train` output), plus the largest
// relative difference between the GLSL prediction and NetworkModel::predict on the G-buffer's inputs.
//
// Every frame moves the light (as dragging it in the GUI does), renders, and waits with glFinish; the
// time is the mean over the frames after two warm-up frames; "GPU ms" is the same frames' GL timer
// queries (the passes alone, the figure the workbench records per run). "read back" adds glReadPixels of the
// global term into an rrf::Image, which the GUI needs if it tone-maps on the CPU.
// The last rows add exact direct light in the shader (prediction "direct": "exact",
// shaders/direct_light.glsl) at 16 and 64 light samples per pixel, the project default's cost.
// Under llvmpipe these are CPU times of a software rasteriser, not GPU times.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <glad/gl.h>

#include "app/gl/gl_context.h"
#include "bench/bench_args.h"
#include "app/gl/glsl_predictor.h"
#include "core/project/project.h"
#include "core/data/record_layout.h"
#include "core/nn/encoding.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/encoding_settings_json.h"
#include "core/project/project_file.h"

using namespace rrf;

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

NetworkModel untrained(const Scene& scene, int object, const std::string& target, const std::vector<int>& hidden,
                       const NetworkEncodingSettings& encoding = {}) {
    NetworkModel m;
    const int inputs = RecordLayout::forScene(scene).inputCount();
    m.encoding = networkEncoding(encoding, inputs);
    m.encodingParams = m.encoding.initialParams(1, uint64_t(object));
    m.arch.inputs = m.encoding.isIdentity() ? inputs : m.encoding.outputs();
    m.arch.hidden = hidden;
    m.arch.outputs = target == "joint" ? 6 : 3;
    m.params = initialParams(m.arch, 1, uint64_t(object));
    m.inputScaler = MinMaxScaler::identity(inputs);
    m.outputScaler = MinMaxScaler::identity(m.arch.outputs);
    m.objectId = object;
    m.target = target;
    return m;
}

ModelSet untrainedSet(const Scene& scene, const std::vector<int>& hidden, const std::vector<std::string>& targets,
                      const NetworkEncodingSettings& encoding = {}) {
    ModelSet set;
    for (const Object& o : scene.objects) {
        ObjectNetworks on;
        on.objectId = o.id;
        on.name = o.name;
        for (const std::string& t : targets) on.byTarget[t] = untrained(scene, o.id, t, hidden, encoding);
        set.objects.push_back(std::move(on));
    }
    return set;
}

struct Timing {
    double renderMs = 0, readMs = 0;
    double gpuMs = 0;  ///< the passes' GPU time (timer queries), what the workbench records per run
};

Timing timeFrames(GlslPredictor& gp, const Scene& scene, int frames) {
    const Bounds3 r = scene.lightRegion.empty() ? Bounds3() : scene.lightRegion;
    auto lightAt = [&](int f) {
        if (scene.lightRegion.empty()) return scene.lightPosition();
        const float s = 0.5f + 0.5f * std::sin(0.37f * float(f)), t = 0.5f + 0.5f * std::cos(0.23f * float(f));
        return Vec3(r.lo.x + s * (r.hi.x - r.lo.x), r.lo.y + t * (r.hi.y - r.lo.y), r.lo.z + (1 - s) * (r.hi.z - r.lo.z));
    };
    for (int f = 0; f < 2; ++f) {  // warm-up: shader compilation in the driver happens at first draw
        gp.setLightPosition(lightAt(f));
        gp.render();
        glFinish();
    }
    Timing t;
    double t0 = now(), gpu = 0;
    for (int f = 0; f < frames; ++f) {
        gp.setLightPosition(lightAt(f));
        gp.render();
        glFinish();
        gpu += gp.gpuSeconds();
    }
    t.renderMs = (now() - t0) * 1e3 / frames;
    t.gpuMs = gpu * 1e3 / frames;
    t0 = now();
    for (int f = 0; f < frames; ++f) {
        gp.setLightPosition(lightAt(f));
        gp.render();
        const Image img = gp.read(Term::Global);
        if (img.data.empty()) std::printf(" ");
    }
    t.readMs = (now() - t0) * 1e3 / frames;
    return t;
}

/// Largest relative difference |gl − cpu| / max(|cpu|, 1e-2) of the global term over covered pixels,
/// and the same measure for the CPU's float prediction against its double one (the float noise floor
/// of these networks: no float implementation can agree with another much better than that).
std::pair<double, double> maxRelativeVsCpu(const GlslPredictor& gp, const Scene& scene, const ModelSet& set) {
    const GlGBuffer g = gp.readGBuffer();
    const Image gl = gp.read(Term::Global);
    const RecordLayout layout = RecordLayout::forScene(scene);
    double worst = 0, floatFloor = 0;
    for (const ObjectNetworks& on : set.objects) {
        std::vector<size_t> px;
        for (size_t i = 0; i < g.pixelCount(); ++i)
            if (g.objectId[i] == on.objectId) px.push_back(i);
        if (px.empty()) continue;
        float brdf[8] = {};
        layout.brdfParameters(scene.materials[size_t(scene.objects[size_t(on.objectId)].material)], brdf);
        MatX<float> raw(layout.inputCount(), Eigen::Index(px.size()));
        for (size_t k = 0; k < px.size(); ++k) {
            const size_t i = px[k];
            const Vec3 p(g.position[3 * i], g.position[3 * i + 1], g.position[3 * i + 2]);
            const Vec3 n(g.normal[3 * i], g.normal[3 * i + 1], g.normal[3 * i + 2]);
            const Vec3 f[4] = {p, normalize(scene.camera.eye - p), gp.lightPosition(), n};
            for (int j = 0; j < 12; ++j) raw(j, Eigen::Index(k)) = f[j / 3][j % 3];
            for (int j = 12; j < layout.inputCount(); ++j) raw(j, Eigen::Index(k)) = brdf[j - 12];
        }
        MatX<float> d = MatX<float>::Zero(3, raw.cols()), ind = d, glob;
        if (on.has("joint")) {
            const MatX<float> y = on.byTarget.at("joint").predict(raw);
            d = y.topRows(3);
            ind = y.bottomRows(3);
        }
        if (on.has("direct")) d = on.byTarget.at("direct").predict(raw);
        if (on.has("indirect")) ind = on.byTarget.at("indirect").predict(raw);
        const bool both = (on.has("direct") || on.has("joint")) && (on.has("indirect") || on.has("joint"));
        glob = !both && on.has("global") ? on.byTarget.at("global").predict(raw) : MatX<float>(d + ind);
        const MatX<double> rawD = raw.cast<double>();
        MatX<double> dd = MatX<double>::Zero(3, raw.cols()), indD = dd, globD;
        if (on.has("joint")) {
            const MatX<double> y = on.byTarget.at("joint").predictDouble(rawD);
            dd = y.topRows(3);
            indD = y.bottomRows(3);
        }
        if (on.has("direct")) dd = on.byTarget.at("direct").predictDouble(rawD);
        if (on.has("indirect")) indD = on.byTarget.at("indirect").predictDouble(rawD);
        globD = !both && on.has("global") ? on.byTarget.at("global").predictDouble(rawD) : MatX<double>(dd + indD);
        for (size_t k = 0; k < px.size(); ++k) {
            const int x = int(px[k] % size_t(g.width)), y = int(px[k] / size_t(g.width));
            for (int c = 0; c < 3; ++c) {
                const double cpu = glob(c, Eigen::Index(k));
                worst = std::max(worst, std::fabs(double(gl.at(x, y)[c]) - cpu) / std::max(std::fabs(cpu), 1e-2));
                const double exact = globD(c, Eigen::Index(k));
                floatFloor = std::max(floatFloor, std::fabs(cpu - exact) / std::max(std::fabs(exact), 1e-2));
            }
        }
    }
    return {worst, floatFloor};
}

std::string join(const std::vector<int>& v) {
    std::string s;
    for (int x : v) s += (s.empty() ? "" : "-") + std::to_string(x);
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    int size = 256, frames = 50;
    std::string project, models, encodingText;
    bool encodingsOnly = false;
    CLI::App app{"Milliseconds per frame of the GLSL predictor (G-buffer + networks)", "bench_glsl"};
    app.add_option("--size", size, "image width and height")->check(CLI::Range(1, 16384))->capture_default_str();
    app.add_option("--frames", frames, "frames to average over (after 2 warm-up frames)")
        ->check(bench::kPositive)
        ->capture_default_str();
    app.add_option("--project", project, bench::kProjectHelp)->type_name("FILE");
    app.add_option("--models", models, "trained model directory of the project (default: untrained networks)")
        ->type_name("DIR");
    app.add_option("--encoding", encodingText,
                   "the encoding timed instead of every named one: a name (" + encodingPresetNames() +
                       ") or an \"encoding\" JSON array (nn/encoding.h)")
        ->type_name("NAME|JSON");
    app.add_flag("--encodings-only", encodingsOnly, "only the encoded rows and their raw counterparts");
    bench::parseArgs(app, argc, argv);
    project = bench::projectOrDefault(project, "bench_glsl");
    try {
        GlContext ctx;
        Scene scene = loadProjectOrScene(project).scene;
        scene.camera.width = scene.camera.height = size;
        std::printf("bench_glsl: %s | %s\n%s, %dx%d, mean of %d frames (light moved every frame)\n\n",
                    ctx.renderer().c_str(), ctx.version().c_str(), project.c_str(), size, size, frames);
        std::printf("%-44s %8s %12s %10s %16s%s\n", "networks", "weights", "ms/frame", "GPU ms", "+read back ms", models.empty() ? "" : "  max rel GLSL-CPU (CPU float-double)");
        auto row = [&](const std::string& name, const ModelSet& set, int directSamples = 0) {
            GlslPredictor gp(scene, set);
            if (directSamples > 0) {
                PredictionSettings exact;
                exact.directSamples = directSamples;
                gp.setPrediction(exact);
            }
            size_t weights = 0;  // MLP weights and encoding parameters (hash tables)
            for (const ObjectNetworks& on : set.objects)
                for (const auto& kv : on.byTarget)
                    for (const NetworkModel& leaf : kv.second.leaves)
                        weights += size_t(leaf.arch.numParams()) + size_t(leaf.encodingParams.size());
            const Timing t = timeFrames(gp, scene, frames);
            std::printf("%-44s %8zu %12.2f %10.2f %16.2f", name.c_str(), weights, t.renderMs, t.gpuMs, t.readMs);
            if (!models.empty() && directSamples == 0) {
                const auto [vsCpu, floor] = maxRelativeVsCpu(gp, scene, set);
                std::printf("  %.3g (%.3g)", vsCpu, floor);
            }
            std::printf("\n");
        };
        if (!models.empty()) {
            const ModelSet set = loadModelSet(models, scene.contentHash());
            row("trained (" + models + ")", set);
            for (int n : {16, 64}) row("trained, exact direct " + std::to_string(n), set, n);
        } else {
            if (!encodingsOnly) {
                row("none (G-buffer only)", ModelSet{});
                for (const auto& hidden : std::vector<std::vector<int>>{{20, 10}, {32, 16}, {64, 32}}) {
                    row(join(hidden) + " tanh, global", untrainedSet(scene, hidden, {"global"}));
                    row(join(hidden) + " tanh, direct+indirect", untrainedSet(scene, hidden, {"direct", "indirect"}));
                }
                for (int n : {16, 64})
                    row("20-10 indirect, exact direct " + std::to_string(n), untrainedSet(scene, {20, 10}, {"indirect"}), n);
            }
            // Encoded networks, each beside the raw network of the same hidden sizes (global target).
            std::vector<std::pair<std::string, NetworkEncodingSettings>> encodings;
            if (encodingText.empty()) {
                for (const EncodingPreset& e : encodingPresets())
                    if (!e.settings.empty()) encodings.emplace_back(e.name, e.settings);
            } else if (!encodingText.empty() && encodingText.front() == '[') {
                encodings.emplace_back("--encoding", encodingSettingsFromJson(nlohmann::json::parse(encodingText), "--encoding"));
            } else {
                encodings.emplace_back(encodingText, encodingPresetSettings(encodingText, "--encoding"));
            }
            for (const auto& hidden : std::vector<std::vector<int>>{{20, 10}, {64, 64}}) {
                row(join(hidden) + " tanh, global, raw inputs", untrainedSet(scene, hidden, {"global"}));
                for (const auto& [name, json] : encodings)
                    row(join(hidden) + " tanh, global, " + name, untrainedSet(scene, hidden, {"global"}, json));
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_glsl: %s\n", e.what());
        return 1;
    }
    return 0;
}
