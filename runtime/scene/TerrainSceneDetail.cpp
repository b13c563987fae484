// Procedural detail near the camera (issue 21; docs/terrain.md §7): the importance-warped
// geometry image of Dachsbacher & Stamminger drawn where the data is coarser than the pixels,
// the quadtree everywhere else. Built from what the quadtree draws (its meshes read back at
// their posts), so the hand-over matches; the quadtree leaves a hole where the grid draws.
#include "runtime/core/Log.h"
#include "runtime/scene/TerrainScene.h"
#include "runtime/terrain/DetailSketch.h"
#include "runtime/terrain/MeshPosts.h"
#include "runtime/terrain/WarpedGridMesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace kiosk::scene {
namespace {

constexpr const char* kTag = "scene::detail";
/** Grid samples per side: 161^2 vertices (DS04 renders 512^2 on a GPU; llvmpipe affords less). */
constexpr int kGridSize = 161;
constexpr int kImportanceSize = 65;
/** DS04's C: the desired face-on size of a grid cell in pixels. */
constexpr double kCellPx = 3.0;
constexpr std::size_t kPostsCacheEntries = 64;
constexpr int kRegionAttempts = 8;

}  // namespace

struct TerrainScene::DetailState {
    std::unique_ptr<render::WarpedGridRenderer> renderer;
    int iterations = 2;
    bool active = false;  ///< the grid is drawn this frame
    terrain::DetailRegion region;
    glm::dvec2 holeMin{1.0}, holeMax{0.0};
    terrain::DetailSketch sketch;
    std::vector<float> tileCap;  ///< scratch of buildDetailSketch
    std::vector<std::uint32_t> fillQueue;
    struct Source {
        glm::dvec2 min, max;
        const terrain::MeshPosts* posts;
    };
    std::vector<Source> sources;  ///< drawn tiles over the region (valid during planDetail)
    terrain::WarpGrid grid;
    terrain::WarpedGridMesh mesh;
    double postSpacing = 0.0;
    struct CachedPosts {
        terrain::MeshPosts posts;
        std::uint64_t lastUsed = 0;
    };
    std::unordered_map<terrain::TileKey, CachedPosts> posts;
    /** A drawn tile the grid overlaps: its clip rectangle and its layer bindings. */
    struct Piece {
        glm::dvec2 clipMin, clipMax;
        std::vector<render::LayerBinding> layers;
        TileId id;
    };
    std::vector<Piece> pieces;
};

void TerrainScene::DetailDeleter::operator()(DetailState* d) const {
    delete d;
}

void TerrainScene::setDetailWarpIterations(int iterations) {
    if (mDetail) mDetail->iterations = std::max(0, iterations);
}

bool TerrainScene::detailHole(glm::dvec2& min, glm::dvec2& max) const {
    if (!mDetail || !mFrame.proceduralDetail) return false;
    min = mDetail->holeMin;
    max = mDetail->holeMax;
    return true;
}

Diagnostics TerrainScene::buildDetailRenderer() {
    if (!mScenario->terrain.proceduralDetail) return {};
    if (!mDetail) mDetail.reset(new DetailState());
    auto r = render::WarpedGridRenderer::create(mDesc, mMaxTextureUnits);
    if (!r) return r.diagnostics;
    mDetail->renderer = std::make_unique<render::WarpedGridRenderer>(std::move(*r.value));
    render::TerrainRenderer& p = mDetail->renderer->program();
    p.setMappings(mMappingSet.get());
    for (std::size_t k = 0; k < mLuts.size(); ++k) p.setLut(int(k), lutBinding(k));
    const std::uint8_t base[8] = {200, 200, 195, 255, 200, 200, 195, 255};
    p.setElevationLut(2, base, 0.0f, 1.0f);
    return {};
}

