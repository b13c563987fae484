// Helpers shared by terrain and overlay shaders.

// Map a data value into the [0,1] coordinate of a LUT texture whose first and last texel
// centres sit at domain.x and domain.y (so stop values land exactly on texel centres).
float lutCoord(float value, vec2 domain, float lutSize) {
    float t = clamp((value - domain.x) / max(domain.y - domain.x, 1e-20), 0.0, 1.0);
    return (t * (lutSize - 1.0) + 0.5) / lutSize;
}

// The same for a layer stack's LUT (render::makeEdgedLutTexture): texel 0 below the domain, the
// lutSize ramp texels, one above, one for nodata. Coordinate 0 reads the below texel and 1 the
// nodata texel exactly (clamp to edge); the above texel is lutAboveCoord().
float lutCoordEdged(float value, vec2 domain, float lutSize) {
    float t = clamp((value - domain.x) / max(domain.y - domain.x, 1e-20), 0.0, 1.0);
    return (t * (lutSize - 1.0) + 1.5) / (lutSize + 3.0);
}
float lutAboveCoord(float lutSize) { return (lutSize + 1.5) / (lutSize + 3.0); }
