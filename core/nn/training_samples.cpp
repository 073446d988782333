#include "core/nn/training_samples.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/data/record_layout.h"

namespace rrf {

std::vector<ObjectSamples> samplesFromDataset(const Dataset& data, uint64_t* dropped) {
    const int in = data.inputCount();
    // Training reads direct RGB and indirect RGB after the inputs; a file with another target
    // layout (written by another tool) would make it read past each record.
    if (data.targetCount() != 6)
        throw std::runtime_error(data.path() + ": expected 6 targets (direct RGB, indirect RGB) after the " +
                                 std::to_string(in) + " inputs, found " + std::to_string(data.targetCount()));
    const bool withNoise = !data.noiseLayout().empty();
    if (withNoise && data.noiseLayout() != RecordLayout::noiseNames())
        throw std::runtime_error(data.path() + ": unexpected noise columns (expected the variances of direct RGB and "
                                               "indirect RGB, direct_var_r … indirect_var_b)");
    uint64_t bad = 0;
    std::vector<ObjectSamples> out;
    for (size_t i = 0; i < data.objects().size(); ++i) {
        const DatasetObject& o = data.objects()[i];
        out.push_back(objectSamples(o.id, o.name, data.records(i), size_t(o.count), in, withNoise, bad));
    }
    if (dropped) *dropped = bad;
    return out;
}

ObjectSamples objectSamples(int objectId, const std::string& name, const float* r, size_t count, int in,
                            bool withNoise, uint64_t& dropped) {
    const int fpr = in + (withNoise ? 12 : 6);
    ObjectSamples s;
    s.objectId = objectId;
    s.name = name;
    s.numInputs = in;
    s.inputs.reserve(count * size_t(in));
    s.direct.reserve(count * 3);
    s.indirect.reserve(count * 3);
    bool noiseKnown = withNoise;
    for (size_t k = 0; k < count; ++k, r += fpr) {
        bool finite = true;
        for (int c = 0; c < fpr; ++c) finite = finite && std::isfinite(r[c]);
        if (!finite) {
            ++dropped;
            continue;
        }
        s.inputs.insert(s.inputs.end(), r, r + in);
        s.direct.insert(s.direct.end(), r + in, r + in + 3);
        s.indirect.insert(s.indirect.end(), r + in + 3, r + in + 6);
        if (noiseKnown) {
            const float* v = r + in + 6;
            for (int c = 0; c < 6; ++c) noiseKnown = noiseKnown && v[c] >= 0.f;
            s.directVariance.insert(s.directVariance.end(), v, v + 3);
            s.indirectVariance.insert(s.indirectVariance.end(), v + 3, v + 6);
        }
    }
    if (!noiseKnown) {
        s.directVariance.clear();
        s.indirectVariance.clear();
    }
    return s;
}

}  // namespace rrf
