#include "core/nn/derived_inputs_json.h"

namespace rrf {

DerivedInputs derivedInputsFromJson(const JsonReader& r) {
    r.requireObject();
    r.checkKeys({"reflected"});
    DerivedInputs d;
    d.reflected = r.booleanOr("reflected", false);
    return d;
}

nlohmann::json toJson(const DerivedInputs& d) { return {{"reflected", d.reflected}}; }

}  // namespace rrf
