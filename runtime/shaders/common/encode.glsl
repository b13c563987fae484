// Helpers shared by terrain and overlay shaders.

// Map a data value into the [0,1] coordinate of a LUT texture whose first and last texel
// centres sit at domain.x and domain.y (so stop values land exactly on texel centres).
float lutCoord(float value, vec2 domain, float lutSize) {
    float t = clamp((value - domain.x) / max(domain.y - domain.x, 1e-20), 0.0, 1.0);
    return (t * (lutSize - 1.0) + 0.5) / lutSize;
}

// The same for a layer stack's LUT, whose lutSize ramp texels lie between two edge texels
// (render::makeEdgedLutTexture): coordinate 0 and 1 read the edges exactly (clamp to edge).
float lutCoordEdged(float value, vec2 domain, float lutSize) {
    float t = clamp((value - domain.x) / max(domain.y - domain.x, 1e-20), 0.0, 1.0);
    return (t * (lutSize - 1.0) + 1.5) / (lutSize + 2.0);
}
