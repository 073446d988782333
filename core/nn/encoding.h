#pragma once
/// Input encodings of a radiance regression network (issue 16; docs/design.md §10a): a fixed or
/// trainable map from the network's normalised inputs to the features its first layer reads.
///
///     raw record inputs x (12 + n)  [+ derived inputs, nn/derived_inputs.h]  --MinMaxScaler-->  x' in [-1, 1]
///        --InputEncoding-->  features (F)  --MLP-->
///
/// Ren et al. 2013 feed x' itself (the identity encoding, F = 12 + n); later work gets far more
/// accuracy per weight from encodings (NeRF's frequencies, NRC's one-blob, instant-NGP's hash grid).
/// As in tiny-cuda-nn, an encoding is picked by "type" and owns its hyperparameters; the
/// implementations live in nn/encodings/ (frequency.h, one_blob.h, hash_grid.h), each registered by
/// its type name in nn/encodings/registry.h, which is where this reader finds them.
///
/// Project / model JSON ("network": {"encoding": [...]}); an empty or missing list is the identity:
///
///     "encoding": [
///       {"type": "hash_grid", "inputs": "position", "levels": 16, "log2_table_size": 14,
///        "features_per_level": 2, "base_resolution": 16, "growth": 1.5},
///       {"type": "frequency", "inputs": ["view", "normal"], "frequencies": 4, "include_input": true},
///       {"type": "one_blob",  "inputs": "light", "bins": 16}
///     ]
///
/// "inputs" names input groups: the record's (RecordLayout) "position" (x' 0–2), "view" (3–5), "light"
/// (6–8), "normal" (9–11), "brdf" (12 … 12+n−1), and the derived "reflected" (12+n … 12+n+2:
/// reflect(view, normal), nn/derived_inputs.h), which exists only in a network that derives it
/// ("network": {"inputs": {"reflected": true}}); a group may be encoded by one component only.
///
/// Feature order (the MLP's input rows; CPU, GLSL and the model file agree on it):
///   the components' outputs in list order, each in its own order (documented per encoding), then
///   every input no component reads, unchanged, in ascending input index (derived rows included:
///   a network with the reflected input and no component on it reads r' as three plain features).
///
/// Trainable parameters (the hash grid's tables) live in one flat float/double vector per network,
/// component after component (`paramOffset`), beside the MLP's weights; fixed encodings have none.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/nn/derived_inputs.h"
#include "core/nn/encodings/encoding_params.h"
#include "core/nn/mlp.h"

namespace rrf {

/// One encoding applied to some of the network's normalised inputs. Implementations are immutable
/// (settings only); parameters are passed in. Every routine works on samples as COLUMNS (dims × N),
/// like nn/mlp.h, and exists for float (training with Adam, prediction) and double (Levenberg–
/// Marquardt, finite-difference tests); both compute the same formula.
class Encoding {
public:
    virtual ~Encoding() = default;
    /// "frequency", "one_blob", "hash_grid".
    virtual const char* typeName() const = 0;
    /// Number of inputs it reads (the size of its input groups).
    virtual int inputDims() const = 0;
    /// Number of features it writes.
    virtual int outputDims() const = 0;
    /// Trainable parameters (0 for fixed encodings).
    virtual int64_t numParams() const { return 0; }
    /// Initial parameters, a pure function of (seed, stream) through Rng (hash grid: uniform in
    /// [−1e-4, 1e-4], as instant-NGP). Nothing for fixed encodings.
    virtual void initParams(double* /*params*/, uint64_t /*seed*/, uint64_t /*stream*/) const {}

    /// out (outputDims × N) = encoding of x (inputDims × N, normalised inputs).
    virtual void forward(const float* params, const Eigen::Ref<const MatX<float>>& x, Eigen::Ref<MatX<float>> out) const = 0;
    virtual void forward(const double* params, const Eigen::Ref<const MatX<double>>& x, Eigen::Ref<MatX<double>> out) const = 0;

    /// Adds ∂loss/∂params to `grad` (numParams entries) given dOut = ∂loss/∂features (outputDims × N),
    /// after forward on the same x. When `touched` is given, the index of every parameter that may
    /// have received a nonzero gradient is appended (duplicates allowed): the sparse Adam update
    /// visits only those (instant-NGP skips table entries with zero gradient). No-op for fixed encodings.
    virtual void backwardParams(const float* /*params*/, const Eigen::Ref<const MatX<float>>& /*x*/,
                                const Eigen::Ref<const MatX<float>>& /*dOut*/, float* /*grad*/,
                                std::vector<int64_t>* /*touched*/) const {}
    virtual void backwardParams(const double* /*params*/, const Eigen::Ref<const MatX<double>>& /*x*/,
                                const Eigen::Ref<const MatX<double>>& /*dOut*/, double* /*grad*/,
                                std::vector<int64_t>* /*touched*/) const {}

