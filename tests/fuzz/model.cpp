// libFuzzer target: the model file reader (loadModel, a ".rrfm" file: magic, version, JSON header,
// float64 payload under an FNV-1a checksum), fed through a file as the programs read it. The
// header is parsed and checked before the payload checksum, so mutations of the header reach every
// field. A loaded model must also validate and predict one input. Only an InputError may come out
// (tests/fuzz/fuzz_input.h).
#include <cstddef>
#include <cstdint>

#include "core/nn/model.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = rrf::fuzz::writeInput("model.rrfm", data, size);
    rrf::fuzz::expectOnlyInputErrors([&] {
        const rrf::NetworkModel m = rrf::loadModel(path);
        // A model the loader accepted is one the predictor may use: it must hold together.
        m.validate();
        const rrf::MatX<float> in = rrf::MatX<float>::Zero(m.arch.inputs, 1);
        (void)m.predict(in);
    });
    return 0;
}
