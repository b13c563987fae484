#pragma once

#include "runtime/core/Result.h"
#include "runtime/gl/Context.h"
#include "runtime/gl/GlObject.h"
#include "runtime/math/Glm.h"

#include <cstdint>
#include <vector>

namespace kiosk::render {

/** @brief One active mapping as the shader sees it (common/mappings.glsl). */
struct MappingGpu {
    glm::vec4 rowS{0.0f}, rowT{0.0f};  ///< scene metres -> rectangle coordinate in [0,1]²
    glm::mat3 textureMatrix{1.0f};     ///< M_T: rectangle -> sampling coordinate
    glm::mat4 colorMatrix{1.0f};       ///< applied to (rgb, 1)
    int layer = 0;                     ///< data layer (index returned by add*)
    int lut = -1;                      ///< LUT row, -1: the layer is an RGBA image
    float opacity = 1.0f;
    bool focus = false;  ///< inside it the context matrix does not apply
    int srcFactor = 6;   ///< config::BlendFactor order (6 = srcAlpha)
    int dstFactor = 7;   ///< (7 = oneMinusSrcAlpha)
    bool operator==(const MappingGpu&) const = default;
};

/**
 * @brief The GPU side of the projective mappings (Trapp & Döllner §4.1): data layers in one 2D
 * texture array (RGBA16F, `layerSize`², images resampled), LUTs in a second array (RGBA8 rows
 * [below, 1024 entries, above]) and the per-mapping parameters in a std140 uniform block,
 * uploaded only when they change. Render thread only.
 *
 * Limits come from gl::Caps: capacity() = what GL_MAX_UNIFORM_BLOCK_SIZE holds (at most
 * kMaxMappings); layers beyond GL_MAX_ARRAY_TEXTURE_LAYERS are refused (add* returns -1).
 */
class MappingSet {
public:
    static constexpr int kMaxMappings = 64;
    static constexpr int kLutEntries = 1024;
    static constexpr int kLutWidth = kLutEntries + 2;
    static constexpr int kVec4PerMapping = 12;
    static constexpr int kHeaderVec4 = 5;
    /** @brief Layer size TerrainScene asks for (clamped to GL_MAX_TEXTURE_SIZE). */
    static constexpr int kSceneLayerSize = 512;

    /** @brief Bytes one data layer holds: the float RGBA CPU copy plus the RGBA16F array layer. */
    static constexpr std::uint64_t bytesPerLayer(int layerSize) {
        return std::uint64_t(layerSize) * std::uint64_t(layerSize) * (16 + 8);
    }
    /** @brief Bytes one LUT row holds: the CPU copy plus the RGBA8 array layer. */
    static constexpr std::uint64_t bytesPerLut() { return std::uint64_t(kLutWidth) * 4 * 2; }

    /**
     * @brief A GL blend factor (config::BlendFactor order, 0..9) as coefficients k of
     * k.x + k.y C_S.rgb + k.z C_D.rgb + k.w C_S.a; destination alpha is 1. Unknown -> zero.
     */
    static glm::vec4 blendCoefficients(int factor);

    /** @brief Mappings a block of `maxUniformBlockSize` bytes holds (capped at kMaxMappings). */
    static int capacityFor(int maxUniformBlockSize);

    static Result<MappingSet> create(const gl::Caps& caps, int layerSize = 512);

    /** @brief An RGBA8 image (top row first), resampled bilinearly to the layer size. */
    int addImage(int width, int height, const std::uint8_t* rgba);
    /**
     * @brief A scalar raster (top row first, NaN = nodata) for LUT `lut`: values are stored as
     * the LUT coordinate (domain [domainMin, domainMax] -> entries 1..1024, below -> entry 0,
     * above -> entry 1025) premultiplied by validity, so filtering never mixes in nodata.
     */
    int addScalar(int width, int height, const float* values, double domainMin, double domainMax);
    /** @brief A LUT row: `rgba` kLutEntries entries, then the below and above colours. */
    int addLut(const std::vector<std::uint8_t>& rgba, const glm::u8vec4& below,
               const glm::u8vec4& above);
    /** @brief Upload the arrays (after the add* calls; again if layers were added later). */
    void commit();

    /**
     * @brief The active mappings in order; uploads the block only when something changed.
     * Mappings beyond capacity() are dropped (counted by the caller). Returns true if uploaded.
     */
    bool setMappings(const std::vector<MappingGpu>& mappings, bool contextOn,
                     const glm::mat4& contextMatrix);

    /** @brief Bind the arrays to `dataUnit`/`lutUnit` and the block to binding point 1. */
    void bind(GLuint program, int dataUnit, int lutUnit) const;

    int capacity() const noexcept { return mCapacity; }
    int layerCount() const noexcept { return int(mLayers.size()); }
    int lutCount() const noexcept { return int(mLuts.size()); }
    std::uint64_t layerBytes() const noexcept { return mLayers.size() * bytesPerLayer(mLayerSize); }
    std::uint64_t lutBytes() const noexcept { return mLuts.size() * bytesPerLut(); }
    std::uint64_t blockUploads() const noexcept { return mBlockUploads; }

private:
    int mLayerSize = 512;
    int mMaxLayers = 256;
    int mCapacity = 0;
    std::vector<std::vector<float>> mLayers;       ///< RGBA float, layerSize²
    std::vector<std::vector<std::uint8_t>> mLuts;  ///< RGBA8, kLutWidth
    gl::Texture mData, mLut;
    gl::Buffer mBlock;
    std::vector<MappingGpu> mLast;
    bool mLastContext = false;
    glm::mat4 mLastContextMatrix{1.0f};
    bool mUploadedOnce = false;
    bool mWarnedCapacity = false;
    std::uint64_t mBlockUploads = 0;
};

}  // namespace kiosk::render