    /// dX (inputDims × N) = ∂loss/∂x given dOut, after forward on the same x (the chain rule through
    /// the encoding; checked against finite differences).
    virtual void backwardInputs(const float* params, const Eigen::Ref<const MatX<float>>& x,
                                const Eigen::Ref<const MatX<float>>& dOut, Eigen::Ref<MatX<float>> dX) const = 0;
    virtual void backwardInputs(const double* params, const Eigen::Ref<const MatX<double>>& x,
                                const Eigen::Ref<const MatX<double>>& dOut, Eigen::Ref<MatX<double>> dX) const = 0;

    /// Its hyperparameters (its type's alternative; written with every key by encodings/encodings_json.h).
    virtual EncodingParams params() const = 0;
};

/// One configured component: the encoding and the normalised input indices it reads, in order.
struct EncodingComponent {
    std::vector<std::string> groups;        ///< as written: "position", "view", "light", "normal", "brdf", "reflected"
    std::vector<int> inputs;                ///< input indices of those groups, in group order
    std::shared_ptr<const Encoding> encoding;
    int64_t paramOffset = 0;                ///< start of its parameters in the network's encoding vector
};

/// `T` itself, in a context where template arguments are not deduced: InputEncoding's routines
/// deduce S from the params pointer alone, so plain MatX<S> arguments convert to their Eigen::Ref.
template <typename T>
struct EncodingNoDeduce {
    using type = T;
};
template <typename S>
using EncodingIn = Eigen::Ref<const MatX<typename EncodingNoDeduce<S>::type>>;

/// Offset of the Rng streams of encodings' initial parameters ("ENCODE"): keeps them apart from the
/// MLP's initial weights (streams stream·128 + layer, mlp.cpp) for any realistic network stream.
constexpr uint64_t kEncodingStreamTag = 0x454E434F44450000ULL;

/// The encoding of one network: its components, then pass-through of every other input. The rows it
/// reads are the record's inputs followed by the derived ones (nn/derived_inputs.h), normalised.
struct InputEncoding {
    int inputs = 0;                            ///< record inputs the network is fed (12 + n)
    DerivedInputs derived;                     ///< inputs derived from them, rows inputs … scaledInputs()−1
    std::vector<EncodingComponent> components; ///< empty: identity (Ren et al.'s raw inputs, plus any derived)

    /// No component: the features are x' itself (derived rows included).
    bool isIdentity() const { return components.empty(); }
    /// Rows of x' the encoding reads: the record inputs and the derived inputs (the input scaler's size).
    int scaledInputs() const { return inputs + derived.count(); }
    /// Features written (the MLP's input count).
    int outputs() const;
    /// Trainable parameters over all components.
    int64_t numParams() const;
    /// Inputs no component reads, ascending (passed through unchanged after the components' outputs).
    std::vector<int> passThrough() const;
    /// Initial parameters (numParams entries; component k keyed by Rng stream
    /// kEncodingStreamTag + stream·16 + k, so they never share random numbers with the MLP's initial
    /// weights, which use streams stream·128 + layer of the same seed).
    VecX<double> initialParams(uint64_t seed, uint64_t stream) const;

    /// features (outputs() × N) for normalised inputs x (scaledInputs() × N). `params` holds numParams()
    /// entries (may be null when there are none); S is deduced from it, so pass e.g. a
    /// `static_cast<const float*>(nullptr)` for a parameter-free encoding.
    template <typename S>
    void forward(const S* params, const EncodingIn<S>& x, MatX<S>& features) const;
    /// Adds ∂loss/∂params to grad (numParams entries) given ∂loss/∂features; appends touched indices
    /// into the same vector (components' paramOffset added; unordered, with duplicates).
    template <typename S>
    void backwardParams(const S* params, const EncodingIn<S>& x, const EncodingIn<S>& dFeatures, S* grad,
                        std::vector<int64_t>* touched) const;
    /// dX (scaledInputs() × N) = ∂loss/∂x given ∂loss/∂features.
    template <typename S>
    void backwardInputs(const S* params, const EncodingIn<S>& x, const EncodingIn<S>& dFeatures, MatX<S>& dX) const;

    /// "identity" or e.g. "hash_grid(position) + frequency(view,normal)", for tables and logs; a
    /// network with derived inputs adds them: "identity +reflected", "one_blob(reflected) +reflected".
    std::string describe() const;

    /// Same components with the same settings and the same derived inputs (the parameters are not
    /// part of an encoding).
    bool operator==(const InputEncoding& o) const {
        return sameComponents(o) && inputs == o.inputs && derived == o.derived;
    }
    bool operator!=(const InputEncoding& o) const { return !(*this == o); }
    /// Same components: types, hyperparameters and input groups, in order (what their JSON holds).
    bool sameComponents(const InputEncoding& o) const;
};

/// Input indices of an input group for `inputs` record inputs and the `derived` ones ("position" →
/// {0,1,2}, "brdf" → {12 … inputs−1}, "reflected" → {inputs, inputs+1, inputs+2}); throws
/// std::invalid_argument for an unknown name or a derived group the network does not derive.
std::vector<int> encodingGroupInputs(const std::string& group, int inputs, const DerivedInputs& derived = {});

}  // namespace rrf
