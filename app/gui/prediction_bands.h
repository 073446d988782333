#pragma once
/// Full-quality GLSL frames rendered in bands of rows (issue 29: no UI-thread stall over 100 ms at
/// open, train end or reopen).
///
/// Under Mesa llvmpipe a full-quality frame of the live prediction takes seconds (64 exact-direct
/// shadow rays per pixel, 40-10 networks: 11 s was seen on the 2-core machine). The GL worker
/// (app/gl/gl_worker.h) renders it while the UI goes on, but one task at a time: a light-drag draft,
/// which the UI waits for, would wait behind a whole frame. The frame is therefore rendered a band
/// of rows per task (GlslPredictor::render(rowBegin, rowEnd)), the view keeping the draft meanwhile,
/// and the band's height adapts to the time a band took, as the drafts' resolution does
/// (prediction_draft.h): above kBandBudgetSeconds the next band is smaller, well below it larger.
/// A GPU ends up rendering whole frames in one band; llvmpipe renders a few rows per band.

namespace rrf {

/// Wall time one band may hold the GL worker: what a draft may have to wait for on top of its own
/// time, within the 100 ms a UI frame may take (the UI's own work is 50-80 ms at 1600x1000 under
/// llvmpipe on the loaded 2-core machine).
constexpr double kBandBudgetSeconds = 0.025;
/// Divisor of the image height for the first band of a frame whose cost per row is not known yet.
constexpr int kFirstBandDivisor = 16;

/// Rows of a frame's first band: what fits the budget at `secondsPerRow` (the last full frame's
/// cost per row; ≤ 0 when unknown: height / kFirstBandDivisor), within 1 … height.
int firstBandRows(int height, double secondsPerRow);

/// Rows of the next band after a band of `rows` took `seconds`: scaled towards the budget (at most
/// doubling, at least one row), within 1 … height.
int nextBandRows(int rows, double seconds, int height);

}  // namespace rrf
