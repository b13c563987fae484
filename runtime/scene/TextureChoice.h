#pragma once

#include "config/Scenario.h"
#include "runtime/gl/Context.h"
#include "runtime/io/TextureBlocks.h"

#include <cstddef>
#include <string>

namespace kiosk::scene {

/** @brief The block format a scene's imagery is uploaded in, chosen once per GL context. */
struct TextureChoice {
    io::TextureFormat format = io::TextureFormat::None;  ///< None: the PNG tiles, RGBA8
    /** @brief The renderer rasterizes in software and expands blocks to RGBA8 on upload. */
    bool software = false;
    std::string reason;  ///< one phrase for the log and the docs' decision table
};

/**
 * @brief Whether `renderer` (GL_RENDERER) is a software rasterizer: llvmpipe, softpipe,
 * SwiftShader. Those expand compressed textures to RGBA8 when they are uploaded and keep the
 * blocks as well (docs/terrain.md §11: 1.25x the bytes of RGBA8, 3x the upload time).
 */
bool softwareRenderer(const std::string& renderer);

/**
 * @brief terrain.textureCompression against what the context offers: Off -> None; Astc -> ASTC
 * 4x4 when GL_KHR_texture_compression_astc_ldr is listed; Auto -> the same, but only on a
 * hardware renderer (on a software one compression costs memory, upload time and colour and
 * saves nothing). Without the extension: None (the PNG tiles), whatever the setting.
 */
TextureChoice chooseTextureFormat(config::TextureCompression mode, const gl::Caps& caps);

/**
 * @brief Bytes a compressed texture holds in the GL: its blocks; plus the RGBA8 levels a
 * software renderer expands them to.
 */
std::size_t compressedTextureBytes(const io::CompressedImage& image, bool software);

}  // namespace kiosk::scene
