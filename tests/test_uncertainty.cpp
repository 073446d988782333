// An ensemble's members' spread as uncertainty (core/nn/model_members.cpp,
// core/predict/member_spread.h, core/eval/uncertainty.h): the members recovered from a merged
// network against the members' own networks evaluated alone, the spread against its definition
// (standard deviation over members with 1/K, sums within one network, variances added across two),
// the model file keeping the members' biases bit for bit and refusing ones that do not fit, and
// Spearman's rank correlation against hand-computed values.

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "core/data/dataset_file.h"
#include "core/eval/uncertainty.h"
#include "core/nn/ensemble.h"
#include "core/nn/model.h"
#include "core/predict/member_spread.h"
#include "core/predict/predictor.h"
#include "core/util/error.h"

namespace test_uncertainty {

using namespace rrf;

namespace {

MlpArch arch(int inputs, std::vector<int> hidden, int outputs) {
    MlpArch m;
    m.inputs = inputs;
    m.hidden = std::move(hidden);
    m.outputs = outputs;
    m.activation = Activation::Tanh;
    return m;
}

MinMaxScaler scaler(int n, double offset, double scale) {
    MinMaxScaler s = MinMaxScaler::identity(n);
    for (int i = 0; i < n; ++i) {
        s.offset[i] = offset + 0.1 * i;
        s.scale[i] = scale * (1.0 + 0.25 * i);
    }
    return s;
}

/// A model of one network of `member` with `params`, scalers as `base`'s.
NetworkModel single(const NetworkModel& base, const MlpArch& member, const VecX<double>& params) {
    NetworkModel m = base;
    m.arch = member;
    m.params = params;
    m.memberOutputBias.resize(0);
    m.training.members = 1;
    return m;
}

/// The merged model of `k` members of `member` (seeds from `seed`) with its members' biases.
NetworkModel ensemble(const MlpArch& member, int k, uint64_t seed, std::vector<VecX<double>>& params) {
    params.clear();
    for (int m = 0; m < k; ++m) params.push_back(initialParams(member, seed + uint64_t(m), 2));
    NetworkModel e;
    e.arch = ensembleArch(member, k);
    e.params = mergeEnsemble(member, params);
    e.memberOutputBias = memberOutputBiases(member, params);
    e.inputScaler = scaler(member.inputs, -0.3, 0.8);
    e.outputScaler = scaler(member.outputs, 0.05, 2.0);
    e.encoding.inputs = member.inputs;
    e.training.members = k;
    return e;
}

/// The bytes of a model file whose header is `model`'s with `edit` applied (its checksum and
/// length recomputed), so the loader's own checks of the header are what is tested.
template <typename Edit>
std::string withHeader(const NetworkModel& model, Edit edit) {
    const std::string bytes = modelFileBytes(model);
    uint32_t hlen = 0;
    std::memcpy(&hlen, bytes.data() + 12, 4);
    nlohmann::json header = nlohmann::json::parse(bytes.substr(24, hlen));
    edit(header);
    const std::string h = header.dump(1);
    const uint32_t n = uint32_t(h.size());
    const uint64_t sum = checksum64(h.data(), h.size());
    std::string out = bytes.substr(0, 12);
    out.append(reinterpret_cast<const char*>(&n), 4);
    out.append(reinterpret_cast<const char*>(&sum), 8);
    return out + h + bytes.substr(24 + hlen);
}

/// The InputError text parseModel gives for `bytes`, "" when it loads.
std::string loadError(const std::string& bytes) {
    try {
        parseModel(bytes, "ens.rrfm");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

MatX<float> inputs(int rows, int cols) {
    MatX<float> x(rows, cols);
    for (int c = 0; c < cols; ++c)
        for (int r = 0; r < rows; ++r) x(r, c) = float(0.5 * std::sin(0.37 * r + 1.3 * c));
    return x;
}

}  // namespace

TEST(Uncertainty, SpearmanMatchesHandComputedRanks) {
    EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {10, 20, 30, 45}), 1.0);
    EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4}, {4, 3, 2, 1}), -1.0);
    // Monotone but not linear: ranks, not values.
    EXPECT_DOUBLE_EQ(spearman({1, 2, 3, 4, 5}, {1, 8, 27, 64, 1000}), 1.0);
    // Ties take the mean rank: ranks (1, 2.5, 2.5, 4) against (1, 2, 3, 4): 4.5 / sqrt(4.5 * 5).
    EXPECT_NEAR(spearman({1, 2, 2, 3}, {1, 2, 3, 4}), 4.5 / std::sqrt(22.5), 1e-12);
    // (3, 1, 2) against (1, 2, 3): d = (2, -1, -1), 1 - 6 * 6 / (3 * 8) = -0.5.
    EXPECT_NEAR(spearman({3, 1, 2}, {1, 2, 3}), -0.5, 1e-12);
    EXPECT_TRUE(std::isnan(spearman({1, 1, 1}, {1, 2, 3})));
    EXPECT_TRUE(std::isnan(spearman({1}, {2})));
    EXPECT_THROW(spearman({1, 2}, {1}), std::invalid_argument);
}

