// The values of a sweep read into settings, and each kind's default series (sweep_values.h).
#include "core/pipeline/sweep_values.h"

#include <algorithm>
#include <sstream>

#include "core/pipeline/sweep.h"
#include "core/nn/encoding_presets.h"
#include "core/nn/trainers/registry.h"
#include "core/nn/network_settings.h"
#include "core/util/error.h"

namespace rrf {

namespace {

/// The setting that lists what a sweep compares (front ends map it to their own field or flag).
const char* const kValuesSetting = "sweep values";

int positiveValue(const std::string& text, const std::string& value, int max, const std::string& expected) {
    try {
        size_t used = 0;
        const int v = std::stoi(text, &used);
        if (used == text.size() && v > 0 && v <= max) return v;
    } catch (const std::exception&) {
    }
    throw SettingError(kValuesSetting, "'" + value + "': expected " + expected);
}

/// A number in (0, max], the whole text.
/// The refusals training would raise before it starts (a trainable encoding under LM or shared by an
/// ensemble's members), stated against the sweep value `v` that made the settings, before anything runs.
void refuseUntrainable(const std::string& v, const ObjectTrainingOptions& t) {
    try {
        checkEncodingTrainer(t.encoding, t.trainer);
        checkEnsembleEncoding(t.encoding, t.ensemble);
    } catch (const SettingError& e) {
        throw SettingError(kValuesSetting, "'" + v + "': " + e.detail());
    }
}

double positiveNumber(const std::string& text, double max, const std::string& expected) {
    try {
        size_t used = 0;
        const double v = std::stod(text, &used);
        if (used == text.size() && v > 0 && v <= max) return v;
    } catch (const std::exception&) {
    }
    throw SettingError(kValuesSetting, "'" + text + "': expected " + expected);
}


/// "4,4,4": the grid as --grid and the project's "grid": [4, 4, 4] spell it.
void readGrid(const std::string& v, SamplingSettings& s) {
    const std::string expected = "3 integers nx,ny,nz in 1.." + std::to_string(kMaxGridCells) + " (e.g. 4,4,4)";
    std::vector<int> n;
    std::istringstream in(v);
    for (std::string part; std::getline(in, part, ',');) n.push_back(positiveValue(part, v, kMaxGridCells, expected));
    if (n.size() != 3 || v.back() == ',') throw SettingError(kValuesSetting, "'" + v + "': expected " + expected);
    s.nx = n[0];
    s.ny = n[1];
    s.nz = n[2];
}

}  // namespace

std::vector<std::string> defaultSweepValues(const std::string& what) {
    if (what == "spp") return {"1", "2", "4", "8", "16", "32", "64"};
    if (what == "grid") return {"2,2,2", "3,3,3", "4,4,4"};
    if (what == "dirs") return {"50", "100", "200"};
    if (what == "hidden") return {"5", "10,5", "20,10"};
    if (what == "trainer") return trainerShortNames();
    if (what == "goal") return {"0.1", "0.05", "0.03"};
    if (what == "leaves") return {"1", "4", "16"};
    if (what == "record_spp") return {"64", "256", "1024"};
    if (what == "encoding") return {"raw", "frequency", "hash_grid"};
    if (what == "ensemble") return {"1", "2", "4"};
    std::string kinds;
    for (const char* k : kSweepKinds) kinds += std::string(kinds.empty() ? "" : ", ") + k;
    throw SettingError("sweep dimension", "expected one of " + kinds + ", got '" + what + "'");
}

std::vector<SweepPoint> sweepPoints(const SweepOptions& o) {
    std::vector<SweepPoint> points;
    for (const std::string& v : o.values) {
        SweepPoint p{v, 0, o.sampling, o.training};
        if (o.what == "spp") {
            p.spp = positiveValue(v, v, 1 << 20, "one positive integer (samples per pixel)");
        } else if (o.what == "grid") {
            readGrid(v, p.sampling);
        } else if (o.what == "dirs") {
            p.sampling.directions = positiveValue(v, v, kMaxDirections, "one positive integer (directions per viewpoint)");
        } else if (o.what == "hidden") {
            p.training.hidden = parseHiddenSizes(v, kValuesSetting);
            dropHiddenOverrides(p.training.perObject);  // a sweep value is every network's
        } else if (o.what == "goal") {
            // One figure for both: the trainer stops at it and the kd-tree splits nodes above it.
            const double goal = positiveNumber(v, 10.0, "an error goal in (0, 10] (validation relative RMSE, e.g. 0.05)");
            for (TrainerCommon* c : p.training.trainer.everyTrainer()) c->errorGoal = goal;
            p.training.partition.goal = goal;
        } else if (o.what == "leaves") {
            p.training.partition.maxLeaves = positiveValue(v, v, kMaxPartitionLeaves, "the most leaves per network, 1.." +
                                                                                        std::to_string(kMaxPartitionLeaves));
            if (p.training.partition.maxLeaves > 1 && p.training.partition.maxDepth == 0)
                p.training.partition.maxDepth = PartitionSettings{}.maxDepth;
        } else if (o.what == "encoding") {
            p.training.encoding = encodingPresetSettings(v, kValuesSetting);
            dropEncodingOverrides(p.training.perObject);
            refuseUntrainable(v, p.training);
        } else if (o.what == "ensemble") {
            p.training.ensemble = positiveValue(v, v, kMaxEnsembleMembers, "networks averaged per leaf, 1.." +
                                                                                std::to_string(kMaxEnsembleMembers));
            refuseUntrainable(v, p.training);
        } else if (o.what == "record_spp") {
            p.sampling.maxSpp = positiveValue(v, v, kMaxSamplesPerRecord, "the most paths per record, 1.." + std::to_string(kMaxSamplesPerRecord));
            p.sampling.spp = std::min(p.sampling.spp, p.sampling.maxSpp);
        } else {
            const std::vector<std::string> trainers = trainerShortNames();
            if (std::find(trainers.begin(), trainers.end(), v) == trainers.end())
                throw SettingError(kValuesSetting, "'" + v + "': expected " + trainerShortNamesText());
            p.training.trainer = p.training.trainer.withType(v);
        }
        points.push_back(std::move(p));
    }
    return points;
}

}  // namespace rrf
