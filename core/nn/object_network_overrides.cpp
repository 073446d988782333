#include "core/nn/object_network_overrides.h"

namespace rrf {

ObjectNetworkChoice objectNetworkChoice(const ObjectNetworkChoice& base, const ObjectNetworkOverrides& overrides,
                                        const std::string& name) {
    ObjectNetworkChoice c = base;
    const auto it = overrides.find(name);
    if (it == overrides.end()) return c;
    const ObjectNetworkOverride& o = it->second;
    if (o.hidden) c.hidden = *o.hidden;
    if (o.inputs) c.inputs = *o.inputs;
    if (o.encoding) c.encoding = *o.encoding;
    return c;
}

namespace {
template <typename Field>
void dropOverrides(ObjectNetworkOverrides& overrides, Field field) {
    for (auto it = overrides.begin(); it != overrides.end();) {
        (it->second.*field).reset();
        it = it->second.empty() ? overrides.erase(it) : std::next(it);
    }
}
}  // namespace

void dropHiddenOverrides(ObjectNetworkOverrides& overrides) { dropOverrides(overrides, &ObjectNetworkOverride::hidden); }
void dropInputsOverrides(ObjectNetworkOverrides& overrides) { dropOverrides(overrides, &ObjectNetworkOverride::inputs); }
void dropEncodingOverrides(ObjectNetworkOverrides& overrides) {
    dropOverrides(overrides, &ObjectNetworkOverride::encoding);
}

}  // namespace rrf
