// Lambert with ambient; light direction points from the surface towards the sun.
float lambert(vec3 normal, vec3 lightDir, float ambient) {
    return ambient + (1.0 - ambient) * max(dot(normalize(normal), lightDir), 0.0);
}
