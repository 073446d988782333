#include "core/render/render_outputs.h"

#include <filesystem>
#include <optional>
#include <stdexcept>

#include "core/render/render_metadata_json.h"
#include "core/render/term.h"
#include "core/util/atomic_file.h"
#include "core/util/directory_replace.h"
#include "core/util/text_format.h"

namespace rrf {

namespace fs = std::filesystem;

void makeDirectories(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) throw std::runtime_error(dir + ": cannot create output directory" + (ec ? ": " + ec.message() : ""));
}

VarianceImageNames writeVarianceImages(const std::string& dir, const std::array<const Image*, kTermCount>& variances,
                                       ImageFormat format, std::vector<std::string>& written) {
    makeDirectories(dir);
    // A variance is a float per channel; an 8-bit format would round it away.
    const ImageFormat floatFormat = format == ImageFormat::PFM ? ImageFormat::PFM : ImageFormat::EXR;
    VarianceImageNames files;
    for (Term t : kTerms) {
        const std::string name = std::string("variance_") + termName(t) + "." + imageFormatName(floatFormat);
        const std::string path = (fs::path(dir) / name).string();
        writeImage(path, *variances[size_t(t)], floatFormat);
        written.push_back(path);
        files[termName(t)] = name;
    }
    return files;
}

bool isRenderOutputEntry(const std::string& name) {
    if (name == "render.json") return true;
    const std::string stem = fs::path(name).stem().string();
    for (Term t : kTerms)
        if (stem == termName(t) || stem == std::string("variance_") + termName(t)) return true;
    return false;
}

RenderOutputs writeRenderOutputs(const std::string& dir, const Scene& scene, const Renderer& renderer,
                                 const RenderSnapshot& snapshot, ImageFormat format, float exposureStops,
                                 const std::vector<std::pair<ImageFormat, float>>& moreFormats,
                                 const RenderStats* stats) {
    RenderOutputs out;
    std::vector<std::pair<ImageFormat, float>> formats = {{format, exposureStops}};
    formats.insert(formats.end(), moreFormats.begin(), moreFormats.end());
    // The images, variances and render.json go into a new directory that replaces the old set in
    // one rename (core/util/directory_replace.h): never a new global beside an old direct.
    replaceDirectory(dir, isRenderOutputEntry, [&](const std::string& staging) {
        // File names are the terms' names, which loadReference (core/eval) reads back.
        const std::pair<const char*, const Image*> images[] = {{termName(Term::Global), &snapshot.global},
                                                               {termName(Term::Direct), &snapshot.direct},
                                                               {termName(Term::Indirect), &snapshot.indirect}};
        for (const auto& [f, exposure] : formats)
            for (const auto& [name, image] : images) {
                const std::string file = std::string(name) + "." + imageFormatName(f);
                writeImage((fs::path(staging) / file).string(), *image, f, exposure);
                out.images.push_back((fs::path(dir) / file).string());
            }
        // With fewer than 2 samples per pixel the variance cannot be estimated (the snapshot holds 0):
        // no files, so a reader sees "unknown" instead of a floor of 0.
        std::optional<VarianceImageNames> varianceImages;
        if (snapshot.varianceKnown()) {
            std::vector<std::string> written;
            varianceImages = writeVarianceImages(
                staging, {&snapshot.varianceOf(Term::Direct), &snapshot.varianceOf(Term::Indirect), &snapshot.varianceOf(Term::Global)},
                format, written);
            for (const std::string& w : written) out.variances.push_back((fs::path(dir) / fs::path(w).filename()).string());
        }
        writeFileAtomically((fs::path(staging) / "render.json").string(),
                            renderMetadataText(scene, renderer, snapshot, stats, varianceImages ? &*varianceImages : nullptr));
    });
    out.metadata = (fs::path(dir) / "render.json").string();
    return out;
}

}  // namespace rrf
