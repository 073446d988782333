#pragma once
/// Trainer settings, read from and written to JSON (the project file's "trainer" section and every
/// model file) by nn/trainer_config_json.h. The JSON is an object with a "type" key, as in tiny-cuda-nn:
///
///     {"type": "levenberg_marquardt", "max_epochs": 1000, "mu": 1e-3, ...}
///     {"type": "adam", "learning_rate": 5e-3, "loss": "relative_l2", "error_goal": 0.05, ...}
///
/// Every key is optional (defaults below, chosen to match Matlab's trainlm for LM). Parsing is strict:
/// an unknown key, a wrong type or an out-of-range value is an InputError naming the file and the
/// JSON path of the key, so a typo such as "mu_decrease" is reported instead of silently ignored.

#include <array>
#include <cstdint>
#include <string>

namespace rrf {

/// The keys every trainer has, declared here once and read and written once (trainer_config_json.cpp), so
/// that a trainer added to the registry (nn/trainers/registry.h) gets them by deriving from this.
/// Each trainer keeps its own copy (TrainerConfig holds both trainers): switching trainers runs the
/// new one with its own limits, and switching back loses no edit.
struct TrainerCommon {
    /// "max_epochs". No initialiser: each trainer's constructor says its own (they differ).
    int maxEpochs;
    /// "error_goal": stop when the validation relative RMSE, noise-corrected when the targets' variance
    /// is known (nn/validation_monitor.h), reaches it; 0 = no goal. 0.05 is the accuracy the workbench
    /// aims for (5 % relative, the figure of core/eval/error_metrics.h).
    double errorGoal = 0.05;
    /// "max_samples": bound on the training samples, 0 = all (the default: a partition's leaf is small
    /// enough for LM to see every record).
    int64_t maxSamples = 0;
    uint64_t seed = 1;  ///< "seed": split, initial weights (and Adam's mini-batch order)

    explicit TrainerCommon(int maxEpochs) : maxEpochs(maxEpochs) {}
};

/// Matlab trainlm semantics (see trainLevenbergMarquardt).
struct LevenbergMarquardtConfig : TrainerCommon {
    LevenbergMarquardtConfig() : TrainerCommon(1000) {}
    double mu = 1e-3;            ///< "mu": initial damping μ0
    double muDec = 0.1;          ///< "mu_dec": μ factor after a successful step
    double muInc = 10.0;         ///< "mu_inc": μ factor after a rejected step
    double muMax = 1e10;         ///< "mu_max": stop when μ exceeds it
    double minGrad = 1e-7;       ///< "min_grad": stop when ‖Jᵀe‖ falls below it
    int maxFail = 6;             ///< "max_fail": stop after this many validation failures in a row
                                 ///< (rises within the targets' noise do not count: nn/validation_monitor.h)
    double goal = 0.0;           ///< "goal": stop when the training MSE reaches it (trainlm's goal)
    /// "max_epoch_gflop": LM costs about 3·N·P² flops per epoch (N samples, P weights); when all N
    /// would exceed this budget, training uses the first N' = budget / (3 P²) samples of the random
    /// split and says so in the log. 100 GFLOP is 55 000 samples for the 20-10 network (P ≈ 600);
    /// its time per epoch at bench_nn's LM rate is in docs/results.md. 0 = no bound.
    double maxEpochGflop = 100.0;
};

/// Loss minimised by Adam (both on the network's outputs).
enum class AdamLoss {
    Mse,        ///< mean (pred − y)² in normalised [-1, 1] units
    RelativeL2,  ///< mean (p − y)² / (|y| + 0.01)² in raw units: the error metric's relative term
                 ///< (nn/training_loss.h), so bright and dark radiance count alike
    /// mean (p − y)² / (|p| + 0.01)² with p held constant (tiny-cuda-nn's RelativeL2, Neural Radiance
    /// Caching): the same weighting without the bias a noisy target in the denominator brings
    /// (≈ −2σ² of the mean for relative target noise σ; nn/training_loss.h)
    RelativeL2Prediction
};

/// The "loss" key's spelling of `loss` ("mse", "relative_l2", "relative_l2_prediction").
const char* adamLossName(AdamLoss loss);

enum class LrSchedule {
    Constant,  ///< learning_rate throughout
    Step,      ///< × step_gamma every step_epochs epochs
    Cosine     ///< cosine decay from learning_rate to min_learning_rate over max_epochs
};

struct AdamConfig : TrainerCommon {
    AdamConfig() : TrainerCommon(300) {}
    int batchSize = 256;              ///< "batch_size"
    double learningRate = 1e-2;       ///< "learning_rate"
    double minLearningRate = 1e-4;    ///< "min_learning_rate" (cosine schedule's end value)
    LrSchedule schedule = LrSchedule::Cosine;  ///< "schedule": "constant" | "step" | "cosine"
    int stepEpochs = 100;             ///< "step_epochs"
    double stepGamma = 0.3;           ///< "step_gamma"
    double beta1 = 0.9;               ///< "beta1"
    double beta2 = 0.999;             ///< "beta2"
    double epsilon = 1e-8;            ///< "epsilon"
    double weightDecay = 0.0;         ///< "weight_decay": decoupled (AdamW), weights only, not biases
    AdamLoss loss = AdamLoss::Mse;    ///< "loss": "mse" | "relative_l2" | "relative_l2_prediction"
    /// "debias_targets" (relative_l2 only, when the records carry their variance): each training target
    /// is raised by 2v/(|y| + ε) (debiasedRelativeL2Targets, nn/training_loss.h), which removes the
    /// first-order low bias of a loss weighted by the noisy target itself.
    bool debiasTargets = true;
    int patience = 30;                ///< "patience": stop after this many counted epochs without a
                                      ///< better validation loss (0 = never stop early); see below
    /// "patience_lr_fraction": an epoch without improvement counts toward patience only when its
    /// learning rate is ≤ this fraction of learning_rate, so early stopping cannot fire while the
    /// rate is high (with the cosine default, the last ~30 % of max_epochs). 1 = count every epoch
    /// (needed with the constant schedule, whose rate never decays).
    double patienceLrFraction = 0.2;
};

enum class TrainerType { LevenbergMarquardt, Adam };

struct TrainerConfig {
    TrainerType type = TrainerType::LevenbergMarquardt;
    LevenbergMarquardtConfig lm;
    AdamConfig adam;

