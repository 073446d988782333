#pragma once
// The smallest hidden-size sweep that still runs every stage (reference, path tracer series, shared
// dataset, one network per point): for tests of what a sweep reports, not of its accuracy.

#include <string>
#include <vector>

#include "core/pipeline/sweep.h"
#include "tests/training_builders.h"

namespace rrf::test {

/// 8x8 images, a 4-spp reference, the path tracer at 1 and 2 spp, one grid cell of 10 directions at
/// 2 paths, one epoch; one point per entry of `values` (hidden sizes).
inline SweepOptions tinyHiddenSweep(std::vector<std::string> values) {
    SweepOptions o;
    o.training = plainTraining();
    o.what = "hidden";
    o.values = std::move(values);
    o.width = o.height = 8;
    o.referenceSpp = 4;
    o.pathTracerSpp = {1, 2};
    o.sampling.nx = o.sampling.ny = o.sampling.nz = 1;
    o.sampling.directions = 10;
    o.sampling.spp = 2;
    o.training.trainer.lm.maxEpochs = 1;
    return o;
}

}  // namespace rrf::test
