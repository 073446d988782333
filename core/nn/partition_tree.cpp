#include "core/nn/partition_tree.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rrf {

std::vector<int> PartitionAxes::columns() const {
    // Pushed one by one: GCC 12 warns (falsely) of an overflow on insert() of a braced list here.
    std::vector<int> c;
    for (int first : {position ? 0 : -1, light ? 6 : -1})
        if (first >= 0)
            for (int k = 0; k < 3; ++k) c.push_back(first + k);
    return c;
}

std::vector<std::string> PartitionAxes::names() const {
    std::vector<std::string> n;
    if (position) n.push_back("position");
    if (light) n.push_back("light");
    return n;
}

void PartitionAxes::enable(PartitionAxes& axes, const std::string& name) {
    if (name == "position") axes.position = true;
    else if (name == "light") axes.light = true;
    else throw std::invalid_argument("unknown split axes '" + name + "' (expected position or light)");
}

const char* splitAxisName(int column) {
    static const char* const names[9] = {"hit_x", "hit_y", "hit_z", "view_x", "view_y", "view_z", "light_x", "light_y", "light_z"};
    return column >= 0 && column < 9 ? names[column] : "?";
}

PartitionTree PartitionTree::singleLeaf(int64_t records, double error) {
    PartitionTree t;
    PartitionNode n;
    n.leaf = 0;
    n.records = records;
    n.error = error;
    t.nodes.push_back(n);
    return t;
}

int PartitionTree::leafCount() const {
    int n = 0;
    for (const PartitionNode& x : nodes) n += x.isLeaf();
    return n;
}

std::vector<int> PartitionTree::leafNodes() const {
    std::vector<int> out(size_t(leafCount()), -1);
    for (size_t i = 0; i < nodes.size(); ++i)
        if (nodes[i].isLeaf() && nodes[i].leaf >= 0 && size_t(nodes[i].leaf) < out.size()) out[size_t(nodes[i].leaf)] = int(i);
    return out;
}

int PartitionTree::depth() const {
    // Children come after their parent (validate), so one forward pass finds every node's depth.
    std::vector<int> d(nodes.size(), 0);
    int deepest = 0;
    for (size_t i = 0; i < nodes.size(); ++i) {
        const PartitionNode& n = nodes[i];
        if (n.isLeaf()) continue;
        for (int c : {n.left, n.right}) {
            d[size_t(c)] = d[i] + 1;
            deepest = std::max(deepest, d[size_t(c)]);
        }
    }
    return deepest;
}

int PartitionTree::findLeaf(const float* x) const {
    int i = 0;
    while (!nodes[size_t(i)].isLeaf()) {
        const PartitionNode& n = nodes[size_t(i)];
        i = x[n.axis] < n.split ? n.left : n.right;
    }
    return nodes[size_t(i)].leaf;
}

void PartitionTree::validate(int inputs) const {
    if (nodes.empty()) throw std::invalid_argument("partition tree has no nodes");
    std::vector<int> parents(nodes.size(), 0);
    std::vector<char> leafSeen;
    const int leaves = leafCount();
    leafSeen.assign(size_t(leaves), 0);
    for (size_t i = 0; i < nodes.size(); ++i) {
        const PartitionNode& n = nodes[i];
        const std::string who = "partition tree node " + std::to_string(i);
        if (n.records < 0) throw std::invalid_argument(who + ": negative record count");
        if (n.isLeaf()) {
            if (n.leaf < 0 || n.leaf >= leaves || leafSeen[size_t(n.leaf)])
                throw std::invalid_argument(who + ": leaf number " + std::to_string(n.leaf) + " is not one of 0 … " +
                                            std::to_string(leaves - 1) + " or appears twice");
            leafSeen[size_t(n.leaf)] = 1;
            continue;
        }
        if (n.axis >= inputs)
            throw std::invalid_argument(who + ": split axis " + std::to_string(n.axis) + " is not an input (the network has " +
                                        std::to_string(inputs) + ")");
        if (!std::isfinite(n.split)) throw std::invalid_argument(who + ": non-finite split value");
        for (int c : {n.left, n.right}) {
            // Children after their parent: no cycles, and lookups and depth() need one forward pass.
            if (c <= int(i) || c >= int(nodes.size()))
                throw std::invalid_argument(who + ": child " + std::to_string(c) + " must be a later node");
            ++parents[size_t(c)];
        }
        if (n.left == n.right) throw std::invalid_argument(who + ": both children are node " + std::to_string(n.left));
    }
    for (size_t i = 1; i < nodes.size(); ++i)
        if (parents[i] != 1)
            throw std::invalid_argument("partition tree node " + std::to_string(i) + " has " + std::to_string(parents[i]) +
                                        " parents, expected 1");
}

std::optional<SplitPlane> splitNode(const float* inputs, int numInputs, const std::vector<uint32_t>& indices,
                                    const PartitionAxes& axes) {
    if (indices.size() < 2) return std::nullopt;
    int best = -1;
    float bestWidth = 0.f;
    for (int c : axes.columns()) {
        if (c >= numInputs) continue;
        float lo = inputs[size_t(indices[0]) * size_t(numInputs) + size_t(c)], hi = lo;
        for (uint32_t r : indices) {
            const float v = inputs[size_t(r) * size_t(numInputs) + size_t(c)];
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
        const float width = hi - lo;
        // mapminmax's constant rule (nn/mlp.h): rounding noise on a flat wall is no extent.
        if (!(width > 1e-5f * std::max(std::fabs(lo), std::fabs(hi)))) continue;
        if (width > bestWidth) {
            best = c;
            bestWidth = width;
        }
    }
    if (best < 0) return std::nullopt;

    std::vector<float> v(indices.size());
    for (size_t k = 0; k < indices.size(); ++k) v[k] = inputs[size_t(indices[k]) * size_t(numInputs) + size_t(best)];
    std::sort(v.begin(), v.end());
    // The cut nearest the median that separates two distinct values: below goes left, above right.
    const size_t m = v.size() / 2;
    size_t cut = 0;
    for (size_t off = 0; off <= v.size(); ++off) {
        if (m >= off && m - off >= 1 && v[m - off - 1] < v[m - off]) {
            cut = m - off;
            break;
        }
        if (m + off < v.size() && m + off >= 1 && v[m + off - 1] < v[m + off]) {
            cut = m + off;
            break;
        }
    }
    if (cut == 0) return std::nullopt;
    const float a = v[cut - 1], b = v[cut];
    float s = a + 0.5f * (b - a);
    if (!(s > a)) s = b;  // adjacent floats: the plane at the upper value still puts a on the left
    return SplitPlane{best, s};
}

}  // namespace rrf
