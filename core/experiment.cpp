#include "core/experiment.h"

namespace rrf {

std::vector<ObjectSamples> samplesFromGenerated(const GeneratedData& data, const Scene& scene, const RecordLayout& layout) {
    const int in = layout.inputCount(), fpr = layout.floatsPerRecord();
    std::vector<ObjectSamples> out;
    for (size_t id = 0; id < data.perObject.size() && id < scene.objects.size(); ++id) {
        ObjectSamples s;
        s.objectId = int(id);
        s.name = scene.objects[id].name;
        s.numInputs = in;
        const std::vector<float>& r = data.perObject[id];
        const size_t n = r.size() / size_t(fpr);
        s.inputs.reserve(n * size_t(in));
        s.direct.reserve(n * 3);
        s.indirect.reserve(n * 3);
        for (size_t k = 0; k < n; ++k) {
            const float* rec = r.data() + k * size_t(fpr);
            s.add(rec, rec + in, rec + in + 3);
        }
        out.push_back(std::move(s));
    }
    return out;
}

ModelSet modelSetFromTrained(const std::vector<ObjectModel>& trained, const Scene& scene, const RecordLayout& layout) {
    ModelSet set;
    set.sceneHash = scene.contentHash();
    set.inputLayout = layout.inputs;
    for (const ObjectModel& m : trained) {
        if (m.skipped) continue;
        ObjectNetworks* o = nullptr;
        for (ObjectNetworks& x : set.objects)
            if (x.objectId == m.objectId) o = &x;
        if (!o) {
            set.objects.push_back({});
            o = &set.objects.back();
            o->objectId = m.objectId;
            o->name = m.objectName;
        }
        o->byTarget[m.target] = m.model;
    }
    return set;
}

}  // namespace rrf
