#pragma once
/// Small models for the tests: trained model sets for the tests of files that hold them (model sets
/// replaced as a whole, their refusals, a full disk): networks of 3 inputs, 4 hidden units and 3
/// outputs, fitted for 2 epochs, so they are real trained models but cost milliseconds; and networks
/// built by hand whose outputs are known exactly (the prediction tests).

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/nn/model.h"
#include "core/nn/model_set.h"
#include "core/nn/trainer_config.h"
#include "core/data/record_layout.h"
#include "core/nn/trainer_config_json.h"
#include "core/scene/scene.h"
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
    NetworkModel net = fitNetwork(a, trainerConfigFromJson({{"max_epochs", 2}}), x, y);
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

/// ReLU network in → 2·outputs → outputs with relu(x_k) − relu(−x_k) = x_k exactly on every output
/// row (`rows[o]` = which input output o copies). Identity scalers, so raw in = raw out.
inline NetworkModel copyInputNet(int inputs, const std::vector<int>& rows) {
    NetworkModel m;
    m.arch.inputs = inputs;
    m.arch.outputs = int(rows.size());
    m.arch.activation = Activation::Relu;
    m.arch.hidden = {2 * int(rows.size())};
    m.params = VecX<double>::Zero(m.arch.numParams());
    const int h = m.arch.hidden[0];
    for (size_t o = 0; o < rows.size(); ++o) {
        // W0 is h × inputs column-major: entry (r, c) at r + h·c.
        m.params[m.arch.weightOffset(0) + Eigen::Index(2 * o) + Eigen::Index(h) * rows[o]] = 1.0;
        m.params[m.arch.weightOffset(0) + Eigen::Index(2 * o + 1) + Eigen::Index(h) * rows[o]] = -1.0;
        // W1 is outputs × h: entry (o, 2o) = 1, (o, 2o+1) = -1.
        m.params[m.arch.weightOffset(1) + Eigen::Index(o) + Eigen::Index(rows.size()) * Eigen::Index(2 * o)] = 1.0;
        m.params[m.arch.weightOffset(1) + Eigen::Index(o) + Eigen::Index(rows.size()) * Eigen::Index(2 * o + 1)] = -1.0;
    }
    m.inputScaler = MinMaxScaler::identity(inputs);
    m.outputScaler = MinMaxScaler::identity(m.arch.outputs);
    m.validate();
    return m;
}

/// For every object of `s`, networks of each target in `targets` that answer the first three BRDF
/// inputs (the diffuse albedo kd, record inputs 12..14): radiance kd per term, whatever the light.
inline ModelSet albedoModels(const Scene& s, const std::vector<std::string>& targets) {
    ModelSet set;
    const RecordLayout layout = RecordLayout::forScene(s);
    set.inputLayout = layout.inputs;
    for (const Object& o : s.objects) {
        ObjectNetworks n;
        n.objectId = o.id;
        n.name = o.name;
        for (const std::string& t : targets) n.byTarget.emplace(t, copyInputNet(layout.inputCount(), {12, 13, 14}));
        set.objects.push_back(std::move(n));
    }
    return set;
}

}  // namespace rrf::test
