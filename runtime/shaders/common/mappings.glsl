// Projective mappings (Trapp & Döllner, "Dynamic Mapping of Raster-Data for 3D Geovirtual
// Environments"; docs/projective-mappings.md). Spliced into the generated terrain shader
// by LayerStack when the stack has mappings; KIOSK_MAX_MAPPINGS is defined before this text.
//
// One std140 block, uploaded only when a mapping changes (render/MappingSet):
//   uMapHeader  x: active count, y: 1 when the context colour matrix applies
//   uMapContext applied to (rgb, 1) of the terrain outside every focus mapping
//   uMap[11 i + 0..1]  rows S, T of M_P · M_O: scene metres -> rectangle coordinate r in [0,1]²
//   uMap[11 i + 2..4]  columns of M_T: r -> sampling coordinate (homogeneous)
//   uMap[11 i + 5..8]  colour matrix M_C columns, applied to (rgb, 1); alpha untouched
//   uMap[11 i + 9]     (data layer, LUT layer or -1, opacity, focus 0/1)
//   uMap[11 i + 10]    (source factor, destination factor, 0, 0)
layout(std140) uniform Mappings {
    vec4 uMapHeader;
    mat4 uMapContext;
    vec4 uMap[KIOSK_MAX_MAPPINGS * 11];
};
// Per draw: the mappings whose footprint touches the tile, ascending (explicit order kept);
// uMapListCount < 0 means all of them. Tiles far from every mapping loop zero times.
uniform ivec4 uMapList[KIOSK_MAX_MAPPINGS / 4 + 1];
uniform int uMapListCount;
uniform highp sampler2DArray uMapData;  // RGBA16F: images, or (LUT coord x valid, valid, 0, 0)
uniform highp sampler2DArray uMapLut;   // RGBA8 rows: [below, LUT..., above]

// Blend factors in the order of config::BlendFactor; destination alpha is 1 (opaque terrain).
vec3 mapFactor(int f, vec4 src, vec3 dst) {
    if (f == 0) return vec3(0.0);
    if (f == 1) return vec3(1.0);
    if (f == 2) return src.rgb;
    if (f == 3) return vec3(1.0) - src.rgb;
    if (f == 4) return dst;
    if (f == 5) return vec3(1.0) - dst;
    if (f == 6) return vec3(src.a);
    if (f == 7) return vec3(1.0 - src.a);
    if (f == 8) return vec3(1.0);
    return vec3(0.0);
}

// The rectangle coordinate of scene point p for mapping i; outside [0,1]^2 fails testAABB2D.
vec2 mapCoord(int i, vec3 p) {
    vec4 h = vec4(p, 1.0);
    return vec2(dot(uMap[11 * i], h), dot(uMap[11 * i + 1], h));
}

bool testAABB2D(vec2 s) {
    return all(greaterThanEqual(s, vec2(0.0))) && all(lessThanEqual(s, vec2(1.0)));
}

// C_S of the paper: the data layer's colour (image, or scalar through its LUT) sampled at
// M_T · (r, 1), colour matrix applied, alpha scaled by the mapping's opacity. The image's top
// row lies at t = 1.
vec4 mapSource(int i, vec2 r) {
    vec4 param = uMap[11 * i + 9];
    vec3 q = mat3(uMap[11 * i + 2].xyz, uMap[11 * i + 3].xyz, uMap[11 * i + 4].xyz) * vec3(r, 1.0);
    vec2 s = q.xy / q.z;
    vec4 d = texture(uMapData, vec3(s.x, 1.0 - s.y, param.x));
    vec4 c = d;
    if (param.y >= 0.0) {
        float u = d.r / max(d.g, 1e-6);
        c = texture(uMapLut, vec3(u, 0.5, param.y));
        c.a *= step(0.5, d.g);
    }
    mat4 m = mat4(uMap[11 * i + 5], uMap[11 * i + 6], uMap[11 * i + 7], uMap[11 * i + 8]);
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
    if (uMapHeader.y > 0.5) {
        // Focus + context: the terrain outside every focus mapping takes the context matrix.
        float focus = 0.0;
        for (int j = 0; j < n; ++j) {
            int i = mapIndex(j);
            if (uMap[11 * i + 9].w < 0.5) continue;
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
        vec4 f = uMap[11 * i + 10];
        C = clamp(src.rgb * mapFactor(int(f.x + 0.5), src, C) +
                      C * mapFactor(int(f.y + 0.5), src, C),
                  0.0, 1.0);
    }
    return C;
}
