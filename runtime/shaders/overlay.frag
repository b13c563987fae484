#version 300 es
precision highp float;

in vec2 vUv;
in vec4 vColor;
flat in int vMode;

uniform sampler2D uAtlas;  // R8 glyph coverage
uniform sampler2D uImage;  // RGBA8 (a LUT for legends)

out vec4 fragColor;

void main() {
    if (vMode == 1) {
        fragColor = vec4(vColor.rgb, vColor.a * texture(uAtlas, vUv).r);
    } else if (vMode == 2) {
        fragColor = texture(uImage, vUv) * vColor;
    } else {
        fragColor = vColor;
    }
}
