#version 300 es
precision highp float;

// A full-screen triangle pair from gl_VertexID; no buffers needed.
out vec2 vUv;

void main() {
    vec2 corners[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1),
                              vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
    vec2 c = corners[gl_VertexID];
    vUv = c * 0.5 + 0.5;
    gl_Position = vec4(c, 0.5, 1.0);
}
