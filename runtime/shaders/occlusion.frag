#version 300 es
precision mediump float;

// Occlusion queries only count samples that pass the depth test; colour writes are masked off.
out vec4 fragColor;

void main() { fragColor = vec4(1.0); }
