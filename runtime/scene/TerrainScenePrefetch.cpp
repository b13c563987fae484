// TerrainScene: prefetch of sequence frames ahead of the playhead (docs/animation.md
// "Prefetch"). Kept apart from TerrainScene.cpp (creation, selection), TerrainSceneUploads.cpp
// and TerrainSceneDraw.cpp.
#include "runtime/scene/TerrainScene.h"

#include <algorithm>
#include <cmath>

namespace kiosk::scene {
namespace {

// Frames ahead of the playhead have deadlines: they go to the loader's frame queue (not the
// idle-time prefetch queue, which a camera still refining its terrain would starve), ordered by
// deadline and above terrain refinement (priority = screen-space error in pixels, far below).
constexpr double kSequencePriority = 1e7;

}  // namespace

void TerrainScene::update(const math::Camera& camera, double time, const Playback& playback) {
    mPlayback = playback;
    update(camera, time);
}

void TerrainScene::recordLoadTime(const loader::LoadResult& result) {
    const std::size_t k = result.request.key.layer;
    if (k == 0 || result.payload.status != terrain::TilePayload::Status::Ready) return;
    for (const StackLayer& l : mLayers)
        if (l.sequence && (l.keyLayer == int(k) || l.keyLayerT == int(k))) {
            mTileLoad.record(result.loadSeconds);
            return;
        }
}

void TerrainScene::countPrefetchHits(StackLayer& l, bool reported) {
    const anim::DisplayPair& s = l.shown;
    const std::size_t n = l.aheadRequested.size();
    if (s.hasPair && (s.i0 != l.lastI0 || s.i1 != l.lastI1)) {
        // A hit: a frame planned ahead became shown the first frame it was wanted (no hold
        // before the switch), i.e. it was resident by its deadline.
        auto fresh = [&](std::size_t f) { return f != l.lastI0 && f != l.lastI1 && f < n; };
        std::uint32_t hits = 0;
        for (std::size_t f : {s.i0, s.i1}) {
            if (f == s.i1 && s.i1 == s.i0 && hits > 0) break;
            if (!fresh(f)) continue;
            if (l.aheadRequested[f] && !s.holding && !l.lastHolding) ++hits;
            l.aheadRequested[f] = 0;
        }
        if (reported) mFrame.prefetchHits += hits;
        l.lastI0 = s.i0;
        l.lastI1 = s.i1;
    }
    l.lastHolding = s.holding;
    if (reported) mFrame.heldFrames = s.heldFrames;
}

void TerrainScene::planSequencePrefetch() {
    mSequencePrefetch.clear();
    mAheadBytes = 0;
    if (!mSelection) return;
    std::size_t sequenceLayers = 0;
    for (const StackLayer& l : mLayers) sequenceLayers += l.sequence && l.specA >= 0 ? 1 : 0;
    if (sequenceLayers == 0) return;
    // A fixed GPU budget: half is left to the terrain and imagery, the sequences share the rest.
    // A budget sized to the view follows the plan instead (the planner's deadline rule sets the
    // depth; sizeBudgetsToView makes room for it), so no byte cap here.
    const std::uint64_t budget =
        mAutoGpu ? 0 : std::uint64_t(mCache->budget().gpuBytes) / 2 / std::uint64_t(sequenceLayers);
    for (std::size_t li = 0; li < mLayers.size(); ++li) {
        StackLayer& l = mLayers[li];
        if (!l.sequence || l.specA < 0 || l.sequence->frameTimes.empty()) continue;
        const bool reported = li == mFirstSequenceLayer;
        std::uint64_t tiles = 0, bytesPerFrame = 0;
        for (const auto& t : mSelection->tiles) {
            if (int(t.textureCount) <= l.specA) continue;
            const auto& a = mSelection->textures[t.firstTexture + std::uint32_t(l.specA)];
            const auto& m =
                mGrid.levels[std::size_t(std::min(a.wanted.id.level, mGrid.maxLevel()))];
            ++tiles;
            // RG16F texture of (tile + 1)^2 posts; the CPU copy is dropped after upload.
            bytesPerFrame += std::uint64_t(m.tileWidth + 1) * std::uint64_t(m.tileHeight + 1) * 4;
        }
        if (tiles == 0) continue;
        const std::size_t frames = l.sequence->frameTimes.size();
        if (l.aheadRequested.size() != frames) l.aheadRequested.assign(frames, 0);

        anim::PrefetchInput in;
        in.playhead = mTime;
        in.rate = mPlayback.paused ? 0.0 : mPlayback.rate;
        in.range = mPlayback.end > mPlayback.start ? mPlayback.range : anim::RangeMode::Unbounded;
        in.rangeStart = mPlayback.start;
        in.rangeEnd = mPlayback.end;
        in.frameTimes = l.sequence->frameTimes;
        in.mode = l.interpolation;
        // Arrival layers load a threshold tile per frame pair as well.
        in.meanLoadSeconds = mTileLoad.mean() * double(tiles) * (l.specT >= 0 ? 2.0 : 1.0);
        in.bytesPerFrame = bytesPerFrame;
        in.byteBudget = budget;
        l.planner.syncSeekSerial(mPlayback.seekSerial);
        l.planner.plan(in, l.plan);
        mAheadBytes += bytesPerFrame * l.plan.items.size();

        std::uint32_t requested = 0;
        for (const anim::PrefetchItem& item : l.plan.items) {
            for (const auto& t : mSelection->tiles) {
                for (int spec : {l.specA, l.specT}) {
                    if (spec < 0 || int(t.textureCount) <= spec) continue;
                    terrain::TileKey key =
                        mSelection->textures[t.firstTexture + std::uint32_t(spec)].wanted;
                    key.frame = std::int32_t(item.frame);
                    const terrain::TileHandle h = mCache->find(key);
                    if (h.valid()) {
                        // Resident ahead of its deadline: keep it (LRU) until it is shown.
                        mCache->touch(h);
                        continue;
                    }
                    mSequencePrefetch.push_back(
                        {key, kSequencePriority / (1.0 + std::max(0.0, item.deadlineSeconds))});
                    ++requested;
                }
            }
            if (item.deadlineSeconds > 0.0) l.aheadRequested[item.frame] = 1;
        }
        if (reported) {
            mFrame.prefetchDepth = l.plan.depth;
            mFrame.prefetchFrames = std::uint32_t(l.plan.items.size());
            mFrame.prefetchRequests = requested;
            mFrame.prefetchGeneration = l.plan.generation;
            mFrame.frameLoadMs = in.meanLoadSeconds * 1000.0;
        }
    }
}

bool TerrainScene::specComplete(int spec) const {
    if (!mSelection || spec < 0) return false;
    for (const auto& t : mSelection->tiles) {
        if (int(t.textureCount) <= spec) return false;
        const auto& a = mSelection->textures[t.firstTexture + std::uint32_t(spec)];
        if (!a.handle.valid() || a.fromAncestor) return false;
    }
    return true;
}

void TerrainScene::bindArrival(const StackLayer& l, const terrain::DrawTile& t,
                               render::LayerBinding& b) const {
    if (l.specT < 0 || int(t.textureCount) <= l.specT) return;
    const auto& a = mSelection->textures[t.firstTexture + std::uint32_t(l.specT)];
    if (!a.handle.valid()) return;  // no thresholds: alpha >= 0 shows the newer frame
    const GpuSlot& slot = mGpu[a.handle.index()];
    // Thresholds may come from another level than the frames (an ancestor while loading).
    const render::LayerBinding tb = bindingFor(a, slot.postsX, slot.postsY);
    if (!tb.valid) return;
    b.textureT = tb.texture;
    b.westT = tb.west;
    b.northT = tb.north;
    b.widthT = tb.width;
    b.heightT = tb.height;
}

void TerrainScene::addPathFramePrefetch(const terrain::SelectionResult& future) {
    for (const StackLayer& l : mLayers) {
        if (!l.sequence || l.specA < 0) continue;
        for (const anim::PrefetchItem& item : l.plan.items) {
            for (const auto& t : future.tiles) {
                for (int spec : {l.specA, l.specT}) {
                    if (spec < 0 || int(t.textureCount) <= spec) continue;
                    terrain::TileKey key =
                        future.textures[t.firstTexture + std::uint32_t(spec)].wanted;
                    key.frame = std::int32_t(item.frame);
                    // Idle-time queue, after the path's own tiles: by deadline, below 1 px SSE.
                    if (!mCache->find(key).valid())
                        mPrefetch.push_back(
                            {key, 0.5 / (1.0 + std::max(0.0, item.deadlineSeconds))});
                }
            }
        }
    }
}

void TerrainScene::sendPrefetch() {
    // Camera-path tiles asked for last frame that have arrived since are not asked again.
    mPrefetchAll.clear();
    for (const auto& r : mPrefetch)
        if (!mCache->find(r.key).valid()) mPrefetchAll.push_back(r);
    mLoader->prefetch(mPrefetchAll);
}

}  // namespace kiosk::scene
