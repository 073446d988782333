#include "core/render/render_outputs.h"

#include <filesystem>
#include <stdexcept>

#include "core/render/term.h"
#include "core/util/atomic_file.h"
#include "core/util/text_format.h"

namespace rrf {

namespace fs = std::filesystem;

void makeDirectories(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) throw std::runtime_error(dir + ": cannot create output directory" + (ec ? ": " + ec.message() : ""));
}

nlohmann::json renderMetadata(const Scene& scene, const Renderer& renderer, const RenderSnapshot& snapshot) {
    const RenderOptions& o = renderer.options();
    const RenderStats st = renderer.stats();
    const Vec3 lp = scene.lightPosition();
    return {
        {"scene", scene.sourcePath},
        {"scene_hash", hexString(scene.contentHash())},
        {"width", o.width},
        {"height", o.height},
        {"spp_requested", o.spp},
        {"spp_completed", snapshot.sppCompleted},
        {"complete", snapshot.sppCompleted >= o.spp},
        {"estimator", o.estimator == Estimator::NEE ? "nee" : "naive"},
        {"seed", o.seed},
        {"max_depth", o.maxDepth},
        {"light_position", {lp.x, lp.y, lp.z}},
        {"effects", renderer.tracer().effects().toJson()},
        {"seconds", st.seconds},
        {"samples", st.samples},
        {"rays", st.rays},
        {"shadow_rays", st.shadowRays},
        {"samples_per_second", st.samplesPerSecond()},
        {"rays_per_second", st.raysPerSecond()},
        {"non_finite_samples_dropped", st.nonFinite},
        {"relative_error_of_mean", snapshot.relativeError},
        {"mean_global", {snapshot.global.mean().x, snapshot.global.mean().y, snapshot.global.mean().z}},
    };
}

nlohmann::json writeVarianceImages(const std::string& dir, const std::array<const Image*, kTermCount>& variances,
                                   ImageFormat format, std::vector<std::string>& written) {
    makeDirectories(dir);
    // A variance is a float per channel; an 8-bit format would round it away.
    const ImageFormat floatFormat = format == ImageFormat::PFM ? ImageFormat::PFM : ImageFormat::EXR;
    nlohmann::json files = nlohmann::json::object();
    for (Term t : kTerms) {
        const std::string name = std::string("variance_") + termName(t) + "." + imageFormatName(floatFormat);
        const std::string path = (fs::path(dir) / name).string();
        writeImage(path, *variances[size_t(t)], floatFormat);
        written.push_back(path);
        files[termName(t)] = name;
    }
    return files;
}

RenderOutputs writeRenderOutputs(const std::string& dir, const Scene& scene, const Renderer& renderer,
                                 const RenderSnapshot& snapshot, ImageFormat format, float exposureStops) {
    makeDirectories(dir);
    RenderOutputs out;
    const std::string ext = imageFormatName(format);
    // File names are the terms' names, which loadReference (core/eval) reads back.
    const std::pair<const char*, const Image*> images[] = {{termName(Term::Global), &snapshot.global},
                                                           {termName(Term::Direct), &snapshot.direct},
                                                           {termName(Term::Indirect), &snapshot.indirect}};
    for (const auto& [name, image] : images) {
        const std::string path = (fs::path(dir) / (std::string(name) + "." + ext)).string();
        writeImage(path, *image, format, exposureStops);
        out.images.push_back(path);
    }
    nlohmann::json meta = renderMetadata(scene, renderer, snapshot);
    // With fewer than 2 samples per pixel the variance cannot be estimated (the snapshot holds 0):
    // no files, so a reader sees "unknown" instead of a floor of 0.
    if (snapshot.varianceKnown())
        meta["variance_images"] = writeVarianceImages(
        dir, {&snapshot.varianceOf(Term::Direct), &snapshot.varianceOf(Term::Indirect), &snapshot.varianceOf(Term::Global)},
        format, out.variances);
    out.metadata = (fs::path(dir) / "render.json").string();
    writeFileAtomically(out.metadata, meta.dump(2) + "\n");
    return out;
}

}  // namespace rrf
