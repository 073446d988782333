#pragma once
/// How converged the references of a project must be (the project's "reference" section,
/// docs/file-formats.md): the noise target the reference store renders to (core/eval/reference_store.h)
/// and the size of its references. core/eval/reference_settings_json.h reads and writes the section.

namespace rrf {

/// How converged a reference must be.
struct NoiseTarget {
    /// Relative RMSE noise floor of the global term over the footprint mask to reach.
    double relativeRmse = 0.01;
    /// When an error is being measured against the reference, this fraction of that error suffices
    /// if it is larger than `relativeRmse` (a 0.2 error needs no 0.01 reference to be ranked).
    double errorFraction = 0.25;
    int sppCap = 4096;        ///< never more samples per pixel than this
    int sppPerPass = 16;      ///< samples added between two checks of the noise (and progress reports)

    /// The noise to reach when the error measured so far is `measuredError` (NaN: none measured).
    double wanted(double measuredError) const;
};

/// The "reference" section: the noise target and the references' size.
struct ReferenceSettings {
    NoiseTarget target;
    int width = 0, height = 0;  ///< 0 = the "render" section's size (which in turn 0 = the camera's)
};

}  // namespace rrf
