#version 330 core
// Network pass: one full-screen triangle; each pixel reads its G-buffer entry and evaluates its
// object's radiance regression networks — the leaf of each model's kd-tree that holds the pixel —
// whose weights and mapminmax scalers come from the float texture uNetworks (layout documented in core/predict/network_texture.h). The host prepends
//   #define RRF_MAX_VEC4 n        vec4s in the widest layer (inputs included)
//   #define RRF_NET_WIDTH_LOG2 k  log2 of the network texture's width in texels
//   #define RRF_TERM_DIRECT 0, RRF_TERM_INDIRECT 1, RRF_TERM_GLOBAL 2
//                                 output location of each term: its index in core's Term
//                                 (core/render/term.h), which is also the host's colour attachment
// All arithmetic is float, in the order of NetworkModel::predict: (x - offset) * scale, the input
// encoding (shaders/encoding.glsl; none for Ren et al.'s raw inputs), affine layers with tanh/ReLU,
// linear output layer, y / scale + offset. evaluateTerms() in core/predict/network_texture.cpp
// mirrors this shader step by step.
//
// shaders/direct_light.glsl and shaders/encoding.glsl are inserted before this file: with
// uDirectMode != 0 the direct term is rrfDirectLight() (exact direct light) instead of the
// networks'; rrfEncode() writes the encoded features into act[] through the functions below.
//
// Outputs (RGBA32F), one per term at location RRF_TERM_<term>; alpha 1 where an object or a light
// was hit.

uniform sampler2D uGPosition;
uniform sampler2D uGNormal;
uniform sampler2D uGEmission;
uniform sampler2D uNetworks;
uniform vec3 uEye;
uniform vec3 uLight;  // movable light's centre: the network's light-position input

layout(location = RRF_TERM_DIRECT) out vec4 oDirect;
layout(location = RRF_TERM_INDIRECT) out vec4 oIndirect;
layout(location = RRF_TERM_GLOBAL) out vec4 oGlobal;

const int kWidthMask = (1 << RRF_NET_WIDTH_LOG2) - 1;

vec4 rawIn[6];                 // 24 raw inputs: p, view, light, normal, BRDF parameters, reflected, zero-padded
vec4 scaledIn[6];              // the same scaled by the network's input scaler: x'
vec4 act[RRF_MAX_VEC4];        // activations of the current layer (first: the encoded features)
vec4 nxt[RRF_MAX_VEC4];        // activations being computed

vec4 texel(int i) { return texelFetch(uNetworks, ivec2(i & kWidthMask, i >> RRF_NET_WIDTH_LOG2), 0); }
// What shaders/encoding.glsl reads and writes.
float rrfScaledInput(int i) { return scaledIn[i >> 2][i & 3]; }
void rrfSetFeature(int j, float v) { act[j >> 2][j & 3] = v; }
void rrfAddFeature(int j, float v) { act[j >> 2][j & 3] += v; }

// tanh as Eigen 3.4 computes it for float (generic_fast_tanh_float, which NetworkModel::predict
// uses): a 13/6 rational approximation on [-7.9053, 7.9053], x itself for |x| < 0.0004. Matching the
// CPU's formula, rather than calling the built-in tanh, keeps the two predictions within a few float
// ulps of each other for every x: built-in tanh differs between drivers (some evaluate
// (e^x - e^-x) / (e^x + e^-x), NaN for |x| > ~44), and exp-based forms such as 1 - 2 / (e^2x + 1)
// lose relative accuracy near 0, which trained networks with large weights amplify.
float tanhEigen(float a) {
    float x = clamp(a, -7.90531110763549805, 7.90531110763549805);
    float x2 = x * x;
    float p = x2 * -2.76076847742355e-16 + 2.00018790482477e-13;
    p = x2 * p + -8.60467152213735e-11;
    p = x2 * p + 5.12229709037114e-08;
    p = x2 * p + 1.48572235717979e-05;
    p = x2 * p + 6.37261928875436e-04;
    p = x2 * p + 4.89352455891786e-03;
    p = x * p;
    float q = x2 * 1.19825839466702e-06 + 1.18534705686654e-04;
    q = x2 * q + 2.26843463243900e-03;
    q = x2 * q + 4.89352518554385e-03;
    return abs(a) < 0.0004 ? a : p / q;
}