TEST(Uncertainty, MembersRecoveredFromTheMergedNetworkAreTheMembersAlone) {
    const MlpArch member = arch(6, {8, 5}, 3);
    std::vector<VecX<double>> p;
    const NetworkModel e = ensemble(member, 3, 40, p);
    e.validate();
    ASSERT_EQ(e.spreadMembers(), 3);
    const MatX<float> x = inputs(6, 3000);  // more than one chunk
    const std::vector<MatX<float>> got = e.predictMembers(x);
    ASSERT_EQ(got.size(), 3u);
    MatX<float> mean = MatX<float>::Zero(3, x.cols());
    for (int m = 0; m < 3; ++m) {
        const MatX<float> alone = single(e, member, p[size_t(m)]).predict(x);
        EXPECT_LT((got[size_t(m)] - alone).cwiseAbs().maxCoeff(), 2e-5f) << "member " << m;
        mean += got[size_t(m)] / 3.f;
    }
    EXPECT_LT((mean - e.predict(x)).cwiseAbs().maxCoeff(), 2e-5f);
    // A single network has no members.
    EXPECT_EQ(single(e, member, p[0]).spreadMembers(), 0);
    EXPECT_TRUE(single(e, member, p[0]).predictMembers(x).empty());
}

TEST(Uncertainty, SpreadIsTheMembersStandardDeviationSummedWithinAndAddedAcrossNetworks) {
    const MlpArch joint = arch(4, {6}, 6), three = arch(4, {6}, 3);
    std::vector<VecX<double>> pj, pa, pb;
    const PartitionedNetwork j(ensemble(joint, 4, 7, pj));
    const NetworkModel ea = ensemble(three, 2, 70, pa), eb = ensemble(three, 3, 90, pb);
    const PartitionedNetwork a(ea), b(eb);
    const MatX<float> x = inputs(4, 50);
    auto stdOf = [](const std::vector<MatX<double>>& v) {
        MatX<double> mean = MatX<double>::Zero(3, v[0].cols()), var = mean;
        for (const MatX<double>& m : v) mean += m / double(v.size());
        for (const MatX<double>& m : v) var += (m - mean).cwiseAbs2() / double(v.size());
        return var;
    };
    // Joint: per member, direct + indirect rows, then the standard deviation.
    std::vector<MatX<double>> sums;
    for (const VecX<double>& w : pj) {
        const MatX<float> y = single(j.leaves[0], joint, w).predict(x);
        sums.push_back((y.topRows(3) + y.bottomRows(3)).cast<double>());
    }
    MatX<float> sd;
    ASSERT_TRUE(memberSpread({{&j, 0}, {&j, 3}}, x, sd));
    EXPECT_LT((sd.cast<double>() - stdOf(sums).cwiseSqrt()).cwiseAbs().maxCoeff(), 1e-5);
    // Two networks: their variances add.
    std::vector<MatX<double>> ya, yb;
    for (const VecX<double>& w : pa) ya.push_back(single(ea, three, w).predict(x).cast<double>());
    for (const VecX<double>& w : pb) yb.push_back(single(eb, three, w).predict(x).cast<double>());
    ASSERT_TRUE(memberSpread({{&a, 0}, {&b, 0}}, x, sd));
    EXPECT_LT((sd.cast<double>() - (stdOf(ya) + stdOf(yb)).cwiseSqrt()).cwiseAbs().maxCoeff(), 1e-5);
    // Identical members agree everywhere: no spread.
    NetworkModel same = ea;
    same.params = mergeEnsemble(three, {pa[0], pa[0]});
    same.memberOutputBias = memberOutputBiases(three, {pa[0], pa[0]});
    ASSERT_TRUE(memberSpread({{nullptr, 0}}, x, sd) == false);
    const PartitionedNetwork s(same);
    ASSERT_TRUE(memberSpread({{&s, 0}}, x, sd));
    EXPECT_LT(sd.cwiseAbs().maxCoeff(), 1e-6f);
    // A term whose network has no members: no spread at all.
    const PartitionedNetwork plain(single(ea, three, pa[0]));
    EXPECT_FALSE(memberSpread({{&a, 0}, {&plain, 0}}, x, sd));
}

