#pragma once

#include <cstdint>
#include <vector>

namespace kiosk::render {

/**
 * @brief CPU mesh ready for upload: interleaved float3 position (metres, relative to the tile
 * origin; x east, y north, z up) + float3 normal, and 32-bit triangle indices.
 */
struct MeshData {
    static constexpr int kFloatsPerVertex = 6;
    std::vector<float> vertices;
    std::vector<std::uint32_t> indices;

    std::size_t vertexCount() const { return vertices.size() / kFloatsPerVertex; }
    std::size_t triangleCount() const { return indices.size() / 3; }
    std::size_t byteSize() const {
        return vertices.size() * sizeof(float) + indices.size() * sizeof(std::uint32_t);
    }
};

}  // namespace kiosk::render
