// Band-limited procedural detail (issue 21, DS04 §4): 2D gradient noise octaves with analytic
// derivatives. Shared by warpgrid.vert (the octaves the warped grid can carry as geometry) and
// the generated fragment program (the remaining octaves as a bump, and texture detail).
// Coordinates are scene metres (small numbers: float precision holds).

const int kDetailOctaves = 4;  // runtime/terrain/DetailSketch.h kDetailOctaves

uint detailHash(ivec2 q) {
    uint h = uint(q.x) * 0x8da6b343u ^ uint(q.y) * 0xd8163841u;
    h = (h ^ (h >> 13)) * 0x5bd1e995u;
    return h ^ (h >> 15);
}

vec2 detailGradient(ivec2 q) {
    float a = float(detailHash(q) & 1023u) * (6.2831853 / 1024.0);
    return vec2(cos(a), sin(a));
}

// Gradient noise in [-1, 1] (2D Perlin noise peaks at sqrt(2)/2; scaled by sqrt(2) and clamped)
// with its gradient: vec3(value, d/dx, d/dy) in units of the noise's own coordinates.
vec3 detailNoise(vec2 p) {
    vec2 i = floor(p);
    vec2 f = p - i;
    ivec2 q = ivec2(i);
    vec2 u = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
    vec2 du = 30.0 * f * f * (f * (f - 2.0) + 1.0);
    vec2 ga = detailGradient(q), gb = detailGradient(q + ivec2(1, 0));
    vec2 gc = detailGradient(q + ivec2(0, 1)), gd = detailGradient(q + ivec2(1, 1));
    float va = dot(ga, f), vb = dot(gb, f - vec2(1.0, 0.0));
    float vc = dot(gc, f - vec2(0.0, 1.0)), vd = dot(gd, f - vec2(1.0, 1.0));
    float v = va + u.x * (vb - va) + u.y * (vc - va) + u.x * u.y * (va - vb - vc + vd);
    vec2 g = ga + u.x * (gb - ga) + u.y * (gc - ga) + u.x * u.y * (ga - gb - gc + gd) +
             du * (u.yx * (va - vb - vc + vd) + vec2(vb, vc) - va);
    return 1.41421356 * vec3(clamp(v, -0.7071068, 0.7071068), g);
}

// Octave k (1-based) of the detail: frequency 2^(k-1) * baseFreq, weight 2^-(k-1) / sum, so the
// weights of all octaves add up to 1 and |sum of weighted octaves| <= 1.
float detailOctaveWeight(int k) {
    return exp2(-float(k - 1)) / (2.0 - exp2(1.0 - float(kDetailOctaves)));
}

// Share of octave k carried by the geometry at split octave o (DS04 Eq. 1, faded over one
// octave): 1 when the grid resolves it, 0 when it is left to the bump.
float detailGeometryShare(int k, float o) {
    return clamp(o - float(k) + 1.0, 0.0, 1.0);
}

// Sum over octaves of weight * share(geometry or bump) * noise, as vec3(value, gradient in
// scene metres). geometry = true: the carried part; false: the rest.
vec3 detailSum(vec2 scenePos, float baseFreq, float o, bool geometry) {
    vec3 s = vec3(0.0);
    for (int k = 1; k <= kDetailOctaves; ++k) {
        float share = detailGeometryShare(k, o);
        float w = detailOctaveWeight(k) * (geometry ? share : 1.0 - share);
        float freq = baseFreq * exp2(float(k - 1));
        vec3 n = detailNoise(scenePos * freq);
        s += w * vec3(n.x, n.yz * freq);
    }
    return s;
}
