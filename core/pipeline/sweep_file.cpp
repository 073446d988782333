#include "core/pipeline/sweep_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/eval/error_metrics_json.h"
#include "core/util/atomic_file.h"
#include "core/util/json_reader.h"

namespace rrf {

namespace {
/// A number or null (unknown) as sweepJson's optionalJson writes it.
double sweepFileOptional(const JsonReader& r, const char* key) {
    const JsonReader v = r.at(key);
    return v.value().is_null() ? SweepRow::kUnknown : v.number();
}

SweepRow sweepFileRow(const JsonReader& r) {
    r.requireObject();
    SweepRow row;
    row.setting = r.at("setting").string();
    const JsonReader stages = r.at("stage_seconds");
    stages.requireObject();
    for (const auto& kv : stages.value().items()) row.stageSeconds.emplace_back(kv.key(), stages.at(kv.key()).number());
    row.overall = errorStatsFromJson(r.at("error").value(), r.file(), JsonReader::child(r.pointer(), "error"));
    const JsonReader objects = r.at("objects");
    for (size_t i = 0, n = objects.requireArray(); i < n; ++i) {
        const JsonReader o = objects.at(i);
        const size_t id = size_t(o.at("id").integer(0, 1 << 20));
        if (row.perObject.size() <= id) row.perObject.resize(id + 1);
        row.perObject[id] = errorStatsFromJson(o.value(), o.file(), o.pointer());
    }
    row.extra = r.at("extra").value();
    row.spp = int(r.integerOr("spp", 0, 0, 1 << 30));
    if (r.has("one_off_seconds")) {  // a model row
        row.oneOffSeconds = r.at("one_off_seconds").number();
        row.frameSeconds = sweepFileOptional(r, "frame_seconds");
        row.glslFrameSeconds = sweepFileOptional(r, "glsl_frame_seconds");
        const JsonReader b = r.at("break_even");
        if (!b.value().is_null()) {
            row.breakEven.known = b.at("known").boolean();
            row.breakEven.extrapolated = b.at("extrapolated").boolean();
            if (row.breakEven.known) {
                row.breakEven.spp = b.at("spp").number();
                row.breakEven.seconds = b.at("seconds").number();
            }
        }
    }
    return row;
}

std::vector<SweepRow> sweepFileRows(const JsonReader& r) {
    std::vector<SweepRow> rows;
    for (size_t i = 0, n = r.requireArray(); i < n; ++i) rows.push_back(sweepFileRow(r.at(i)));
    return rows;
}
}  // namespace

SweepResult readSweepFile(const std::string& path) {
    const nlohmann::json doc = parseJsonText(readFile(path), path);
    const JsonReader r(doc, path);
    r.requireObject();
    SweepResult s;
    s.what = r.at("what").string();
    s.lightPosition = r.at("light_position").vec3();
    const JsonReader resolution = r.at("resolution");
    if (resolution.requireArray() != 2) resolution.fail("expected [width, height]");
    s.width = int(resolution.at(size_t(0)).integer(1, 1 << 16));
    s.height = int(resolution.at(size_t(1)).integer(1, 1 << 16));
    const JsonReader reference = r.at("reference");
    s.referenceSpp = int(reference.at("spp").integer(0, int64_t(1) << 40));
    s.referenceSeconds = reference.at("seconds").number();
    s.relativeNoiseFloor = sweepFileOptional(reference, "relative_rmse_noise_floor");
    s.cancelled = r.at("cancelled").boolean();
    s.extra = r.at("extra").value();
    s.rows = sweepFileRows(r.at("rows"));
    s.pathTracer = sweepFileRows(r.at("path_tracer"));
    return s;
}

std::vector<std::string> sweepFilesIn(const std::string& dir) {
    namespace fs = std::filesystem;
    std::vector<std::string> files;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return files;
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
        if (e.is_regular_file(ec) && e.path().extension() == ".json") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace rrf
