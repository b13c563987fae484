#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
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

/**
 * @brief The header words both blobs start with: 4-byte magic, u32 version, post intervals,
 * vertex count, index count, vertex stream bytes, index stream bytes.
 */
struct StreamHeader {
    std::uint32_t postIntervals = 0, vertexCount = 0, indexCount = 0;
    std::uint32_t vertexBytes = 0, indexBytes = 0;
};
inline constexpr std::size_t kStreamHeaderBytes = 28;

/** @brief Write the shared header words of `streams` (`indexCount` indices) into `blob`. */
void putStreamHeader(std::vector<std::uint8_t>& blob, const char* magic, std::uint32_t version,
                     std::uint32_t postIntervals, const MeshStreams& streams,
                     std::size_t indexCount);

/**
 * @brief Read them from a blob of `size` bytes whose whole header is `headerBytes` long: empty,
 * or what is wrong ("is shorter than its header", ...) for the caller's corruption message.
 * The streams' sizes are checked against the blob's later, by the caller.
 */
std::string readStreamHeader(const std::uint8_t* data, std::size_t size, std::size_t headerBytes,
                             std::size_t maxBytes, const char* magic, std::uint32_t version,
                             StreamHeader& out);

/** @brief A blob of `headerBytes` zero bytes (for the caller's header) and the streams. */
std::vector<std::uint8_t> blobWithStreams(std::size_t headerBytes, const MeshStreams& streams);

}  // namespace kiosk::io
