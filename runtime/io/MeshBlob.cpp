#include "runtime/io/MeshBlob.h"

#include "runtime/io/MeshStreams.h"

#include <cmath>
#include <cstring>
#include <meshoptimizer.h>

namespace kiosk::io {

namespace {

// Blob layout (little-endian): "KMSH", u32 version, u32 postIntervals, u32 vertexCount,
// u32 indexCount, u32 vertexStreamBytes, u32 indexStreamBytes, u32 flags, f64 zOffset, f64 zScale,
// then the meshoptimizer vertex stream and index stream.
constexpr char kMagic[4] = {'K', 'M', 'S', 'H'};
constexpr std::uint32_t kVersion = 1;
constexpr std::size_t kHeaderBytes = 48;
constexpr int kNormalBits = 12;
constexpr std::uint32_t kFlagSplitTiers = 1;  // vertex component 3 holds QuantizedMesh::splitTiers
constexpr int kMaxPostIntervals = 4096;
constexpr std::size_t kComponents = 8;  // uint16 per vertex in the blob
constexpr std::size_t kVertexBytes = kComponents * sizeof(std::uint16_t);

void putF64(std::vector<std::uint8_t>& b, std::size_t at, double v) {
    std::uint64_t u;
    std::memcpy(&u, &v, sizeof u);
    for (int i = 0; i < 8; ++i) b[at + std::size_t(i)] = std::uint8_t(u >> (8 * i));
}
double getF64(const std::uint8_t* p) {
    std::uint64_t u = 0;
    for (int i = 0; i < 8; ++i) u |= std::uint64_t(p[i]) << (8 * i);
    double v;
    std::memcpy(&v, &u, sizeof v);
    return v;
}

}  // namespace

std::vector<std::uint8_t> encodeMeshBlob(const QuantizedMesh& mesh) {
    const std::size_t count = mesh.vertexCount();
    std::vector<std::uint16_t> packed(count * kComponents, 0);
    std::vector<float> normal4(count * 4, 0.0f);
    for (std::size_t v = 0; v < count; ++v) {
        for (int c = 0; c < 3; ++c) {
            packed[v * kComponents + std::size_t(c)] = mesh.posts[v * 3 + std::size_t(c)];
            normal4[v * 4 + std::size_t(c)] = mesh.normals[v * 3 + std::size_t(c)];
        }
        if (!mesh.splitTiers.empty()) packed[v * kComponents + 3] = mesh.splitTiers[v];
    }
    // 12-bit octahedral normals: within 0.05 degrees (shading matches the built mesh to well
    // under one 8-bit level), and the zero low bits compress (other widths not measured).
    std::vector<std::int16_t> oct(count * 4);
    if (count) meshopt_encodeFilterOct(oct.data(), count, 8, kNormalBits, normal4.data());
    for (std::size_t v = 0; v < count; ++v)
        for (int c = 0; c < 4; ++c)
            packed[v * kComponents + 4 + std::size_t(c)] =
                std::uint16_t(oct[v * 4 + std::size_t(c)]);
    // Vertices in first-use order, triangle order (the cell order) unchanged.
    std::vector<std::uint32_t> indices = mesh.indices;
    const MeshStreams streams = encodeMeshStreams(packed.data(), count, kVertexBytes, indices);
    std::vector<std::uint8_t> blob = blobWithStreams(kHeaderBytes, streams);
    putStreamHeader(blob, kMagic, kVersion, std::uint32_t(mesh.postIntervals), streams,
                    indices.size());
    putU32(blob, 28, mesh.splitTiers.empty() ? 0u : kFlagSplitTiers);
    putF64(blob, 32, mesh.zOffset);
    putF64(blob, 40, mesh.zScale);
    return blob;
}

Result<QuantizedMesh> decodeMeshBlob(const std::uint8_t* data, std::size_t size,
                                     const std::string& where) {
    QuantizedMesh m;
    Diagnostics d = decodeMeshBlob(data, size, where, m);
    if (d.hasErrors()) return d;
    return m;
}

Diagnostics decodeMeshBlob(const std::uint8_t* data, std::size_t size, const std::string& where,
                           QuantizedMesh& m) {
    Diagnostics d;
    auto corrupt = [&](const std::string& what) {
        d.error("STORE_MESH_CORRUPT", "", where, "stored mesh " + what);
        return d;
    };
    StreamHeader h;
    const std::string bad =
        readStreamHeader(data, size, kHeaderBytes, kMaxMeshBlobBytes, kMagic, kVersion, h);
    if (!bad.empty()) return corrupt(bad);
    const std::uint32_t n = h.postIntervals, vCount = h.vertexCount, iCount = h.indexCount;
    const std::uint32_t vBytes = h.vertexBytes, iBytes = h.indexBytes;
    const std::uint32_t flags = getU32(data + 28);
    m.zOffset = getF64(data + 32);
    m.zScale = getF64(data + 40);
    // Bounds before any allocation: a (n+1)^2 post grid has at most that many vertices and
    // 2 n^2 triangles.
    if (n < 1 || n > std::uint32_t(kMaxPostIntervals))
        return corrupt("has " + std::to_string(n) + " post intervals (1.." +
                       std::to_string(kMaxPostIntervals) + ")");
    const std::uint64_t posts = std::uint64_t(n + 1) * (n + 1);
    if (vCount > posts || iCount > 6ull * n * n || iCount % 3 != 0 || (iCount > 0) != (vCount > 0))
        return corrupt("has " + std::to_string(vCount) + " vertices and " + std::to_string(iCount) +
                       " indices, impossible on its post grid");
    if (std::uint64_t(kHeaderBytes) + vBytes + iBytes != size)
        return corrupt("stream sizes do not add up to the blob size");
    if (flags & ~kFlagSplitTiers) return corrupt("has unknown flags");
    if (!std::isfinite(m.zOffset) || !std::isfinite(m.zScale) || !(m.zScale > 0))
        return corrupt("has a non-finite height offset or scale");
    m.postIntervals = int(n);
    // Per-thread scratch, reused across tiles like `m`'s buffers.
    thread_local std::vector<std::uint16_t> packed;
    thread_local std::vector<std::int16_t> oct;
    packed.resize(std::size_t(vCount) * kComponents);
    m.indices.resize(iCount);
    const std::uint8_t* vData = data + kHeaderBytes;
    if (vCount &&
        meshopt_decodeVertexBuffer(packed.data(), vCount, kVertexBytes, vData, vBytes) != 0)
        return corrupt("vertex stream does not decode");
    if (iCount && meshopt_decodeIndexBuffer(m.indices.data(), iCount, sizeof(std::uint32_t),
                                            vData + vBytes, iBytes) != 0)
        return corrupt("index stream does not decode");
    m.posts.resize(std::size_t(vCount) * 3);
    m.normals.resize(std::size_t(vCount) * 3);
    m.splitTiers.resize((flags & kFlagSplitTiers) ? vCount : 0);
    // int16 octahedral (x, y, 1, 0) -> int16 unit vector, in place in a stride-8 array.
    oct.resize(std::size_t(vCount) * 4);
    for (std::size_t v = 0; v < vCount; ++v)
        for (std::size_t k = 0; k < 4; ++k)
            oct[v * 4 + k] = std::int16_t(packed[v * kComponents + 4 + k]);
    if (vCount) meshopt_decodeFilterOct(oct.data(), vCount, 8);
    for (std::size_t v = 0; v < vCount; ++v) {
        const std::uint16_t* c = &packed[v * kComponents];
        if (c[0] > n || c[1] > n) return corrupt("has a vertex off its post grid");
        if (!m.splitTiers.empty()) m.splitTiers[v] = c[3];
        for (std::size_t k = 0; k < 3; ++k) {
            m.posts[v * 3 + k] = c[k];
            const double q = double(oct[v * 4 + k]) / 32767.0;
            m.normals[v * 3 + k] = float(q);
        }
        // Renormalise: the int16 vector is unit to 1/32767 per component.
        float* nv = &m.normals[v * 3];
        const double len =
            std::sqrt(double(nv[0]) * nv[0] + double(nv[1]) * nv[1] + double(nv[2]) * nv[2]);
        if (!(len > 0.5)) return corrupt("has a vertex without a normal");
        for (int k = 0; k < 3; ++k) nv[k] = float(nv[k] / len);
    }
    for (std::size_t t = 0; t < iCount; t += 3) {
        const std::uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
        if (a >= vCount || b >= vCount || c >= vCount)
            return corrupt("has an index past its vertices");
        const std::uint16_t* pa = &m.posts[std::size_t(a) * 3];
        const std::uint16_t* pb = &m.posts[std::size_t(b) * 3];
        const std::uint16_t* pc = &m.posts[std::size_t(c) * 3];
        // Counter-clockwise in world (y north) is clockwise in post rows (y down).
        const long long area = (long long)(pb[0] - pa[0]) * (pc[1] - pa[1]) -
                               (long long)(pb[1] - pa[1]) * (pc[0] - pa[0]);
        if (area >= 0) return corrupt("has a degenerate or flipped triangle");
    }
    return d;
}

}  // namespace kiosk::io
