#pragma once

#include "runtime/core/Result.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

// The stored form of a tile's simplified surface mesh (table kiosk_tile_meshes,
// docs/store-format.md): quantised vertices and a triangle list, compressed with meshoptimizer's
// vertex and index codecs (Wahl et al. 2004, section 4 "Compression": implicit xy grid address,
// explicit quantised height, coded connectivity). No skirts: they depend on the run's
// neighbour error bound and are added on load (terrain/StoredMesh.h).
namespace kiosk::io {

/**
 * @brief A tile's surface mesh in store units. Vertex v: post column and row at
 * `posts[3v], posts[3v + 1]` (0..postIntervals, posts at pixel centres), quantised height
 * `posts[3v + 2]` (z = zOffset + q * zScale, metres), unit normal at `normals[3v]`. Indices are
 * counter-clockwise (seen from above) triangles in the order the renderer needs (TileMesh cell
 * order). In the blob each vertex is 16 bytes: the three uint16, the split tier (or 0), and the
 * normal as meshoptimizer's octahedral encoding.
 */
struct QuantizedMesh {
    int postIntervals = 0;
    double zOffset = 0.0;
    double zScale = 1.0;
    std::vector<std::uint16_t> posts;
    std::vector<float> normals;
    std::vector<std::uint32_t> indices;
    /**
     * @brief Per vertex, or empty: the first tolerance tier k at which the vertex no longer
     * splits its triangles (its split error <= tolerance * 2^k; 0xFFFF: never, next to nodata).
     * With it, the mesh of any coarser tier is the RTIN extraction that splits at a midpoint
     * only while its tier is above k (terrain/StoredMesh.h): one stored mesh serves all tiers.
     */
    std::vector<std::uint16_t> splitTiers;

    std::size_t vertexCount() const noexcept { return posts.size() / 3; }
};

/** @brief One row of kiosk_tile_meshes, decoded. */
struct TileMeshRow {
    int tier = 0;            ///< tolerance tier the importer built it for (TerrainOptions)
    double tolerance = 0.0;  ///< TIN tolerance it was simplified with (metres)
    QuantizedMesh mesh;
};

/** @brief Largest encoded mesh accepted (far above a full-resolution 257x257 tile's ~0.5 MB). */
inline constexpr std::size_t kMaxMeshBlobBytes = 16u << 20;

/** @brief Compress (vertex order optimised for fetch, indices rewritten; triangle order kept). */
std::vector<std::uint8_t> encodeMeshBlob(const QuantizedMesh& mesh);

/**
 * @brief Decompress and check a blob: header, sizes bounded by `postIntervals` (<= 4096),
 * every index a vertex, every vertex on the post grid, no degenerate triangle. Errors are
 * STORE_MESH_CORRUPT with `where` (a tile name) and no file (the caller adds it).
 */
Result<QuantizedMesh> decodeMeshBlob(const std::uint8_t* data, std::size_t size,
                                     const std::string& where);
/**
 * @brief Same into `out`, whose buffers are reused: the loader decodes every tile into one
 * QuantizedMesh (fresh megabyte buffers per tile cost more in page faults than the decoding).
 */
Diagnostics decodeMeshBlob(const std::uint8_t* data, std::size_t size, const std::string& where,
                           QuantizedMesh& out);

}  // namespace kiosk::io
