#pragma once
/// The kd-tree of a partitioned radiance regression function (Ren et al. 2013; docs/design.md §10a):
/// each object's record-input space is cut by axis-aligned planes into cells, and each cell (leaf)
/// has its own small network. This file holds the tree only — its nodes, the split rule that builds
/// it and the leaf lookup that prediction runs per pixel; the networks live in
/// nn/model.h (PartitionedNetwork) and the training that grows the tree in nn/object_training.h.
///
/// Which inputs may be split (PartitionAxes): the hit position (record columns 0–2) and the light
/// position (6–8), nothing else. Both are world-space lengths, so "the widest axis" compares like
/// with like; the light-position axes let the tree follow error that moves with the light (its own
/// shadow on the ceiling) rather than only error that sits at fixed places. View direction and
/// normal are unit vectors (no width comparable to a length); the diffuse scenes' radiance does not
/// depend on the view, and a normal is constant per face, a step every network already sees as an
/// input. Keeping the lookup on position and light also makes it exact on the GPU: those inputs
/// reach the shader bit-identical to the CPU's (G-buffer texture, uniform), whereas the view
/// direction is re-normalised there and could put a pixel on a plane into the other leaf.
///
/// Split rule (splitNode): the allowed axis along which the node's records spread widest, cut at the
/// median of the records along it (Ren et al.), so both children get half the records and the
/// min-records rule stops every branch at the same depth for evenly spread data. The plane sits
/// halfway between the two middle distinct values, so no record lies on it.

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace rrf {

/// Record input columns a kd-tree may split (RecordLayout order).
struct PartitionAxes {
    bool position = true;  ///< hit_x/y/z (columns 0–2)
    bool light = true;     ///< light_x/y/z (columns 6–8)

    /// The allowed input columns, ascending.
    std::vector<int> columns() const;
    /// Names as settings spell them: "position", "light".
    std::vector<std::string> names() const;
    /// Parses one name ("position" | "light") into `axes`; throws std::invalid_argument otherwise.
    static void enable(PartitionAxes& axes, const std::string& name);
    bool any() const { return position || light; }
    bool operator==(const PartitionAxes& o) const { return position == o.position && light == o.light; }
};

/// Name of a splittable input column as the record layout spells it ("hit_x", "light_z"), "?" otherwise.
const char* splitAxisName(int column);

/// One node of a PartitionTree. An internal node sends an input x to `left` when x[axis] < split
/// and to `right` otherwise; a leaf names the network (`leaf`) that predicts its cell.
struct PartitionNode {
    int axis = -1;       ///< input column split on; −1 for a leaf
    float split = 0.f;   ///< the plane x[axis] = split (internal nodes)
    int left = -1;       ///< child node index for x[axis] < split (internal nodes)
    int right = -1;      ///< child node index for x[axis] ≥ split (internal nodes)
    int leaf = -1;       ///< index of the leaf's network (leaves), 0 … leafCount − 1
    int64_t records = 0; ///< training records that fell into the node (all of train/validation/test)
    /// Validation relative RMSE (§14's figure, ε = 0.01, raw units) of the network trained on the
    /// node's records: for a leaf the network that predicts it, for an internal node the network its
    /// children replaced (the reason it was split). NaN when the node had no validation set.
    double error = std::numeric_limits<double>::quiet_NaN();

    bool isLeaf() const { return axis < 0; }
};

/// A kd-tree over record inputs; node 0 is the root. A tree of one leaf is an unpartitioned network.
struct PartitionTree {
    std::vector<PartitionNode> nodes;

    /// One leaf (network 0) holding `records` records with validation error `error`.
    static PartitionTree singleLeaf(int64_t records = 0,
                                    double error = std::numeric_limits<double>::quiet_NaN());

    int leafCount() const;
    /// Node index of each leaf, indexed by leaf number.
    std::vector<int> leafNodes() const;
    /// Longest root-to-leaf path in edges (0 for a single leaf).
    int depth() const;
    /// Leaf number of the cell holding the input record `x` (at least max axis + 1 floats).
    int findLeaf(const float* x) const;
    /// Throws std::invalid_argument unless the nodes form a tree rooted at node 0 (every node but the
    /// root the child of exactly one earlier node), every axis lies in [0, inputs), every split is
    /// finite, and the leaves are numbered 0 … leafCount − 1, each once.
    void validate(int inputs) const;
};

/// Where to cut a node: the plane x[axis] = split.
struct SplitPlane {
    int axis = -1;
    float split = 0.f;
};

/// The split rule above for the records `indices` of `inputs` (numInputs floats per record,
/// record-major). Returns nothing when no allowed axis spreads (each one's range is at most 1e-5 of
/// its magnitude — mapminmax's "constant" — or fewer than two distinct values). Ties between
/// equally wide axes go to the lower column.
std::optional<SplitPlane> splitNode(const float* inputs, int numInputs, const std::vector<uint32_t>& indices,
                                    const PartitionAxes& axes);

}  // namespace rrf
