// Cache and memory-budget bytes by kind for the kiosk's /metrics and --stats (split from
// TerrainScene.cpp: read-only view).
#include "runtime/render/MappingSet.h"
#include "runtime/scene/TerrainScene.h"

namespace kiosk::scene {

SceneCacheUsage TerrainScene::cacheUsage() const {
    SceneCacheUsage u;
    u.cpuTiles = mCache->cpuBytes();
    for (const GpuSlot& slot : mGpu) {
        if (slot.mesh.valid())
            u.gpuMeshes += slot.bytes;
        else if (slot.texture)
            u.gpuTextures += slot.bytes;
        if (slot.texture && slot.compressed) u.gpuTexturesCompressed += slot.bytes;
    }
    u.loaderQueue = mLoader ? mLoader->queued() : 0;
    u.cpuBudget = mCache->budget().cpuBytes;
    u.gpuBudget = mCache->budget().gpuBytes;
    return u;
}

SceneMemoryUsage TerrainScene::memoryUsage() const {
    SceneMemoryUsage u;
    // RGBA8 on the GPU: the ramp (legends) and the stack's copy with its below, above and
    // nodata texels.
    for (const SceneLut& lut : mLuts) u.lutBytes += std::uint64_t(lut.size * 2 + 3) * 4;
    if (mMappingSet) {
        u.lutBytes += mMappingSet->lutBytes();
        u.mappingBytes = mMappingSet->layerBytes();
    }
    return u;
}

}  // namespace kiosk::scene
