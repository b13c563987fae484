#version 300 es
precision highp float;

// Positions are relative to the tile origin (float precision holds for kilometre tiles); the
// tile's model-view-projection carries the origin.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;

uniform mat4 uModelViewProj;
uniform vec3 uOrigin;        // tile origin in scene coordinates (metres)
uniform vec2 uExtentMin;     // scene coordinates of the data extent, for drape texture coords
uniform vec2 uExtentSize;
uniform float uVerticalScale;

out vec3 vNormal;
out float vElevation;
out vec2 vDrapeUv;

void main() {
    vec3 p = aPosition;
    vElevation = p.z + uOrigin.z;
    vNormal = vec3(aNormal.xy * uVerticalScale, aNormal.z);
    vec2 world = p.xy + uOrigin.xy;
    vDrapeUv = vec2((world.x - uExtentMin.x) / uExtentSize.x,
                    1.0 - (world.y - uExtentMin.y) / uExtentSize.y);
    gl_Position = uModelViewProj * vec4(p.xy, p.z * uVerticalScale, 1.0);
}