TEST(Uncertainty, ModelFileKeepsTheMembersBiasesAndRefusesOnesThatDoNotFit) {
    const MlpArch member = arch(5, {7, 4}, 3);
    std::vector<VecX<double>> p;
    const NetworkModel e = ensemble(member, 2, 3, p);
    const std::string bytes = modelFileBytes(e);
    const NetworkModel back = parseModel(bytes, "ens.rrfm");
    ASSERT_EQ(back.memberOutputBias.size(), e.memberOutputBias.size());
    for (Eigen::Index i = 0; i < e.memberOutputBias.size(); ++i)
        EXPECT_EQ(back.memberOutputBias[i], e.memberOutputBias[i]) << i;  // the very bits
    const MatX<float> x = inputs(5, 20);
    EXPECT_TRUE(back.predictMembers(x)[1] == e.predictMembers(x)[1]);

    // The loader refuses member biases that do not fit, naming the file and the field: biases
    // that do not average to the network's output bias (not these members'), a member count other
    // than the training record's, a row of the wrong length, a misspelt key.
    const std::string unchanged = loadError(withHeader(e, [](nlohmann::json&) {}));
    EXPECT_EQ(unchanged, "");
    const std::string shifted = loadError(withHeader(e, [](nlohmann::json& h) {
        h["ensemble"]["output_bias"][0][0] = h["ensemble"]["output_bias"][0][0].get<double>() + 0.5;
    }));
    EXPECT_NE(shifted.find("ens.rrfm"), std::string::npos) << shifted;
    EXPECT_NE(shifted.find("average"), std::string::npos) << shifted;
    const std::string count = loadError(withHeader(e, [](nlohmann::json& h) { h["training"]["members"] = 3; }));
    EXPECT_NE(count.find("training record says 3"), std::string::npos) << count;
    const std::string row = loadError(withHeader(e, [](nlohmann::json& h) { h["ensemble"]["output_bias"][1].erase(0); }));
    EXPECT_NE(row.find("header/ensemble/output_bias/1"), std::string::npos) << row;
    const std::string key = loadError(withHeader(e, [](nlohmann::json& h) { h["ensemble"]["bias"] = 1; }));
    EXPECT_NE(key.find("bias"), std::string::npos) << key;
    EXPECT_NE(key.find("ens.rrfm"), std::string::npos) << key;
    // Biases of the wrong shape in memory.
    NetworkModel shapeless = e;
    shapeless.memberOutputBias.conservativeResize(5);
    try {
        shapeless.validate();
        ADD_FAILURE() << "five biases for two members of three outputs were accepted";
    } catch (const std::invalid_argument& ex) {
        EXPECT_NE(std::string(ex.what()).find("not a multiple"), std::string::npos) << ex.what();
    }
    // A model file written without the members' biases loads as an ensemble without spread.
    NetworkModel old = e;
    old.memberOutputBias.resize(0);
    const NetworkModel loaded = parseModel(modelFileBytes(old), "old.rrfm");
    EXPECT_EQ(loaded.spreadMembers(), 0);
    EXPECT_TRUE(loaded.predict(x) == e.predict(x));
}

