#pragma once
/// Small trained model sets for the tests of files that hold them (model sets replaced as a whole,
/// their refusals, a full disk): networks of 3 inputs, 4 hidden units and 3 outputs, fitted for 2
/// epochs, so they are real trained models but cost milliseconds.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/nn/model.h"
#include "core/nn/model_set.h"
#include "core/nn/trainer_config.h"
#include "core/util/rng.h"

namespace rrf::test {

/// Inputs of every network tinyModel makes.
constexpr int kTinyModelInputs = 3;

/// A 3-4-3 network of object `id` fitted for 2 epochs to data drawn with `seed`.
inline ObjectModel tinyModel(int id, uint64_t seed) {
    MlpArch a;
    a.inputs = kTinyModelInputs;
    a.hidden = {4};
    a.outputs = 3;
    MatX<float> x(kTinyModelInputs, 40), y(3, 40);
    for (int c = 0; c < 40; ++c) {
        Rng rng(seed, uint64_t(c));
        for (int r = 0; r < kTinyModelInputs; ++r) x(r, c) = rng.uniform();
        for (int r = 0; r < 3; ++r) y(r, c) = rng.uniform() + float(id);
    }
    NetworkModel net = fitNetwork(a, TrainerConfig::fromJson({{"max_epochs", 2}}), x, y);
    net.objectId = id;
    net.objectName = "object " + std::to_string(id);
    net.target = "global";
    ObjectModel m;
    m.objectId = id;
    m.objectName = net.objectName;
    m.target = "global";
    m.model = PartitionedNetwork(std::move(net));
    return m;
}

/// `objects` tiny models (objects 0 … objects−1), drawn from `seed`.
inline std::vector<ObjectModel> tinyModelSet(uint64_t seed, int objects = 2) {
    std::vector<ObjectModel> set;
    for (int id = 0; id < objects; ++id) set.push_back(tinyModel(id, seed * 10 + uint64_t(id)));
    return set;
}

}  // namespace rrf::test
