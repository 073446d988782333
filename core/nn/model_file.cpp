// Model file reading and writing (format in nn/model.h).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/nn/model.h"

namespace rrf {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "model files store little-endian doubles");

namespace {

using nlohmann::json;

constexpr char kMagic[8] = {'R', 'R', 'F', 'M', 'O', 'D', 'E', 'L'};
constexpr uint32_t kVersion = 1;
constexpr size_t kPreamble = 16;  // magic + version + header length
constexpr uint32_t kMaxHeader = 64u << 20;

uint64_t fnv1a64(const char* p, size_t n) {
    uint64_t h = 0xCBF29CE484222325ULL;
    for (size_t i = 0; i < n; ++i) h = (h ^ uint8_t(p[i])) * 0x100000001B3ULL;
    return h;
}

std::string hex64(uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

/// NaN (an empty validation set) has no JSON spelling: it becomes null and back.
json num(double d) { return std::isfinite(d) ? json(d) : json(nullptr); }
double num(const json& j) { return j.is_number() ? j.get<double>() : std::numeric_limits<double>::quiet_NaN(); }

void appendDoubles(std::string& out, const double* p, Eigen::Index n) {
    out.append(reinterpret_cast<const char*>(p), size_t(n) * sizeof(double));
}

}  // namespace

json modelHeader(const NetworkModel& m) {
    const TrainResult& t = m.training;
    json hist = {{"epoch", json::array()}, {"train", json::array()}, {"validation", json::array()},
                 {"step", json::array()}, {"seconds", json::array()}};
    for (const EpochRecord& r : t.history) {
        hist["epoch"].push_back(r.epoch);
        hist["train"].push_back(num(r.trainLoss));
        hist["validation"].push_back(num(r.validationLoss));
        hist["step"].push_back(num(r.step));
        hist["seconds"].push_back(num(r.seconds));
    }
    return json{
        {"format", "rrf-model"},
        {"version", kVersion},
        {"object", m.objectId},
        {"object_name", m.objectName},
        {"target", m.target},
        {"architecture",
         {{"inputs", m.arch.inputs}, {"hidden", m.arch.hidden}, {"outputs", m.arch.outputs},
          {"activation", activationName(m.arch.activation)}, {"parameters", m.arch.numParams()}}},
        {"trainer", m.trainer.toJson()},
        {"training",
         {{"epochs", t.epochs}, {"best_epoch", t.bestEpoch}, {"stop_reason", t.stopReason},
          {"cancelled", t.cancelled}, {"seconds", num(t.seconds)},
          {"samples", {{"train", t.trainSamples}, {"validation", t.validationSamples}, {"test", t.testSamples},
                       {"train_used", t.trainSamplesUsed}}},
          {"loss", {{"train", num(t.trainLoss)}, {"validation", num(t.validationLoss)}, {"test", num(t.testLoss)}}},
          {"rmse", {{"train", num(m.errors.train)}, {"validation", num(m.errors.validation)}, {"test", num(m.errors.test)}}},
          {"messages", t.messages},
          {"history", hist}}},
    };
}

void saveModel(const NetworkModel& model, const std::string& path) {
    model.validate();
    std::string payload;
    appendDoubles(payload, model.params.data(), model.params.size());
    appendDoubles(payload, model.inputScaler.offset.data(), model.inputScaler.size());
    appendDoubles(payload, model.inputScaler.scale.data(), model.inputScaler.size());
    appendDoubles(payload, model.outputScaler.offset.data(), model.outputScaler.size());
    appendDoubles(payload, model.outputScaler.scale.data(), model.outputScaler.size());

    json header = modelHeader(model);
    header["payload"] = {{"encoding", "float64-le"},
                         {"order", {"params", "input_offset", "input_scale", "output_offset", "output_scale"}},
                         {"bytes", payload.size()},
                         {"fnv1a64", hex64(fnv1a64(payload.data(), payload.size()))}};
    const std::string h = header.dump(1);
    const uint32_t version = kVersion, hlen = uint32_t(h.size());

    AtomicFile f(path);
    f.write(kMagic, sizeof kMagic);
    f.write(&version, 4);
    f.write(&hlen, 4);
    f.write(h);
    f.write(payload);
    f.commit();
}

NetworkModel loadModel(const std::string& path) {
    std::string bytes;
    try {
        bytes = readFile(path);
    } catch (const std::exception& e) {
        throw InputError(path, "", std::string("cannot read model file: ") + e.what());
    }
    auto fail = [&](const std::string& where, const std::string& what) -> void { throw InputError(path, where, what); };

    if (bytes.size() < kPreamble) fail("", "truncated model file (" + std::to_string(bytes.size()) + " bytes)");
    if (std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) fail("", "not an RRF model file (bad magic)");
    uint32_t version = 0, hlen = 0;
    std::memcpy(&version, bytes.data() + 8, 4);
    std::memcpy(&hlen, bytes.data() + 12, 4);
    if (version != kVersion) fail("", "unsupported model file version " + std::to_string(version));
    if (hlen > kMaxHeader || kPreamble + hlen > bytes.size())
        fail("header", "truncated model file (header of " + std::to_string(hlen) + " bytes does not fit)");

    json h;
    try {
        h = json::parse(bytes.begin() + long(kPreamble), bytes.begin() + long(kPreamble + hlen));
    } catch (const json::exception& e) {
        fail("header", std::string("malformed JSON header: ") + e.what());
    }

    NetworkModel m;
    try {
        const json& a = h.at("architecture");
        m.arch.inputs = a.at("inputs").get<int>();
        m.arch.hidden = a.at("hidden").get<std::vector<int>>();
        m.arch.outputs = a.at("outputs").get<int>();
        m.arch.activation = parseActivation(a.at("activation").get<std::string>());
        m.arch.validate();
        m.objectId = h.at("object").get<int>();
        m.objectName = h.at("object_name").get<std::string>();
        m.target = h.at("target").get<std::string>();
    } catch (const std::exception& e) {
        fail("header/architecture", std::string("bad architecture: ") + e.what());
    }
    try {
        m.trainer = TrainerConfig::fromJson(h.at("trainer"), path, "header/trainer");
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        fail("header/trainer", e.what());
    }
    try {
        const json& t = h.at("training");
        TrainResult& r = m.training;
        r.epochs = t.at("epochs").get<int>();
        r.bestEpoch = t.at("best_epoch").get<int>();
        r.stopReason = t.at("stop_reason").get<std::string>();
        r.cancelled = t.at("cancelled").get<bool>();
        r.seconds = num(t.at("seconds"));
        const json& s = t.at("samples");
        r.trainSamples = s.at("train").get<int64_t>();
        r.validationSamples = s.at("validation").get<int64_t>();
        r.testSamples = s.at("test").get<int64_t>();
        r.trainSamplesUsed = s.at("train_used").get<int64_t>();
        r.trainLoss = num(t.at("loss").at("train"));
        r.validationLoss = num(t.at("loss").at("validation"));
        r.testLoss = num(t.at("loss").at("test"));
        m.errors.train = num(t.at("rmse").at("train"));
        m.errors.validation = num(t.at("rmse").at("validation"));
        m.errors.test = num(t.at("rmse").at("test"));
        r.messages = t.at("messages").get<std::vector<std::string>>();
        const json& hist = t.at("history");
        const size_t n = hist.at("epoch").size();
        for (const char* k : {"train", "validation", "step", "seconds"})
            if (hist.at(k).size() != n) fail("header/training/history", "history columns differ in length");
        for (size_t i = 0; i < n; ++i)
            r.history.push_back({hist["epoch"][i].get<int>(), num(hist["train"][i]), num(hist["validation"][i]),
                                 num(hist["step"][i]), num(hist["seconds"][i])});
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        fail("header/training", std::string("bad training record: ") + e.what());
    }

    const size_t P = size_t(m.arch.numParams()), in = size_t(m.arch.inputs), out = size_t(m.arch.outputs);
    const size_t expected = (P + 2 * in + 2 * out) * sizeof(double);
    const size_t have = bytes.size() - kPreamble - hlen;
    uint64_t declared = 0;
    std::string checksum;
    try {
        declared = h.at("payload").at("bytes").get<uint64_t>();
        checksum = h.at("payload").at("fnv1a64").get<std::string>();
    } catch (const std::exception& e) {
        fail("header/payload", e.what());
    }
    if (declared != expected)
        fail("header/payload/bytes", "payload of " + std::to_string(declared) + " bytes declared, the " +
                                         m.arch.describe() + " network needs " + std::to_string(expected));
    if (have < expected)
        fail("payload", "truncated model file: payload has " + std::to_string(have) + " of " +
                            std::to_string(expected) + " bytes");
    if (have > expected) fail("payload", std::to_string(have - expected) + " unexpected bytes after the payload");
    const char* p = bytes.data() + kPreamble + hlen;
    if (hex64(fnv1a64(p, expected)) != checksum) fail("payload", "checksum mismatch: the file is corrupted");

    auto readVec = [&](size_t n) {
        VecX<double> v(Eigen::Index(n), 1);
        if (n) std::memcpy(v.data(), p, n * sizeof(double));
        p += n * sizeof(double);
        return v;
    };
    m.params = readVec(P);
    m.inputScaler.offset = readVec(in);
    m.inputScaler.scale = readVec(in);
    m.outputScaler.offset = readVec(out);
    m.outputScaler.scale = readVec(out);
    try {
        m.validate();
    } catch (const std::exception& e) {
        fail("payload", e.what());
    }
    return m;
}

}  // namespace rrf