TEST(Uncertainty, FitNetworkKeepsTheMembersOfItsEnsemble) {
    const MlpArch member = arch(3, {6}, 3);
    MatX<float> x(3, 400), y(3, 400);
    for (int c = 0; c < 400; ++c) {
        for (int r = 0; r < 3; ++r) x(r, c) = float(std::sin(0.7 * c + r));
        for (int r = 0; r < 3; ++r) y(r, c) = float(0.5 + 0.3 * x(r, c) * x((r + 1) % 3, c));
    }
    TrainerConfig cfg;
    cfg.type = TrainerType::Adam;
    cfg.adam.maxEpochs = 5;
    InputEncoding identity;
    identity.inputs = 3;
    const NetworkModel m = fitNetwork(member, identity, cfg, x, y, MatX<float>(), {}, 0, 3);
    ASSERT_EQ(m.spreadMembers(), 3);
    const std::vector<MatX<float>> members = m.predictMembers(x);
    MatX<float> mean = MatX<float>::Zero(3, x.cols());
    for (const MatX<float>& p : members) mean += p / 3.f;
    EXPECT_LT((mean - m.predict(x)).cwiseAbs().maxCoeff(), 1e-5f);
    EXPECT_GT((members[0] - members[1]).cwiseAbs().maxCoeff(), 1e-4f);  // trained from different starts
}

TEST(Uncertainty, EvaluationRanksTheSpreadAgainstTheRelativeError) {
    // Four pixels of object 0: relative errors 0.1, 0.2, 0.3, 0.4 against a reference of 1; the
    // spread orders them the same way (Spearman 1) for object 0. Object 1's two pixels have the
    // spread reversed (-1). One pixel of object 0 without a known spread is left out.
    Prediction p;
    p.images[int(Term::Global)] = Image(8, 1);
    p.spread = Image(8, 1);
    p.spreadKnown.assign(8, 1);
    Image ref(8, 1);
    const float err[8] = {0.1f, 0.2f, 0.3f, 0.4f, 0.9f, 0.1f, 0.5f, 0.f};
    const float sd[8] = {0.01f, 0.02f, 0.05f, 0.06f, 0.f, 0.3f, 0.1f, 0.f};
    for (int i = 0; i < 8; ++i) {
        ref.set(i, 0, Vec3(1.f));
        p.images[int(Term::Global)].set(i, 0, Vec3(1.f + err[i] * 1.01f));
        p.spread.set(i, 0, Vec3(sd[i]));
    }
    p.spreadKnown[4] = 0;
    const UncertaintyEvaluation u = evaluateUncertainty(p, ref, {{0, 1, 2, 3, 4}, {5, 6}}, {0, 1, 2, 3, 4, 5, 6});
    ASSERT_TRUE(u.available);
    EXPECT_EQ(u.perObject[0].pixels, 4u);
    EXPECT_NEAR(u.perObject[0].spearman, 1.0, 1e-12);
    EXPECT_NEAR(u.perObject[0].meanRelativeError, 0.25, 1e-5);
    EXPECT_TRUE(std::isnan(u.perObject[1].spearman) == false);
    EXPECT_NEAR(u.perObject[1].spearman, -1.0, 1e-12);
    EXPECT_EQ(u.overall.pixels, 6u);
    // Relative spread: sd / (|pred| + 0.01), channel mean.
    const Image rel = relativeSpreadMap(p.spread, p.images[int(Term::Global)], p.spreadKnown);
    EXPECT_NEAR(rel.at(2, 0).x, 0.05 / (1.0 + 0.3 * 1.01 + 0.01), 1e-6);
    EXPECT_EQ(rel.at(4, 0).x, 0.f);
    // No spread in the prediction: nothing to judge.
    Prediction none;
    none.images[int(Term::Global)] = Image(8, 1);
    EXPECT_FALSE(evaluateUncertainty(none, ref, {{0}}, {0}).available);
}

}  // namespace test_uncertainty
