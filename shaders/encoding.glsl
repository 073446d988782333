// Input encodings of a network block (core/nn/encoding.h; issue 16): frequency, one-blob and the
// multiresolution hash grid, evaluated from the scaled inputs x' into the features the first layer
// reads. The host inserts this file in front of predict.frag, which defines the four functions
// declared below. The descriptors and hash tables are read from the network texture (layout in
// core/predict/network_texture.h, whose evaluateTerms() mirrors this file step by step).
//
// Float operations follow InputEncoding::forward in the same order, so the features agree with the
// CPU's to float rounding; sin, cos and exp are the driver's (a few ulps from the C library's).

vec4 texel(int i);                 // texel i of the network texture
float rrfScaledInput(int i);       // x'_i = (x_i - offset_i) * scale_i
void rrfSetFeature(int j, float v);
void rrfAddFeature(int j, float v);

const float kRrfPi = 3.14159265358979323846;  // float(pi): float(pi * 2^k) = kRrfPi * 2^k exactly
// The hash grid's per-dimension primes (instant-NGP); uint multiplication wraps modulo 2^32 as the
// CPU's uint32_t does.
const uint kRrfPrimes[4] = uint[4](1u, 2654435761u, 805459861u, 3674653429u);

// Normalised input index i of a component whose index texels start at `at`.
int rrfComponentInput(int at, int i) { return int(texel(at + (i >> 2))[i & 3]); }

// frequency: per input, [x], then for k = 0..K-1: sin(x * pi 2^k), cos(x * pi 2^k).
void rrfEncodeFrequency(int inputsAt, int d, int first, vec4 settings) {
    int frequencies = int(settings.x);
    bool includeInput = settings.y > 0.5;
    int j = first;
    for (int i = 0; i < d; ++i) {
        float x = rrfScaledInput(rrfComponentInput(inputsAt, i));
        if (includeInput) rrfSetFeature(j++, x);
        float m = kRrfPi;
        for (int k = 0; k < frequencies; ++k) {
            float a = x * m;
            rrfSetFeature(j++, sin(a));
            rrfSetFeature(j++, cos(a));
            m *= 2.0;
        }
    }
}

// one_blob: per input, u = clamp((x + 1) / 2, 0, 1) and B Gaussian bins of width 1/B.
void rrfEncodeOneBlob(int inputsAt, int d, int first, vec4 settings) {
    int bins = int(settings.x);
    float b = float(bins);
    int j = first;
    for (int i = 0; i < d; ++i) {
        float x = rrfScaledInput(rrfComponentInput(inputsAt, i));
        float u = clamp((x + 1.0) * 0.5, 0.0, 1.0);
        for (int k = 0; k < bins; ++k) {
            float z = (u - (float(k) + 0.5) / b) * b;
            rrfSetFeature(j++, exp(-0.5 * z * z));
        }
    }
}

// hash_grid: per level, d-linear interpolation of the 2^d surrounding grid vertices' feature
// vectors; a vertex's table entry is its dense index when the level's grid fits the table, else
// its spatial hash. `levelsAt`: the (resolution, dense) pairs; the table's texel is settings.w.
void rrfEncodeHashGrid(int inputsAt, int d, int first, vec4 settings, int levelsAt) {
    int levels = int(settings.x), log2Size = int(settings.y), perLevel = int(settings.z), table = int(settings.w);
    uint mask = (1u << uint(log2Size)) - 1u;
    float u[4];
    // Clamp to [0, 1] with NaN → 0, as the CPU (GLSL's clamp of NaN is undefined).
    for (int i = 0; i < d; ++i) {
        float r = (rrfScaledInput(rrfComponentInput(inputsAt, i)) + 1.0) * 0.5;
        u[i] = r > 0.0 ? (r < 1.0 ? r : 1.0) : 0.0;
    }
    for (int l = 0; l < levels; ++l) {
        vec4 lv = texel(levelsAt + (l >> 1));
        int res = int(lv[(l & 1) * 2]);
        bool dense = lv[(l & 1) * 2 + 1] > 0.5;
        float s = float(res);
        int c[4];
        float f[4];
        for (int i = 0; i < d; ++i) {
            float pos = u[i] * s;
            c[i] = min(int(floor(pos)), res - 1);
            f[i] = pos - float(c[i]);
        }
        int out0 = first + l * perLevel;
        for (int q = 0; q < perLevel; ++q) rrfSetFeature(out0 + q, 0.0);
        for (int k = 0; k < (1 << d); ++k) {
            float w = 1.0;
            uint idx = 0u, stride = 1u;
            for (int i = 0; i < d; ++i) {
                bool up = ((k >> i) & 1) != 0;
                w *= up ? f[i] : 1.0 - f[i];
                uint v = uint(c[i] + (up ? 1 : 0));
                if (dense) {
                    idx += v * stride;
                    stride *= uint(res + 1);
                } else {
                    idx ^= v * kRrfPrimes[i];
                }
            }
            if (!dense) idx &= mask;
            // Float index of the entry's first feature in the component's table (< 2^26: the
            // texture holds at most 2^24 texels).
            int at = ((l << log2Size) + int(idx)) * perLevel;
            vec4 t = texel(table + (at >> 2));
            for (int q = 0; q < perLevel; ++q) {
                int fi = at + q;
                if (q > 0 && (fi & 3) == 0) t = texel(table + (fi >> 2));
                rrfAddFeature(out0 + q, w * t[fi & 3]);
            }
        }
    }
}

// Writes the features of the encoding whose component descriptors start at texel `t` (C = comps
// components, then the pass-through indices of `passCount` inputs, features - passCount ...
// features - 1); returns the texel after them (the first layer's header).
int rrfEncode(int t, int comps, int features, int passCount) {
    for (int c = 0; c < comps; ++c) {
        vec4 h = texel(t);
        int type = int(h.x), d = int(h.y), first = int(h.z);
        int inputsAt = t + 1;
        int settingsAt = inputsAt + ((d + 3) >> 2);
        vec4 settings = texel(settingsAt);
        t = settingsAt + 1;
        if (type == 0) {
            rrfEncodeFrequency(inputsAt, d, first, settings);
        } else if (type == 1) {
            rrfEncodeOneBlob(inputsAt, d, first, settings);
        } else {
            rrfEncodeHashGrid(inputsAt, d, first, settings, t);
            t += (int(settings.x) + 1) >> 1;
        }
    }
    int firstPass = features - passCount;
    for (int q = 0; q < passCount; ++q) rrfSetFeature(firstPass + q, rrfScaledInput(int(texel(t + (q >> 2))[q & 3])));
    return t + ((passCount + 3) >> 2);
}
