#include "core/nn/encodings/one_blob.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rrf {

OneBlobEncoding::OneBlobEncoding(int inputDims, OneBlobSettings settings) : inputDims_(inputDims), settings_(settings) {
    if (inputDims < 1) throw std::invalid_argument(std::string(type().name) + " encoding needs at least one input");
    if (settings.bins < kMinBins || settings.bins > kMaxBins)
        throw std::invalid_argument("bins must be in " + std::to_string(kMinBins) + ".." + std::to_string(kMaxBins) +
                                    ", got " + std::to_string(settings.bins));
}

const EncodingType& OneBlobEncoding::type() {
    static const EncodingType t{"one_blob", {"bins"}, std::numeric_limits<int>::max(), kGlslId,
                                [](const EncodingParams& s, int inputDims) -> std::shared_ptr<const Encoding> {
                                    return std::make_shared<const OneBlobEncoding>(inputDims, std::get<OneBlobSettings>(s));
                                }};
    return t;
}

template <typename S>
void OneBlobEncoding::forwardImpl(const Eigen::Ref<const MatX<S>>& x, Eigen::Ref<MatX<S>> out) const {
    const int B = settings_.bins;
    const S Bs = S(B);
    for (Eigen::Index n = 0; n < x.cols(); ++n) {
        Eigen::Index row = 0;
        for (int j = 0; j < inputDims_; ++j) {
            const S u = std::clamp((x(j, n) + S(1)) * S(0.5), S(0), S(1));
            for (int k = 0; k < B; ++k) {
                const S c = (S(k) + S(0.5)) / Bs;
                const S t = (u - c) * Bs;
                out(row++, n) = std::exp(S(-0.5) * t * t);
            }
        }
    }
}

template <typename S>
void OneBlobEncoding::backwardInputsImpl(const Eigen::Ref<const MatX<S>>& x, const Eigen::Ref<const MatX<S>>& dOut,
                                         Eigen::Ref<MatX<S>> dX) const {
    const int B = settings_.bins;
    const S Bs = S(B);
    for (Eigen::Index n = 0; n < x.cols(); ++n) {
        Eigen::Index row = 0;
        for (int j = 0; j < inputDims_; ++j) {
            const S uRaw = (x(j, n) + S(1)) * S(0.5);
            const S u = std::clamp(uRaw, S(0), S(1));
            // The clamp is flat outside [0, 1]: no gradient reaches x there.
            const bool clamped = uRaw < S(0) || uRaw > S(1);
            S g = 0;
            for (int k = 0; k < B; ++k) {
                const S c = (S(k) + S(0.5)) / Bs;
                const S t = (u - c) * Bs;
                g += dOut(row++, n) * (-t * std::exp(S(-0.5) * t * t));
            }
            dX(j, n) = clamped ? S(0) : g * Bs * S(0.5);
        }
    }
}

void OneBlobEncoding::forward(const float*, const Eigen::Ref<const MatX<float>>& x, Eigen::Ref<MatX<float>> out) const {
    forwardImpl<float>(x, out);
}
void OneBlobEncoding::forward(const double*, const Eigen::Ref<const MatX<double>>& x,
                              Eigen::Ref<MatX<double>> out) const {
    forwardImpl<double>(x, out);
}
void OneBlobEncoding::backwardInputs(const float*, const Eigen::Ref<const MatX<float>>& x,
                                     const Eigen::Ref<const MatX<float>>& dOut, Eigen::Ref<MatX<float>> dX) const {
    backwardInputsImpl<float>(x, dOut, dX);
}
void OneBlobEncoding::backwardInputs(const double*, const Eigen::Ref<const MatX<double>>& x,
                                     const Eigen::Ref<const MatX<double>>& dOut, Eigen::Ref<MatX<double>> dX) const {
    backwardInputsImpl<double>(x, dOut, dX);
}

}  // namespace rrf
