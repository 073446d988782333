#pragma once
/// Network inputs derived from a record's stored inputs (issue 26, item 5): today the view direction
/// reflected about the normal, Ref-NeRF's reparametrisation. A near-mirror's indirect light is a
/// smooth function of where the mirror direction points, while as a function of the view direction
/// and the normal it is a sharp ridge along r = reflect(view, normal) that a small MLP cannot follow.
///
///     record inputs (12 + n) --DerivedInputs::append--> model inputs (12 + n + d)
///        --MinMaxScaler--> x' in [-1, 1] --InputEncoding--> features --MLP-->
///
/// The derived rows are computed from the RAW record inputs, before the MinMaxScaler: the stored view
/// direction and normal are unit vectors there, so r = 2 (n·v) n − v is the true mirror direction (a
/// reflection of the min-max-normalised vectors would not be: the scaler stretches each axis by its
/// own range). The rows then get their own mapminmax scaling, fitted on the training records like any
/// other input, and an input encoding reads them as the input group "reflected". Nothing is stored in
/// datasets: CPU training (fitNetwork), CPU prediction (NetworkModel::predict) and the GLSL predictor
/// (shaders/predict.frag, mirrored by evaluateTerms) all derive them from the same stored inputs with
/// the same float operations (reflectAboutNormal).
///
/// Derived rows follow the record inputs, in this order (one group today):
///   "reflected" (3): reflected_x, reflected_y, reflected_z
///
/// Project / model JSON: {"reflected": true}; a missing key is false, and {} is no derived input
/// (read and written by nn/derived_inputs_json.h).

#include <string>
#include <vector>

#include "core/nn/mlp.h"

namespace rrf {

/// First record input of the view direction and of the normal (RecordLayout's order).
constexpr int kViewInput = 3;
constexpr int kNormalInput = 9;

/// r = 2 (n·v) n − v for the view direction v (towards the viewer) and the normal n, both unit. The
/// operations and their order are the ones shaders/predict.frag performs (float: the dot product
/// left to right, then t = d + d, then t·n_i − v_i), so CPU and GLSL derive the same floats.
template <typename S>
inline void reflectAboutNormal(const S* v, const S* n, S* r) {
    const S d = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
    const S t = d + d;
    for (int i = 0; i < 3; ++i) r[i] = t * n[i] - v[i];
}

/// Which derived inputs a network reads.
struct DerivedInputs {
    bool reflected = false;  ///< "reflected": reflect(view, normal), 3 rows

    /// Rows appended after the record inputs.
    int count() const { return reflected ? 3 : 0; }
    bool any() const { return reflected; }
    bool operator==(const DerivedInputs& o) const { return reflected == o.reflected; }
    bool operator!=(const DerivedInputs& o) const { return !(*this == o); }

    /// Names of the appended rows, in order ("reflected_x", ...), for tables and logs.
    std::vector<std::string> rowNames() const;
    /// "reflected", or "" when there is none.
    std::string describe() const;

    /// out ((record.rows() + count()) × N) = the record rows, then the derived rows of each column.
    /// `record` needs the 12 geometric inputs (it is a std::invalid_argument otherwise). S is float
    /// (training, prediction) or double (predictDouble).
    template <typename S>
    void append(const Eigen::Ref<const MatX<S>>& record, MatX<S>& out) const;
};

}  // namespace rrf
