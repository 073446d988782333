#include "core/pipeline/run_summary.h"

#include "core/nn/network_settings.h"
#include "core/pipeline/run_recording.h"

namespace rrf {

RunSummary summarizeRun(const Run& run) {
    RunSummary r;
    r.kind = run.kind;
    r.status = trainRunStatusText(run);
    r.stopped = isStoppedTrainRun(run);
    const RunMetrics& m = run.metrics;
    if (run.kind == "train") {
        if (const auto& t = run.settings.trainer) r.trainer = t->type == TrainerType::Adam ? "Adam" : "LM";
        if (const auto& net = run.settings.network) r.hidden = net->options.hidden;
        r.leaves = m.leaves;
        if (m.records) r.records = double(*m.records);
        r.seconds = finiteOrNone(run.timings.train);
        r.error = finiteOrNone(m.relativeRmse);
        r.noiseFloor = finiteOrNone(m.relativeRmseNoiseFloor);
        r.corrected = finiteOrNone(m.relativeRmseCorrected);
        if (const auto glsl = finiteOrNone(m.glslFrameSeconds)) {
            r.frameSeconds = glsl;
            r.frameGlsl = true;
            r.frameWidth = m.glslFrameWidth.value_or(0);
            r.frameHeight = m.glslFrameHeight.value_or(0);
        } else {
            r.frameSeconds = finiteOrNone(m.frameSeconds);
            r.frameWidth = m.frameWidth.value_or(0);
            r.frameHeight = m.frameHeight.value_or(0);
        }
        r.evaluatedWidth = m.evaluatedWidth.value_or(0);
        r.evaluatedHeight = m.evaluatedHeight.value_or(0);
    } else {
        if (m.spp) r.spp = double(*m.spp);
        r.seconds = finiteOrNone(run.timings.render);
        // A render's own relative error estimate is its noise: the floor any comparison with it has.
        r.noiseFloor = finiteOrNone(m.relativeError);
    }
    return r;
}

namespace {
/// The endings `name` may be cut to, shortest first: from the start of each '-'-separated part, and
/// within a date part (8 digits, yyyymmdd) from its month and its day, so runs of other days read
/// "01-194512" / "02-194512" rather than the whole date. Each ending holds at least one part of 3 or
/// more characters (a "-2" counter keeps its time).
std::vector<std::string> nameEndings(const std::string& name) {
    std::vector<std::string> endings;
    bool readable = false;
    size_t end = name.size();
    while (true) {
        const size_t dash = name.rfind('-', end == 0 ? 0 : end - 1);
        const size_t start = dash == std::string::npos || end == 0 ? 0 : dash + 1;
        const std::string part = name.substr(start, end - start);
        const bool date = part.size() == 8 && part.find_first_not_of("0123456789") == std::string::npos;
        if (date && readable) {
            endings.push_back(name.substr(start + 6));
            endings.push_back(name.substr(start + 4));
        }
        readable |= part.size() >= 3;
        if (readable) endings.push_back(name.substr(start));
        if (start == 0) break;
        end = start - 1;
    }
    if (endings.empty() || endings.back() != name) endings.push_back(name);
    return endings;
}
}  // namespace

std::vector<std::string> shortRunNames(const std::vector<Run>& runs) {
    // A chosen name is shown whole: it is never cut, and others are cut only as far as it allows.
    std::vector<std::vector<std::string>> endings;
    for (const Run& r : runs) endings.push_back(r.name == r.id ? nameEndings(r.name) : std::vector<std::string>{r.name});
    auto endsWith = [](const std::string& s, const std::string& e) {
        return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
    };
    std::vector<std::string> shown(runs.size());
    for (size_t i = 0; i < runs.size(); ++i) {
        for (const std::string& e : endings[i]) {
            shown[i] = e;
            // Unique: no other name ends the same way (so no other can be shown the same).
            bool unique = true;
            for (size_t j = 0; j < runs.size() && unique; ++j) unique = j == i || !endsWith(endings[j].back(), e);
            if (unique) break;
        }
    }
    // Equal whole names (two runs renamed alike) are left alike: the row number tells them apart.
    const std::vector<std::string> cut = shown;
    for (size_t i = 0; i < runs.size(); ++i)
        for (size_t j = 0; j < runs.size(); ++j)
            if (j != i && cut[j] == cut[i]) {
                shown[i] += " #" + std::to_string(i + 1);
                break;
            }
    return shown;
}

const std::vector<std::string>& ShortRunNames::of(const std::vector<Run>& runs) {
    bool same = key_.size() == runs.size();
    for (size_t i = 0; same && i < runs.size(); ++i) same = key_[i].first == runs[i].id && key_[i].second == runs[i].name;
    if (same) return names_;
    key_.clear();
    for (const Run& r : runs) key_.emplace_back(r.id, r.name);
    names_ = shortRunNames(runs);
    ++computations_;
    return names_;
}

std::string hiddenText(const std::vector<int>& hidden) {
    return hidden.empty() ? "-" : hiddenSizesText(hidden);
}

}  // namespace rrf
