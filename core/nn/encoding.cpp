#include "core/nn/encoding.h"

#include <stdexcept>

#include "core/nn/encodings/registry.h"
#include "core/util/error.h"

namespace rrf {

namespace {

/// The record input groups (RecordLayout's input order): name, first index, size (brdf: the rest).
struct InputGroup {
    const char* name;
    int first, size;
};
constexpr InputGroup kGroups[] = {{"position", 0, 3}, {"view", 3, 3}, {"light", 6, 3}, {"normal", 9, 3}, {"brdf", 12, -1}};
constexpr int kGeometryInputs = 12;

/// The component's inputs as one contiguous block of rows, if they are (first row), else −1.
int contiguousStart(const EncodingComponent& c) {
    for (size_t k = 1; k < c.inputs.size(); ++k)
        if (c.inputs[k] != c.inputs[0] + int(k)) return -1;
    return c.inputs[0];
}

/// Calls fn(xc) with the component's inputs (dims × N): rows of x when contiguous, else gathered
/// into `scratch`.
template <typename S, typename Fn>
void withComponentInputs(const EncodingComponent& c, const Eigen::Ref<const MatX<S>>& x, MatX<S>& scratch, Fn&& fn) {
    const int first = contiguousStart(c);
    const Eigen::Index d = Eigen::Index(c.inputs.size());
    if (first >= 0) {
        const Eigen::Ref<const MatX<S>> xc(x.middleRows(first, d));
        fn(xc);
        return;
    }
    scratch.resize(d, x.cols());
    for (Eigen::Index k = 0; k < d; ++k) scratch.row(k) = x.row(c.inputs[size_t(k)]);
    const Eigen::Ref<const MatX<S>> xc(scratch);
    fn(xc);
}

template <typename S>
const S* offsetParams(const S* params, const EncodingComponent& c) {
    return params ? params + c.paramOffset : nullptr;
}

}  // namespace

std::vector<int> encodingGroupInputs(const std::string& group, int inputs, const DerivedInputs& derived) {
    if (group == "reflected") {
        // Derived rows follow the record inputs (nn/derived_inputs.h).
        if (!derived.reflected)
            throw std::invalid_argument("input group 'reflected' is not an input of this network (it needs "
                                        "\"network\": {\"inputs\": {\"reflected\": true}})");
        return {inputs, inputs + 1, inputs + 2};
    }
    for (const InputGroup& g : kGroups) {
        if (group != g.name) continue;
        const int size = g.size >= 0 ? g.size : inputs - kGeometryInputs;
        if (size < 0 || g.first + size > inputs)
            throw std::invalid_argument("input group '" + group + "' does not fit in " + std::to_string(inputs) +
                                        " inputs");
        std::vector<int> idx(static_cast<size_t>(size));
        for (int k = 0; k < size; ++k) idx[size_t(k)] = g.first + k;
        return idx;
    }
    throw std::invalid_argument("unknown input group '" + group +
                                "' (expected \"position\", \"view\", \"light\", \"normal\", \"brdf\" or \"reflected\")");
}

int InputEncoding::outputs() const {
    int n = int(passThrough().size());
    for (const EncodingComponent& c : components) n += c.encoding->outputDims();
    return n;
}

int64_t InputEncoding::numParams() const {
    int64_t n = 0;
    for (const EncodingComponent& c : components) n += c.encoding->numParams();
    return n;
}

std::vector<int> InputEncoding::passThrough() const {
    const int rows = scaledInputs();
    std::vector<bool> read(size_t(rows), false);
    for (const EncodingComponent& c : components)
        for (int i : c.inputs) read[size_t(i)] = true;
    std::vector<int> rest;
    for (int i = 0; i < rows; ++i)
        if (!read[size_t(i)]) rest.push_back(i);
    return rest;
}

VecX<double> InputEncoding::initialParams(uint64_t seed, uint64_t stream) const {
    VecX<double> p = VecX<double>::Zero(Eigen::Index(numParams()));
    for (size_t k = 0; k < components.size(); ++k)
        components[k].encoding->initParams(p.data() + components[k].paramOffset, seed,
                                           kEncodingStreamTag + stream * 16 + k);
    return p;
}

template <typename S>
void InputEncoding::forward(const S* params, const EncodingIn<S>& x, MatX<S>& features) const {
    features.resize(outputs(), x.cols());
    Eigen::Index row = 0;
    MatX<S> scratch;
    for (const EncodingComponent& c : components) {
        const int out = c.encoding->outputDims();
        withComponentInputs<S>(c, x, scratch, [&](const Eigen::Ref<const MatX<S>>& xc) {
            c.encoding->forward(offsetParams(params, c), xc, features.middleRows(row, out));
        });
        row += out;
    }
    for (int i : passThrough()) features.row(row++) = x.row(i);
}

template <typename S>
void InputEncoding::backwardParams(const S* params, const EncodingIn<S>& x, const EncodingIn<S>& dFeatures, S* grad,
                                   std::vector<int64_t>* touched) const {
    Eigen::Index row = 0;
    MatX<S> scratch;
    for (const EncodingComponent& c : components) {
        const int out = c.encoding->outputDims();
        if (c.encoding->numParams() > 0) {
            const size_t before = touched ? touched->size() : 0;
            withComponentInputs<S>(c, x, scratch, [&](const Eigen::Ref<const MatX<S>>& xc) {
                c.encoding->backwardParams(offsetParams(params, c), xc, dFeatures.middleRows(row, out),
                                           grad + c.paramOffset, touched);
            });
            // The component reports indices into its own block; callers see the network's vector.
            if (touched)
                for (size_t k = before; k < touched->size(); ++k) (*touched)[k] += c.paramOffset;
        }
        row += out;
    }
}

template <typename S>
void InputEncoding::backwardInputs(const S* params, const EncodingIn<S>& x, const EncodingIn<S>& dFeatures,
                                   MatX<S>& dX) const {
    dX.setZero(scaledInputs(), x.cols());
    Eigen::Index row = 0;
    MatX<S> scratch, dXc;
    for (const EncodingComponent& c : components) {
        const int out = c.encoding->outputDims();
        dXc.resize(Eigen::Index(c.inputs.size()), x.cols());
        withComponentInputs<S>(c, x, scratch, [&](const Eigen::Ref<const MatX<S>>& xc) {
            c.encoding->backwardInputs(offsetParams(params, c), xc, dFeatures.middleRows(row, out), dXc);
        });
        // Groups are disjoint, so each input's gradient comes from exactly one component.
        for (size_t k = 0; k < c.inputs.size(); ++k) dX.row(c.inputs[k]) = dXc.row(Eigen::Index(k));
        row += out;
    }
    for (int i : passThrough()) dX.row(i) = dFeatures.row(row++);
}

template void InputEncoding::forward<float>(const float*, const Eigen::Ref<const MatX<float>>&, MatX<float>&) const;
template void InputEncoding::forward<double>(const double*, const Eigen::Ref<const MatX<double>>&, MatX<double>&) const;
template void InputEncoding::backwardParams<float>(const float*, const Eigen::Ref<const MatX<float>>&,
                                                   const Eigen::Ref<const MatX<float>>&, float*,
                                                   std::vector<int64_t>*) const;
template void InputEncoding::backwardParams<double>(const double*, const Eigen::Ref<const MatX<double>>&,
                                                    const Eigen::Ref<const MatX<double>>&, double*,
                                                    std::vector<int64_t>*) const;
template void InputEncoding::backwardInputs<float>(const float*, const Eigen::Ref<const MatX<float>>&,
                                                   const Eigen::Ref<const MatX<float>>&, MatX<float>&) const;
template void InputEncoding::backwardInputs<double>(const double*, const Eigen::Ref<const MatX<double>>&,
                                                    const Eigen::Ref<const MatX<double>>&, MatX<double>&) const;

bool InputEncoding::sameComponents(const InputEncoding& o) const {
    if (components.size() != o.components.size()) return false;
    for (size_t k = 0; k < components.size(); ++k) {
        const EncodingComponent &a = components[k], &b = o.components[k];
        if (std::string(a.encoding->typeName()) != b.encoding->typeName() || a.groups != b.groups ||
            a.encoding->params() != b.encoding->params())
            return false;
    }
    return true;
}

std::string InputEncoding::describe() const {
    std::string s;
    for (const EncodingComponent& c : components) {
        if (!s.empty()) s += " + ";
        s += std::string(c.encoding->typeName()) + "(";
        for (size_t g = 0; g < c.groups.size(); ++g) s += (g ? "," : "") + c.groups[g];
        s += ")";
    }
    if (s.empty()) s = "identity";
    if (derived.any()) s += " +" + derived.describe();
    return s;
}

}  // namespace rrf