const terrain::MeshPosts* TerrainScene::detailPosts(const terrain::DrawTile& t) {
    auto it = mDetail->posts.find(t.geometry);
    if (it == mDetail->posts.end()) {
        const terrain::TilePayload* p = mCache->get(t.handle);
        if (!p || !p->mesh) return nullptr;
        if (mDetail->posts.size() >= kPostsCacheEntries) {
            auto oldest = mDetail->posts.begin();
            for (auto i = mDetail->posts.begin(); i != mDetail->posts.end(); ++i)
                if (i->second.lastUsed < oldest->second.lastUsed) oldest = i;
            mDetail->posts.erase(oldest);
        }
        it = mDetail->posts
                 .emplace(t.geometry, DetailState::CachedPosts{terrain::meshPosts(*p->mesh), 0})
                 .first;
    }
    it->second.lastUsed = mFrameNumber;
    return &it->second.posts;
}

void TerrainScene::setDetailLens(int index, const render::LensBinding& lens) {
    if (mDetail->renderer) mDetail->renderer->program().setLens(index, lens);
}

void TerrainScene::planDetail(const math::Camera& camera, render::TerrainRenderer& quadtree) {
    DetailState& d = *mDetail;
    d.active = false;
    d.pieces.clear();
    d.holeMin = glm::dvec2(1.0);
    d.holeMax = glm::dvec2(0.0);
    quadtree.setHole(d.holeMin, d.holeMax);
    if (!d.renderer || !mSelection) return;
    const int finest = mElevation->levels - 1;
    const io::TileMatrix& m = mGrid.levels[std::size_t(std::min(finest, mGrid.maxLevel()))];
    const double d0 = std::max(m.pixelXSize, m.pixelYSize);
    d.postSpacing = d0;
    // The ground under the eye, from the drawn tile there (else the data's lowest point).
    double groundZ = mBounds.min.z;
    const glm::dvec2 eye(camera.eye);
    for (const auto& t : mSelection->tiles)
        if (eye.x >= t.clipMin.x && eye.x <= t.clipMax.x && eye.y >= t.clipMin.y &&
            eye.y <= t.clipMax.y)
            if (const terrain::MeshPosts* p = detailPosts(t)) {
                const double z = p->at(eye);
                if (std::isfinite(z)) groundZ = z;
            }
    const glm::dvec2 lattice(mGrid.minX + 0.5 * m.pixelXSize, mGrid.maxY - 0.5 * m.pixelYSize);
    // The grid must sample the data at least as densely as its posts everywhere (else it would
    // lose data the quadtree shows): shrink the region until the warped grid's largest spacing
    // is at most one post spacing.
    for (int attempt = 0; attempt < kRegionAttempts; ++attempt) {
        d.region =
            terrain::planDetailRegion(camera, groundZ, d0, lattice, glm::dvec2(mBounds.min) + d0,
                                      glm::dvec2(mBounds.max) - d0, std::pow(0.7, attempt));
        if (!d.region.valid()) {
            KIOSK_LOG_DEBUG(kTag, "no region (ground %.0f m)", groundZ);
            return;
        }
        // Only where the finest data is coarser than the pixels: a post spacing seen from the
        // region's nearest point must cover more than a pixel.
        const glm::dvec2 nearest = glm::clamp(eye, d.region.min, d.region.max);
        const double nearestDistance =
            std::max(glm::distance(camera.eye, glm::dvec3(nearest, groundZ)), 1.0);
        if (d0 * camera.pixelsPerMetreAt(nearestDistance) <= 1.0) return;
        if (!buildDetailSketch(d0, finest)) return;
        const terrain::ImportanceMap imp =
            terrain::viewImportance(d.sketch, camera, kCellPx, kImportanceSize);
        d.grid = terrain::warpGeometryImage(imp, kGridSize, d.iterations);
        const double spacing = terrain::maxVisibleGridSpacing(d.grid, d.sketch, camera);
        KIOSK_LOG_DEBUG(kTag,
                        "attempt %d: region %.0f m, largest grid spacing %.1f m (posts %.1f m)",
                        attempt, d.region.max.x - d.region.min.x, spacing, d0);
        if (spacing <= d0) break;
        if (attempt + 1 == kRegionAttempts) return;
    }
    const double size = std::min(d.region.max.x - d.region.min.x, d.region.max.y - d.region.min.y);
    const double fade = std::max(0.1 * size, 2.0 * d0);
    // Vertices take the drawn TIN's own height and normal (so the grid shows what the quadtree
    // would, and data layers are shaded alike); posts under no drawn tile fall back to the sketch.
    d.sources.clear();
    for (const auto& t : mSelection->tiles)
        if (t.clipMax.x >= d.region.min.x && t.clipMin.x <= d.region.max.x &&
            t.clipMax.y >= d.region.min.y && t.clipMin.y <= d.region.max.y)
            if (const terrain::MeshPosts* p = detailPosts(t))
                d.sources.push_back({t.clipMin, t.clipMax, p});
    const auto surface = [&d](const glm::dvec2& p, double& z, glm::dvec3& n) {
        for (const auto& src : d.sources)
            if (p.x >= src.min.x && p.x <= src.max.x && p.y >= src.min.y && p.y <= src.max.y &&
                src.posts->sample(p, z, n))
                return true;
        return false;
    };
    terrain::buildWarpedGridMesh(d.grid, d.sketch, fade, 0.5 * d0 + 2.0, d.mesh, surface);
    d.renderer->upload(d.mesh);
    d.holeMin = d.region.min + d0;
    d.holeMax = d.region.max - d0;
    quadtree.setHole(d.holeMin, d.holeMax);
    d.active = true;
}

