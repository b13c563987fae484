// Projective mappings (Trapp & Döllner, "Dynamic Mapping of Raster-Data for 3D Geovirtual
// Environments"; docs/projective-mappings.md). Spliced into the generated terrain shader
// by LayerStack when the stack has mappings; KIOSK_MAX_MAPPINGS is defined before this text.
//
// One std140 block, uploaded only when a mapping changes (render/MappingSet):
//   uMapHeader  x: active count, y: 1 when the context colour matrix applies
//   uMapContext applied to (rgb, 1) of the terrain outside every focus mapping
//   uMap[12 i + 0..1]  rows S, T of M_P · M_O: scene metres -> rectangle coordinate r in [0,1]²
//   uMap[12 i + 2..4]  columns of M_T: r -> sampling coordinate (homogeneous)
//   uMap[12 i + 5..8]  colour matrix M_C columns, applied to (rgb, 1); alpha untouched
//   uMap[12 i + 9]     (data layer, LUT layer or -1, opacity, focus 0/1)
//   uMap[12 i + 10..11] source / destination blend factor as coefficients k of
//                      k.x + k.y C_S.rgb + k.z C.rgb + k.w C_S.a (every GL factor is one)
layout(std140) uniform Mappings {
    vec4 uMapHeader;
    mat4 uMapContext;
    vec4 uMap[KIOSK_MAX_MAPPINGS * 12];
};
// Per draw: the mappings whose footprint touches the tile, ascending (explicit order kept);
// uMapListCount < 0 means all of them. Tiles far from every mapping loop zero times.
uniform ivec4 uMapList[KIOSK_MAX_MAPPINGS / 4 + 1];
uniform int uMapListCount;
uniform highp sampler2DArray uMapData;  // RGBA16F: images, or (LUT coord x valid, valid, 0, 0)
uniform highp sampler2DArray uMapLut;   // RGBA8 rows: [below, LUT..., above]

#ifdef KIOSK_MAP_INPUTS
// Mappings of a layer of the stack (scenario "layer"): main() sets input k from that layer's
// value at the fragment before applyMappings; a mapping whose data layer is -1 - k reads it
// instead of uMapData. Stored as a data layer holds its values: (LUT coordinate x validity,
// validity), the coordinate by render::MappingSet::addScalar's rule (domain -> entries
// 1..1024 of the 1026-texel row, below -> 0, above -> 1025).
vec2 gMapInput[KIOSK_MAP_INPUTS];

vec2 mapInputOf(vec2 d, float present, vec2 domain) {
    float ok = step(0.5, d.g) * step(0.5, present);
    float v = d.r / max(d.g, 1e-6);
    float range = domain.y - domain.x;
    float e = 1.0 + (range > 0.0 ? (v - domain.x) / range : 0.0) * 1023.0;
    e = v < domain.x ? 0.0 : (v > domain.y ? 1025.0 : e);  // below / above entries
    return vec2((e + 0.5) / 1026.0 * ok, ok);
}
#endif

// A blend factor from its coefficients (render::blendCoefficients): no branches, which matters
// on llvmpipe where a per-mapping switch runs every case for every lane.
vec3 mapFactor(vec4 k, vec4 src, vec3 dst) {
    return vec3(k.x) + k.y * src.rgb + k.z * dst + vec3(k.w * src.a);
}

// The rectangle coordinate of scene point p for mapping i; outside [0,1]^2 fails testAABB2D.
vec2 mapCoord(int i, vec3 p) {
    vec4 h = vec4(p, 1.0);
    return vec2(dot(uMap[12 * i], h), dot(uMap[12 * i + 1], h));
}

bool testAABB2D(vec2 s) {
    return all(greaterThanEqual(s, vec2(0.0))) && all(lessThanEqual(s, vec2(1.0)));
}

// C_S of the paper: the data layer's colour (image, or scalar through its LUT) sampled at
// M_T · (r, 1), colour matrix applied, alpha scaled by the mapping's opacity. The image's top
// row lies at t = 1.
vec4 mapSource(int i, vec2 r) {
    vec4 param = uMap[12 * i + 9];
    vec3 q = mat3(uMap[12 * i + 2].xyz, uMap[12 * i + 3].xyz, uMap[12 * i + 4].xyz) * vec3(r, 1.0);
    vec2 s = q.xy / q.z;
    vec4 d = texture(uMapData, vec3(s.x, 1.0 - s.y, max(param.x, 0.0)));
#ifdef KIOSK_MAP_INPUTS
    if (param.x < -0.5) d = vec4(gMapInput[int(-0.5 - param.x)], 0.0, 0.0);
#endif
    vec4 c = d;
    if (param.y >= 0.0) {
        float u = d.r / max(d.g, 1e-6);
        c = texture(uMapLut, vec3(u, 0.5, param.y));
        c.a *= step(0.5, d.g);
    }
    mat4 m = mat4(uMap[12 * i + 5], uMap[12 * i + 6], uMap[12 * i + 7], uMap[12 * i + 8]);
    c.rgb = clamp((m * vec4(c.rgb, 1.0)).rgb, 0.0, 1.0);
    c.a = clamp(c.a * param.z, 0.0, 1.0);
    return c;
}

// Figure 2 of the paper: every active mapping in its explicit order (later over earlier),
// skipping those whose coordinates fall outside [0,1]^2.
int mapIndex(int j) {
    return uMapListCount < 0 ? j : uMapList[j / 4][j % 4];
}

vec3 applyMappings(vec3 C, vec3 p) {
    int n = uMapListCount < 0 ? int(uMapHeader.x + 0.5) : uMapListCount;
    // Uniform early out: on llvmpipe even loops that run zero times cost (measured ~2x).
    if (n <= 0 && uMapHeader.y < 0.5) return C;
    if (uMapHeader.y > 0.5) {
        // Focus + context: the terrain outside every focus mapping takes the context matrix.
        float focus = 0.0;
        for (int j = 0; j < n; ++j) {
            int i = mapIndex(j);
            if (uMap[12 * i + 9].w < 0.5) continue;
            vec2 s = mapCoord(i, p);
            if (testAABB2D(s)) focus = max(focus, mapSource(i, s).a);
        }
        vec3 dimmed = clamp((uMapContext * vec4(C, 1.0)).rgb, 0.0, 1.0);
        C = mix(dimmed, C, focus);
    }
    for (int j = 0; j < n; ++j) {
        int i = mapIndex(j);
        vec2 s = mapCoord(i, p);
        if (!testAABB2D(s)) continue;
        vec4 src = mapSource(i, s);
        C = clamp(src.rgb * mapFactor(uMap[12 * i + 10], src, C) +
                      C * mapFactor(uMap[12 * i + 11], src, C),
                  0.0, 1.0);
    }
    return C;
}
