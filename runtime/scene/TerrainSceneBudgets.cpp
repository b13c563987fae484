// TerrainScene: cache budgets sized to the working set of the view (docs/performance.md).
#include "runtime/loader/StoreTileLoader.h"
#include "runtime/scene/TerrainScene.h"

#include <algorithm>

namespace kiosk::scene {

void TerrainScene::sizeBudgetsToView() {
    if (!mAutoCpu && !mAutoGpu) return;
    // Pinned now: the tiles the selection uses (its ancestors included) and this frame's
    // arrivals; the sequences' frames ahead are added from the last plan (mAheadBytes).
    const auto [cpu, gpu] = mCache->pinnedBytes();
    mViewCpuHigh = std::max(mViewCpuHigh, cpu);
    mViewGpuHigh = std::max(mViewGpuHigh, gpu);
    terrain::CacheBudget b = mCache->budget();
    // Arrivals are inserted with their full decoded payload before the upload frees it: leave
    // one frame of uploads on top of the CPU working set.
    if (mAutoCpu)
        b.cpuBytes = workingSetBudget(mViewCpuHigh, CacheDefaults::kUploadBytesPerFrame,
                                      CacheDefaults::kFloorCpuBytes);
    if (mAutoGpu)
        b.gpuBytes = workingSetBudget(mViewGpuHigh, mAheadBytes, CacheDefaults::kFloorGpuBytes);
    if (b.cpuBytes != mCache->budget().cpuBytes || b.gpuBytes != mCache->budget().gpuBytes)
        mCache->setBudget(b);
}

void TerrainScene::sizeDerivedStatesToView() {
    if (!mStoreLoader || !mSelection) return;
    // One running state per (tile, cumulative product layer): the tiles each product layer
    // draws now, whose next steps (and prefetched frames ahead) fold into those states.
    std::size_t tracks = 0;
    for (const StackLayer& l : mLayers) {
        if (!l.productClock || l.specA < 0) continue;
        mViewTrackIds.clear();
        for (const auto& t : mSelection->tiles)
            if (int(t.textureCount) > l.specA)
                mViewTrackIds.push_back(
                    mSelection->textures[t.firstTexture + std::uint32_t(l.specA)]
                        .wanted.id.packed());
        std::sort(mViewTrackIds.begin(), mViewTrackIds.end());
        tracks += std::size_t(std::unique(mViewTrackIds.begin(), mViewTrackIds.end()) -
                              mViewTrackIds.begin());
    }
    mStoreLoader->setDerivedTracksInView(tracks);
}

std::vector<std::pair<std::string, double>> TerrainScene::budgets() const {
    const terrain::CacheBudget& b = mCache->budget();
    const SceneCacheUsage u = cacheUsage();
    return {{"cache_cpu_bytes", double(b.cpuBytes)},
            {"cache_gpu_bytes", double(b.gpuBytes)},
            {"cache_cpu_sized_to_view", mAutoCpu ? 1.0 : 0.0},
            {"cache_gpu_sized_to_view", mAutoGpu ? 1.0 : 0.0},
            {"view_working_set_cpu_bytes", double(mViewCpuHigh)},
            {"view_working_set_gpu_bytes", double(mViewGpuHigh)},
            // Decoded tiles between loader and upload: the bound and the most held at once.
            {"loader_max_bytes_in_flight", double(loader::LoaderOptions{}.maxBytesInFlight)},
            {"loader_held_bytes_high", double(mLoader ? mLoader->counters().heldBytesHigh : 0)},
            {"sequence_prefetch_bytes", double(mAheadBytes)},
            // Running states of the derived products (loader thread), docs/products.md.
            {"derived_state_bytes", double(mStoreLoader ? mStoreLoader->derivedBytes() : 0)},
            {"upload_bytes_per_frame", double(mBudget.bytesPerFrame())},
            {"upload_ms_per_frame", mBudget.msPerFrame()},
            {"loader_max_in_flight", double(loader::LoaderOptions{}.maxInFlight)},
            {"cache_slots", double(mCache->capacity())},
            // Resident now; compressed: imagery uploaded as stored GPU blocks (§11 of terrain.md)
            {"gpu_texture_bytes", double(u.gpuTextures)},
            {"gpu_texture_bytes_compressed", double(u.gpuTexturesCompressed)},
            {"texture_compression_astc",
             mTextureChoice.format == io::TextureFormat::Astc4x4 ? 1.0 : 0.0}};
}

}  // namespace kiosk::scene