bool TerrainScene::buildDetailSketch(double d0, int finest) {
    DetailState& d = *mDetail;
    terrain::DetailSketch& sk = d.sketch;
    sk.min = d.region.min;
    sk.spacing = d0;
    sk.width = int(std::lround((d.region.max.x - d.region.min.x) / d0)) + 1;
    sk.height = int(std::lround((d.region.max.y - d.region.min.y) / d0)) + 1;
    const std::size_t count = std::size_t(sk.width) * std::size_t(sk.height);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    sk.heights.assign(count, nan);
    sk.normals.assign(count, glm::vec3(0.0f, 0.0f, 1.0f));
    sk.cap.assign(count, 0.0f);
    std::vector<float>& tileCap = d.tileCap;
    tileCap.assign(count, std::numeric_limits<float>::infinity());
    for (const auto& t : mSelection->tiles) {
        if (t.clipMax.x < sk.min.x || t.clipMin.x > sk.max().x || t.clipMax.y < sk.min.y ||
            t.clipMin.y > sk.max().y)
            continue;
        const terrain::MeshPosts* posts = detailPosts(t);
        if (!posts) continue;
        // E: the error the parent of a finest-level tile has (what one more level changed);
        // no decoration on coarser or stand-in meshes.
        double cap = 0.0;
        io::TileStats st;
        if (t.id.level == finest && !t.fromAncestor && t.id.level > 0 &&
            mStats.lookup(t.id.parent(), st) == terrain::TileState::Known)
            cap = terrain::kDetailErrorFraction * std::max(0.0, double(st.geometricError));
        const int i0 = std::max(0, int(std::ceil((t.clipMin.x - sk.min.x) / d0 - 1e-6)));
        const int i1 =
            std::min(sk.width - 1, int(std::floor((t.clipMax.x - sk.min.x) / d0 + 1e-6)));
        const int j0 = std::max(0, int(std::ceil((t.clipMin.y - sk.min.y) / d0 - 1e-6)));
        const int j1 =
            std::min(sk.height - 1, int(std::floor((t.clipMax.y - sk.min.y) / d0 + 1e-6)));
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                const glm::dvec2 p = sk.min + glm::dvec2(i, j) * d0;
                const double z = posts->at(p);
                if (!std::isfinite(z)) continue;
                const std::size_t k = sk.index(i, j);
                sk.heights[k] = float(z);
                int pi = 0, pj = 0;
                if (posts->nearest(p, pi, pj))
                    sk.normals[k] =
                        posts->n[std::size_t(pj) * std::size_t(posts->size) + std::size_t(pi)];
                tileCap[k] = std::min(tileCap[k], float(cap));
            }
    }
    // Posts under no drawn tile lie outside the view frustum (the selector culls whole tiles):
    // they take the nearest drawn post's height, with no decoration, so the grid stays a
    // surface there. A region with no drawn post at all is not drawn.
    if (!terrain::fillFromNearest(sk.heights, sk.normals, sk.width, sk.height, d.fillQueue))
        return false;
    // A post's cap is the smallest of the tiles within one post, so the bilinear amplitude
    // anywhere stays under the cap of the tile it lies in.
    for (int j = 0; j < sk.height; ++j)
        for (int i = 0; i < sk.width; ++i) {
            float c = std::numeric_limits<float>::infinity();
            for (int y = std::max(j - 1, 0); y <= std::min(j + 1, sk.height - 1); ++y)
                for (int x = std::max(i - 1, 0); x <= std::min(i + 1, sk.width - 1); ++x)
                    c = std::min(c, tileCap[sk.index(x, y)]);
            sk.cap[sk.index(i, j)] = std::isfinite(c) ? c : 0.0f;
        }
    terrain::computeDetailAmplitude(sk);
    return true;
}

