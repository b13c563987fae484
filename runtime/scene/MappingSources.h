#pragma once

#include "config/Scenario.h"
#include "runtime/core/Result.h"
#include "runtime/io/StoreReader.h"
#include "runtime/mapping/MappingModel.h"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace kiosk::scene {

/** @brief An RGBA8 image, top row first. */
struct MappingImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;
};

/**
 * @brief Read a PNG or JPEG file (1-4 channels, any bit depth) as RGBA8 (grey spreads to RGB,
 * missing alpha is opaque). Errors: MAPPING_IMAGE naming the file.
 */
Result<MappingImage> loadMappingImage(const std::filesystem::path& file);

/**
 * @brief Sample a store raster over a mapping's rectangle into `size` x `size` values (top row
 * at the +V edge, NaN = nodata): `source.layer` (a scalar layer, read as elevation posts) or
 * `source.sequence` (its last frame: the largest extent of a flood). The pyramid level is the
 * coarsest whose pixels are no larger than the rectangle's texels; posts are taken nearest.
 * Render thread (uses the scene's reader). Errors: MAPPING_SOURCE naming layer and tile.
 */
Result<std::vector<float>> sampleStoreRaster(io::StoreReader& reader,
                                             const config::SourceRef& source,
                                             const mapping::MappingState& rect, int size);

}  // namespace kiosk::scene
