#pragma once
/// Packing of a scene's trained networks into one float texture for the GLSL predictor
/// (shaders/predict.frag). GL-free: the packing is plain floats so that it can be built and tested
/// without a context; app/gl uploads `texels` as an RGBA32F texture.
///
/// Texel layout. The texture is `width` = kNetworkTextureWidth texels wide; texel index t lives at
/// (t mod width, t div width). A texel is 4 floats. Integers (counts, offsets) are stored as floats,
/// exact because every one is < 2^24 (packNetworkTexture enforces it).
///
///     texel 0                (version = 4, object count O, network input count I, max layer width)
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
///       N                    (scaled inputs I' = I + derived, outputs, layer count L, activation:
///                             0 = tanh, 1 = ReLU)
///       N + 1                (encoding components C, features F = the first layer's inputs,
///                             pass-through count P, derived inputs: 1 = reflected, 0 = none);
///                             C = 0: the identity (F = P = I')
///       next ⌈I'/4⌉          input scaler offsets   (mapminmax: x' = (x − offset) · scale)
///       next ⌈I'/4⌉          input scaler scales
///       next ⌈out/4⌉         output scaler offsets  (y = y' / scale + offset)
///       next ⌈out/4⌉         output scaler scales
///       then per encoding component c = 0 … C−1 (nn/encoding.h, in the model's list order):
///         1 texel            (type: 0 frequency, 1 one_blob, 2 hash_grid; input count d;
///                             index of its first feature; its feature count)
///         ⌈d/4⌉ texels       the normalised input indices it reads, in order
///         1 texel            settings: frequency (frequencies K, include_input 0/1, 0, 0)
///                                      one_blob  (bins B, 0, 0, 0)
///                                      hash_grid (levels Lh, log2 table size, features per level
///                                                 Fh, texel index of its table)
///         hash_grid only:    ⌈Lh/2⌉ texels (res_l, dense_l, res_l+1, dense_l+1): the grid
///                            resolution of each level and 1 when it is indexed densely
///                            ((res_l + 1)^d ≤ table size), 0 when hashed
///       next ⌈P/4⌉           the pass-through input indices, ascending (features F − P … F − 1)
///       then per layer l = 0 … L−1:
///         1 texel            (layer inputs n_in, layer outputs n_out, row texels R = ⌈n_in/4⌉, 0)
///         n_out · R texels   weight rows: row j holds W_l(j, 0 … n_in−1), zero-padded to 4R
///         ⌈n_out/4⌉ texels   bias b_l, zero-padded
///       then each hash_grid component's table: its Lh · 2^log2 · Fh trainable parameters in the
///         order of nn/encoding.h (float index (l · 2^log2 + entry) · Fh + f), zero-padded to a
///         whole texel; entry is the level's dense or hashed index (nn/encodings/hash_grid.h)
/// Raw inputs x of a pixel: its 12 geometric inputs, its object's I − 12 BRDF parameters, then at
/// I … I+2 the reflected direction reflect(view, normal) (nn/derived_inputs.h, the same float
/// operations), which the shader computes for every pixel: a network that derives it has I' = I + 3
/// and scales those slots, one that does not reads them through its scaler's zero padding as 0.
/// The encoding features are computed from the scaled inputs x' exactly as InputEncoding::forward
/// does (same float operations in the same order; sin, cos and exp are the platform's), and the
/// first layer reads them as it reads x' for the identity. Hash tables make the texture large
/// (16 levels of 2^14 entries with 2 features: 128 rows per network); packNetworkTexture rejects a
/// texture of more than maxRows rows and says how many texels the tables take.
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
/// (2: every model is a kd-tree block followed by its leaves' networks; 3: every network block
/// carries its input encoding and hash tables; 4: and its derived inputs, scaled after the raw ones).
constexpr int kNetworkTextureVersion = 4;
/// Slots of the per-object offset texel, in texel component order.
enum NetworkSlot { kSlotDirect = 0, kSlotIndirect = 1, kSlotGlobal = 2, kSlotJoint = 3 };

struct NetworkTexture {
    int width = kNetworkTextureWidth;  ///< texels per row
    int height = 0;                    ///< rows
    std::vector<float> texels;         ///< 4 · width · height floats, row-major, texel 0 first
    int objectCount = 0;               ///< O: objects of the scene (ids 0 … O−1)
    int inputCount = 0;                ///< I: network inputs per pixel (12 + BRDF parameters)
    int maxLayerWidth = 0;             ///< widest layer input or output (encoding features included)
    int networkCount = 0;              ///< leaf networks over all models
    int maxTreeDepth = 0;              ///< deepest kd-tree (0: no model is partitioned)
    size_t tableTexels = 0;            ///< texels taken by hash-grid tables over all networks
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
