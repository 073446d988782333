// ErrorStats and noise figures in JSON (see error_metrics_json.h).
#include "core/eval/error_metrics_json.h"

#include <cmath>

#include "core/util/json_reader.h"

namespace rrf {

nlohmann::json noiseFigureJson(double value) { return std::isnan(value) ? nlohmann::json(nullptr) : nlohmann::json(value); }

double noiseFigureFromJson(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : ErrorStats::kUnknownNoise; }

nlohmann::json toJson(const ErrorStats& s) {
    return {{"pixels", s.pixels},
            {"non_finite_pixels", s.nonFinite},
            {"rmse", s.rmse},
            {"rmse_noise_floor", noiseFigureJson(s.rmseNoiseFloor)},
            {"rmse_corrected", noiseFigureJson(s.rmseCorrected)},
            {"relative_rmse", s.relativeRmse},
            {"relative_rmse_noise_floor", noiseFigureJson(s.relativeRmseNoiseFloor)},
            {"relative_rmse_corrected", noiseFigureJson(s.relativeRmseCorrected)},
            {"signed_relative_mean", s.signedRelativeMean},
            {"relmse", s.relMse},
            {"relmse_noise_floor", noiseFigureJson(s.relMseNoiseFloor)},
            {"relmse_corrected", noiseFigureJson(s.relMseCorrected)},
            {"smape", s.smape},
            {"mae", s.mae},
            {"max_error", s.maxError},
            {"mean_reference", s.meanReference}};
}

ErrorStats errorStatsFromJson(const nlohmann::json& j, const std::string& file, const std::string& pointer) {
    const JsonReader r(j, file, pointer);
    r.requireObject();
    auto count = [&](const char* key) { return r.at(key).unsignedInteger(); };
    auto number = [&](const char* key) { return r.at(key).number(); };
    // A noise figure: a number, or null for unknown (noiseFigureJson).
    auto noise = [&](const char* key) {
        const JsonReader v = r.at(key);
        return v.value().is_null() ? ErrorStats::kUnknownNoise : v.number();
    };
    ErrorStats s;
    s.pixels = count("pixels");
    s.nonFinite = count("non_finite_pixels");
    s.rmse = number("rmse");
    s.rmseNoiseFloor = noise("rmse_noise_floor");
    s.rmseCorrected = noise("rmse_corrected");
    s.relativeRmse = number("relative_rmse");
    s.relativeRmseNoiseFloor = noise("relative_rmse_noise_floor");
    s.relativeRmseCorrected = noise("relative_rmse_corrected");
    s.signedRelativeMean = number("signed_relative_mean");
    s.relMse = number("relmse");
    s.relMseNoiseFloor = noise("relmse_noise_floor");
    s.relMseCorrected = noise("relmse_corrected");
    s.smape = number("smape");
    s.mae = number("mae");
    s.maxError = number("max_error");
    s.meanReference = number("mean_reference");
    s.noiseKnown = !std::isnan(s.relativeRmseNoiseFloor);
    return s;
}

}  // namespace rrf
