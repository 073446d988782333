// libFuzzer target: the OBJ + MTL reader (core/scene/obj_loader.cpp with its text scan,
// obj_text_scan.cpp) and the scene builder's OBJ shapes (scene_obj_shapes.cpp: MTL materials, Ke
// emitters as rect and triangle lights, the derived light region). One input holds both files: the
// OBJ text, then — after a line "#MTL" (a comment to the OBJ reader; any line ending) — the text
// of the MTL library it may name as "input.mtl".
// Each input is read twice, as a scene shape with its own materials and emitters (the MTL in use)
// and as one with a JSON material (the MTL ignored). Only an InputError may come out
// (tests/fuzz/fuzz_input.h), and a scene that was accepted must keep the promises the reader makes
// (core/scene/radiometric_range.h): emission, exponents and light sizes within their bounds,
// albedos finite and energy-conserving.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "core/scene/radiometric_range.h"
#include "core/scene/scene_json.h"
#include "tests/fuzz/fuzz_input.h"

namespace {

const char* const kSeparator = "\n#MTL";

/// Aborts (a finding) if the accepted scene holds a value the reader promises to refuse.
void checkPromises(const rrf::Scene& scene) {
    for (const rrf::Light& l : scene.lights) {
        if (!rrf::emissionProblem(l.isArea() ? l.radiance : l.intensity, "emission").empty())
            rrf::fuzz::finding("an accepted light", "emission outside the radiometric range");
        if (l.isArea() && !rrf::lightSizeProblem(l.edge1, l.edge2).empty())
            rrf::fuzz::finding("an accepted light", "smaller than the smallest light");
    }
    for (const rrf::Material& m : scene.materials) {
        if (!rrf::exponentProblem(m.exponent, "exponent").empty())
            rrf::fuzz::finding("an accepted material", "exponent outside its range");
        for (int i = 0; i < 3; ++i)
            if (!(m.kd[i] >= 0.f && m.ks[i] >= 0.f && double(m.kd[i]) + m.ks[i] <= 1.0 + 1e-5))
                rrf::fuzz::finding("an accepted material", "kd or ks negative, not finite or above energy conservation");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const size_t cut = text.find(kSeparator);
    const size_t mtlStart = cut == std::string::npos ? std::string::npos : text.find('\n', cut + 1);
    const std::string obj = cut == std::string::npos ? text : text.substr(0, cut + 1);
    const std::string mtl = mtlStart == std::string::npos ? "" : text.substr(mtlStart + 1);
    rrf::fuzz::writeInput("input.obj", reinterpret_cast<const uint8_t*>(obj.data()), obj.size());
    rrf::fuzz::writeInput("input.mtl", reinterpret_cast<const uint8_t*>(mtl.data()), mtl.size());

    const nlohmann::json camera = {{"eye", {0, 0.5, 4}}, {"target", {0, 0.5, 0}}, {"fov_y", 40}, {"width", 8}, {"height", 8}};
    const std::string file = rrf::fuzz::scratchDir() + "/scene.json";
    const nlohmann::json own = {{"camera", camera}, {"shapes", {{{"type", "obj"}, {"file", "input.obj"}}}}};
    const nlohmann::json plain = {
        {"camera", camera},
        {"materials", {{"grey", {{"type", "lambert"}, {"albedo", {0.5, 0.5, 0.5}}}}}},
        {"shapes", {{{"type", "obj"}, {"file", "input.obj"}, {"material", "grey"}}}},
        {"lights", {{{"type", "point"}, {"position", {0, 3, 0}}, {"intensity", {1, 1, 1}}}}}};
    for (const nlohmann::json* doc : {&own, &plain})
        rrf::fuzz::expectOnlyInputErrors([&] { checkPromises(rrf::parseScene(*doc, file, rrf::fuzz::scratchDir())); });
    return 0;
}
