#include "runtime/scene/TextureChoice.h"

namespace kiosk::scene {

bool softwareRenderer(const std::string& renderer) {
    for (const char* name : {"llvmpipe", "softpipe", "SwiftShader", "swrast"})
        if (renderer.find(name) != std::string::npos) return true;
    return false;
}

TextureChoice chooseTextureFormat(config::TextureCompression mode, const gl::Caps& caps) {
    TextureChoice c;
    c.software = softwareRenderer(caps.renderer);
    if (mode == config::TextureCompression::Off) {
        c.reason = "off in the scenario";
        return c;
    }
    if (!caps.hasExtension("GL_KHR_texture_compression_astc_ldr")) {
        c.reason = "the context has no GL_KHR_texture_compression_astc_ldr";
        return c;
    }
    if (mode == config::TextureCompression::Auto && c.software) {
        c.reason = "software renderer (it expands blocks to RGBA8 on upload)";
        return c;
    }
    c.format = io::TextureFormat::Astc4x4;
    c.reason = c.software ? "astc requested (software renderer: expanded on upload)"
                          : "the context has ASTC LDR";
    return c;
}

std::size_t compressedTextureBytes(const io::CompressedImage& image, bool software) {
    std::size_t bytes = image.blocks.size();
    if (software)
        for (int level = 0; level < image.levels; ++level)
            bytes +=
                std::size_t(image.levelWidth(level)) * std::size_t(image.levelHeight(level)) * 4;
    return bytes;
}

}  // namespace kiosk::scene
