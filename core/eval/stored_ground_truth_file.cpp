// The last finished ground-truth render beside a project (see stored_ground_truth_file.h).
#include "core/eval/stored_ground_truth_file.h"

#include <filesystem>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/eval/reference_store_file.h"
#include "core/render/term.h"
#include "core/util/atomic_file.h"
#include "core/util/directory_replace.h"
#include "core/util/error.h"
#include "core/util/image_io.h"
#include "core/util/json_reader.h"

namespace rrf {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kFormat = "rrf-ground-truth-1";
constexpr const char* kMetaFile = "ground_truth.json";

std::string imageName(Term t) { return std::string(termName(t)) + ".exr"; }
std::string varianceName(Term t) { return "variance_" + std::string(termName(t)) + ".exr"; }

Image& varianceSlot(RenderSnapshot& s, Term t) {
    return t == Term::Direct ? s.directVariance : t == Term::Indirect ? s.indirectVariance : s.variance;
}
Image& imageSlot(RenderSnapshot& s, Term t) {
    return t == Term::Direct ? s.direct : t == Term::Indirect ? s.indirect : s.global;
}

}  // namespace

void storeGroundTruth(const std::string& dir, const ReferenceKey& key, const RenderSnapshot& snapshot,
                      const RenderStats& stats) {
    const bool variance = snapshot.varianceKnown();
    // Every file of the set is this module's: nothing of an old set is kept.
    replaceDirectory(dir, [](const std::string&) { return true; }, [&](const std::string& staging) {
        const fs::path tmp(staging);
        for (Term t : kTerms) {
            writeImage((tmp / imageName(t)).string(), snapshot.image(t), ImageFormat::EXR);
            if (variance) writeImage((tmp / varianceName(t)).string(), snapshot.varianceOf(t), ImageFormat::EXR);
        }
        const json meta{{"format", kFormat},
                        {"key", toJson(key)},
                        {"spp", snapshot.sppCompleted},
                        {"passes", snapshot.passes},
                        {"samples", snapshot.samples},
                        {"non_finite_samples", snapshot.nonFinite},
                        {"seconds", snapshot.seconds},
                        {"relative_error", snapshot.relativeError},
                        {"rays", stats.rays},
                        {"shadow_rays", stats.shadowRays},
                        {"variance", variance}};
        writeFileAtomically((tmp / kMetaFile).string(), meta.dump(2) + "\n");
    });
}

StoredGroundTruth loadGroundTruth(const std::string& dir, const ReferenceKey& key, int spp) {
    StoredGroundTruth out;
    const fs::path meta = fs::path(dir) / kMetaFile;
    std::error_code ec;
    if (!fs::exists(meta, ec)) return out;  // nothing stored: a first render, no reason to give
    try {
        const json j = readJsonFile(meta.string());
        const JsonReader r(j, meta.string());
        r.checkKeys({"format", "key", "spp", "passes", "samples", "non_finite_samples", "seconds", "relative_error",
                     "rays", "shadow_rays", "variance"});
        if (r.at("format").string() != kFormat)
            r.at("format").fail(std::string("unknown format (expected \"") + kFormat + "\")");
        r.at("key").requireObject();  // an InputError naming the file when it is missing
        const ReferenceKey stored = referenceKeyFromJson(j.at("key"), meta.string(), "/key");
        if (!(stored == key)) {
            out.why = "the stored one is of another scene, light, camera or size";
            return out;
        }
        const int storedSpp = int(r.at("spp").integer(1, 1 << 30));
        if (storedSpp != spp) {
            out.why = "the stored one has " + std::to_string(storedSpp) + " spp, " + std::to_string(spp) + " are asked for";
            return out;
        }
        RenderSnapshot s;
        s.sppCompleted = storedSpp;
        s.passes = int(r.at("passes").integer(0, 1 << 30));
        s.samples = r.at("samples").unsignedInteger();
        s.nonFinite = r.at("non_finite_samples").unsignedInteger();
        s.seconds = r.at("seconds").number(0, 1e12);
        s.relativeError = r.at("relative_error").number();
        out.stats.samples = s.samples;
        out.stats.nonFinite = s.nonFinite;
        out.stats.seconds = s.seconds;
        out.stats.rays = r.at("rays").unsignedInteger();
        out.stats.shadowRays = r.at("shadow_rays").unsignedInteger();
        const bool variance = r.at("variance").boolean();
        for (Term t : kTerms) {
            Image& im = imageSlot(s, t);
            im = readImage((fs::path(dir) / imageName(t)).string());
            if (im.width != key.width || im.height != key.height)
                throw InputError((fs::path(dir) / imageName(t)).string(), "",
                                 "is " + std::to_string(im.width) + "x" + std::to_string(im.height) + ", its key says " +
                                     std::to_string(key.width) + "x" + std::to_string(key.height));
            Image& var = varianceSlot(s, t);
            if (variance) var = readImage((fs::path(dir) / varianceName(t)).string());
            else var = Image(key.width, key.height);  // below 2 spp the renderer's variance is 0 too
            if (var.width != key.width || var.height != key.height)
                throw InputError((fs::path(dir) / varianceName(t)).string(), "", "does not have the images' size");
        }
        if (variance != s.varianceKnown())
            r.at("variance").fail("does not match the spp (variance images exist from 2 spp on)");
        out.snapshot = std::move(s);
    } catch (const std::exception& e) {
        out.snapshot.reset();
        out.stats = RenderStats{};
        out.why = std::string("the stored one cannot be read: ") + e.what();
    }
    return out;
}

}  // namespace rrf
