#pragma once
/// Ensembles of networks merged into one network.
///
/// K networks of one architecture trained on the same records from different initial weights and
/// mini-batch orders land in different local minima; their mean has a smaller error than each
/// member (the members' disagreement averages out; Perrone & Cooper 1993, the "deep ensembles" of
/// Lakshminarayanan et al. 2017). The mean of K tanh/ReLU MLPs that share their input and output
/// scalers is itself one MLP, with K times the hidden width:
///   first layer   W' = [W₁; …; W_K] (members' rows stacked: every member reads all inputs)
///   hidden layers W' = diag(W₁, …, W_K) (block-diagonal: a member only reads its own units)
///   output layer  W' = [W₁ … W_K] / K, b' = (b₁ + … + b_K) / K (the mean of the members' outputs)
/// so prediction (CPU, GLSL, model files) needs nothing new: a merged ensemble is a plain network.
///
/// The members themselves stay recoverable from the merged weights but for one thing: member m's
/// output is K·W'_m h_m + b_m (W'_m its columns of the output layer, h_m its last hidden units), and
/// the merged network keeps only the mean of the b_m. memberOutputBiases keeps them (the model file
/// stores them, nn/model.h), and NetworkModel::predictMembers gives every member's output, whose
/// spread is the ensemble's uncertainty (core/eval/uncertainty.h).

#include <cstdint>
#include <string>
#include <vector>

#include "core/nn/mlp.h"
#include "core/nn/trainer.h"

namespace rrf {

/// The architecture of the mean of `members` networks of architecture `member`: every hidden layer
/// `members` times as wide, the same inputs, outputs and activation. Throws std::invalid_argument
/// unless members ≥ 1.
MlpArch ensembleArch(const MlpArch& member, int members);

/// The flat parameters (layout in nn/mlp.h) of ensembleArch(member, params.size()) whose output is
/// the mean of the members' outputs, for every input. Each entry of `params` must hold
/// member.numParams() values; throws std::invalid_argument otherwise or when `params` is empty.
VecX<double> mergeEnsemble(const MlpArch& member, const std::vector<VecX<double>>& params);

/// The members' own output-layer biases, member after member (K × outputs values, K = params.size()):
/// what mergeEnsemble averages away. Each entry of `params` must hold member.numParams() values.
VecX<double> memberOutputBiases(const MlpArch& member, const std::vector<VecX<double>>& params);

/// Why an ensemble of `members` cannot use the encoding `encodingDescription` (one with trainable
/// parameters): the text of the SettingError naming "network.ensemble" that training, sweeps and
/// fitNetwork raise.
std::string ensembleEncodingRefusal(const std::string& encodingDescription, int members);

/// The seed of ensemble member `member`: the trainer's own seed for member 0 (so a one-member
/// ensemble is exactly the single network), Rng(seed, kEnsembleStream, member) for the others.
uint64_t ensembleMemberSeed(uint64_t seed, int member);

/// Trains `members` networks of architecture `arch` on `data` with trainNetwork (nn/trainer.h), all
/// on the same split: member 0 from `params` (its initial weights) with `cfg`; member m from
/// initialParams(arch, s_m, stream) with the trainer's seed (its mini-batch order) replaced by
/// s_m = ensembleMemberSeed(cfg.seed(), m). On return `arch` and `params` are the merged network
/// (unchanged in shape for one member) and the result's losses and validation figures are the
/// merged network's, its history the first member's; `observer` sees every member's epochs, each
/// marked with its member. A cancel ends the ensemble: a member cut short by it is left out (but
/// the first, which is kept as the single network it is). `memberBiases`, when given, receives
/// memberOutputBiases of the kept members (empty when one is kept or `arch` has no hidden layers).
TrainResult trainEnsemble(MlpArch& arch, const TrainerConfig& cfg, const TrainingData& data,
                          const MinMaxScaler& outputScaler, VecX<double>& params, int members, uint64_t stream,
                          const TrainObserver& observer = {}, VecX<double>* memberBiases = nullptr);

}  // namespace rrf
