#include "core/pipeline/experiment.h"

#include "core/nn/training_samples.h"

namespace rrf {

std::vector<ObjectSamples> samplesFromGenerated(const GeneratedData& data, const Scene& scene, const RecordLayout& layout) {
    const int in = layout.inputCount(), fpr = layout.floatsPerRecord();
    std::vector<ObjectSamples> out;
    uint64_t dropped = 0;  // the generator writes finite records only, so this stays 0
    for (size_t id = 0; id < data.perObject.size() && id < scene.objects.size(); ++id) {
        const std::vector<float>& r = data.perObject[id];
        out.push_back(objectSamples(int(id), scene.objects[id].name, r.data(), r.size() / size_t(fpr), in,
                                    layout.noiseCount() > 0, dropped));
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
