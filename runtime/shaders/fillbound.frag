#version 300 es
precision highp float;

// The llvmpipe fill-rate bound: every pixel does FETCHES dependent texture reads, the same work
// per pixel as the terrain shader, with no geometry cost. Benchmarks report frame time / this.
#ifndef FETCHES
#define FETCHES 2
#endif

in vec2 vUv;
uniform sampler2D uTex;
out vec4 fragColor;

void main() {
    vec4 acc = vec4(0.0);
    vec2 uv = vUv;
    for (int i = 0; i < FETCHES; ++i) {
        vec4 t = texture(uTex, uv);
        acc += t;
        uv = fract(uv + t.xy * 0.01 + 0.003);
    }
    fragColor = vec4(acc.rgb / float(FETCHES), 1.0);
}
