#pragma once

#include "runtime/core/Result.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

// The stored form of a tile's local TIN (table kiosk_tile_tins, docs/store-format.md; Baumann
// et al. 2000, "Hybrid Terrain Models"): a triangulation that replaces the tile's grid mesh,
// built at import from breaklines or a hydraulic model's own mesh. Its border is the tile's
// border posts, so it meets the neighbouring grid tiles like a full-resolution grid tile would.
// Compressed with meshoptimizer's vertex and index codecs like the stored grid meshes
// (MeshBlob.h). No skirts: the loader adds them (terrain/TinMesh.h).
namespace kiosk::io {

/** @brief Sub-post steps per post interval of a TIN vertex's stored x and y. */
inline constexpr std::uint32_t kTinSubdivisions = 1024;

/**
 * @brief A tile's TIN in store units. Vertex v: x and y in 1/kTinSubdivisions of a post interval
 * from post (0, 0) (column east, row south: `xy[2v]`, `xy[2v + 1]`, 0..postIntervals *
 * kTinSubdivisions, so posts are exact), height `z[v]` in metres (float: a post's height is the
 * same float the grid mesh has there), unit normal at `normals[3v]` (east, north, up).
 * Triangles are counter-clockwise seen from above.
 */
struct TinMesh {
    int postIntervals = 0;
    /** @brief Every border post is a vertex (false only where border posts are nodata). */
    bool fullBorder = true;
    std::vector<std::uint32_t> xy;
    std::vector<float> z;
    std::vector<float> normals;
    std::vector<std::uint32_t> indices;

    std::size_t vertexCount() const noexcept { return z.size(); }
    std::size_t triangleCount() const noexcept { return indices.size() / 3; }
    /** @brief Whether vertex v sits exactly on a post. */
    bool onPost(std::size_t v) const noexcept {
        return xy[2 * v] % kTinSubdivisions == 0 && xy[2 * v + 1] % kTinSubdivisions == 0;
    }
};

/** @brief One row of kiosk_tile_tins, decoded. */
struct TileTinRow {
    std::string source;      ///< the import's --name (which lines or model built it)
    int tier = 0;            ///< tolerance tier (TerrainOptions) it was built for
    double tolerance = 0.0;  ///< TIN tolerance it was built with (metres)
    TinMesh mesh;
};

/** @brief Largest encoded TIN accepted. */
inline constexpr std::size_t kMaxTinBlobBytes = 16u << 20;

/** @brief Compress (vertex order optimised for fetch, indices rewritten; triangle order kept). */
std::vector<std::uint8_t> encodeTinBlob(const TinMesh& mesh);

/**
 * @brief Decompress and check a blob into `out` (buffers reused): header, sizes bounded before
 * allocating, every index a vertex, every vertex inside the tile, finite heights and normals,
 * every triangle counter-clockwise and not degenerate, and (TinMesh::fullBorder) every border
 * post of the tile a vertex (the crack-free seam with the grid). Errors are STORE_TIN_CORRUPT with
 * `where`.
 */
Diagnostics decodeTinBlob(const std::uint8_t* data, std::size_t size, const std::string& where,
                          TinMesh& out);

}  // namespace kiosk::io
