// `rrf render`: progressive ground-truth render of a project or scene file.
#include <cstdio>
#include <string>

#include "app/cli/cli_common.h"
#include "app/cli/commands.h"
#include "core/scene/accel.h"
#include "core/util/error.h"
#include "core/render/render_outputs.h"
#include "core/render/renderer.h"
#include "core/project/project.h"

namespace rrf::cli {

namespace {
struct RenderArgs {
    std::string input, out, mode, format = "exr", lightPos;
    int spp = -1, width = -1, height = -1, threads = 0;
    long long seed = -1;
    float exposure = 0.f;
    bool exposureSet = false;
};

int runRender(const RenderArgs& a) {
    Project project = loadProjectOrScene(a.input);
    Scene& scene = project.scene;
    RenderSettings settings = project.render;
    if (a.width > 0) settings.width = a.width;
    if (a.height > 0) settings.height = a.height;
    if (a.spp > 0) settings.spp = a.spp;
    if (a.seed >= 0) settings.seed = uint64_t(a.seed);
    if (!a.mode.empty()) settings.estimator = a.mode == "naive" ? Estimator::Naive : Estimator::NEE;
    // Enough passes for a live progress line, few enough that pass overhead stays negligible.
    const RenderOptions o = renderOptionsFor(scene, settings, 16);
    const ImageFormat format = imageFormatFromName(a.format);
    const float exposure = a.exposureSet ? a.exposure : project.render.exposure;
    if (!a.lightPos.empty()) {
        if (scene.lights.empty()) throw InputError(a.input, "/lights", "--light-pos given but the scene has no light");
        scene.setLightPosition(parseVec3(a.lightPos, "--light-pos"));
    }
    auto threads = limitThreads(a.threads);

    Accel accel(scene);
    Renderer renderer(scene, accel, o);
    std::printf("rrf render: %s, %dx%d, %d spp, %s estimator, seed %llu\n", a.input.c_str(), o.width, o.height, o.spp,
                o.estimator == Estimator::NEE ? "NEE" : "naive", (unsigned long long)o.seed);
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
    const RenderOutputs out = writeRenderOutputs(a.out, scene, renderer, snap, format, exposure);
    std::printf("%s %d/%d spp in %.2f s: %ssamples/s, %srays/s (%llu rays + %llu shadow rays)\n",
                renderer.cancelled() ? "cancelled after" : "rendered", snap.sppCompleted, o.spp, st.seconds,
                humanCount(st.samplesPerSecond()).c_str(), humanCount(st.raysPerSecond()).c_str(),
                (unsigned long long)st.rays, (unsigned long long)st.shadowRays);
    std::printf("NaN/Inf samples dropped: %llu\n", (unsigned long long)st.nonFinite);
    std::printf("relative standard error of the image mean: %.3g\n", snap.relativeError);
    for (const std::string& p : out.images) std::printf("wrote %s\n", p.c_str());
    std::printf("wrote %s\n", out.metadata.c_str());
    return renderer.cancelled() ? 130 : 0;
}
}  // namespace

void addRenderCommand(CLI::App& app, int& exitCode) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render the ground truth (global, direct, indirect images)");
    cmd->add_option("input", args->input, "project or scene JSON file")->required();
    cmd->add_option("--out", args->out, "output directory")->required();
    cmd->add_option("--spp", args->spp, "samples per pixel (default: the project's)")->check(CLI::PositiveNumber);
    cmd->add_option("--width", args->width, "image width")->check(CLI::Range(1, 16384));
    cmd->add_option("--height", args->height, "image height")->check(CLI::Range(1, 16384));
    cmd->add_option("--mode", args->mode, "estimator")->check(CLI::IsMember({"nee", "naive"}));
    cmd->add_option("--light-pos", args->lightPos, "move the light's centre to x,y,z");
    cmd->add_option("--threads", args->threads, "worker threads (0 = all cores)")->check(CLI::NonNegativeNumber);
    cmd->add_option("--seed", args->seed, "random seed")->check(CLI::NonNegativeNumber);
    cmd->add_option("--format", args->format, "image format")->check(CLI::IsMember({"exr", "pfm", "png"}));
    cmd->add_option("--exposure", args->exposure, "exposure in stops for PNG output")
        ->each([args](const std::string&) { args->exposureSet = true; });
    cmd->callback([args, &exitCode] { exitCode = runRender(*args); });
}

}  // namespace rrf::cli
