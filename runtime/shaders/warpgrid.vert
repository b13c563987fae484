#version 300 es
precision highp float;

// The importance-warped grid near the camera (issue 21; docs/terrain.md §7). Vertices carry the
// data surface (heights and normals read from the drawn tiles) at warped positions; the octaves
// of procedural detail the local grid spacing resolves are added here as displacement, the rest
// is left to the fragment stage as a bump (DS04 §4.1).
// #pragma include "common/detailnoise.glsl"

layout(location = 0) in vec3 aPosition;  // xy relative to uOrigin, z absolute (data surface)
layout(location = 1) in vec3 aNormal;    // data normal
layout(location = 2) in vec4 aDetail;    // amplitude (m), split octave, border fade, skirt depth (m)

uniform mat4 uModelViewProj;
uniform vec3 uOrigin;
uniform float uVerticalScale;
uniform float uDetailFreq;  // 1 / data post spacing

out vec3 vNormalDetail;
out vec3 vNormalData;
out float vElevation;
out vec2 vScenePos;
out float vDetailOffset;
out vec2 vDetailParam;  // (amplitude * fade, split octave)

void main() {
    vec3 p = aPosition;
    vScenePos = p.xy + uOrigin.xy;
    float amp = aDetail.x * aDetail.z;
    vec3 d = amp * detailSum(vScenePos, uDetailFreq, aDetail.y, true);
    vDetailOffset = d.x;
    vElevation = p.z;
    vDetailParam = vec2(amp, aDetail.y);
    vec2 slope = -aNormal.xy / max(aNormal.z, 1e-3);  // dz/dx, dz/dy of the data
    vNormalData = vec3(aNormal.xy * uVerticalScale, aNormal.z);
    vNormalDetail = normalize(vec3(-(slope + d.yz) * uVerticalScale, 1.0));
    float z = p.z + d.x - aDetail.w;  // skirt vertices hang below the border
    gl_Position = uModelViewProj * vec4(p.xy, z * uVerticalScale - uOrigin.z, 1.0);
}
