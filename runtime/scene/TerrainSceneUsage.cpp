// Cache bytes by kind for the kiosk's /metrics (split from TerrainScene.cpp: read-only view).
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
    }
    u.loaderQueue = mLoader ? mLoader->queued() : 0;
    return u;
}

}  // namespace kiosk::scene
