#include "runtime/io/TinBlob.h"

#include "runtime/io/MeshStreams.h"

#include <cmath>
#include <cstring>
#include <meshoptimizer.h>

namespace kiosk::io {

namespace {

// Blob layout (little-endian): "KTIN", u32 version, u32 postIntervals, u32 vertexCount,
// u32 indexCount, u32 vertexStreamBytes, u32 indexStreamBytes, u32 flags, then the
// meshoptimizer vertex stream (16 bytes a vertex: u32 x, u32 y, f32 z, i8 normal x, y, z, 0) and
// index stream.
constexpr char kMagic[4] = {'K', 'T', 'I', 'N'};
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kHeaderBytes = 32;
constexpr std::size_t kVertexBytes = 16;
constexpr std::uint32_t kMaxPostIntervals = 4096;
constexpr std::uint32_t kFlagFullBorder = 1;  // every border post is a vertex (TinMesh::fullBorder)
// A TIN has at most every post plus the lines' vertices; 4 vertices per post bounds both.
constexpr std::uint64_t kVerticesPerPost = 4;

struct PackedVertex {
    std::uint32_t x, y;
    float z;
    std::int8_t n[4];
};
static_assert(sizeof(PackedVertex) == kVertexBytes);

std::int8_t snorm8(float v) {
    return std::int8_t(std::lround(std::fmax(-1.0f, std::fmin(1.0f, v)) * 127.0f));
}

}  // namespace

std::vector<std::uint8_t> encodeTinBlob(const TinMesh& mesh) {
    const std::size_t count = mesh.vertexCount();
    std::vector<PackedVertex> packed(count);
    for (std::size_t v = 0; v < count; ++v) {
        PackedVertex& p = packed[v];
        p.x = mesh.xy[2 * v];
        p.y = mesh.xy[2 * v + 1];
        p.z = mesh.z[v];
        // 8-bit normals: within about half a degree, below what the 8-bit shading shows.
        for (int c = 0; c < 3; ++c) p.n[c] = snorm8(mesh.normals[3 * v + std::size_t(c)]);
        p.n[3] = 0;
    }
    std::vector<std::uint32_t> indices = mesh.indices;
    const MeshStreams streams = encodeMeshStreams(packed.data(), count, kVertexBytes, indices);
    std::vector<std::uint8_t> blob = blobWithStreams(kHeaderBytes, streams);
    putStreamHeader(blob, kMagic, kVersion, std::uint32_t(mesh.postIntervals), streams,
                    indices.size());
    putU32(blob, 28, mesh.fullBorder ? kFlagFullBorder : 0u);
    return blob;
}

Diagnostics decodeTinBlob(const std::uint8_t* data, std::size_t size, const std::string& where,
                          TinMesh& m) {
    Diagnostics d;
    auto corrupt = [&](const std::string& what) {
        d.error("STORE_TIN_CORRUPT", "", where, "stored TIN " + what);
        return d;
    };
    StreamHeader h;
    const std::string bad =
        readStreamHeader(data, size, kHeaderBytes, kMaxTinBlobBytes, kMagic, kVersion, h);
    if (!bad.empty()) return corrupt(bad);
    const std::uint32_t n = h.postIntervals, vCount = h.vertexCount, iCount = h.indexCount;
    const std::uint32_t vBytes = h.vertexBytes, iBytes = h.indexBytes;
    if (n < 1 || n > kMaxPostIntervals)
        return corrupt("has " + std::to_string(n) + " post intervals (1.." +
                       std::to_string(kMaxPostIntervals) + ")");
    // Bounds before any allocation: a planar triangulation of V vertices has < 2V triangles.
    const std::uint64_t maxVertices = kVerticesPerPost * std::uint64_t(n + 1) * (n + 1);
    if (vCount < 3 || vCount > maxVertices || iCount % 3 != 0 || iCount < 3 ||
        iCount / 3 > 2ull * vCount)
        return corrupt("has " + std::to_string(vCount) + " vertices and " + std::to_string(iCount) +
                       " indices, impossible for its tile");
    if (std::uint64_t(kHeaderBytes) + vBytes + iBytes != size)
        return corrupt("stream sizes do not add up to the blob size");
    const std::uint32_t flags = getU32(data + 28);
    if (flags & ~kFlagFullBorder) return corrupt("has unknown flags");
    m.postIntervals = int(n);
    m.fullBorder = (flags & kFlagFullBorder) != 0;
    thread_local std::vector<PackedVertex> packed;
    packed.resize(vCount);
    m.indices.resize(iCount);
    const std::uint8_t* vData = data + kHeaderBytes;
    if (meshopt_decodeVertexBuffer(packed.data(), vCount, kVertexBytes, vData, vBytes) != 0)
        return corrupt("vertex stream does not decode");
    if (meshopt_decodeIndexBuffer(m.indices.data(), iCount, sizeof(std::uint32_t), vData + vBytes,
                                  iBytes) != 0)
        return corrupt("index stream does not decode");
    const std::uint32_t extent = n * kTinSubdivisions;
    m.xy.resize(std::size_t(vCount) * 2);
    m.z.resize(vCount);
    m.normals.resize(std::size_t(vCount) * 3);
    // Border posts seen as vertices: 4n of them (corners once each).
    thread_local std::vector<std::uint8_t> border;
    border.assign(std::size_t(4) * n, 0);
    std::size_t borderSeen = 0;
    for (std::size_t v = 0; v < vCount; ++v) {
        const PackedVertex& p = packed[v];
        if (p.x > extent || p.y > extent) return corrupt("has a vertex outside its tile");
        if (!std::isfinite(p.z)) return corrupt("has a non-finite height");
        m.xy[2 * v] = p.x;
        m.xy[2 * v + 1] = p.y;
        m.z[v] = p.z;
        const double nx = p.n[0] / 127.0, ny = p.n[1] / 127.0, nz = p.n[2] / 127.0;
        const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
        if (!(len > 0.5)) return corrupt("has a vertex without a normal");
        m.normals[3 * v] = float(nx / len);
        m.normals[3 * v + 1] = float(ny / len);
        m.normals[3 * v + 2] = float(nz / len);
        if (!m.onPost(v)) continue;
        const std::uint32_t i = p.x / kTinSubdivisions, j = p.y / kTinSubdivisions;
        // Walk the border clockwise from the north-west corner: north, east, south, west.
        std::size_t slot = 0;
        if (j == 0)
            slot = i;
        else if (i == n)
            slot = std::size_t(n) + j;
        else if (j == n)
            slot = 2 * std::size_t(n) + (n - i);
        else if (i == 0)
            slot = 3 * std::size_t(n) + (n - j);
        else
            continue;
        slot %= border.size();
        if (!border[slot]) ++borderSeen;
        border[slot] = 1;
    }
    for (std::size_t t = 0; t < iCount; t += 3) {
        const std::uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
        if (a >= vCount || b >= vCount || c >= vCount)
            return corrupt("has an index past its vertices");
        const auto* pa = &m.xy[std::size_t(a) * 2];
        const auto* pb = &m.xy[std::size_t(b) * 2];
        const auto* pc = &m.xy[std::size_t(c) * 2];
        // Counter-clockwise in world (y north) is clockwise in post rows (y down).
        const std::int64_t area = (std::int64_t(pb[0]) - pa[0]) * (std::int64_t(pc[1]) - pa[1]) -
                                  (std::int64_t(pb[1]) - pa[1]) * (std::int64_t(pc[0]) - pa[0]);
        if (area >= 0) return corrupt("has a degenerate or flipped triangle");
    }
    // Nodata border posts are left out (a hole there, as in the grid); otherwise every border
    // post must be a vertex, or the seam with the neighbouring grid tile would not hold.
    if (m.fullBorder && borderSeen != border.size())
        return corrupt("lacks " + std::to_string(border.size() - borderSeen) +
                       " of its tile's border posts");
    return d;
}

}  // namespace kiosk::io
