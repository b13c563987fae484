#include "runtime/io/MeshStreams.h"

#include <cstring>
#include <meshoptimizer.h>
#include <mutex>

namespace kiosk::io {

void putU32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
}

std::uint32_t getU32(const std::uint8_t* p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
           std::uint32_t(p[3]) << 24;
}

MeshStreams encodeMeshStreams(const void* vertices, std::size_t count, std::size_t stride,
                              std::vector<std::uint32_t>& indices) {
    // Version 1 of the index codec compresses about 10 % better; the setting is process-wide,
    // so set it once.
    static std::once_flag once;
    std::call_once(once, [] { meshopt_encodeIndexVersion(1); });
    MeshStreams s;
    const void* source = vertices;
    s.vertexCount = count;
    std::vector<std::uint8_t> fetched;
    if (count > 0 && !indices.empty()) {
        fetched.resize(count * stride);
        s.vertexCount = meshopt_optimizeVertexFetch(fetched.data(), indices.data(), indices.size(),
                                                    vertices, count, stride);
        source = fetched.data();
    }
    s.vertices.resize(meshopt_encodeVertexBufferBound(s.vertexCount, stride));
    s.vertices.resize(s.vertexCount
                          ? meshopt_encodeVertexBuffer(s.vertices.data(), s.vertices.size(), source,
                                                       s.vertexCount, stride)
                          : 0);
    s.indices.resize(meshopt_encodeIndexBufferBound(indices.size(), s.vertexCount));
    s.indices.resize(indices.empty() ? 0
                                     : meshopt_encodeIndexBuffer(s.indices.data(), s.indices.size(),
                                                                 indices.data(), indices.size()));
    return s;
}

void putStreamHeader(std::vector<std::uint8_t>& blob, const char* magic, std::uint32_t version,
                     std::uint32_t postIntervals, const MeshStreams& streams,
                     std::size_t indexCount) {
    std::memcpy(blob.data(), magic, 4);
    putU32(blob, 4, version);
    putU32(blob, 8, postIntervals);
    putU32(blob, 12, std::uint32_t(streams.vertexCount));
    putU32(blob, 16, std::uint32_t(indexCount));
    putU32(blob, 20, std::uint32_t(streams.vertices.size()));
    putU32(blob, 24, std::uint32_t(streams.indices.size()));
}

std::string readStreamHeader(const std::uint8_t* data, std::size_t size, std::size_t headerBytes,
                             std::size_t maxBytes, const char* magic, std::uint32_t version,
                             StreamHeader& out) {
    if (!data || size < headerBytes) return "is shorter than its header";
    if (size > maxBytes) return "is larger than " + std::to_string(maxBytes >> 20) + " MiB";
    if (std::memcmp(data, magic, 4) != 0)
        return "does not start with '" + std::string(magic, 4) + "'";
    if (getU32(data + 4) != version)
        return "has version " + std::to_string(getU32(data + 4)) + " (this reads " +
               std::to_string(version) + ")";
    out.postIntervals = getU32(data + 8);
    out.vertexCount = getU32(data + 12);
    out.indexCount = getU32(data + 16);
    out.vertexBytes = getU32(data + 20);
    out.indexBytes = getU32(data + 24);
    return {};
}

std::vector<std::uint8_t> blobWithStreams(std::size_t headerBytes, const MeshStreams& s) {
    std::vector<std::uint8_t> blob(headerBytes + s.vertices.size() + s.indices.size(), 0);
    std::memcpy(blob.data() + headerBytes, s.vertices.data(), s.vertices.size());
    std::memcpy(blob.data() + headerBytes + s.vertices.size(), s.indices.data(), s.indices.size());
    return blob;
}

}  // namespace kiosk::io
