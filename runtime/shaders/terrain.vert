#version 300 es
precision highp float;

// Positions are relative to the tile origin (float precision holds for kilometre tiles); the
// tile's model-view-projection carries the origin. Layers are sampled by scene position (metres
// from the scene origin), so every layer can use its own pyramid level or an ancestor's tile.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;

uniform mat4 uModelViewProj;
uniform vec3 uOrigin;  // tile origin relative to the scene origin; z is absolute metres
uniform float uVerticalScale;

out vec3 vNormal;
out float vElevation;
out vec2 vScenePos;

void main() {
    vec3 p = aPosition;
    vElevation = p.z + uOrigin.z;
    // Exaggerating heights by s scales the gradient by s: n ~ (-s dz/dx, -s dz/dy, 1).
    vNormal = vec3(aNormal.xy * uVerticalScale, aNormal.z);
    vScenePos = p.xy + uOrigin.xy;
    gl_Position = uModelViewProj * vec4(p.xy, (p.z + uOrigin.z) * uVerticalScale - uOrigin.z, 1.0);
}
