// Model files: bit-exact round trip and clear errors for damaged files.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>

#include <unistd.h>

#include "core/data/dataset_file.h"
#include "core/nn/trainer_config_json.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/nn/model.h"
#include "core/util/rng.h"

namespace test_nn_model_file {

using namespace rrf;
namespace fs = std::filesystem;

namespace {

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() /
               ("rrf_nn_model_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter()++));
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    std::string file(const std::string& name) const { return (path / name).string(); }
    static int& counter() {
        static int c = 0;
        return c;
    }
};

NetworkModel trainedModel() {
    MlpArch a;
    a.inputs = 5;
    a.hidden = {7, 4};
    a.outputs = 6;
    MatX<float> x(5, 120), y(6, 120);
    for (int c = 0; c < 120; ++c) {
        Rng rng(21, uint64_t(c));
        for (int r = 0; r < 5; ++r) x(r, c) = rng.uniform() * 10.f - 3.f;
        for (int r = 0; r < 6; ++r) y(r, c) = std::exp(0.3f * x(r % 5, c)) + 0.1f * r;
    }
    NetworkModel m = fitNetwork(a, trainerConfigFromJson({{"max_epochs", 5}}), x, y);
    m.objectId = 4;
    m.objectName = "small box";
    m.target = "joint";
    return m;
}

std::string errorOf(const std::string& path) {
    try {
        loadModel(path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

uint64_t fnv1a64(const char* p, size_t n) {
    uint64_t h = 0xCBF29CE484222325ULL;
    for (size_t i = 0; i < n; ++i) h = (h ^ uint8_t(p[i])) * 0x100000001B3ULL;
    return h;
}

/// Rewrites a model file (version 2: 24-byte preamble with the header's checksum64) with `editHeader`
/// applied to its JSON header and `edit` to its payload, and matching checksums, so that the
/// loader's own validation (not a checksum) must catch the defect.
void rewrite(const std::string& path, const std::function<void(std::string&)>& editHeader,
             const std::function<void(std::string&)>& edit) {
    std::string bytes = readFile(path);
    uint32_t hlen = 0;
    std::memcpy(&hlen, bytes.data() + 12, 4);
    std::string hs = bytes.substr(24, hlen);
    std::string payload = bytes.substr(24 + hlen);
    edit(payload);
    nlohmann::json h = nlohmann::json::parse(hs);
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a64(payload.data(), payload.size())));
    h["payload"]["fnv1a64"] = hex;
    hs = h.dump();
    editHeader(hs);
    hlen = uint32_t(hs.size());
    const uint64_t sum = checksum64(hs.data(), hs.size());
    std::string out = bytes.substr(0, 12);
    out.append(reinterpret_cast<const char*>(&hlen), 4);
    out.append(reinterpret_cast<const char*>(&sum), 8);
    writeFileAtomically(path, out + hs + payload);
}

void editPayload(const std::string& path, const std::function<void(std::string&)>& edit) {
    rewrite(path, [](std::string&) {}, edit);
}

}  // namespace

TEST(ModelFile, RoundTripIsBitExact) {
    TempDir dir;
    const NetworkModel m = trainedModel();
    const std::string path = dir.file("m.rrfm");
    saveModel(m, path);
    const NetworkModel l = loadModel(path);
    EXPECT_EQ(l.arch, m.arch);
    ASSERT_EQ(l.params.size(), m.params.size());
    EXPECT_EQ(std::memcmp(l.params.data(), m.params.data(), size_t(m.params.size()) * 8), 0);
    EXPECT_EQ(l.inputScaler.scale, m.inputScaler.scale);
    EXPECT_EQ(l.outputScaler.offset, m.outputScaler.offset);
    EXPECT_EQ(l.objectId, 4);
    EXPECT_EQ(l.objectName, "small box");
    EXPECT_EQ(l.target, "joint");
    EXPECT_EQ(toJson(l.trainer), toJson(m.trainer));
    ASSERT_EQ(l.training.history.size(), m.training.history.size());
    for (size_t i = 0; i < l.training.history.size(); ++i) {
        EXPECT_EQ(l.training.history[i].trainLoss, m.training.history[i].trainLoss);
        EXPECT_EQ(l.training.history[i].step, m.training.history[i].step);
    }
    EXPECT_EQ(l.training.stopReason, m.training.stopReason);
    EXPECT_EQ(l.errors.test, m.errors.test);

    MatX<float> x(5, 3000);
    for (int c = 0; c < 3000; ++c) {
        Rng rng(5, uint64_t(c));
        for (int r = 0; r < 5; ++r) x(r, c) = rng.uniform() * 12.f - 4.f;
    }
    const MatX<float> pm = m.predict(x), pl = l.predict(x);
    EXPECT_EQ(std::memcmp(pm.data(), pl.data(), size_t(pm.size()) * 4), 0);
    EXPECT_EQ(m.predictDouble(x.cast<double>()), l.predictDouble(x.cast<double>()));
    // Saving the loaded model reproduces the file byte for byte.
    saveModel(l, dir.file("again.rrfm"));
    EXPECT_EQ(readFile(path), readFile(dir.file("again.rrfm")));
}

TEST(ModelFile, EmptyValidationSetRoundTrips) {
    TempDir dir;
    MlpArch a;
    a.inputs = 2;
    a.hidden = {3};
    MatX<float> x(2, 1), y(3, 1);
    x << 1, 2;
    y << 3, 4, 5;
    const NetworkModel m = fitNetwork(a, trainerConfigFromJson({{"max_epochs", 3}}), x, y);
    EXPECT_TRUE(std::isnan(m.errors.validation));
    saveModel(m, dir.file("one.rrfm"));
    const NetworkModel l = loadModel(dir.file("one.rrfm"));
    EXPECT_TRUE(std::isnan(l.errors.validation));
    EXPECT_TRUE(std::isnan(l.training.history[0].validationLoss));
    EXPECT_EQ(l.predict(x), m.predict(x));
}

TEST(ModelFile, DamagedFilesNameTheFile) {
    TempDir dir;
    const NetworkModel m = trainedModel();
    const std::string good = dir.file("good.rrfm");
    saveModel(m, good);
    const std::string bytes = readFile(good);
    auto variant = [&](const std::string& name, const std::string& content) {
        const std::string p = dir.file(name);
        writeFileAtomically(p, content);
        return p;
    };

    const std::string missing = dir.file("missing.rrfm");
    EXPECT_NE(errorOf(missing).find(missing), std::string::npos);

    std::string p = variant("short.rrfm", bytes.substr(0, 10));
    EXPECT_NE(errorOf(p).find("short.rrfm"), std::string::npos);
    EXPECT_NE(errorOf(p).find("truncated"), std::string::npos);

    p = variant("cut.rrfm", bytes.substr(0, bytes.size() - 9));
    EXPECT_NE(errorOf(p).find("truncated"), std::string::npos);

    p = variant("cuthdr.rrfm", bytes.substr(0, 100));
    EXPECT_NE(errorOf(p).find("cuthdr.rrfm"), std::string::npos);

    std::string magic = bytes;
    magic[0] = 'X';
    p = variant("magic.rrfm", magic);
    EXPECT_NE(errorOf(p).find("bad magic"), std::string::npos);

    p = variant("extra.rrfm", bytes + "junk");
    EXPECT_NE(errorOf(p).find("unexpected bytes"), std::string::npos);

    std::string flipped = bytes;
    flipped[flipped.size() - 20] ^= 0x40;
    p = variant("flip.rrfm", flipped);
    EXPECT_NE(errorOf(p).find("checksum"), std::string::npos);

    p = variant("nan.rrfm", bytes);
    editPayload(p, [](std::string& pl) {
        const double nan = std::nan("");
        std::memcpy(&pl[8 * 3], &nan, 8);
    });
    EXPECT_NE(errorOf(p).find("non-finite weight at index 3"), std::string::npos);

    p = variant("zeroscale.rrfm", bytes);
    editPayload(p, [&](std::string& pl) {
        const double zero = 0;
        std::memcpy(&pl[8 * size_t(m.arch.numParams() + 5)], &zero, 8);  // input_scale[0]
    });
    EXPECT_NE(errorOf(p).find("normalisation"), std::string::npos);

    // Header claiming a different architecture than the payload holds.
    p = variant("arch.rrfm", bytes);
    rewrite(p, [](std::string& h) {
        const size_t at = h.find("\"hidden\"");
        ASSERT_NE(at, std::string::npos);
        h[h.find('7', at)] = '8';
    }, [](std::string&) {});
    EXPECT_NE(errorOf(p).find("needs"), std::string::npos);

    EXPECT_NO_THROW(loadModel(good));
}

TEST(ModelFile, RefusesAnEncodingInputCountNoRecordHas) {
    // A header whose input_encoding claims 65 or 2^31 − 1 inputs: an InputError naming the file and
    // the field before anything is allocated per input (not a bad_alloc).
    TempDir dir;
    const std::string path = dir.file("wide.rrfm");
    saveModel(trainedModel(), path);
    const std::string bytes = readFile(path);
    for (const int64_t inputs : {int64_t(65), int64_t(std::numeric_limits<int>::max())}) {
        writeFileAtomically(path, bytes);
        rewrite(path, [&](std::string& h) {
            nlohmann::json j = nlohmann::json::parse(h);
            ASSERT_EQ(j.at("input_encoding").at("inputs"), 5);
            j["input_encoding"]["inputs"] = inputs;
            h = j.dump();
        }, [](std::string&) {});
        const std::string error = errorOf(path);
        EXPECT_NE(error.find("wide.rrfm"), std::string::npos) << error;
        EXPECT_NE(error.find("header/input_encoding/inputs"), std::string::npos) << error;
    }
}

TEST(ModelFile, RefusesToSaveNonFiniteWeights) {
    TempDir dir;
    NetworkModel m = trainedModel();
    m.params[0] = std::numeric_limits<double>::infinity();
    EXPECT_THROW(saveModel(m, dir.file("inf.rrfm")), std::invalid_argument);
    EXPECT_FALSE(fs::exists(dir.file("inf.rrfm")));
}

}  // namespace test_nn_model_file
