// TerrainScene: what arrives from the loader (completions drained under the frame's upload
// budget, payloads turned into GPU meshes and textures, failures counted per layer) and what the
// cache evicts. Kept apart from TerrainScene.cpp, which holds creation, selection and drawing.
#include "runtime/core/Log.h"
#include "runtime/render/Textures.h"
#include "runtime/scene/TerrainScene.h"

#include <algorithm>
#include <optional>
#include <string>

namespace kiosk::scene {
namespace {

constexpr const char* kTag = "scene::TerrainScene";

}  // namespace

void TerrainScene::noteFailure(const terrain::TilePayload& payload) {
    const std::size_t k = payload.key.layer;
    const int idx = k < mKeyLayerStatus.size() ? mKeyLayerStatus[k] : -1;
    if (idx < 0) return;
    LayerStatus& st = mStatus[std::size_t(idx)];
    ++st.failedTiles;
    if (st.state == LayerState::Ready) st.state = LayerState::Degraded;
    const Diagnostic* d = payload.diagnostics.firstError();
    st.message = std::to_string(st.failedTiles) + " tile(s) unreadable" +
                 (d ? ", last: " + d->format() : std::string());
    // Rate limiting is per tile: each bad tile is reported once and then cached as Failed.
    KIOSK_LOG_WARN(kTag, "%s", st.message.c_str());
}

void TerrainScene::uploadPayload(terrain::TileHandle handle, terrain::TilePayload& payload) {
    GpuSlot& slot = mGpu[handle.index()];
    slot = GpuSlot{};
    std::size_t bytes = 0;
    if (payload.mesh) {
        // A tile whose data is all nodata but a sliver meshes to nothing; it still counts as
        // resident (one byte), otherwise the selector would ask for it again every frame.
        bytes = std::max<std::size_t>(payload.mesh->byteSize(), 1);
        if (!mCache->reserveGpu(handle, bytes)) return;
        slot.mesh =
            render::GpuMesh::upload(payload.mesh->vertices.data(), payload.mesh->vertices.size(),
                                    payload.mesh->indices.data(), payload.mesh->indices.size());
        // The GPU copy is what is drawn; the CPU vertices are not needed again (except by the
        // procedural detail, which reads the TIN back near the camera; counted in the budget).
        if (!mDetail) {
            payload.mesh->vertices = {};
            payload.mesh->indices = {};
        }
    } else if (payload.image) {
        const io::ImageTile& im = *payload.image;  // level 0, and its mipmaps (io/MipChain.h)
        bytes =
            std::max<std::size_t>(std::size_t(im.width) * std::size_t(im.height) * 4 * 4 / 3, 1);
        if (!mCache->reserveGpu(handle, bytes)) return;
        slot.texture =
            render::makeRgbaTextureLevels(im.width, im.height, im.rgba.data(), im.rgba.size());
        payload.image->rgba = {};
    } else if (payload.compressed) {
        bytes = std::max<std::size_t>(
            compressedTextureBytes(*payload.compressed, mTextureChoice.software), 1);
        if (!mCache->reserveGpu(handle, bytes)) return;
        slot.texture = render::makeCompressedTexture(*payload.compressed);
        slot.compressed = true;
        payload.compressed->blocks = {};
    } else if (payload.raster) {
        const auto& r = *payload.raster;
        // RG16F (value, validity), or RGBA16F for a derived product's tile (4 channels).
        bytes = std::max<std::size_t>(
            std::size_t(r.postsX) * std::size_t(r.postsY) * (r.channels == 4 ? 8 : 4), 1);
        if (!mCache->reserveGpu(handle, bytes)) return;
        std::optional<float> nodataAs;
        for (const auto& l : mLayers)
            if (l.keyLayer == int(payload.key.layer)) nodataAs = l.nodataAs;
        slot.texture =
            r.channels == 4
                ? render::makeProductTexture(r.postsX, r.postsY, r.values.data())
                : render::makeScalarTexture(r.postsX, r.postsY, r.values.data(), nodataAs);
        slot.postsX = r.postsX;
        slot.postsY = r.postsY;
        payload.raster->values = {};
    }
    slot.bytes = bytes;
    mCache->setCpuBytes(handle, payload.byteSize());
    ++mFrame.uploads;
}

void TerrainScene::drainCompletions() {
    loader::LoadResult result;
    // The budget is checked before each pop: what stays in the loader's completion ring is
    // uploaded next frame, so a burst of arrivals never makes one long frame.
    while (mBudget.allow(0) && mLoader->tryPop(result)) {
        recordLoadTime(result);
        terrain::TilePayload& p = result.payload;
        if (p.key.layer == 0) {
            if (p.stats) mStats.set(p.key.id, *p.stats);
            if (p.status == terrain::TilePayload::Status::Absent) mStats.markAbsent(p.key.id);
        }
        if (p.status == terrain::TilePayload::Status::Failed) noteFailure(p);
        // A bad stored mesh or TIN: drawn from the posts / as the grid, said once per tile.
        if (p.diagnostics.has("STORE_MESH_CORRUPT") || p.diagnostics.has("STORE_TIN_CORRUPT") ||
            p.diagnostics.has("STORE_TEXTURE_CORRUPT"))
            KIOSK_LOG_WARN(kTag, "%s", p.diagnostics.format().c_str());
        const terrain::TileKey key = p.key;
        const std::size_t cpu = p.byteSize();
        terrain::TileHandle h = mCache->insert(key, std::move(p), cpu);
        if (!h.valid()) continue;  // does not fit the budget this frame; requested again later
        terrain::TilePayload* stored = mCache->get(h);
        if (stored->status == terrain::TilePayload::Status::Ready) {
            uploadPayload(h, *stored);
            mBudget.consume(mGpu[h.index()].bytes);
        }
    }
}

void TerrainScene::releaseEvicted() {
    for (const auto& e : mCache->evicted())
        if (e.handle.index() < mGpu.size()) mGpu[e.handle.index()] = GpuSlot{};
    mCache->clearEvicted();
}

}  // namespace kiosk::scene
