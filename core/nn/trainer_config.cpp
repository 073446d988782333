#include "core/nn/trainer_config.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <stdexcept>

#include "core/util/error.h"

namespace rrf {

namespace {

using nlohmann::json;

/// Reads the keys of one trainer object, remembering which were consumed so that anything left over
/// is reported as unknown.
class KeyReader {
public:
    KeyReader(const json& j, std::string file, std::string where)
        : j_(j), file_(std::move(file)), where_(std::move(where)) {}

    [[noreturn]] void fail(const std::string& key, const std::string& what) const {
        throw InputError(file_, where_ + "/" + key, what);
    }

    void number(const char* key, double& v, double lo, double hi, bool openLo = false) {
        const json* x = take(key);
        if (!x) return;
        if (!x->is_number()) fail(key, "expected a number, got " + std::string(x->type_name()));
        const double d = x->get<double>();
        if (!std::isfinite(d) || d < lo || d > hi || (openLo && d == lo))
            fail(key, "value " + x->dump() + " out of range " + (openLo ? "(" : "[") + fmt(lo) + ", " + fmt(hi) + "]");
        v = d;
    }

    template <typename Int>
    void integer(const char* key, Int& v, int64_t lo, int64_t hi) {
        const json* x = take(key);
        if (!x) return;
        if (!x->is_number_integer()) fail(key, "expected an integer, got " + x->dump());
        const int64_t i = x->is_number_unsigned() && x->get<uint64_t>() > uint64_t(INT64_MAX)
                              ? INT64_MAX
                              : x->get<int64_t>();
        if (i < lo || i > hi)
            fail(key, "value " + x->dump() + " out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        v = Int(i);
    }

    void seed(uint64_t& v) {
        const json* x = take("seed");
        if (!x) return;
        if (!x->is_number_unsigned() && !(x->is_number_integer() && x->get<int64_t>() >= 0))
            fail("seed", "expected a non-negative integer, got " + x->dump());
        v = x->get<uint64_t>();
    }

    std::string choice(const char* key, const std::string& dflt, const std::set<std::string>& allowed) {
        const json* x = take(key);
        if (!x) return dflt;
        if (!x->is_string()) fail(key, "expected a string, got " + x->dump());
        const std::string s = x->get<std::string>();
        if (!allowed.count(s)) {
            std::string list;
            for (const auto& a : allowed) list += (list.empty() ? "\"" : ", \"") + a + "\"";
            fail(key, "unknown value \"" + s + "\" (expected one of " + list + ")");
        }
        return s;
    }

    /// Throws on the first key that no reader consumed.
    void finish() const {
        for (auto it = j_.begin(); it != j_.end(); ++it)
            if (!used_.count(it.key())) fail(it.key(), "unknown trainer key \"" + it.key() + "\"");
    }

private:
    const json* take(const char* key) {
        used_.insert(key);
        auto it = j_.find(key);
        return it == j_.end() ? nullptr : &*it;
    }
    static std::string fmt(double d) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", d);
        return buf;
    }

