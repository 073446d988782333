#pragma once
/// Draft frames of the live GLSL prediction while the light is dragged (issue 14, item 10).
///
/// A full-quality frame computes exact direct light with `direct_samples` shadow rays per pixel
/// (64 by default): under Mesa llvmpipe that is seconds per frame, so a drag would stall the UI.
/// While the light moves the workbench therefore renders drafts: 1/16 of the light samples (at
/// least 1) at a resolution divided by 1 … kMaxDraftDivisor per direction, scaled back to the view's
/// size by pixel replication so that the error map and hover read-outs keep working. The divisor
/// adapts to the driver (dynamic resolution, as games do): a draft slower than kDraftBudgetSeconds
/// makes the next one coarser, one much faster makes it finer, so a GPU drafts at full resolution
/// and llvmpipe at a quarter. The full-quality frame
/// replaces the draft once the light has rested for kDraftRestSeconds; the view's label says
/// which one is shown. Draft times are kept apart from the runs table's per-frame figure, which
/// stays the full-quality frame.

#include "core/predict/prediction_settings.h"
#include "core/scene/scene.h"
#include "core/util/image.h"

namespace rrf {

/// Seconds without a light move after which the full-quality frame is rendered.
constexpr double kDraftRestSeconds = 0.3;
/// Largest resolution divisor per direction of a draft frame, and the first one tried.
constexpr int kMaxDraftDivisor = 4;
/// Time a draft's prediction may take: 20 ms of the 50 ms a frame may take while dragging (issue 14).
constexpr double kDraftBudgetSeconds = 0.020;
/// Divisor of the exact direct light's samples per pixel in a draft frame.
constexpr int kDraftSampleDivisor = 16;

/// The draft camera: the same view (eye, target, up, vertical field of view) at ⌈w/d⌉ × ⌈h/d⌉.
Camera draftCamera(const Camera& full, int divisor);

/// The divisor for the next draft after one at `divisor` took `seconds`: one coarser above the
/// budget, one finer below a third of it (a finer draft costs up to (d/(d−1))² more), else the same;
/// always within 1 … kMaxDraftDivisor.
int nextDraftDivisor(int divisor, double seconds);

/// The draft prediction settings: direct samples divided by kDraftSampleDivisor, at least 1; the
/// rest (direct mode, seed) unchanged.
PredictionSettings draftPrediction(const PredictionSettings& full);

/// `small` scaled to width × height by pixel replication: output pixel (x, y) takes the small
/// image's pixel whose footprint holds the output pixel's centre.
Image replicatePixels(const Image& small, int width, int height);

}  // namespace rrf
