// TerrainScene: drawing the selected tiles (each tile's layer bindings, ancestors clipped to the
// quadrant they stand in for, the sequence frames a tile actually drew). Kept apart from
// TerrainScene.cpp, which holds creation and selection.
#include "runtime/scene/TerrainScene.h"
#include "runtime/terrain/MeshCells.h"

#include <algorithm>
#include <cstdint>

namespace kiosk::scene {

render::LayerBinding TerrainScene::bindingFor(const terrain::TextureAssignment& a, int postsX,
                                              int postsY) const {
    render::LayerBinding b;
    b.valid = a.handle.valid();
    if (!b.valid) return b;
    const GpuSlot& slot = mGpu[a.handle.index()];
    b.texture = slot.texture.id();
    b.valid = b.texture != 0;
    b.west = a.boundsMin.x;
    b.north = a.boundsMax.y;
    b.width = a.boundsMax.x - a.boundsMin.x;
    b.height = a.boundsMax.y - a.boundsMin.y;
    if (postsX > 1 && postsY > 1) {
        // Raster posts sit at pixel centres and include the east/south neighbours' first
        // column/row: texel i's centre is at west + (i + 0.5) px, so the texture spans
        // postsX pixels starting at the tile's west edge.
        b.width *= double(postsX) / double(postsX - 1);
        b.height *= double(postsY) / double(postsY - 1);
    }
    return b;
}

void TerrainScene::noteDrawnFrames(const StackLayer& l, const terrain::DrawTile& t) {
    for (int k = 0; k < 2; ++k) {
        const int spec = k == 0 ? l.specA : l.specB;
        if (spec < 0 || int(t.textureCount) <= spec) continue;
        const auto& a = mSelection->textures[t.firstTexture + std::uint32_t(spec)];
        if (!a.handle.valid() || a.fromAncestor) ++mFrame.shownTilesIncomplete;
        if (!a.handle.valid()) continue;
        std::int32_t& shown = k == 0 ? mFrame.shownFrameA : mFrame.shownFrameB;
        if (shown >= 0 && shown != a.key.frame) mFrame.mixedSequenceFrames = true;
        shown = a.key.frame;
    }
    // A derived product's state (or arrival thresholds) belongs to the pair's first frame: a
    // tile drawing another step's state mixes times as much as one drawing another frame.
    if (l.specT >= 0 && int(t.textureCount) > l.specT) {
        const auto& a = mSelection->textures[t.firstTexture + std::uint32_t(l.specT)];
        if (!a.handle.valid() || a.fromAncestor) ++mFrame.shownTilesIncomplete;
        if (a.handle.valid() && mFrame.shownFrameA >= 0 && a.key.frame != mFrame.shownFrameA)
            mFrame.mixedSequenceFrames = true;
    }
}

void TerrainScene::draw(const math::Camera& camera, const render::TerrainStyle& style) {
    if (!mSelection) return;
    mFrame.shownFrameA = mFrame.shownFrameB = -1;
    mFrame.mixedSequenceFrames = false;
    mFrame.shownTilesIncomplete = 0;
    mFrame.sequencePairCommitted =
        mFirstSequenceLayer < mLayers.size() && mLayers[mFirstSequenceLayer].shown.hasPair;
    bindLenses();
    bindMappings(camera);
    auto& r = *mRenderer;
    r.counters().clear();
    if (mDetail) planDetail(camera, r);  // the quadtree leaves a hole where the detail grid draws
    r.begin(camera, mSceneOrigin, style);
    // Front to back: llvmpipe's early depth test then skips shading hidden terrain.
    mDrawOrder.clear();
    for (std::uint32_t i = 0; i < mSelection->tiles.size(); ++i) mDrawOrder.push_back(i);
    std::sort(mDrawOrder.begin(), mDrawOrder.end(), [&](std::uint32_t a, std::uint32_t b) {
        return mSelection->tiles[a].distance < mSelection->tiles[b].distance;
    });
    planOcclusion(camera, style.verticalScale);
    for (std::size_t k = 0; k < mDrawOrder.size(); ++k) {
        const terrain::DrawTile& t = mSelection->tiles[mDrawOrder[k]];
        if (!t.handle.valid()) continue;
        const GpuSlot& g = mGpu[t.handle.index()];
        const terrain::TilePayload* p = mCache->get(t.handle);
        if (!g.mesh.valid() || !p || !p->mesh) continue;
        groupTileValidity(t);
        for (std::size_t li = 0; li < mLayers.size(); ++li) {
            const StackLayer& l = mLayers[li];
            render::LayerBinding b;
            if (l.specA < 0) {
                b.valid = true;  // drawn from the mesh's own elevation
            } else if (int(t.textureCount) > l.specA) {
                const auto& a = mSelection->textures[t.firstTexture + std::uint32_t(l.specA)];
                const GpuSlot& ta = a.handle.valid() ? mGpu[a.handle.index()] : g;
                b = bindingFor(a, ta.postsX, ta.postsY);
                if (l.specB >= 0 && int(t.textureCount) > l.specB) {
                    const auto& bb = mSelection->textures[t.firstTexture + std::uint32_t(l.specB)];
                    b.textureB =
                        bb.handle.valid() ? mGpu[bb.handle.index()].texture.id() : b.texture;
                    b.alpha = float(l.shown.alpha);
                } else if (l.sequence) {
                    b.alpha = float(l.shown.alpha);  // products: the pair is in one texel
                }
                if (l.specT >= 0) bindArrival(l, t, b);
                if (l.productClock) {
                    const auto& ft = l.sequence->frameTimes;
                    b.product = glm::vec4(float((ft[l.shown.i0] - l.timeOrigin) / l.timeUnit),
                                          float((ft[l.shown.i1] - ft[l.shown.i0]) / l.timeUnit),
                                          0.0f, 0.0f);
                }
                // A sync group draws on a tile only where every member has its frames there
                // (alone, a layer shows what has arrived meanwhile): no side shows alone.
                if (l.syncGroup >= 0 && !groupDrawsTile(l)) b.valid = false;
            }
            b.strength = l.strengthOverride.value_or(l.strength);
            r.setLayer(int(li), b);
            if (mDetail) recordDetailTile(t, li, b);
            if (li == mFirstSequenceLayer) noteDrawnFrames(l, t);
        }
        if (mDetail && detailHides(t)) continue;  // entirely under the detail grid
        if (occluded(k)) continue;                // behind nearer terrain (§10 of terrain.md)
        bindTileMappings(p->key.id);
        const int depthBelowMesh = t.id.level - t.geometry.id.level;
        if (t.clipped && t.domainLevel == t.geometry.id.level &&
            depthBelowMesh <= p->mesh->cellLevels) {
            // The node's share of its geometry tile's mesh is a block of whole cells (its edges
            // lie on the mesh's post grid, §2 of docs/terrain.md): draw exactly those cells,
            // nothing to clip, so the shared edges are mesh edges and cannot open a crack.
            const auto& gm = mGrid.levels[std::size_t(t.geometry.id.level)];
            const glm::dvec2 inset(0.25 * gm.pixelXSize, 0.25 * gm.pixelYSize);
            terrain::meshRangesInRect(*p->mesh, t.clipMin + inset, t.clipMax - inset, mCellRanges);
            mRuns.clear();
            for (const auto& c : mCellRanges) mRuns.push_back({c.first, c.count});
            r.drawRanges(g.mesh, p->mesh->origin, t.fromAncestor,
                         glm::dvec2(-render::TerrainRenderer::kNoClip),
                         glm::dvec2(render::TerrainRenderer::kNoClip), mRuns.data(), mRuns.size());
        } else if (t.clipped) {
            // Overlap the neighbours by a quarter post: with both clip edges on the same line,
            // float interpolation can leave a fragment neither side keeps (a one-pixel crack);
            // the overlap is resolved by the depth test.
            const auto& m = mGrid.levels[std::size_t(std::min(t.id.level, mGrid.maxLevel()))];
            const glm::dvec2 margin(0.25 * m.pixelXSize, 0.25 * m.pixelYSize);
            // Only the mesh cells under the node: an ancestor drawn for four (or sixteen)
            // descendants then costs about one whole draw, not four (docs/terrain.md §3).
            if (terrain::meshRangesInRect(*p->mesh, t.clipMin - margin, t.clipMax + margin,
                                          mCellRanges)) {
                mRuns.clear();
                for (const auto& c : mCellRanges) mRuns.push_back({c.first, c.count});
                r.drawRanges(g.mesh, p->mesh->origin, t.fromAncestor, t.clipMin - margin,
                             t.clipMax + margin, mRuns.data(), mRuns.size());
            } else {
                r.draw(g.mesh, p->mesh->origin, t.fromAncestor, t.clipMin - margin,
                       t.clipMax + margin);
            }
        } else {
            r.draw(g.mesh, p->mesh->origin, t.fromAncestor);
        }
    }
    r.end();
    mFrame.tilesDrawn = r.counters().tilesDrawn;
    mFrame.triangles = r.counters().triangles;
    mFrame.drawCalls = r.counters().drawCalls;
    if (mDetail) drawDetail(camera, style);
}

}  // namespace kiosk::scene
