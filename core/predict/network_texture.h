#pragma once
/// Packing of a scene's trained networks into one float texture for the GLSL predictor
/// (shaders/predict.frag). GL-free: the packing is plain floats so that it can be built and tested
/// without a context; app/gl uploads `texels` as an RGBA32F texture.
///
/// Texel layout. The texture is `width` = kNetworkTextureWidth texels wide; texel index t lives at
/// (t mod width, t div width). A texel is 4 floats. Integers (counts, offsets) are stored as floats,
/// exact because every one is < 2^24 (packNetworkTexture enforces it).
///
///     texel 0                (version = 2, object count O, network input count I, max layer width)
///     texels 1 + 3o … 3 + 3o for object o = 0 … O−1:
///       1 + 3o               model offsets (direct, indirect, global, joint): texel index of the
///                            model's tree block, or −1 when the object has no such network
///       2 + 3o, 3 + 3o       the object's BRDF network inputs (I − 12 floats: kd, [ks, log10(1+n)],
///                            as RecordLayout::brdfParameters), zero-padded to 8 floats
///     tree block at texel T (one per model: its kd-tree, nn/partition_tree.h):
///       T                    (node count K, leaf count, 0, 0)
///       T + 1 + k            node k = 0 … K−1 (node 0 the root):
///                              internal: (input column a, split s, left node, right node): an input
///                                        x goes left when x[a] < s (a < 12: a geometric input)
///                              leaf:     (−1, texel index of the leaf's network block, 0, 0)
///       then the leaves' network blocks
///     network block at texel N:
///       N                    (inputs, outputs, layer count L, activation: 0 = tanh, 1 = ReLU)
///       next ⌈in/4⌉          input scaler offsets   (mapminmax: x' = (x − offset) · scale)
///       next ⌈in/4⌉          input scaler scales
///       next ⌈out/4⌉         output scaler offsets  (y = y' / scale + offset)
///       next ⌈out/4⌉         output scaler scales
///       then per layer l = 0 … L−1:
///         1 texel            (layer inputs n_in, layer outputs n_out, row texels R = ⌈n_in/4⌉, 0)
///         n_out · R texels   weight rows: row j holds W_l(j, 0 … n_in−1), zero-padded to 4R
///         ⌈n_out/4⌉ texels   bias b_l, zero-padded
/// Rows are stored whole (row-major, unlike the column-major flat parameter vector of nn/mlp.h) so
/// that the shader computes each neuron as a sum of vec4 dot products. Zero padding multiplies
/// zero activations, so padded lanes never change a sum.
///
/// How the terms are formed (shader, evaluateTerms below and core/predict/predictor.cpp agree):
///   direct   = the "direct" network, else outputs 0–2 of the "joint" network, else 0 (unavailable)
///   indirect = the "indirect" network, else outputs 3–5 of the "joint" network, else 0 (unavailable)
///   global   = direct + indirect when both are available, else the "global" network if there is
///              one, else direct + indirect of what there is (unavailable)
///   a non-finite network output (any channel) becomes 0, as in the CPU predictor.
/// Emission of lights seen directly is added by the renderer, not by the networks.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/nn/model_set.h"
#include "core/scene/scene.h"

namespace rrf {

/// Texture width in texels; 1024 is the smallest GL_MAX_TEXTURE_SIZE that OpenGL 3.3 guarantees.
constexpr int kNetworkTextureWidth = 1024;
/// Version written into texel 0.x, so that a dump of the texture says which layout it follows
/// (2: every model is a kd-tree block followed by its leaves' networks).
constexpr int kNetworkTextureVersion = 2;
/// Slots of the per-object offset texel, in texel component order.
enum NetworkSlot { kSlotDirect = 0, kSlotIndirect = 1, kSlotGlobal = 2, kSlotJoint = 3 };

struct NetworkTexture {
    int width = kNetworkTextureWidth;  ///< texels per row
    int height = 0;                    ///< rows
    std::vector<float> texels;         ///< 4 · width · height floats, row-major, texel 0 first
    int objectCount = 0;               ///< O: objects of the scene (ids 0 … O−1)
    int inputCount = 0;                ///< I: network inputs per pixel (12 + BRDF parameters)
    int maxLayerWidth = 0;             ///< widest layer input or output over all networks
    int networkCount = 0;              ///< leaf networks over all models
    int maxTreeDepth = 0;              ///< deepest kd-tree (0: no model is partitioned)
    /// Texel offset of each object's networks by slot (NetworkSlot), −1 where absent.
    std::vector<std::array<int, 4>> offsets;
    /// Per object (index = object id): whether its networks provide direct, indirect, global by the
    /// rules above; all false for an object without networks (shown black).
    std::vector<std::array<bool, 3>> provides;
    /// Per term: every object that has networks provides it (the CPU predictor calls a term
    /// unavailable when a covered pixel's object does not).
    bool termAvailable[3] = {false, false, false};
    size_t texelCount() const { return size_t(width) * size_t(height); }
};

/// Packs every network of `models` for `scene`. Throws std::invalid_argument when a network does not
/// fit the scene (object id out of range, input count ≠ RecordLayout::forScene(scene), output count
/// not 3 — or 6 for "joint"), when a model fails NetworkModel::validate(), when a layer is wider than
/// `maxLayerWidth`, when a tree splits on an input past the 12 geometric ones, or when the texture
/// would need more than `maxRows` rows.
NetworkTexture packNetworkTexture(const Scene& scene, const ModelSet& models, int maxLayerWidth = 256,
                                  int maxRows = 16384);

/// Direct, indirect and global prediction of object `objectId` for the 12 geometric inputs
/// (hit point, view direction, light position, normal), read from the packed texture exactly as the
/// shader reads it (leaf lookup in each model's tree block, then the leaf's network) (same layout, same order of operations, float arithmetic). A reference for the
/// layout that needs no GL; an object without networks gives zeros.
std::array<Vec3, 3> evaluateTerms(const NetworkTexture& tex, int objectId, const float geometricInputs[12]);

}  // namespace rrf
