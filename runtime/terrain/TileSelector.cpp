#include "runtime/terrain/TileSelector.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace kiosk::terrain {

namespace {

// Requests for tiles with nothing drawable in their whole ancestry come first: a hole is worse
// than any blur.
constexpr double kNothingDrawnPriority = 1e9;

TileId ancestorAt(const TileId& id, int level) {
    TileId a = id;
    while (a.level > level) a = a.parent();
    return a;
}

}  // namespace

Diagnostics TileSelector::configure(SelectorSetup setup) {
    Diagnostics diags;
    const auto& levels = setup.grid.levels;
    for (std::size_t l = 0; l < levels.size(); ++l) {
        const io::TileMatrix& m = levels[l];
        std::string why;
        if (m.matrixWidth < 1 || m.matrixHeight < 1 || !(m.pixelXSize > 0) || !(m.pixelYSize > 0) ||
            m.tileWidth < 1 || m.tileHeight < 1) {
            why = "empty matrix or non-positive pixel size";
        } else if (l > 0) {
            const io::TileMatrix& p = levels[l - 1];
            auto halves = [](double fine, double coarse) {
                return std::abs(fine * 2.0 - coarse) <= 1e-6 * coarse;
            };
            if (!halves(m.pixelXSize, p.pixelXSize) || !halves(m.pixelYSize, p.pixelYSize) ||
                m.tileWidth != p.tileWidth || m.tileHeight != p.tileHeight)
                why = "pixel size is not half of level " + std::to_string(l - 1) + "'s";
            else if (m.matrixWidth > 2 * p.matrixWidth || m.matrixHeight > 2 * p.matrixHeight)
                why = "more than twice the tiles of level " + std::to_string(l - 1);
        }
        if (!why.empty()) {
            diags.error("TERRAIN_GRID_NOT_QUADTREE", "", "tile matrix level " + std::to_string(l),
                        why);
            break;
        }
    }
    if (diags.hasErrors()) setup.grid.levels.clear();
    mSetup = std::move(setup);
    const int gridMax = mSetup.grid.maxLevel();
    mSetup.geometryMaxLevel = std::clamp(mSetup.geometryMaxLevel, 0, std::max(0, gridMax));
    const int textureCap =
        mSetup.geometryMaxLevel + std::max(0, mSetup.options.textureLevelsBeyondGeometry);
    mMaxDepth = mSetup.geometryMaxLevel;
    for (auto& t : mSetup.textures) {
        t.maxLevel = std::clamp(t.maxLevel, 0, std::min(std::max(0, gridMax), textureCap));
        mMaxDepth = std::max(mMaxDepth, t.maxLevel);
    }
    std::size_t roots = 0;
    if (!mSetup.grid.levels.empty())
        roots = std::size_t(mSetup.grid.levels[0].matrixWidth) *
                std::size_t(std::max(0, mSetup.grid.levels[0].matrixHeight));
    mRootRequested.assign(roots * (1 + mSetup.textures.size()), 0);
    mResult = SelectionResult{};
    return diags;
}

void TileSelector::setTextureFrame(std::size_t textureIndex, std::int32_t frame) {
    if (textureIndex < mSetup.textures.size()) mSetup.textures[textureIndex].frame = frame;
}

bool TileSelector::inMatrix(const TileId& id) const {
    if (id.level < 0 || id.level > mSetup.grid.maxLevel()) return false;
    const io::TileMatrix& m = mSetup.grid.levels[std::size_t(id.level)];
    return id.column >= 0 && id.row >= 0 && id.column < m.matrixWidth && id.row < m.matrixHeight;
}

math::Aabb TileSelector::nodeBounds(const TileId& id, double minZ, double maxZ) const {
    double x0, y0, x1, y1;
    mSetup.grid.tileBounds(id, x0, y0, x1, y1);
    const io::TileMatrix& m = mSetup.grid.levels[std::size_t(id.level)];
    // Posts sit half a pixel east/south of the tile corner and skirts flare half a pixel out:
    // one pixel of margin covers both.
    math::Aabb b;
    b.min = glm::dvec3(x0 - m.pixelXSize, y0 - m.pixelYSize, minZ);
    b.max = glm::dvec3(x1 + m.pixelXSize, y1 + m.pixelYSize, maxZ);
    return b;
}