    const json& j_;
    std::string file_, where_;
    std::set<std::string> used_;
};

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int64_t kMaxEpochs = 100000000;

}  // namespace

const char* TrainerConfig::typeName() const {
    return type == TrainerType::Adam ? "adam" : "levenberg_marquardt";
}

TrainerConfig TrainerConfig::fromJson(const json& j, const std::string& file, const std::string& where) {
    if (!j.is_object()) throw InputError(file, where, "trainer settings must be a JSON object, got " + j.dump());
    KeyReader r(j, file, where);
    TrainerConfig c;
    const std::string type = r.choice("type", "levenberg_marquardt", {"levenberg_marquardt", "lm", "adam"});
    if (type == "adam") {
        c.type = TrainerType::Adam;
        AdamConfig& a = c.adam;
        r.integer("max_epochs", a.maxEpochs, 0, kMaxEpochs);
        r.integer("batch_size", a.batchSize, 1, 1 << 24);
        r.number("learning_rate", a.learningRate, 0.0, 1e3, true);
        r.number("min_learning_rate", a.minLearningRate, 0.0, 1e3);
        const std::string sched = r.choice("schedule", "cosine", {"constant", "step", "cosine"});
        a.schedule = sched == "constant" ? LrSchedule::Constant : sched == "step" ? LrSchedule::Step : LrSchedule::Cosine;
        r.integer("step_epochs", a.stepEpochs, 1, kMaxEpochs);
        r.number("step_gamma", a.stepGamma, 0.0, 1.0, true);
        r.number("beta1", a.beta1, 0.0, 1.0 - 1e-12);
        r.number("beta2", a.beta2, 0.0, 1.0 - 1e-12);
        r.number("epsilon", a.epsilon, 0.0, 1.0, true);
        r.number("weight_decay", a.weightDecay, 0.0, 1.0);
        a.loss = r.choice("loss", "mse", {"mse", "relative_l2"}) == "relative_l2" ? AdamLoss::RelativeL2 : AdamLoss::Mse;
        r.integer("patience", a.patience, 0, kMaxEpochs);
        r.integer("max_samples", a.maxSamples, 0, INT64_MAX);
        r.seed(a.seed);
    } else {
        c.type = TrainerType::LevenbergMarquardt;
        LevenbergMarquardtConfig& l = c.lm;
        r.integer("max_epochs", l.maxEpochs, 0, kMaxEpochs);
        r.number("mu", l.mu, 0.0, kInf, true);
        r.number("mu_dec", l.muDec, 0.0, 1.0, true);
        r.number("mu_inc", l.muInc, 1.0, kInf, true);
        r.number("mu_max", l.muMax, 0.0, kInf, true);
        r.number("min_grad", l.minGrad, 0.0, kInf);
        r.integer("max_fail", l.maxFail, 1, kMaxEpochs);
        r.number("goal", l.goal, 0.0, kInf);
        r.integer("max_samples", l.maxSamples, 0, INT64_MAX);
        r.seed(l.seed);
        if (l.mu > l.muMax) r.fail("mu", "initial mu exceeds mu_max");
    }
    r.finish();
    return c;
}

json TrainerConfig::toJson() const {
    if (type == TrainerType::Adam) {
        const AdamConfig& a = adam;
        const char* sched = a.schedule == LrSchedule::Constant ? "constant"
                            : a.schedule == LrSchedule::Step   ? "step"
                                                               : "cosine";
        return json{{"type", "adam"},
                    {"max_epochs", a.maxEpochs},
                    {"batch_size", a.batchSize},
                    {"learning_rate", a.learningRate},
                    {"min_learning_rate", a.minLearningRate},
                    {"schedule", sched},
                    {"step_epochs", a.stepEpochs},
                    {"step_gamma", a.stepGamma},
                    {"beta1", a.beta1},
                    {"beta2", a.beta2},
                    {"epsilon", a.epsilon},
                    {"weight_decay", a.weightDecay},
                    {"loss", a.loss == AdamLoss::RelativeL2 ? "relative_l2" : "mse"},
                    {"patience", a.patience},
                    {"max_samples", a.maxSamples},
                    {"seed", a.seed}};
    }
    const LevenbergMarquardtConfig& l = lm;
    return json{{"type", "levenberg_marquardt"},
                {"max_epochs", l.maxEpochs},
                {"mu", l.mu},
                {"mu_dec", l.muDec},
                {"mu_inc", l.muInc},
                {"mu_max", l.muMax},
                {"min_grad", l.minGrad},
                {"max_fail", l.maxFail},
                {"goal", l.goal},
                {"max_samples", l.maxSamples},
                {"seed", l.seed}};
}

TrainerConfig TrainerConfig::withType(const std::string& name) const {
    if (name != "lm" && name != "levenberg_marquardt" && name != "adam")
        throw std::invalid_argument("unknown trainer '" + name + "' (expected lm or adam)");
    const TrainerType t = name == "adam" ? TrainerType::Adam : TrainerType::LevenbergMarquardt;
    if (t == type) return *this;
    TrainerConfig c;
    c.type = t;
    c.lm.maxEpochs = c.adam.maxEpochs = maxEpochs();
    return c;
}

}  // namespace rrf