// Walks the kd-tree block at texel `tree` (core/predict/network_texture.h) with the raw inputs and
// returns the texel index of the leaf's network block: x goes left when x[axis] < split. The split
// axes are geometric inputs that reach this shader bit-identical to the CPU's (position from the
// G-buffer, light from a uniform), so every pixel finds the CPU's leaf.
int findLeafNetwork(int tree) {
    int count = int(texel(tree).x);
    int node = 0;
    for (int step = 0; step < count; ++step) {
        vec4 n = texel(tree + 1 + node);
        if (n.x < 0.0) return int(n.y);
        int a = int(n.x);
        node = rawIn[a >> 2][a & 3] < n.y ? int(n.z) : int(n.w);
    }
    return int(texel(tree + 1).y);  // not reached for a valid tree (packNetworkTexture checks it)
}

// A non-finite network output is replaced by 0, as the CPU predictor does.
vec3 finiteOrZero(vec3 v) { return any(isnan(v)) || any(isinf(v)) ? vec3(0.0) : v; }

// Evaluates the network block at texel `base`; outputs 0-2 go to `first`, 3-5 (joint nets) to `second`.
void predictNetwork(int base, out vec3 first, out vec3 second) {
    vec4 h = texel(base), e = texel(base + 1);
    int nIn = int(h.x), nOut = int(h.y), layers = int(h.z);
    bool relu = h.w > 0.5;
    int comps = int(e.x), features = int(e.y), passCount = int(e.z);
    int inV = (nIn + 3) >> 2, outV = (nOut + 3) >> 2;
    int inOff = base + 2, inScale = inOff + inV, outOff = inScale + inV, outScale = outOff + outV;
    int t = outScale + outV;

    for (int k = 0; k < RRF_MAX_VEC4; ++k) act[k] = vec4(0.0);
    for (int k = 0; k < inV; ++k) scaledIn[k] = (rawIn[k] - texel(inOff + k)) * texel(inScale + k);
    if (comps == 0) {  // identity: the features are x' itself (its pass-through indices are 0 ... I-1)
        for (int k = 0; k < inV; ++k) act[k] = scaledIn[k];
        t += (passCount + 3) >> 2;
    } else {
        t = rrfEncode(t, comps, features, passCount);
    }

    for (int l = 0; l < layers; ++l) {
        vec4 lh = texel(t);
        int n = int(lh.y), rowTexels = int(lh.z);
        int rows = t + 1, bias = rows + n * rowTexels;
        for (int k = 0; k < RRF_MAX_VEC4; ++k) nxt[k] = vec4(0.0);
        bool hidden = l + 1 < layers;
        for (int j = 0; j < n; ++j) {
            float s = texel(bias + (j >> 2))[j & 3];
            int row = rows + j * rowTexels;
            for (int k = 0; k < rowTexels; ++k) s += dot(texel(row + k), act[k]);
            if (hidden) s = relu ? max(s, 0.0) : tanhEigen(s);
            nxt[j >> 2][j & 3] = s;
        }
        for (int k = 0; k < RRF_MAX_VEC4; ++k) act[k] = nxt[k];
        t = bias + ((n + 3) >> 2);
    }

    float y[8];
    for (int k = 0; k < 8; ++k) y[k] = 0.0;
    for (int k = 0; k < nOut && k < 8; ++k)
        y[k] = act[k >> 2][k & 3] / texel(outScale + (k >> 2))[k & 3] + texel(outOff + (k >> 2))[k & 3];
    first = vec3(y[0], y[1], y[2]);
    second = vec3(y[3], y[4], y[5]);
}

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 gp = texelFetch(uGPosition, px, 0);
    vec3 emission = texelFetch(uGEmission, px, 0).rgb;
    int id = int(gp.w);
    float covered = id == -1 ? 0.0 : 1.0;
    // Emission seen directly belongs to the direct term (as in rrf::PathTracer).
    oDirect = vec4(emission, covered);
    oIndirect = vec4(0.0, 0.0, 0.0, covered);
    oGlobal = vec4(emission, covered);
    if (id < 0) return;

    vec3 p = gp.xyz;
    vec3 n = texelFetch(uGNormal, px, 0).xyz;
    vec3 v = normalize(uEye - p);
    int entry = 1 + 3 * id;
    rawIn[0] = vec4(p, v.x);
    rawIn[1] = vec4(v.yz, uLight.xy);
    rawIn[2] = vec4(uLight.z, n);
    rawIn[3] = texel(entry + 1);
    rawIn[4] = texel(entry + 2);
    rawIn[5] = vec4(0.0);
    // The derived reflected direction (core/nn/derived_inputs.h) at raw inputs I ... I+2, after the
    // BRDF parameters, in reflectAboutNormal's float operations. Networks that do not derive it read
    // these slots through their scaler's zero padding (scale 0), so one array serves every network.
    int nRecord = int(texel(0).z);
    float d = n.x * v.x + n.y * v.y + n.z * v.z;
    float t2 = d + d;
    for (int i = 0; i < 3; ++i) {
        int slot = nRecord + i;
        rawIn[slot >> 2][slot & 3] = t2 * n[i] - v[i];
    }

    // Term rules of core/predict/network_texture.h (the same as core/predict/predictor.cpp). Which
    // networks run is decided first, then one loop evaluates them through a single call of
    // predictNetwork: drivers inline every call site, and a second, third and fourth inlined copy of
    // the network and its encodings multiplies the program's compile time (llvmpipe compiles on the CPU)
    // without changing a single operation. The loop walks a bit mask (a count unknown to the compiler,
    // so it is not unrolled back into four copies): bit 0 joint, 1 direct, 2 indirect, 3 global.
    vec4 off = texel(entry);
    bool hasDirect = off.x >= 0.0 || off.w >= 0.0 || uDirectMode != 0;
    bool both = hasDirect && (off.y >= 0.0 || off.w >= 0.0);
    int pending = (off.w >= 0.0 ? 1 : 0) | (off.x >= 0.0 && uDirectMode == 0 ? 2 : 0) | (off.y >= 0.0 ? 4 : 0) |
               (!both && off.z >= 0.0 ? 8 : 0);
    vec3 direct = vec3(0.0), indirect = vec3(0.0), global = vec3(0.0);
    while (pending != 0) {
        int bit = (pending & 1) != 0 ? 0 : ((pending & 2) != 0 ? 1 : ((pending & 4) != 0 ? 2 : 3));
        pending &= pending - 1;
        float tree = bit == 0 ? off.w : (bit == 1 ? off.x : (bit == 2 ? off.y : off.z));
        vec3 first, second;
        predictNetwork(findLeafNetwork(int(tree)), first, second);
        first = finiteOrZero(first);
        if (bit == 0) {
            direct = first;
            indirect = finiteOrZero(second);
        } else if (bit == 1) {
            direct = first;
        } else if (bit == 2) {
            indirect = first;
        } else {
            global = first;
        }
    }
    if (uDirectMode != 0)  // direct light computed, not learned (direct_light.glsl, as core/predict/predictor.cpp)
        direct = finiteOrZero(rrfDirectLight(px, textureSize(uGPosition, 0), p, n, v, id));
    if (both || off.z < 0.0) global = direct + indirect;

    oDirect = vec4(direct + emission, 1.0);
    oIndirect = vec4(indirect, 1.0);
    oGlobal = vec4(global + emission, 1.0);
}
