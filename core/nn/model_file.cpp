// Model file reading and writing (format in nn/model.h).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "core/data/dataset_file.h"
#include "core/nn/derived_inputs_json.h"
#include "core/nn/encoding_json.h"
#include "core/nn/model_file.h"
#include "core/nn/trainer_config_json.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/json_reader.h"
#include "core/util/text_format.h"

namespace rrf {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "model files store little-endian doubles");

namespace {

using nlohmann::json;

constexpr char kMagic[8] = {'R', 'R', 'F', 'M', 'O', 'D', 'E', 'L'};
/// Version 2 adds the header's checksum to the preamble, version 3 the input encoding and its
/// parameters, version 4 the derived inputs (nn/derived_inputs.h: "input_encoding"/"derived", and
/// the input scaler then covers them); version 1 and 2 files still load (as the identity encoding),
/// version 3 files as networks without derived inputs.
constexpr uint32_t kVersion = 4;
constexpr size_t kPreambleV1 = 16;  // magic + version + header length
constexpr size_t kPreamble = 24;    // ... + checksum64 of the header
constexpr uint32_t kMaxHeader = 64u << 20;
constexpr int64_t kMaxInt = std::numeric_limits<int>::max();
/// Raw inputs an encoded network may read: records have 12 geometric inputs and a BRDF's parameters
/// (at most 7 today), with room to spare. The bound keeps a crafted header from making the encoding
/// allocate per input (an "inputs" of 2^31 was a bad_alloc, not an InputError).
constexpr int64_t kMaxEncodingInputs = 64;
/// Record counts: 2^62 is far above any dataset and, unlike INT64_MAX, exactly a double, so a float
/// field at the bound still converts to int64 without overflow.
constexpr int64_t kMaxCount = int64_t(1) << 62;

uint64_t fnv1a64(const char* p, size_t n) {
    uint64_t h = 0xCBF29CE484222325ULL;
    for (size_t i = 0; i < n; ++i) h = (h ^ uint8_t(p[i])) * 0x100000001B3ULL;
    return h;
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
    json header{
        {"format", "rrf-model"},
        {"version", kVersion},
        {"object", m.objectId},
        {"object_name", m.objectName},
        {"target", m.target},
        {"architecture",
         {{"inputs", m.arch.inputs}, {"hidden", m.arch.hidden}, {"outputs", m.arch.outputs},
          {"activation", activationName(m.arch.activation)}, {"parameters", m.arch.numParams()}}},
        {"input_encoding",
         {{"inputs", m.rawInputs()},
          {"derived", toJson(m.encoding.derived)},
          {"components", m.encoding.isIdentity() ? json::array() : toJson(m.encoding)},
          {"parameters", m.encodingParams.size()}}},
        {"trainer", toJson(m.trainer)},
        {"training",
         {{"epochs", t.epochs}, {"best_epoch", t.bestEpoch}, {"stop_reason", t.stopReason},
          {"members", t.members}, {"member_epochs", t.memberEpochs},
          {"cancelled", t.cancelled}, {"seconds", num(t.seconds)},
          {"samples", {{"train", t.trainSamples}, {"validation", t.validationSamples}, {"test", t.testSamples},
                       {"train_used", t.trainSamplesUsed}}},
          {"loss", {{"train", num(t.trainLoss)}, {"validation", num(t.validationLoss)}, {"test", num(t.testLoss)}}},
          {"rmse", {{"train", num(m.errors.train)}, {"validation", num(m.errors.validation)}, {"test", num(m.errors.test)}}},
          {"messages", t.messages},
          {"history", hist}}},
    };
    if (m.spreadMembers() > 0) {
        // The members' own output biases (nn/ensemble.h), one array per member; JSON numbers keep a
        // double's bits (nlohmann writes the shortest text that reads back to them).
        json biases = json::array();
        const Eigen::Index outs = m.arch.outputs;
        for (int k = 0; k < m.spreadMembers(); ++k) {
            json row = json::array();
            for (Eigen::Index o = 0; o < outs; ++o) row.push_back(m.memberOutputBias[Eigen::Index(k) * outs + o]);
            biases.push_back(std::move(row));
        }
        header["ensemble"] = {{"members", m.spreadMembers()}, {"output_bias", std::move(biases)}};
    }
    return header;
}

std::string modelFileBytes(const NetworkModel& model) {
    model.validate();
    std::string payload;
    appendDoubles(payload, model.params.data(), model.params.size());
    appendDoubles(payload, model.inputScaler.offset.data(), model.inputScaler.size());
    appendDoubles(payload, model.inputScaler.scale.data(), model.inputScaler.size());
    appendDoubles(payload, model.outputScaler.offset.data(), model.outputScaler.size());
    appendDoubles(payload, model.outputScaler.scale.data(), model.outputScaler.size());
    appendDoubles(payload, model.encodingParams.data(), model.encodingParams.size());

    json header = modelHeader(model);
    header["payload"] = {{"encoding", "float64-le"},
                         {"order", {"params", "input_offset", "input_scale", "output_offset", "output_scale", "encoding_params"}},
                         {"bytes", payload.size()},
                         {"fnv1a64", hexString16(fnv1a64(payload.data(), payload.size()))}};
    const std::string h = header.dump(1);
    const uint32_t version = kVersion, hlen = uint32_t(h.size());
    const uint64_t headerChecksum = checksum64(h.data(), h.size());

    std::string bytes(kMagic, sizeof kMagic);
    bytes.append(reinterpret_cast<const char*>(&version), 4);
    bytes.append(reinterpret_cast<const char*>(&hlen), 4);
    bytes.append(reinterpret_cast<const char*>(&headerChecksum), 8);
    bytes += h;
    bytes += payload;
    return bytes;
}

void saveModel(const NetworkModel& model, const std::string& path) {
    const std::string bytes = modelFileBytes(model);
    AtomicFile f(path);
    f.write(bytes);
    f.commit();
}

NetworkModel loadModel(const std::string& path) {
    std::string bytes;
    try {
        bytes = readFile(path);
    } catch (const std::exception& e) {
        throw InputError(path, "", std::string("cannot read model file: ") + e.what());
    }
    return parseModel(bytes, path);
}

NetworkModel parseModel(const std::string& bytes, const std::string& path) {
    auto fail = [&](const std::string& where, const std::string& what) -> void { throw InputError(path, where, what); };

    if (bytes.size() < kPreambleV1) fail("", "truncated model file (" + std::to_string(bytes.size()) + " bytes)");
    if (std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) fail("", "not an RRF model file (bad magic)");
    uint32_t version = 0, hlen = 0;
    std::memcpy(&version, bytes.data() + 8, 4);
    std::memcpy(&hlen, bytes.data() + 12, 4);
    if (version < 1 || version > kVersion)
        fail("", "unsupported model file version " + std::to_string(version) + " (this build reads 1 … " +
                     std::to_string(kVersion) + ")");
    const size_t preamble = version == 1 ? kPreambleV1 : kPreamble;
    if (bytes.size() < preamble) fail("", "truncated model file (" + std::to_string(bytes.size()) + " bytes)");
    if (hlen > kMaxHeader || preamble + hlen > bytes.size())
        fail("header", "truncated model file (header of " + std::to_string(hlen) + " bytes does not fit)");
    if (version >= 2) {
        uint64_t stored = 0;
        std::memcpy(&stored, bytes.data() + 16, 8);
        if (stored != checksum64(bytes.data() + preamble, hlen))
            fail("header", "checksum mismatch: the header was changed or damaged after it was written");
    }

    json h;
    try {
        h = json::parse(bytes.begin() + long(preamble), bytes.begin() + long(preamble + hlen));
    } catch (const json::exception& e) {
        fail("header", std::string("malformed JSON header: ") + e.what());
    }

    // Typed reads (core/util/json_reader.h): an integer field holding 1e300 or "3" is an InputError
    // naming the field, never a float-to-int conversion out of range.
    const JsonReader header(h, path, "header");
    // A checksummed header repeats the version: a damaged preamble version, which the header's checksum
    // does not cover, would otherwise read a version 3 file as version 2 (version 1 headers are unchecked).
    if (version >= 2 && header.has("version") && header.at("version").integer(0, kMaxInt) != int64_t(version))
        fail("header/version", "the header says version " + header.value().at("version").dump() + ", the preamble " +
                                   std::to_string(version));
    NetworkModel m;
    try {
        const JsonReader a = header.at("architecture");
        m.arch.inputs = int(a.at("inputs").integer(1, kMaxInt));
        const JsonReader hidden = a.at("hidden");
        const size_t layers = hidden.requireArray();
        m.arch.hidden.clear();  // MlpArch's default layers are not the file's
        for (size_t i = 0; i < layers; ++i) m.arch.hidden.push_back(int(hidden.at(i).integer(1, kMaxInt)));
        m.arch.outputs = int(a.at("outputs").integer(1, kMaxInt));
        m.arch.activation = parseActivation(a.at("activation").string());
        m.arch.validate();
        m.objectId = int(header.at("object").integer(-1, kMaxInt));
        m.objectName = header.at("object_name").string();
        m.target = header.at("target").string();
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        fail("header/architecture", std::string("bad architecture: ") + e.what());
    }
    m.encoding.inputs = m.arch.inputs;  // versions 1 and 2: the identity
    if (version >= 3) {
        const JsonReader e = header.at("input_encoding");
        const int inputs = int(e.at("inputs").integer(1, kMaxEncodingInputs));
        // Version 3 files derive nothing; version 4 files always say what they derive.
        const DerivedInputs derived = version >= 4 ? derivedInputsFromJson(e.at("derived")) : DerivedInputs();
        if (derived.any() && inputs < kNormalInput + 3)
            fail("header/input_encoding/derived", "derived inputs need the 12 geometric record inputs, the network reads " +
                                                      std::to_string(inputs));
        m.encoding = inputEncodingFromJson(e.at("components"), inputs, derived);
        const int features = m.encoding.outputs();  // the identity: the raw and derived inputs
        if (features != m.arch.inputs)
            fail("header/input_encoding", "the encoding " + m.encoding.describe() + " writes " + std::to_string(features) +
                                              " features, the " + m.arch.describe() + " network reads " +
                                              std::to_string(m.arch.inputs));
    }
    try {
        m.trainer = trainerConfigFromJson(header.at("trainer"));
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        fail("header/trainer", e.what());
    }
    try {
        const JsonReader t = header.at("training");
        TrainResult& r = m.training;
        r.epochs = int(t.at("epochs").integer(0, kMaxInt));
        r.bestEpoch = int(t.at("best_epoch").integer(-1, kMaxInt));
        r.stopReason = t.at("stop_reason").string();
        // An ensemble's size and all its members' epochs (nn/ensemble.h); files before them: one network.
        r.members = int(t.integerOr("members", 1, 1, kMaxInt));
        r.memberEpochs = t.integerOr("member_epochs", r.epochs, 0, kMaxCount);
        r.cancelled = t.at("cancelled").boolean();
        r.seconds = num(t.value().at("seconds"));
        const JsonReader s = t.at("samples");
        r.trainSamples = s.at("train").integer(0, kMaxCount);
        r.validationSamples = s.at("validation").integer(0, kMaxCount);
        r.testSamples = s.at("test").integer(0, kMaxCount);
        r.trainSamplesUsed = s.at("train_used").integer(0, kMaxCount);
        const json& tj = t.value();
        r.trainLoss = num(tj.at("loss").at("train"));
        r.validationLoss = num(tj.at("loss").at("validation"));
        r.testLoss = num(tj.at("loss").at("test"));
        m.errors.train = num(tj.at("rmse").at("train"));
        m.errors.validation = num(tj.at("rmse").at("validation"));
        m.errors.test = num(tj.at("rmse").at("test"));
        const JsonReader messages = t.at("messages");
        for (size_t i = 0, n = messages.requireArray(); i < n; ++i) r.messages.push_back(messages.at(i).string());
        const JsonReader hist = t.at("history");
        const JsonReader epochs = hist.at("epoch");
        const size_t n = epochs.requireArray();
        for (const char* k : {"train", "validation", "step", "seconds"})
            if (hist.at(k).requireArray() != n) fail("header/training/history", "history columns differ in length");
        const json& hj = hist.value();
        for (size_t i = 0; i < n; ++i)
            r.history.push_back({int(epochs.at(i).integer(0, kMaxInt)), num(hj["train"][i]), num(hj["validation"][i]),
                                 num(hj["step"][i]), num(hj["seconds"][i])});
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        fail("header/training", std::string("bad training record: ") + e.what());
    }
    if (const std::optional<JsonReader> ens = header.find("ensemble")) {
        // An ensemble's members' output biases (files before them have none: no spread).
        ens->checkKeys({"members", "output_bias"});
        const int k = int(ens->at("members").integer(2, kMaxInt));
        const JsonReader rows = ens->at("output_bias");
        if (rows.requireArray() != size_t(k))
            fail("header/ensemble/output_bias", "expected " + std::to_string(k) + " members' biases, got " +
                                                    std::to_string(rows.value().size()));
        const Eigen::Index outs = m.arch.outputs;
        m.memberOutputBias.resize(Eigen::Index(k) * outs);
        for (int j = 0; j < k; ++j) {
            const JsonReader row = rows.at(size_t(j));
            if (row.requireArray() != size_t(outs))
                fail("header/ensemble/output_bias/" + std::to_string(j),
                     "expected " + std::to_string(outs) + " biases (one per output), got " + std::to_string(row.value().size()));
            for (Eigen::Index o = 0; o < outs; ++o) m.memberOutputBias[Eigen::Index(j) * outs + o] = row.at(size_t(o)).number();
        }
    }

    const size_t P = size_t(m.arch.numParams()), in = size_t(m.scaledInputs()), out = size_t(m.arch.outputs);
    const size_t E = size_t(m.encoding.isIdentity() ? 0 : m.encoding.numParams());
    const size_t expected = size_t(modelPayloadBytes(m));
    const size_t have = bytes.size() - preamble - hlen;
    const JsonReader payload = header.at("payload");
    const uint64_t declared = payload.at("bytes").unsignedInteger();
    const std::string checksum = payload.at("fnv1a64").string();
    if (declared != expected)
        fail("header/payload/bytes", "payload of " + std::to_string(declared) + " bytes declared, the " +
                                         m.arch.describe() + " network needs " + std::to_string(expected));
    if (have < expected)
        fail("payload", "truncated model file: payload has " + std::to_string(have) + " of " +
                            std::to_string(expected) + " bytes");
    if (have > expected) fail("payload", std::to_string(have - expected) + " unexpected bytes after the payload");
    const char* p = bytes.data() + preamble + hlen;
    if (hexString16(fnv1a64(p, expected)) != checksum) fail("payload", "checksum mismatch: the file is corrupted");

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
    m.encodingParams = readVec(E);
    try {
        m.validate();
    } catch (const std::exception& e) {
        fail("payload", e.what());
    }
    return m;
}

}  // namespace rrf
