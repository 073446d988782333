#include "core/nn/encoding_settings.h"

#include <algorithm>
#include <stdexcept>

#include "core/nn/encodings/registry.h"

namespace rrf {

const EncodingType& EncodingSettings::type() const { return encodingTypeOf(params); }

EncodingSettings encodingComponent(EncodingParams params, std::vector<std::string> groups) {
    EncodingSettings c;
    c.params = params;
    c.groupsListed = groups.size() != 1;
    c.groups = std::move(groups);
    c.keys = c.type().keys;
    std::sort(c.keys.begin(), c.keys.end());
    return c;
}

bool sameEncoding(const NetworkEncodingSettings& a, const NetworkEncodingSettings& b) {
    if (a.size() != b.size()) return false;
    for (size_t k = 0; k < a.size(); ++k)
        if (a[k].params != b[k].params || a[k].groups != b[k].groups) return false;
    return true;
}

InputEncoding buildInputEncoding(const NetworkEncodingSettings& s, int inputs, const DerivedInputs& derived,
                                 const EncodingFault& fault) {
    InputEncoding e;
    e.inputs = inputs;
    e.derived = derived;
    std::vector<int> encodedBy(size_t(e.scaledInputs()), -1);  // component reading each input, −1: none yet
    int64_t offset = 0;
    for (size_t k = 0; k < s.size(); ++k) {
        const EncodingSettings& cs = s[k];
        const EncodingType& type = cs.type();
        const std::string at = "/" + std::to_string(k);
        // A lone group written as a string is the "inputs" value itself; listed groups are its elements.
        auto groupAt = [&](size_t g) { return at + "/inputs" + (cs.groupsListed ? "/" + std::to_string(g) : ""); };
        if (cs.groups.empty()) fault(at + "/inputs", "expected at least one input group");

        EncodingComponent c;
        for (size_t g = 0; g < cs.groups.size(); ++g) {
            const std::string& group = cs.groups[g];
            std::vector<int> idx;
            try {
                idx = encodingGroupInputs(group, inputs, derived);
            } catch (const std::invalid_argument& err) {
                fault(groupAt(g), err.what());
            }
            if (idx.empty()) fault(groupAt(g), "input group '" + group + "' is empty (the scene's materials have no BRDF parameters)");
            for (int i : idx) {
                if (encodedBy[size_t(i)] == int(k)) fault(groupAt(g), "input group '" + group + "' is named twice");
                if (encodedBy[size_t(i)] >= 0)
                    fault(groupAt(g), "input group '" + group + "' is already encoded by component " +
                                          std::to_string(encodedBy[size_t(i)]) + " (a group may be encoded once)");
                encodedBy[size_t(i)] = int(k);
            }
            c.groups.push_back(group);
            c.inputs.insert(c.inputs.end(), idx.begin(), idx.end());
        }

        const int dims = int(c.inputs.size());
        if (dims > type.maxInputs)
            fault(at + "/inputs", "a " + std::string(type.name) + " reads at most " + std::to_string(type.maxInputs) +
                                      " inputs, these groups have " + std::to_string(dims));
        try {
            c.encoding = type.make(cs.params, dims);
        } catch (const std::invalid_argument& err) {
            fault(at, err.what());  // hyperparameters out of range (a setting made in code; the reader checks a file's)
        }
        c.paramOffset = offset;
        offset += c.encoding->numParams();
        e.components.push_back(std::move(c));
    }
    return e;
}

}  // namespace rrf