    /// "levenberg_marquardt" / "adam".
    const char* typeName() const;
    /// The active trainer's shared keys.
    const TrainerCommon& common() const { return type == TrainerType::Adam ? static_cast<const TrainerCommon&>(adam) : lm; }
    TrainerCommon& common() { return type == TrainerType::Adam ? static_cast<TrainerCommon&>(adam) : lm; }
    /// Both trainers' shared keys, for a setting that applies whichever trainer runs (--epochs, a
    /// preset's epoch limit, a sweep's error goal, a run's seed): the active one and the one a switch
    /// would bring back.
    std::array<TrainerCommon*, 2> everyTrainer() { return {&lm, &adam}; }
    uint64_t seed() const { return common().seed; }
    int maxEpochs() const { return common().maxEpochs; }
    /// The active trainer's error goal (validation relative RMSE; 0 = none).
    double errorGoal() const { return common().errorGoal; }

    /// The project's trainer: what a project file without a "trainer" section trains with, and the
    /// initialiser of ObjectTrainingOptions::trainer. Adam with the relative L2 loss (the error
    /// metric's own weighting, so dark regions such as the light's shadow on the ceiling count as the
    /// evaluation counts them) on all records, error goal 0.02 and at most 600 epochs. On the Cornell
    /// box with the default data it generalises better than Levenberg–Marquardt, which costs 3·N·P²
    /// per epoch and so cannot use all the records in the same time (docs/results-history.md, issue
    /// 11). Unlike TrainerConfig() (a trainer object without keys: Levenberg–Marquardt with the
    /// defaults above, which the file format fixes), this is a project setting.
    static TrainerConfig projectDefault();
    /// Switches the trainer, the one way every front end does it (CLI --trainer, sweeps, the Network
    /// panel, scripts): only `type` changes. Both trainers' parameters are kept, so switching back
    /// and forth loses no edit; the new trainer runs with its own parameters (its own epoch limit
    /// included), which are its defaults unless they were set. Unchanged if it already is `t`.
    TrainerConfig withType(TrainerType t) const;
    /// withType by name: "lm", "levenberg_marquardt" or "adam"; throws SettingError naming
    /// `setting` for another name.
    TrainerConfig withType(const std::string& name, const std::string& setting = "trainer") const;
};

}  // namespace rrf
