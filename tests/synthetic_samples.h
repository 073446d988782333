#pragma once
/// Per-object training samples made in code for the training tests: smooth direct and indirect
/// targets of random inputs, so a small network fits them within a few epochs.

#include <cmath>
#include <cstdint>
#include <string>

#include "core/nn/object_training.h"
#include "core/util/rng.h"

namespace rrf {

/// A synthetic object with `n` samples: 14 inputs (12 geometry + 2 BRDF, the second a constant, so
/// a dead input) in [-1, 1), smooth direct and indirect targets. Deterministic in (id, i).
inline ObjectSamples syntheticObject(int id, int n) {
    ObjectSamples s;
    s.objectId = id;
    s.name = "object" + std::to_string(id);
    s.numInputs = 14;
    for (int i = 0; i < n; ++i) {
        Rng rng(100 + uint64_t(id), uint64_t(i));
        float in[14];
        for (float& v : in) v = 2.f * rng.uniform() - 1.f;
        in[13] = 0.25f;  // a BRDF parameter constant over the object: a dead input
        const float d[3] = {1.f + in[6] * in[0], 0.5f + 0.2f * in[7], 3.f};
        const float ind[3] = {0.1f * std::exp(in[1]), 0.2f, 0.05f * (in[2] + 1.f)};
        s.add(in, d, ind);
    }
    return s;
}

}  // namespace rrf
