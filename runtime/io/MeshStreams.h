#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

// What the stored mesh blobs (MeshBlob.h: grid meshes, TinBlob.h: local TINs) share: a
// little-endian header of words and meshoptimizer's vertex and index streams after it.
namespace kiosk::io {

void putU32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v);
std::uint32_t getU32(const std::uint8_t* p);

/** @brief meshoptimizer's streams of a triangle list (MeshStreams.h). */
struct MeshStreams {
    std::size_t vertexCount = 0;  ///< vertices used by the triangles, in first-use order
    std::vector<std::uint8_t> vertices, indices;
};

/**
 * @brief Encode `count` vertices of `stride` bytes and a triangle list: vertices reordered to
 * first use (the delta coding of the vertex stream and the index codec both work best that way;
 * unused ones are dropped), `indices` rewritten to match, triangle order kept. Index codec
 * version 1 (meshoptimizer >= 0.14).
 */
MeshStreams encodeMeshStreams(const void* vertices, std::size_t count, std::size_t stride,
                              std::vector<std::uint32_t>& indices);

/** @brief A blob of `headerBytes` zero bytes (for the caller's header) and the streams. */
std::vector<std::uint8_t> blobWithStreams(std::size_t headerBytes, const MeshStreams& streams);

}  // namespace kiosk::io
