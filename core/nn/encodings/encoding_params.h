#pragma once
/// The hyperparameters of every encoding type as plain values (docs/design.md §10a), apart from the
/// implementations, so that a setting (nn/encoding_settings.h) can carry them without building an
/// encoding and without JSON. Each struct's initialisers are the defaults a component object gets for
/// the keys it leaves out; the ranges are checked by the reader (encodings/registry.h's readParams)
/// and again by each implementation's constructor.
///
/// EncodingParams holds one of them; its alternatives are in the order of encodingTypes()
/// (encodings/registry.cpp), so `params.index()` is the type's row there (test_registries checks it).

#include <variant>

namespace rrf {

/// Hyperparameters of the frequency encoding (encodings/frequency.h).
struct FrequencySettings {
    int frequencies = 6;       ///< "frequencies": K, 1..16
    bool includeInput = true;  ///< "include_input": prepend x_j itself

    bool operator==(const FrequencySettings& o) const {
        return frequencies == o.frequencies && includeInput == o.includeInput;
    }
    bool operator!=(const FrequencySettings& o) const { return !(*this == o); }
};

/// Hyperparameters of the one-blob encoding (encodings/one_blob.h).
struct OneBlobSettings {
    int bins = 16;  ///< "bins": B, 2..64

    bool operator==(const OneBlobSettings& o) const { return bins == o.bins; }
    bool operator!=(const OneBlobSettings& o) const { return !(*this == o); }
};

/// Hyperparameters of the hash grid (encodings/hash_grid.h).
struct HashGridSettings {
    int levels = 16;            ///< "levels": L, 1..24
    int log2TableSize = 14;     ///< "log2_table_size": log2 T, 10..22
    int featuresPerLevel = 2;   ///< "features_per_level": F, 1, 2, 4 or 8
    int baseResolution = 16;    ///< "base_resolution": b, 2..1024
    double growth = 1.5;        ///< "growth": g, 1..4

    bool operator==(const HashGridSettings& o) const {
        return levels == o.levels && log2TableSize == o.log2TableSize && featuresPerLevel == o.featuresPerLevel &&
               baseResolution == o.baseResolution && growth == o.growth;
    }
    bool operator!=(const HashGridSettings& o) const { return !(*this == o); }
};

/// One component's hyperparameters; the alternative says the type (in encodingTypes() order).
using EncodingParams = std::variant<FrequencySettings, OneBlobSettings, HashGridSettings>;

}  // namespace rrf