void TileSelector::nodeDomain(const TileId& id, const TileId& geometry, bool meshIsGeometry,
                              glm::dvec2& min, glm::dvec2& max) const {
    // The planned geometry tile G's mesh covers G's bounds shifted half a post of G's level
    // east/south (posts at pixel centres), plus skirts flaring another half post outwards. Its
    // descendants partition exactly that domain, so their clip edges lie on G's post grid and
    // the union of G's descendants is G drawn whole (docs/terrain.md §2).
    double x0, y0, x1, y1;
    mSetup.grid.tileBounds(id, x0, y0, x1, y1);
    const io::TileMatrix& m = mSetup.grid.levels[std::size_t(geometry.level)];
    const double px = m.pixelXSize, py = m.pixelYSize;
    min = glm::dvec2(x0 + 0.5 * px, y0 - 0.5 * py);
    max = glm::dvec2(x1 + 0.5 * px, y1 - 0.5 * py);
    if (!meshIsGeometry) return;  // an ancestor drawn while G loads has no skirts on G's border
    if (id.level > mSetup.geometryMaxLevel) {
        // Finer than any mesh (imagery at its own resolution): the node's sides inside G are its
        // texture tile's own edges, so its texture covers all it draws (shifted by half a post,
        // each node showed a strip of its neighbour's ground with its own clamped edge texels).
        // Siblings cut the same mesh there, so the shared edge cannot crack (fragment clip).
        min = glm::dvec2(x0, y0);
        max = glm::dvec2(x1, y1);
        // Across the sides of its ancestor A at the finest mesh level, the node may meet a
        // node of A's level or coarser under the same G, whose domain is shifted by G's half
        // post: sharing that shifted edge keeps G's descendants a partition of G's domain
        // (clipped at its own edge, a texture-only node west or north of such a node left a
        // strip of half a post of G uncovered on each axis).
        const int inA = 1 << (id.level - mSetup.geometryMaxLevel);
        if (id.column % inA == 0) min.x = x0 + 0.5 * px;
        if ((id.column + 1) % inA == 0) max.x = x1 + 0.5 * px;
        if (id.row % inA == 0) max.y = y1 - 0.5 * py;
        if ((id.row + 1) % inA == 0) min.y = y0 - 0.5 * py;
    }
    // Sides on G's border keep G's skirts (their bottoms flare to half a post past the surface).
    const int span = 1 << (id.level - geometry.level);
    if (id.column % span == 0) min.x = x0 - px;
    if ((id.column + 1) % span == 0) max.x = x1 + 2.0 * px;
    if (id.row % span == 0) max.y = y1 + py;
    if ((id.row + 1) % span == 0) min.y = y0 - 2.0 * py;
}

double TileSelector::levelError(const TileId& geometryTile, int tier) const {
    io::TileStats s;
    double e = 0.0;
    TileId t = geometryTile;
    // Unknown stats: inherit the nearest known ancestor's error (coarser levels bound finer).
    while (t.level >= 0) {
        const TileState st = mStats->lookup(t, s);
        if (st == TileState::Known) {
            e = s.geometricError;
            break;
        }
        if (t.level == 0) break;
        t = t.parent();
    }
    return e + mSetup.options.tinTolerance(e, tier);
}

bool TileSelector::findGeometry(TileKey& key, TileHandle& handle) {
    const int want = std::max(0, key.frame);
    const int maxTier = mSetup.options.maxToleranceTier();
    auto tryTier = [&](const TileId& id, int tier) {
        const TileHandle h = mResidency->drawable(TileKey{key.layer, tier, id});
        if (!h.valid()) return false;
        key = TileKey{key.layer, tier, id};
        handle = h;
        return true;
    };
    // Same tile first: the wanted tier, then finer tiers (they meet the bound too), then coarser
    // ones (a stand-in like an ancestor while the wanted tier loads).
    if (tryTier(key.id, want)) return true;
    for (int tier = want - 1; tier >= 0; --tier)
        if (tryTier(key.id, tier)) return true;
    for (int tier = want + 1; tier <= maxTier; ++tier)
        if (tryTier(key.id, tier)) return true;
    // Then the nearest ancestor with any tier, finest first.
    for (TileId id = key.id; id.level > 0;) {
        id = id.parent();
        for (int tier = 0; tier <= maxTier; ++tier)
            if (tryTier(id, tier)) return true;
    }
    // Nothing at all: the plain walk makes sure the branch's root is requested.
    TileKey plain{key.layer, 0, key.id};
    return findDrawable(plain, handle) ? (key = plain, true) : false;
}

void TileSelector::request(const TileKey& key, double priority) {
    mResult.requests.push_back(TileRequest{key, priority});
}

bool TileSelector::findDrawable(TileKey& key, TileHandle& handle) {
    // Walks from key.id up to the root; leaves `key` at the drawable tile.
    TileKey k = key;
    while (true) {
        const TileHandle h = mResidency->drawable(k);
        if (h.valid()) {
            key = k;
            handle = h;
            return true;
        }
        if (k.id.level == 0) break;
        k.id = k.id.parent();
    }
    // Nothing drawable at all: make sure the root of this branch is on its way.
    const std::size_t rootIndex =
        std::size_t(k.id.row) * std::size_t(mSetup.grid.levels[0].matrixWidth) +
        std::size_t(k.id.column);
    std::size_t layerSlot = 0;
    for (std::size_t i = 0; i < mSetup.textures.size(); ++i)
        if (mSetup.textures[i].layer == k.layer) layerSlot = i + 1;
    const std::size_t roots = mRootRequested.size() / (1 + mSetup.textures.size());
    const std::size_t slot = layerSlot * roots + rootIndex;
    if (slot < mRootRequested.size() && !mRootRequested[slot] && k.id != key.id) {
        mRootRequested[slot] = 1;
        request(k, kNothingDrawnPriority * 2);
    }
    return false;
}

