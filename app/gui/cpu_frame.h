#pragma once
// The last finished CPU prediction of the workbench's loaded models, kept with what it was predicted
// from, so that an evaluation of the same models, settings, light, scene and size reuses its pixels
// instead of predicting them again: on a glossy scene the CPU frame carries the glossy gather, the
// costliest part of a prediction, and a manual Train starts both the frame and the evaluation.
#include <memory>

#include "core/nn/model_set.h"
#include "core/predict/gbuffer.h"
#include "core/predict/prediction_settings.h"
#include "core/predict/predictor.h"
#include "panels/workbench_state.h"

namespace rrf {

struct CpuFrame {
    std::shared_ptr<const ModelSet> models;  ///< the models that predicted it (compared by identity)
    PredictionSettings settings;             ///< the prediction settings it was predicted with
    panels::ImageStamp stamp;                ///< light, scene and size it was predicted for
    GBuffer gbuffer;                         ///< its primary hits
    double gbufferSeconds = 0.0;
    Prediction prediction;                   ///< its images and timings

    /// Whether an evaluation of `m` with `s` against a reference of `of` (light, scene, size) would
    /// predict exactly these pixels (the predictor is deterministic).
    bool matches(const std::shared_ptr<const ModelSet>& m, const PredictionSettings& s,
                 const panels::ImageStamp& of) const {
        return m == models && s == settings && of == stamp;
    }
};

}  // namespace rrf
