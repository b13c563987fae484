// Occlusion culling (Wahl et al. 2004 §5; docs/terrain.md §10): while the selected tiles are
// drawn front to back, the boxes of the farther ones are tested against the depth of the nearer
// ones already drawn this frame, a few batches per frame; a tile whose box has no sample passing
// the depth test cannot change a pixel and is skipped.
#include "runtime/core/Log.h"
#include "runtime/scene/TerrainScene.h"
#include "runtime/terrain/OcclusionPlan.h"

#include <chrono>
#include <cmath>

namespace kiosk::scene {
namespace {

constexpr const char* kTag = "scene::Occlusion";

}  // namespace

void TerrainScene::setOcclusionCulling(bool on) {
    mOcclusionOn = on;
    if (!on || mOcclusionQueries) return;
    auto q = render::OcclusionQueries::create();
    if (!q) {
        // The box program is ours and tiny; should it not build, draw everything (never a hole).
        KIOSK_LOG_WARN(kTag, "occlusion culling off: %s", q.diagnostics.format().c_str());
        mOcclusionOn = false;
        return;
    }
    mOcclusionQueries = std::make_unique<render::OcclusionQueries>(std::move(*q.value));
}

void TerrainScene::planOcclusion(const math::Camera& camera, float verticalScale) {
    mOcclusionCamera = &camera;
    mOcclusionVScale = double(verticalScale);
    mOcclusionRounds.clear();
    mNextOcclusionRound = 0;
    mFrame.tilesOccluded = mFrame.occlusionQueries = mFrame.occlusionRounds = 0;
    mFrame.occlusionMs = 0;
    if (mOcclusionOn && mOcclusionQueries)
        mOcclusionRounds = terrain::OcclusionPlan::roundStarts(mDrawOrder.size());
    mOcclusionHidden.assign(mDrawOrder.size(), 0);
}

bool TerrainScene::occlusionBox(const terrain::DrawTile& t, math::Aabb& box,
                                double& postSpacing) const {
    const terrain::TilePayload* p = mCache->get(t.handle);
    if (!p || !p->mesh) return false;
    const terrain::TileMesh& m = *p->mesh;
    const glm::dvec2 post = glm::abs(m.postSpacing);
    if (m.postIntervals < 1 || !(post.x > 0 && post.y > 0) || !std::isfinite(m.minZ) ||
        !std::isfinite(m.maxZ) || !std::isfinite(m.skirtDepth))
        return false;
    // Posts sit at pixel centres: (i + 0.5) posts east and south of the origin, i <= intervals.
    const double n = double(m.postIntervals) + 1.0;
    glm::dvec2 lo(m.origin.x, m.origin.y - n * post.y), hi(m.origin.x + n * post.x, m.origin.y);
    if (t.clipped) {  // drawn clipped to the node (a quarter post overlap, or whole cells)
        lo = glm::max(lo, t.clipMin - post);
        hi = glm::min(hi, t.clipMax + post);
        if (lo.x > hi.x || lo.y > hi.y) return false;
    }
    // Skirts hang skirtDepth below the lowest surface vertex at most; heights as drawn.
    const double z0 = (double(m.minZ) - m.skirtDepth) * mOcclusionVScale;
    const double z1 = double(m.maxZ) * mOcclusionVScale;
    box = {glm::dvec3(lo, std::min(z0, z1)), glm::dvec3(hi, std::max(z0, z1))};
    postSpacing = std::max(post.x, post.y);
    return true;
}

void TerrainScene::runOcclusionRound(std::size_t first, std::size_t last) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    render::OcclusionQueries& q = *mOcclusionQueries;
    std::vector<std::int32_t>& slots = mOcclusionSlots;
    slots.assign(last - first, -1);
    q.begin(*mOcclusionCamera);
    for (std::size_t k = first; k < last; ++k) {
        const terrain::DrawTile& t = mSelection->tiles[mDrawOrder[k]];
        math::Aabb tight;
        double post = 0.0;
        if (!t.handle.valid() || !occlusionBox(t, tight, post)) continue;
        const auto box = terrain::OcclusionPlan::queryBox(*mOcclusionCamera, tight, post);
        if (!box) continue;  // reaches the near plane: drawn untested
        slots[k - first] = std::int32_t(q.query(*box));
    }
    q.end();
    mFrame.occlusionQueries += std::uint32_t(q.batchSize());
    ++mFrame.occlusionRounds;
    for (std::size_t k = first; k < last; ++k)
        if (slots[k - first] >= 0 && !q.passed(std::size_t(slots[k - first])))
            mOcclusionHidden[k] = 1;
    mFrame.occlusionMs += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

bool TerrainScene::occluded(std::size_t k) {
    // Rounds run when the draw order reaches them, so their queries see every nearer tile.
    while (mNextOcclusionRound < mOcclusionRounds.size() &&
           k >= mOcclusionRounds[mNextOcclusionRound]) {
        const std::size_t first = mOcclusionRounds[mNextOcclusionRound];
        const std::size_t last = mNextOcclusionRound + 1 < mOcclusionRounds.size()
                                     ? mOcclusionRounds[mNextOcclusionRound + 1]
                                     : mDrawOrder.size();
        ++mNextOcclusionRound;
        runOcclusionRound(first, last);
    }
    if (k >= mOcclusionHidden.size() || !mOcclusionHidden[k]) return false;
    ++mFrame.tilesOccluded;
    return true;
}

}  // namespace kiosk::scene
