#pragma once
/// The workbench's last evaluation (the Objects table and its figures), kept beside the project so
/// that reopening it shows the table again (issue 29 item 7: everything a project shows is restored).
///
/// An evaluation judged one model set against one ground truth: it is kept with the ground truth's
/// ReferenceKey (the same key that invalidates the stored ground truth, core/eval/stored_ground_truth_file.h:
/// scene, camera, light, size, estimator) and the model set's directory (relative to the project)
/// and index checksum (models.json's index_checksum64). On reopen it is shown only when all three
/// still hold: another scene, light, size or a retrained set makes it stale, and it is dropped with
/// a line saying why. A damaged file is a warning naming the file, never a crash.
///
/// On disk: <project dir>/evaluation.json, {"format": "rrf-evaluation-1", "key", "models",
/// "models_checksum", "evaluation": {...}}, written atomically.

#include <optional>
#include <string>

#include "core/eval/reference_store.h"
#include "panels/learning_state.h"

namespace rrf {

/// The file beside a project (in its folder) where the workbench keeps its last evaluation.
constexpr const char* kEvaluationFile = "evaluation.json";

/// What an evaluation was made of: the ground truth's key and the judged model set.
struct EvaluationSource {
    ReferenceKey key;
    std::string models;          ///< the model set's directory, relative to the project
    std::string modelsChecksum;  ///< models.json's index_checksum64 ("" when the index has none)
};

/// Writes `e` (a valid evaluation of `source`) to `path` atomically. Throws OutputError naming the file.
void storeEvaluation(const std::string& path, const panels::EvaluationInfo& e, const EvaluationSource& source);

/// What loadEvaluation found.
struct StoredEvaluation {
    std::optional<panels::EvaluationInfo> info;  ///< the stored evaluation, when it is of `source`
    /// Why there is none: empty when nothing is stored; else stale ("the scene, light, camera or size
    /// changed since", "the models were trained again since") or the damaged file, named.
    std::string why;
    bool damaged = false;  ///< `why` is a problem with the file (a warning), not a stale evaluation
};

/// The evaluation stored at `path` when it was made of `source`. Never throws.
StoredEvaluation loadEvaluation(const std::string& path, const EvaluationSource& source);

}  // namespace rrf
