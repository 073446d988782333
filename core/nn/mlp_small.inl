// The blocked small-layer kernel of the float MLP passes (issue 28 item 1; docs/design.md §10,
// "Kernels"), included by mlp_isa.inl inside one instruction set's namespace, so it is compiled once
// per set with that set's packets (Eigen's Packet8f for AVX2, Packet16f for AVX-512).
//
// Why not the GEMM: the radiance networks' layers are 3 to 64 wide, so every product W · A has an
// inner dimension of 10 to 64 and the GEMM spends as long packing its operands as multiplying them.
// Here samples lie in the SIMD lanes instead: a tile of kTile samples is copied once, transposed, into
// feature-major rows (feature f of the tile's samples is row f, kTile floats), and every layer of the
// network runs on the tile while it is in L1: one output row is a broadcast weight times an input row,
// accumulated over the layer's inputs in registers, the weights read from L1. The backward pass walks
// the same tiles down the network; its weight gradients stay in one vector accumulator per weight,
// whose lanes are summed once at the end.
//
// Every sample is computed by the same instructions in whichever lane and tile it lands, so forward
// results do not depend on how a batch is cut into calls (threads, chunks, shards); gradients are
// sums in a fixed order given the batch. Padded lanes of the last tile hold zero inputs and zero
// deltas, which add nothing to any gradient.
#ifndef RRF_ISA
#error "mlp_small.inl is included by mlp_isa.inl only"
#endif