void TileSelector::emit(const TileId& id, const NodeInfo& info, double distance, double ppm) {
    const TerrainOptions& opt = mSetup.options;
    DrawTile tile;
    tile.id = id;
    tile.distance = distance;

    // Geometry: the coarsest ancestor whose mesh meets tauGeom (texture-driven refinement must
    // not multiply triangles), else the node itself or its ancestor at the finest level.
    const int geometryLevel =
        info.geometryLevel >= 0 ? std::min(info.geometryLevel, mSetup.geometryMaxLevel)
                                : mSetup.geometryMaxLevel;
    const TileId wantedGeom = ancestorAt(id, geometryLevel);
    const int wantedTier = info.geometryLevel >= 0 ? info.geometryTier : 0;
    const TileKey wantedKey{mSetup.geometryLayer, wantedTier, wantedGeom};
    TileKey gk = wantedKey;
    TileHandle gh;
    const bool found = findGeometry(gk, gh);
    // A coarser tier than wanted breaks the bound like an ancestor does; a finer one only costs
    // triangles, so replacing it is requested at the lowest priority.
    const bool coarser = found && (gk.id != wantedGeom || gk.frame > wantedTier);
    if (!found || gk != wantedKey) {
        const double shownPx = found ? levelError(gk.id, gk.frame) * ppm : 0.0;
        request(wantedKey,
                found ? (coarser ? shownPx : 0.0) : kNothingDrawnPriority + info.error * ppm);
    }
    if (!found) {
        ++mResult.counters.tilesMissing;
        return;
    }
    tile.geometry = gk;
    tile.handle = gh;
    tile.fromAncestor = coarser;
    tile.clipped = gk.id != id;
    tile.geometricErrorPx = levelError(gk.id, gk.frame) * ppm;
    // Texture-only nodes (finer than the finest mesh) clip at their own tile edges (nodeDomain).
    tile.domainLevel =
        id.level > mSetup.geometryMaxLevel && gk.id == wantedGeom ? id.level : wantedGeom.level;
    nodeDomain(id, wantedGeom, gk.id == wantedGeom, tile.clipMin, tile.clipMax);

    // Textures, per layer (Döllner's texture loop): coarsest level whose texel is fine enough.
    tile.firstTexture = std::uint32_t(mResult.textures.size());
    bool anyTextureFallback = false;
    for (const TextureLayerSpec& layer : mSetup.textures) {
        int level = std::min(id.level, layer.maxLevel);
        while (level > 0 && !opt.fullResolution &&
               TerrainOptions::postSpacing(mSetup.grid, level - 1) * ppm <= opt.tauTex)
            --level;
        TextureAssignment ta;
        ta.wanted = TileKey{layer.layer, layer.frame, ancestorAt(id, level)};
        ta.key = ta.wanted;
        const bool have = findDrawable(ta.key, ta.handle);
        ta.fromAncestor = have && ta.key.id != ta.wanted.id;
        if (!have || ta.fromAncestor) {
            const double shownPx =
                have ? TerrainOptions::postSpacing(mSetup.grid, ta.key.id.level) * ppm
                     : kNothingDrawnPriority;
            request(ta.wanted, shownPx);
        }
        if (ta.fromAncestor) {
            ++mResult.counters.texturesFromAncestor;
            anyTextureFallback = true;
        }
        double x0, y0, x1, y1;
        mSetup.grid.tileBounds(ta.key.id, x0, y0, x1, y1);
        ta.boundsMin = glm::dvec2(x0, y0);
        ta.boundsMax = glm::dvec2(x1, y1);
        mResult.textures.push_back(ta);
    }
    tile.textureCount = std::uint32_t(mResult.textures.size()) - tile.firstTexture;

    if (tile.fromAncestor) ++mResult.counters.geometryFromAncestor;
    if (tile.fromAncestor || anyTextureFallback) ++mResult.counters.tilesFromAncestor;
    mResult.tiles.push_back(tile);
}

