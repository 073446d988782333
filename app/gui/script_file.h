#pragma once
/// The script file of a scripted session (app/gui/script.h for the steps and their keys): a JSON
/// array of steps, read once into typed steps that the runner carries out. Every key is checked
/// when the file is read (unknown steps and keys, wrong types, out-of-range values), naming the
/// file and the JSON pointer. The settings a generate, train or pipeline step carries are the
/// project's own sections, read over the settings in effect when the step runs
/// (samplingOver, networkOver).

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/data/sampling_settings.h"
#include "core/nn/network_settings.h"
#include "core/util/json_text.h"
#include "core/util/vec3.h"

namespace rrf {

/// Keys of a step that are a project settings section ("sampling" for generate and pipeline,
/// "network" for train and pipeline's "hidden"), kept as written.
struct ScriptSection {
    JsonText keys;        ///< the section's keys; empty: the step sets none
    std::string file;     ///< the script, for messages
    std::string pointer;  ///< the step's JSON pointer ("/3"), for messages
    bool empty() const { return keys.empty(); }
};

/// `base` with the section's "sampling" keys applied (missing keys keep base's values); InputError
/// names the script and the key's pointer for an unknown key or a bad value.
SamplingSettings samplingOver(const ScriptSection& section, const SamplingSettings& base);
/// `base` with the section's "network" keys applied, as samplingOver.
NetworkSettings networkOver(const ScriptSection& section, const NetworkSettings& base);

/// One step, its keys read (absent optional keys are empty; keys with a fixed default hold it).
struct ScriptStep {
    std::string what;     ///< "do"
    std::string file;     ///< the script, for messages
    std::string pointer;  ///< the step's JSON pointer, "/<index>"

    // render
    std::optional<int> spp, width, height;
    // wait
    std::string waitFor = "jobs";  ///< "for"
    double timeoutSeconds = 300;   ///< "timeout_s"
    // generate (sampling keys), train (network keys), pipeline (sampling keys; "hidden")
    ScriptSection sampling, network;
    // train
    std::optional<std::string> trainer;
    bool refused = false;
    int epochs = 0;  ///< train: "epochs" (0: the trainer's own); pipeline: see pipelineEpochs
    // sweep
    std::string sweepWhat;  ///< "what"
    // light_grid
    std::optional<std::array<int, 3>> grid;
    // pipeline
    std::string preset;                  ///< "" without "preset"
    std::optional<int> pipelineEpochs;   ///< "epochs"
    // measure_frames
    std::string label;
    int frames = 60;
    bool dragLight = false;
    // tab, move_tab
    std::string tabName, moveTab, moveTo, side = "centre";
    // compare_run, reopen_run, select_object, compare_runs, frames
    int index = 0, objectId = -1, runA = 0, runB = 1, frameCount = 1;
    // set_light
    Vec3 position;
    // view
    std::optional<std::string> term, metric;
    std::optional<float> exposure, errorMax, zoom;
    std::optional<bool> spread;
    std::optional<std::vector<int>> region;  ///< [] or [x0, y0, x1, y1]
    // open, request_open, save, export_images, screenshot
    std::optional<std::string> path;
    std::string dir;
    // answer_unsaved, stop
    std::string choice, job;
    // shortcut
    std::string keys;
    // check: the expectations given, by key
    std::map<std::string, int64_t> counts;  ///< counts and minimums ("runs", "errors", ...)
    std::map<std::string, bool> flags;      ///< states ("dataset", "dirty", ...)
    std::optional<std::string> predictionLabel;
    std::optional<Vec3> lightPosition;
    std::optional<std::pair<std::string, std::string>> samePane;

    /// Throws InputError naming the script and `key`'s pointer in this step.
    [[noreturn]] void fail(const std::string& key, const std::string& what) const;
};

/// Reads the script at `path`: a JSON array of steps, each with a known "do", only its keys, and
/// values of the right types and ranges. Throws InputError naming the file and the JSON pointer.
std::vector<ScriptStep> readScriptFile(const std::string& path);

}  // namespace rrf