namespace small {

using Packet = Eigen::internal::packet_traits<float>::type;
constexpr int kLanes = Eigen::internal::packet_traits<float>::size;
/// Packets per tile row: enough independent accumulators to hide the FMA latency, and a weight
/// gradient's accumulator is loaded and stored once per kVectors multiply-adds.
constexpr int kVectors = 8;
constexpr int kTile = kLanes * kVectors;
/// Rows computed together: each broadcast weight feeds kChunk packets, each loaded input packet
/// feeds kRows rows. kRows × kChunk accumulators plus kChunk inputs fit the register file.
constexpr int kChunk = 2;
constexpr int kRows = kLanes >= 16 ? 8 : 4;
/// The widest layer this kernel's forward pass takes; wider networks use the GEMM (mlp_isa.inl).
constexpr int kMaxWidth = 64;
/// The widest layer its backward pass takes. Its weight gradients go through memory once per tile
/// and weight, which costs more than the GEMM's packing from 32-wide layers on in the AVX-512 build
/// (bench_nn, "Adam training" rows; docs/results-history.md, "Kernels: the blocked small-layer kernel"); the 20-10 network gains in both.
constexpr int kMaxBackwardWidth = 24;

// kLanes packets transposed in registers. The packet type's vector attribute is not part of the
// template's identity, which GCC warns about; Eigen's own uses are in system headers, silent.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wignored-attributes"
using Block = Eigen::internal::PacketBlock<Packet, kLanes>;
#pragma GCC diagnostic pop

enum class Finish { None, Tanh, Relu };

/// Copies samples [s0, s0 + count) of a features × n column-major matrix (column stride ld) into
/// tile rows (feature f at tile + f·kTile), zero beyond `count`. kLanes × kLanes blocks go through
/// registers (a packet transpose); the features and samples left over element by element.
inline void loadTile(const float* src, Index ld, int features, Index s0, int count, float* tile) {
    using namespace Eigen::internal;
    int s = 0;
    for (; s + kLanes <= count; s += kLanes) {
        const float* col = src + (s0 + s) * ld;
        int f = 0;
        for (; f + kLanes <= features; f += kLanes) {
            Block b;
            for (int j = 0; j < kLanes; ++j) b.packet[j] = ploadu<Packet>(col + j * ld + f);
            ptranspose(b);
            for (int j = 0; j < kLanes; ++j) pstoreu(tile + (f + j) * kTile + s, b.packet[j]);
        }
        for (; f < features; ++f)
            for (int j = 0; j < kLanes; ++j) tile[f * kTile + s + j] = col[j * ld + f];
    }
    for (; s < count; ++s) {
        const float* col = src + (s0 + s) * ld;
        for (int f = 0; f < features; ++f) tile[f * kTile + s] = col[f];
    }
    for (int f = 0; f < features; ++f)
        for (int z = count; z < kTile; ++z) tile[f * kTile + z] = 0.f;
}

/// The inverse of loadTile for the first `count` samples: tile rows back into a contiguous
/// features × n column-major matrix.
inline void storeTile(const float* tile, int features, Index s0, int count, float* dst) {
    using namespace Eigen::internal;
    int s = 0;
    for (; s + kLanes <= count; s += kLanes) {
        float* col = dst + (s0 + s) * features;
        int f = 0;
        for (; f + kLanes <= features; f += kLanes) {
            Block b;
            for (int j = 0; j < kLanes; ++j) b.packet[j] = ploadu<Packet>(tile + (f + j) * kTile + s);
            ptranspose(b);
            for (int j = 0; j < kLanes; ++j) pstoreu(col + j * features + f, b.packet[j]);
        }
        for (; f < features; ++f)
            for (int j = 0; j < kLanes; ++j) col[j * features + f] = tile[f * kTile + s + j];
    }
    for (; s < count; ++s) {
        float* col = dst + (s0 + s) * features;
        for (int f = 0; f < features; ++f) col[f] = tile[f * kTile + s];
    }
}

/// R rows of out = M · in (+ bias) on a tile: out row r = Σ_k M(r, k) · in row k, with M(r, k) at
/// m[r·rs + k·ks] (a layer's W for the forward pass, Wᵀ for the backward one), then `finish`.
template <int R>
void rowBlock(const float* m, Index rs, Index ks, int K, const float* bias, Finish finish, const float* in,
              float* out) {
    using namespace Eigen::internal;
    for (int c0 = 0; c0 < kVectors; c0 += kChunk) {
        Packet acc[R][kChunk];
        for (int r = 0; r < R; ++r)
            for (int c = 0; c < kChunk; ++c) acc[r][c] = bias ? pset1<Packet>(bias[r]) : pzero(Packet());
        for (int k = 0; k < K; ++k) {
            const float* row = in + k * kTile + c0 * kLanes;
            Packet a[kChunk];
            for (int c = 0; c < kChunk; ++c) a[c] = ploadu<Packet>(row + c * kLanes);
            for (int r = 0; r < R; ++r) {
                const Packet w = pset1<Packet>(m[r * rs + k * ks]);
                for (int c = 0; c < kChunk; ++c) acc[r][c] = pmadd(w, a[c], acc[r][c]);
            }
        }
        for (int r = 0; r < R; ++r)
            for (int c = 0; c < kChunk; ++c) {
                Packet z = acc[r][c];
                if (finish == Finish::Tanh)
                    z = ptanh(z);
                else if (finish == Finish::Relu)
                    z = pmax(z, pzero(Packet()));
                pstoreu(out + r * kTile + (c0 + c) * kLanes, z);
            }
    }
}

/// All `rows` rows of out = M · in (+ bias), kRows at a time, the rest by one narrower block.
inline void rowsTimesTile(const float* m, Index rs, Index ks, int rows, int K, const float* bias, Finish finish,
                          const float* in, float* out) {
    int r0 = 0;
    for (; r0 + kRows <= rows; r0 += kRows)
        rowBlock<kRows>(m + r0 * rs, rs, ks, K, bias ? bias + r0 : nullptr, finish, in, out + r0 * kTile);
    const float* mr = m + r0 * rs;
    const float* br = bias ? bias + r0 : nullptr;
    float* o = out + r0 * kTile;
    switch (rows - r0) {
        case 0: break;
        case 1: rowBlock<1>(mr, rs, ks, K, br, finish, in, o); break;
        case 2: rowBlock<2>(mr, rs, ks, K, br, finish, in, o); break;
        case 3: rowBlock<3>(mr, rs, ks, K, br, finish, in, o); break;
        case 4: rowBlock<(4 < kRows ? 4 : 1)>(mr, rs, ks, K, br, finish, in, o); break;
        case 5: rowBlock<(5 < kRows ? 5 : 1)>(mr, rs, ks, K, br, finish, in, o); break;
        case 6: rowBlock<(6 < kRows ? 6 : 1)>(mr, rs, ks, K, br, finish, in, o); break;
        default: rowBlock<(7 < kRows ? 7 : 1)>(mr, rs, ks, K, br, finish, in, o); break;
    }
}

/// True when every layer of `net` is at most `width` wide.
inline bool fits(const Layers& net, int width = kMaxWidth) {
    for (int l = 0; l < net.count; ++l)
        if (net.inputs[l] > width || net.outputs[l] > width) return false;
    return true;
}

inline Finish hiddenFinish(const Layers& net) { return net.tanh ? Finish::Tanh : Finish::Relu; }

/// The forward pass (nn/mlp_isa.h) tile by tile.
inline void forward(const Layers& net, const float* params, const float* x, Index xStride, Index n,
                    float* const* acts) {
    Eigen::Matrix<float, Eigen::Dynamic, 1> buffers(2 * kMaxWidth * kTile);
    float* a = buffers.data();
    float* z = a + kMaxWidth * kTile;
    for (Index s0 = 0; s0 < n; s0 += kTile) {
        const int count = n - s0 < kTile ? int(n - s0) : kTile;
        loadTile(x, xStride, net.inputs[0], s0, count, a);
        for (int l = 0; l < net.count; ++l) {
            const int in = net.inputs[l], out = net.outputs[l];
            const Finish finish = l + 1 < net.count ? hiddenFinish(net) : Finish::None;
            rowsTimesTile(params + net.weight[l], 1, out, out, in, params + net.bias[l], finish, a, z);
            storeTile(z, out, s0, count, acts[l]);
            float* t = a;  // this layer's output is the next one's input (no std:: helpers here: mlp_isa.h)
            a = z;
            z = t;
        }
    }
}

/// Multiplies tile rows of deltas by the activation's derivative, expressed through the activation
/// a = f(z) that the forward pass kept: 1 − a² for tanh, [a > 0] for ReLU.
inline void multiplyByDerivative(bool tanh, int rows, const float* a, float* d) {
    using namespace Eigen::internal;
    const Packet one = pset1<Packet>(1.f), zero = pzero(Packet());
    for (int i = 0; i < rows * kVectors; ++i) {
        const Packet ai = ploadu<Packet>(a + i * kLanes);
        const Packet f = tanh ? psub(one, pmul(ai, ai)) : pand(one, pcmp_lt(zero, ai));
        pstoreu(d + i * kLanes, pmul(ploadu<Packet>(d + i * kLanes), f));
    }
}

/// Adds a tile's contribution to one layer's gradient accumulators: g[o·in + i] += Σ_s d[o][s] a[i][s]
/// lane by lane, gb[o] += Σ_s d[o][s].
inline void accumulateGradient(int out, int in, const float* d, const float* a, float* g, float* gb) {
    using namespace Eigen::internal;
    for (int o = 0; o < out; ++o) {
        Packet dv[kVectors];
        for (int c = 0; c < kVectors; ++c) dv[c] = ploadu<Packet>(d + o * kTile + c * kLanes);
        Packet sum = ploadu<Packet>(gb + o * kLanes);
        for (int c = 0; c < kVectors; ++c) sum = padd(sum, dv[c]);
        pstoreu(gb + o * kLanes, sum);
        float* go = g + Index(o) * in * kLanes;
        for (int i = 0; i < in; ++i) {
            const float* ai = a + i * kTile;
            // Two chains of kVectors / 2 multiply-adds: half the latency of one.
            Packet acc0 = ploadu<Packet>(go + i * kLanes), acc1 = pzero(Packet());
            for (int c = 0; c < kVectors; c += 2) {
                acc0 = pmadd(dv[c], ploadu<Packet>(ai + c * kLanes), acc0);
                acc1 = pmadd(dv[c + 1], ploadu<Packet>(ai + (c + 1) * kLanes), acc1);
            }
            pstoreu(go + i * kLanes, padd(acc0, acc1));
        }
    }
}

/// The backward pass (nn/mlp_isa.h) tile by tile, down the network.
inline void backward(const Layers& net, const float* params, const float* x, Index xStride, Index n,
                     const float* const* acts, float* const* deltas, float* grad, float* dInputs) {
    using namespace Eigen::internal;
    Index accSize = 0;
    for (int l = 0; l < net.count; ++l) accSize += Index(net.outputs[l]) * (net.inputs[l] + 1);
    Eigen::Matrix<float, Eigen::Dynamic, 1> acc = Eigen::Matrix<float, Eigen::Dynamic, 1>::Zero(accSize * kLanes);
    Eigen::Matrix<float, Eigen::Dynamic, 1> buffers(3 * kMaxWidth * kTile);
    float* d = buffers.data();
    float* prev = d + kMaxWidth * kTile;
    float* a = prev + kMaxWidth * kTile;
    const int top = net.count - 1;
    for (Index s0 = 0; s0 < n; s0 += kTile) {
        const int count = n - s0 < kTile ? int(n - s0) : kTile;
        loadTile(deltas[top], net.outputs[top], net.outputs[top], s0, count, d);
        float* layerAcc = acc.data() + acc.size();
        for (int l = top; l >= 0; --l) {
            const int in = net.inputs[l], out = net.outputs[l];
            layerAcc -= Index(out) * (in + 1) * kLanes;
            if (l > 0)
                loadTile(acts[l - 1], in, in, s0, count, a);
            else
                loadTile(x, xStride, in, s0, count, a);
            accumulateGradient(out, in, d, a, layerAcc, layerAcc + Index(out) * in * kLanes);
            if (l == 0 && !dInputs) break;
            // deltas of the layer below: Wᵀ · d, M(r, k) = W(k, r) at W + r·out + k.
            rowsTimesTile(params + net.weight[l], out, 1, in, out, nullptr, Finish::None, d, prev);
            if (l > 0) {
                multiplyByDerivative(net.tanh != 0, in, a, prev);
                storeTile(prev, in, s0, count, deltas[l - 1]);
            } else {
                storeTile(prev, in, s0, count, dInputs);
            }
            float* t = d;
            d = prev;
            prev = t;
        }
    }
    // Each gradient is the sum of its accumulator's lanes, in one fixed order.
    const float* layerAcc = acc.data();
    for (int l = 0; l < net.count; ++l) {
        const int in = net.inputs[l], out = net.outputs[l];
        float* gW = grad + net.weight[l];
        for (int o = 0; o < out; ++o)
            for (int i = 0; i < in; ++i) gW[o + Index(i) * out] = predux(ploadu<Packet>(layerAcc + (Index(o) * in + i) * kLanes));
        const float* gbAcc = layerAcc + Index(out) * in * kLanes;
        for (int o = 0; o < out; ++o) grad[net.bias[l] + o] = predux(ploadu<Packet>(gbAcc + Index(o) * kLanes));
        layerAcc += Index(out) * (in + 1) * kLanes;
    }
}

}  // namespace small
