#pragma once
/// Scripted sessions (`rrf-workbench --script steps.json`): a JSON array of steps that drive the
/// workbench as a user would, one step per frame, for CI and for reproducible screenshots.
///
///     [ {"do": "render", "spp": 8}, {"do": "wait", "for": "render"}, {"do": "save_run"},
///       {"do": "set_light", "position": [0.2, 0.9, 0]}, {"do": "wait", "for": "render"},
///       {"do": "compare_run", "index": 0}, {"do": "check", "runs": 1}, {"do": "frames", "count": 5} ]
///
/// Steps: render {spp}, generate {the "sampling" section's keys: grid, directions, spp, seed, light,
/// estimator, max_depth}, train {epochs, trainer, refused (expect a refusal), and the "network"
/// section's keys: hidden, activation, targets}, evaluate,
/// sweep {what: spp|grid|dirs|hidden|trainer},
/// wait {for: render|jobs|train_epoch|loads (what open, compare_run and reopen_run read on workers), timeout_s}, save_run, compare_run {index},
/// reopen_run {index}, request_open {path?: as File > Open, asking about unsaved changes},
/// answer_unsaved {choice: save|discard|cancel}, stop {job: render|generate|train}, compare_runs {a, b:
/// run indices, as ticking A and B}, set_light {position}, select_object {id}, view {term, metric, exposure,
/// error_max, zoom}, open {path?: default re-opens the current file}, save {path?}, export_images {dir}, screenshot {path},
/// frames {count}, tab {name: bring a panel tab to the front}, move_tab {tab, to: a tab of the target
/// pane, side: centre (join it, the default)|left|right|top|bottom (split it)}, reset_layout,
/// pipeline {preset, and optional sizes over it: grid, directions, spp, max_spp, epochs, hidden},
/// stop_pipeline, wait {for: pipeline | train_running}, measure_frames {label, frames, drag_light:
/// print the median and 95th percentile frame time},
/// check {runs, ground_truth_spp_min, errors, compare, dataset, prediction, evaluated, train_runs,
/// sweeps, unsaved_prompt, dirty, stopped_runs, prediction_partial, render_cancelled, notice, pair,
/// panes (how many), same_pane [tab, tab], clipped (how many texts are cut off in this frame,
/// panels/clip_check.h), pipeline_done, pipeline_stopped}. An unknown step or key fails the script
/// when it is loaded (it never skips silently), naming the file and the step's JSON pointer; so does
/// a value of the wrong type or out of range (app/gui/script_file.h reads the file).

#include <chrono>
#include <string>
#include <vector>

#include "app/gui/script_file.h"
#include "core/util/vec3.h"

namespace rrf {

class Workbench;

class Script {
public:
    enum class Status { Running, Done, Failed };

    /// Reads and checks the step list (each step's "do" and keys); false with `error` set (file, JSON
    /// pointer, what was expected) if the file is unusable.
    bool load(const std::string& path, std::string& error);
    /// Carries out (or keeps waiting on) the current step; call once per frame.
    Status step(Workbench& workbench);
    const std::string& error() const { return error_; }
    bool empty() const { return steps_.empty(); }

private:
    Status fail(const std::string& message);
    /// Runs one step; returns true when it is complete (false: keep waiting).
    bool execute(Workbench& wb, const ScriptStep& s);

    std::vector<ScriptStep> steps_;
    std::string file_;  ///< the script's path, for messages
    size_t next_ = 0;
    bool waiting_ = false;
    int framesLeft_ = 0;
    std::chrono::steady_clock::time_point waitStart_;
    Vec3 dragStart_;  ///< measure_frames drag_light: the light's position when the step began
    std::string error_;
    bool failed_ = false;
};

}  // namespace rrf