void TileSelector::visit(const TileId& id, const NodeInfo& parent) {
    ++mResult.counters.nodesVisited;
    NodeInfo info = parent;
    info.known = false;
    if (id.level <= mSetup.geometryMaxLevel) {
        io::TileStats s;
        const TileState st = mStats->lookup(id, s);
        if (st == TileState::Absent) return;
        if (st == TileState::Known) {
            info.minZ = s.minValue;
            info.maxZ = s.maxValue;
            info.error = s.geometricError;
            info.known = true;
        }
    }
    const TerrainOptions& opt = mSetup.options;
    const double tol = opt.tinTolerance(info.error);
    const double slack = info.error + tol;
    const math::Aabb box = nodeBounds(id, info.minZ - slack, info.maxZ + slack);
    // Below its geometry tile G a node draws its share of G's mesh, which reaches a post of G's
    // level past the node's bounds (nodeDomain); cull with that margin, keep `box` for distance.
    math::Aabb cullBox = box;
    if (info.geometryLevel >= 0 && info.geometryLevel < id.level) {
        const io::TileMatrix& g = mSetup.grid.levels[std::size_t(info.geometryLevel)];
        cullBox.min -= glm::dvec3(g.pixelXSize, g.pixelYSize, 0.0);
        cullBox.max += glm::dvec3(g.pixelXSize, g.pixelYSize, 0.0);
    }
    if (!mFrustum.intersects(cullBox)) {
        ++mResult.counters.culled;
        return;
    }
    const double distance = box.distanceTo(mCamera->eye);
    const double ppm = mCamera->pixelsPerMetreAt(distance);

    bool refine = false;
    if (id.level < mSetup.geometryMaxLevel) {
        const double gammaPx = (info.error + tol) * ppm;
        refine = opt.fullResolution || gammaPx > opt.tauGeom;
    }
    // Only a node whose error is known may stand in for its descendants' geometry.
    if (!refine && info.geometryLevel < 0 && (info.known || id.level == 0) &&
        id.level <= mSetup.geometryMaxLevel) {
        info.geometryLevel = id.level;
        // The coarsest mesh of this tile that still meets tauGeom here (tiers double the TIN
        // tolerance); nodes below it (texture detail) share this mesh.
        info.geometryTier = 0;
        for (int tier = opt.maxToleranceTier(); tier > 0; --tier)
            if ((info.error + opt.tinTolerance(info.error, tier)) * ppm <= opt.tauGeom) {
                info.geometryTier = tier;
                break;
            }
    }
    if (!refine) {
        const double texelPx = TerrainOptions::postSpacing(mSetup.grid, id.level) * ppm;
        for (const TextureLayerSpec& t : mSetup.textures)
            if (t.maxLevel > id.level && (opt.fullResolution || texelPx > opt.tauTex))
                refine = true;
    }
    if (refine && id.level < mMaxDepth) {
        bool anyChild = false;
        for (int q = 0; q < 4; ++q) {
            const TileId c = id.child(q);
            if (!inMatrix(c)) continue;
            anyChild = true;
            visit(c, info);
        }
        if (anyChild) return;
    }
    emit(id, info, distance, ppm);
}

const SelectionResult& TileSelector::select(const math::Camera& camera, const TileStatsTable& stats,
                                            TileResidency& residency) {
    mResult.tiles.clear();
    mResult.textures.clear();
    mResult.requests.clear();
    mResult.counters = SelectionCounters{};
    std::fill(mRootRequested.begin(), mRootRequested.end(), std::uint8_t(0));
    if (mSetup.grid.levels.empty()) return mResult;

    mCamera = &camera;
    mStats = &stats;
    mResidency = &residency;
    mFrustum = math::Frustum(camera.projection() * camera.view());

    const io::TileMatrix& root = mSetup.grid.levels[0];
    NodeInfo unknownRoot;
    unknownRoot.minZ = mSetup.heightMin;
    unknownRoot.maxZ = mSetup.heightMax;
    for (int row = 0; row < root.matrixHeight; ++row)
        for (int col = 0; col < root.matrixWidth; ++col) visit(TileId{0, col, row}, unknownRoot);

    // Several nodes can want the same payload (a shared texture ancestor, geometry beyond the
    // elevation pyramid): keep one request per key with the highest priority. In-place sort.
    auto& req = mResult.requests;
    std::sort(req.begin(), req.end(), [](const TileRequest& a, const TileRequest& b) {
        if (a.key.layer != b.key.layer) return a.key.layer < b.key.layer;
        if (a.key.frame != b.key.frame) return a.key.frame < b.key.frame;
        if (a.key.id != b.key.id) return a.key.id < b.key.id;
        return a.priority > b.priority;
    });
    req.erase(
        std::unique(req.begin(), req.end(),
                    [](const TileRequest& a, const TileRequest& b) { return a.key == b.key; }),
        req.end());

    mResult.counters.tilesDrawn = std::uint32_t(mResult.tiles.size());
    mResult.counters.requested = std::uint32_t(mResult.requests.size());
    mCamera = nullptr;
    mStats = nullptr;
    mResidency = nullptr;
    return mResult;
}

}  // namespace kiosk::terrain
