#include "core/nn/encodings/frequency.h"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rrf {

namespace {
// vec3.h's kPi is a float; ω_k must be formed in double before the single rounding to float.
constexpr double kOmegaPi = 3.14159265358979323846;
}  // namespace

FrequencyEncoding::FrequencyEncoding(int inputDims, FrequencySettings settings)
    : inputDims_(inputDims), settings_(settings) {
    if (inputDims < 1) throw std::invalid_argument(std::string(type().name) + " encoding needs at least one input");
    if (settings.frequencies < 1 || settings.frequencies > kMaxFrequencies)
        throw std::invalid_argument("frequencies must be in 1.." + std::to_string(kMaxFrequencies) + ", got " +
                                    std::to_string(settings.frequencies));
}

const EncodingType& FrequencyEncoding::type() {
    static const EncodingType t{"frequency", {"frequencies", "include_input"}, std::numeric_limits<int>::max(), kGlslId,
                                [](const EncodingParams& s, int inputDims) -> std::shared_ptr<const Encoding> {
                                    return std::make_shared<const FrequencyEncoding>(inputDims, std::get<FrequencySettings>(s));
                                }};
    return t;
}

template <typename S>
S FrequencyEncoding::angularFrequency(int k) {
    return S(kOmegaPi * std::ldexp(1.0, k));
}

template float FrequencyEncoding::angularFrequency<float>(int);
template double FrequencyEncoding::angularFrequency<double>(int);

namespace {
/// ω_0 … ω_{K−1} (angularFrequency), the table forward and backward both read.
template <typename S>
std::array<S, FrequencyEncoding::kMaxFrequencies> angularFrequencies(int K) {
    std::array<S, FrequencyEncoding::kMaxFrequencies> omega{};
    for (int k = 0; k < K; ++k) omega[size_t(k)] = FrequencyEncoding::angularFrequency<S>(k);
    return omega;
}
}  // namespace

template <typename S>
void FrequencyEncoding::forwardImpl(const Eigen::Ref<const MatX<S>>& x, Eigen::Ref<MatX<S>> out) const {
    const int K = settings_.frequencies;
    const auto omega = angularFrequencies<S>(K);
    for (Eigen::Index n = 0; n < x.cols(); ++n) {
        Eigen::Index row = 0;
        for (int j = 0; j < inputDims_; ++j) {
            const S xj = x(j, n);
            if (settings_.includeInput) out(row++, n) = xj;
            for (int k = 0; k < K; ++k) {
                const S a = xj * omega[k];
                out(row++, n) = std::sin(a);
                out(row++, n) = std::cos(a);
            }
        }
    }
}

template <typename S>
void FrequencyEncoding::backwardInputsImpl(const Eigen::Ref<const MatX<S>>& x, const Eigen::Ref<const MatX<S>>& dOut,
                                           Eigen::Ref<MatX<S>> dX) const {
    const int K = settings_.frequencies;
    const auto omega = angularFrequencies<S>(K);
    for (Eigen::Index n = 0; n < x.cols(); ++n) {
        Eigen::Index row = 0;
        for (int j = 0; j < inputDims_; ++j) {
            const S xj = x(j, n);
            S g = 0;
            if (settings_.includeInput) g += dOut(row++, n);
            for (int k = 0; k < K; ++k) {
                const S a = xj * omega[k];
                g += dOut(row, n) * std::cos(a) * omega[k];
                g -= dOut(row + 1, n) * std::sin(a) * omega[k];
                row += 2;
            }
            dX(j, n) = g;
        }
    }
}

void FrequencyEncoding::forward(const float*, const Eigen::Ref<const MatX<float>>& x, Eigen::Ref<MatX<float>> out) const {
    forwardImpl<float>(x, out);
}
void FrequencyEncoding::forward(const double*, const Eigen::Ref<const MatX<double>>& x,
                                Eigen::Ref<MatX<double>> out) const {
    forwardImpl<double>(x, out);
}
void FrequencyEncoding::backwardInputs(const float*, const Eigen::Ref<const MatX<float>>& x,
                                       const Eigen::Ref<const MatX<float>>& dOut, Eigen::Ref<MatX<float>> dX) const {
    backwardInputsImpl<float>(x, dOut, dX);
}
void FrequencyEncoding::backwardInputs(const double*, const Eigen::Ref<const MatX<double>>& x,
                                       const Eigen::Ref<const MatX<double>>& dOut, Eigen::Ref<MatX<double>> dX) const {
    backwardInputsImpl<double>(x, dOut, dX);
}

}  // namespace rrf
