#pragma once
/// Full-quality GLSL frames rendered in bands of rows over several UI frames (issue 29: no UI-thread
/// stall over 100 ms at open, train end or reopen).
///
/// Under Mesa llvmpipe a full-quality frame of the live prediction takes seconds (64 exact-direct
/// shadow rays per pixel, 40-10 networks: 11 s was seen on the 2-core machine), and GL runs on the
/// UI thread only, so rendering it in one call froze the window for that long whenever models were
/// loaded or the light came to rest. The frame is instead rendered a band of rows per UI frame
/// (GlslPredictor::render(rowBegin, rowEnd)), the view keeping the draft meanwhile, and the band's
/// height adapts to the time a band took, as the drafts' resolution does (prediction_draft.h):
/// above kBandBudgetSeconds the next band is smaller, well below it larger. A GPU ends up rendering
/// whole frames in one band; llvmpipe renders a few rows per frame.

namespace rrf {

/// Wall time one band may take on the UI thread: the rest of the 100 ms a frame may take is the
/// UI's own (50-80 ms at 1600x1000 under llvmpipe on the loaded 2-core machine).
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