void TerrainScene::recordDetailTile(const terrain::DrawTile& t, std::size_t layerIndex,
                                    const render::LayerBinding& binding) {
    DetailState& d = *mDetail;
    if (!d.active || t.clipMax.x < d.region.min.x || t.clipMin.x > d.region.max.x ||
        t.clipMax.y < d.region.min.y || t.clipMin.y > d.region.max.y)
        return;
    if (d.pieces.empty() || d.pieces.back().id != t.id) {
        // Overlap the neighbours by a quarter post, as the quadtree's clipped draws do.
        const auto& m = mGrid.levels[std::size_t(std::min(t.id.level, mGrid.maxLevel()))];
        const glm::dvec2 margin(0.25 * m.pixelXSize, 0.25 * m.pixelYSize);
        d.pieces.push_back({t.clipMin - margin, t.clipMax + margin, {}, t.id});
        d.pieces.back().layers.resize(mLayers.size());
    }
    if (layerIndex < d.pieces.back().layers.size()) d.pieces.back().layers[layerIndex] = binding;
}

bool TerrainScene::detailHides(const terrain::DrawTile& t) const {
    const DetailState& d = *mDetail;
    return d.active && t.clipMin.x >= d.holeMin.x && t.clipMax.x <= d.holeMax.x &&
           t.clipMin.y >= d.holeMin.y && t.clipMax.y <= d.holeMax.y;
}

void TerrainScene::drawDetail(const math::Camera& camera, const render::TerrainStyle& style) {
    DetailState& d = *mDetail;
    mFrame.proceduralDetail = false;
    if (!d.active || d.pieces.empty()) return;
    render::TerrainRenderer& p = d.renderer->program();
    p.counters().clear();
    p.begin(camera, mSceneOrigin, style);
    d.renderer->setDetail(d.postSpacing, style.tauTex);
    for (const auto& piece : d.pieces) {
        for (std::size_t li = 0; li < piece.layers.size(); ++li)
            p.setLayer(int(li), piece.layers[li]);
        int first = 0, last = 0;
        terrain::warpedGridRows(d.mesh, piece.clipMin.y, piece.clipMax.y, first, last);
        d.renderer->draw(first, last, piece.clipMin, piece.clipMax);
    }
    p.end();
    mFrame.proceduralDetail = true;
    mFrame.tilesDrawn += p.counters().tilesDrawn;
    mFrame.triangles += p.counters().triangles;
    mFrame.drawCalls += p.counters().drawCalls;
    if (log::threshold() == log::Level::Debug)
        KIOSK_LOG_DEBUG(kTag, "grid over %.0f x %.0f m, %zu pieces, %llu triangles",
                        d.region.max.x - d.region.min.x, d.region.max.y - d.region.min.y,
                        d.pieces.size(), (unsigned long long)p.counters().triangles);
}

}  // namespace kiosk::scene
