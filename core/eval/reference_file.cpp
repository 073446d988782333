// Reading a reference render's directory (see reference_file.h).
#include "core/eval/reference_file.h"

#include <filesystem>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/render/render_outputs.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/image_io.h"

namespace rrf {

namespace fs = std::filesystem;

Reference loadReference(const std::string& dir) {
    const std::string meta = (fs::path(dir) / "render.json").string();
    Reference r;
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(readFile(meta));
        const auto lp = j.at("light_position").get<std::vector<float>>();
        if (lp.size() != 3) throw InputError(meta, "/light_position", "expected 3 numbers");
        r.lightPosition = Vec3(lp[0], lp[1], lp[2]);
        r.spp = j.value("spp_completed", 0);
        r.seconds = j.value("seconds", 0.0);
        r.nonFinite = j.value("non_finite_samples_dropped", uint64_t(0));
    } catch (const nlohmann::json::exception& e) {
        throw InputError(meta, "", std::string("not a render.json written by rrf render: ") + e.what());
    } catch (const std::runtime_error& e) {
        throw InputError(meta, "", std::string("no reference render here: ") + e.what());
    }
    for (int t = 0; t < kTermCount; ++t) {
        std::string path;
        for (const char* ext : {".exr", ".pfm"}) {
            const std::string p = (fs::path(dir) / (std::string(termName(Term(t))) + ext)).string();
            if (fs::exists(p)) {
                path = p;
                break;
            }
        }
        if (path.empty())
            throw InputError((fs::path(dir) / termName(Term(t))).string() + ".exr", "",
                             "missing: render the reference with --format exr or pfm");
        r.images[t] = readImage(path);
    }
    // Variances are optional: a render.json without "variance_images" leaves the noise unknown.
    if (j.contains("variance_images")) {
        const nlohmann::json& files = j["variance_images"];
        for (Term t : kTerms) {
            const std::string pointer = std::string("/variance_images/") + termName(t);
            if (!files.is_object() || !files.contains(termName(t)) || !files[termName(t)].is_string())
                throw InputError(meta, pointer, "expected the file name of the variance image");
            const std::string path = (fs::path(dir) / files[termName(t)].get<std::string>()).string();
            if (!fs::exists(path)) throw InputError(path, "", std::string("missing: listed in ") + meta + " at " + pointer);
            Image v = readImage(path);
            const Image& im = r.image(t);
            if (v.width != im.width || v.height != im.height)
                throw InputError(path, "", "expected a " + std::to_string(im.width) + "x" + std::to_string(im.height) +
                                               " variance image like " + termName(t) + ", got " + std::to_string(v.width) +
                                               "x" + std::to_string(v.height));
            r.variances[int(t)] = std::move(v);
        }
    }
    return r;
}

void writeReferenceDescription(const std::string& dir, const Reference& ref, int width, int height,
                               const std::string& writtenBy) {
    nlohmann::json render{{"light_position", {ref.lightPosition.x, ref.lightPosition.y, ref.lightPosition.z}},
                          {"spp_completed", ref.spp},
                          {"seconds", ref.seconds},
                          {"non_finite_samples_dropped", ref.nonFinite},
                          {"width", width},
                          {"height", height}};
    if (!writtenBy.empty()) render["written_by"] = writtenBy;
    if (!ref.variance(Term::Global).empty()) {
        std::vector<std::string> written;
        render["variance_images"] =
            writeVarianceImages(dir, {&ref.variance(Term::Direct), &ref.variance(Term::Indirect), &ref.variance(Term::Global)},
                                ImageFormat::EXR, written);
    }
    writeFileAtomically((fs::path(dir) / "render.json").string(), render.dump(2) + "\n");
}

}  // namespace rrf
