#version 300 es
precision highp float;

// Occlusion culling (docs/terrain.md §10): the 12 triangles of an axis-aligned box from
// gl_VertexID, no buffers. Corner c has x = bit 0, y = bit 1, z = bit 2 (0: min, 1: max).
// Face culling is off in the terrain pass, so the winding does not matter.
uniform mat4 uModelViewProj;
uniform vec3 uBoxMin;  // relative to the matrix's origin
uniform vec3 uBoxMax;

const int kCorners[36] = int[36](0, 2, 6, 0, 6, 4,   // x min
                                 1, 3, 7, 1, 7, 5,   // x max
                                 0, 1, 5, 0, 5, 4,   // y min
                                 2, 3, 7, 2, 7, 6,   // y max
                                 0, 1, 3, 0, 3, 2,   // z min
                                 4, 5, 7, 4, 7, 6);  // z max

void main() {
    int c = kCorners[gl_VertexID];
    vec3 t = vec3(float(c & 1), float((c >> 1) & 1), float((c >> 2) & 1));
    gl_Position = uModelViewProj * vec4(mix(uBoxMin, uBoxMax, t), 1.0);
}
