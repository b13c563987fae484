#version 300 es
precision highp float;

// Screen-space quads in pixels (origin top-left), batched per frame.
layout(location = 0) in vec2 aPos;
layout(location = 1) in vec2 aUv;
layout(location = 2) in vec4 aColor;
layout(location = 3) in float aMode;  // 0 solid, 1 glyph (atlas alpha), 2 image

uniform vec2 uViewport;

out vec2 vUv;
out vec4 vColor;
flat out int vMode;

void main() {
    vUv = aUv;
    vColor = aColor;
    vMode = int(aMode + 0.5);
    vec2 ndc = aPos / uViewport * 2.0 - 1.0;
    gl_Position = vec4(ndc.x, -ndc.y, 0.0, 1.0);
}
