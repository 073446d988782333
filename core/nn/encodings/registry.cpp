#include "core/nn/encodings/registry.h"

#include <stdexcept>

#include "core/nn/encodings/frequency.h"
#include "core/nn/encodings/hash_grid.h"
#include "core/nn/encodings/one_blob.h"

namespace rrf {

const std::vector<const EncodingType*>& encodingTypes() {
    static const std::vector<const EncodingType*> types = {&FrequencyEncoding::type(), &OneBlobEncoding::type(),
                                                           &HashGridEncoding::type()};
    return types;
}

const EncodingType* findEncodingType(const std::string& name) {
    for (const EncodingType* t : encodingTypes())
        if (name == t->name) return t;
    return nullptr;
}

const EncodingType& encodingTypeOf(const Encoding& encoding) {
    if (const EncodingType* t = findEncodingType(encoding.typeName())) return *t;
    throw std::invalid_argument(std::string("encoding type '") + encoding.typeName() + "' is not registered");
}

const EncodingType& encodingTypeOf(const EncodingParams& params) {
    // EncodingParams' alternatives follow encodingTypes() (encodings/encoding_params.h).
    return *encodingTypes().at(params.index());
}

std::string encodingTypeNames() {
    const auto& types = encodingTypes();
    std::string s;
    for (size_t k = 0; k < types.size(); ++k) {
        if (k > 0) s += k + 1 == types.size() ? " or " : ", ";
        s += "\"" + std::string(types[k]->name) + "\"";
    }
    return s;
}

}  // namespace rrf
