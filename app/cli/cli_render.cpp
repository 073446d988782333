// `rrf render`: progressive ground-truth render of a project or scene file.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "app/cli/cli_common.h"
#include "app/cli/cli_flags.h"
#include "app/cli/commands.h"
#include "core/project/project_file.h"
#include "core/scene/accel.h"
#include "core/util/error.h"
#include "core/render/render_outputs.h"
#include "core/render/renderer.h"
#include "core/project/project.h"
#include "core/pipeline/run_recording.h"
#include "app/cli/cli_record.h"

namespace rrf::cli {

namespace {
struct RenderArgs {
    std::string input, out, format = "exr";
    std::optional<Vec3> lightPos;
    int threads = 0;
    bool record = false;
    SettingFlags<RenderSettings> render;  ///< --spp, --width, --height, --estimator, --seed, --exposure
};

int runRender(RenderArgs a) {
    // With --record the outputs go where the workbench puts a run's files, unless --out says otherwise.
    if (a.record && a.format != "exr")
        throw InputError("command line", "--format",
                         "a recorded run stores EXR images, as the workbench does (it re-opens and compares those); got " + a.format);
    std::optional<Run> run = beginRecording(a.record, a.input, "render", a.out, "");
    Project project = loadProjectOrScene(a.input);
    refuseOverwritingInputs(a.out, projectInputs(project));
    Scene& scene = project.scene;
    const RenderSettings settings = a.render.applied(project.render);
    // Enough passes for a live progress line, few enough that pass overhead stays negligible.
    const RenderOptions o = renderOptionsFor(scene, settings, 16);
    const ImageFormat format = imageFormatFromName(a.format);
    if (a.lightPos) {
        if (scene.lights.empty()) throw InputError(a.input, "/lights", "--light-pos given but the scene has no light");
        checkLightPosition(scene, *a.lightPos);
        scene.setLightPosition(*a.lightPos);
    }
    auto threads = limitThreads(a.threads);

    Accel accel(scene);
    Renderer renderer(scene, accel, o);
    std::printf("rrf render: %s, %dx%d, %d spp, %s estimator, seed %llu\n", a.input.c_str(), o.width, o.height, o.spp,
                estimatorName(renderer.estimatorChoice().estimator), (unsigned long long)o.seed);
    // Which path loop runs: the SIMD lanes (diffuse NEE on a CPU that has them) or the portable one.
    // The image is the same either way.
    if (renderer.estimatorChoice().estimator != Estimator::BDPT)
        std::printf("path loop: %s\n", path_lanes::isaName(renderer.tracer().lanes()));
    std::printf("effects:\n");
    for (const std::string& line : renderer.tracer().effects().describe()) std::printf("  - %s\n", line.c_str());
    for (const std::string& w : scene.warnings) std::printf("warning: %s\n", w.c_str());
    std::fflush(stdout);

    runWithProgress(
        "render", [&] { renderer.run(); },
        [&] {
            const RenderStats s = renderer.stats();
            return std::make_pair(renderer.progress(), humanCount(s.samplesPerSecond()) + "samples/s");
        },
        [&] { renderer.cancel(); });

    const RenderSnapshot snap = renderer.snapshot();
    const RenderStats st = renderer.stats();
    if (snap.samples == 0 && snap.nonFinite > 0)
        throw InputError(a.input, "",
                         "every sample was NaN or infinite (" + std::to_string(snap.nonFinite) +
                             " dropped, no image written): the scene's radiance must stay finite in single precision "
                             "(check light radiance/intensity, light size and material values)");
    const RenderOutputs out = writeRenderOutputs(a.out, scene, renderer, snap, format, settings.exposure);
    std::printf("%s %d/%d spp in %.2f s: %ssamples/s, %srays/s (%llu rays + %llu shadow rays)\n",
                renderer.cancelled() ? "cancelled after" : "rendered", snap.sppCompleted, o.spp, st.seconds,
                humanCount(st.samplesPerSecond()).c_str(), humanCount(st.raysPerSecond()).c_str(),
                (unsigned long long)st.rays, (unsigned long long)st.shadowRays);
    std::printf("NaN/Inf samples dropped: %llu\n", (unsigned long long)st.nonFinite);
    std::printf("relative standard error of the image mean: %.3g\n", snap.relativeError);
    for (const std::string& p : out.images) std::printf("wrote %s\n", p.c_str());
    for (const std::string& p : out.variances) std::printf("wrote %s (per-pixel variance of the mean)\n", p.c_str());
    std::printf("wrote %s\n", out.metadata.c_str());
    if (run) {
        setRenderRun(*run, projectDirectory(project), settings, o.spp, scene, project.overrides, snap, st, out);
        finishRecording(a.input, *run);
    }
    return renderer.cancelled() ? 130 : 0;
}
}  // namespace

void addRenderCommand(CLI::App& app, int& exitCode) {
    auto a = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render the ground truth (global, direct, indirect images)");
    cmd->add_option("input", a->input, "project or scene JSON file")->required();
    cmd->add_option("--out", a->out, "output directory (required unless --record)");
    SettingFlags<RenderSettings>& r = a->render;
    r.add<int>(cmd, "--spp", "samples per pixel (default: the project's)", [](RenderSettings& s, const int& n) { s.spp = n; })
        ->check(positive());
    r.add<int>(cmd, "--width", "image width", [](RenderSettings& s, const int& n) { s.width = n; })->check(CLI::Range(1, kMaxImageSide));
    r.add<int>(cmd, "--height", "image height", [](RenderSettings& s, const int& n) { s.height = n; })->check(CLI::Range(1, kMaxImageSide));
    r.add<std::string>(cmd, "--estimator", "light-transport estimator (auto: bdpt where the scene has caustics, else nee)",
                       [](RenderSettings& s, const std::string& m) { s.estimator = *parseEstimator(m); })
        ->check(CLI::IsMember(estimatorChoices()));
    addVec3Option(cmd, "--light-pos", a->lightPos, "move the light's centre to x,y,z");
    cmd->add_option("--threads", a->threads, "worker threads (0 = all cores)")->check(nonNegative());
    r.add<long long>(cmd, "--seed", "random seed", [](RenderSettings& s, const long long& seed) { s.seed = uint64_t(seed); })
        ->check(nonNegative());
    cmd->add_option("--format", a->format, "image format")->check(CLI::IsMember({"exr", "pfm", "png"}));
    r.add<float>(cmd, "--exposure", "exposure in stops for PNG output (default: the project's)",
                 [](RenderSettings& s, const float& stops) { s.exposure = stops; })
        ->check(finiteNumber());
    cmd->add_flag("--record", a->record, recordHelp("a render run"));
    cmd->callback([a, &exitCode] { exitCode = runRender(*a); });
}

}  // namespace rrf::cli
