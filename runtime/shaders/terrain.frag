#version 300 es
precision highp float;

// #pragma include "common/encode.glsl"
// #pragma include "common/lighting.glsl"

in vec3 vNormal;
in float vElevation;
in vec2 vDrapeUv;

uniform sampler2D uLut;        // elevation colour ramp (RGBA8, lutSize x 1)
uniform float uLutSize;
uniform vec2 uLutDomain;       // data values at the first and last LUT texel centres
uniform sampler2D uDrape;      // optional imagery drape
uniform float uDrapeWeight;    // 0: ramp only, 1: imagery only
uniform vec3 uLightDir;
uniform float uAmbient;

out vec4 fragColor;

void main() {
    vec4 ramp = texture(uLut, vec2(lutCoord(vElevation, uLutDomain, uLutSize), 0.5));
    vec4 drape = texture(uDrape, vDrapeUv);
    vec3 base = mix(ramp.rgb, drape.rgb, uDrapeWeight);
    fragColor = vec4(base * lambert(vNormal, uLightDir, uAmbient), 1.0);
}
