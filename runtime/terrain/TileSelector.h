#pragma once

#include "runtime/core/Diagnostics.h"
#include "runtime/core/TileId.h"
#include "runtime/io/StoreTypes.h"
#include "runtime/math/Camera.h"
#include "runtime/math/Frustum.h"
#include "runtime/math/Glm.h"
#include "runtime/terrain/TerrainOptions.h"
#include "runtime/terrain/TileKey.h"
#include "runtime/terrain/TileStatsTable.h"

#include <cstdint>
#include <vector>

namespace kiosk::terrain {

/** @brief A texture (or sequence) layer draped on the terrain, selected per layer. */
struct TextureLayerSpec {
    std::uint16_t layer = 1;  ///< cache/request key layer index
    std::int32_t frame = 0;   ///< frame of a time-keyed sequence (0 for static layers)
    int maxLevel = 0;         ///< finest level the layer has (LayerInfo::levels - 1)
};

/** @brief Fixed at setup (allocates); see TileSelector::configure. */
struct SelectorSetup {
    io::TileGrid grid;
    std::uint16_t geometryLayer = 0;  ///< key layer index of the elevation payloads (meshes)
    int geometryMaxLevel = 0;         ///< finest elevation level (LayerInfo::levels - 1)
    /** @brief Height range (metres) assumed for tiles with no known stats up their ancestry,
     * e.g. before the root arrives: set from the elevation LayerInfo min/max. */
    double heightMin = -500.0;
    double heightMax = 9000.0;
    std::vector<TextureLayerSpec> textures;
    TerrainOptions options;
};

/**
 * @brief Answers "can this payload be drawn now?" for the selector (render thread).
 * A cache-backed implementation returns the slot handle and pins it for the current frame
 * (TileCache::acquire); it must not block or allocate.
 */
class TileResidency {
public:
    virtual ~TileResidency() = default;
    virtual TileHandle drawable(const TileKey& key) = 0;
};

/** @brief The texture of one layer chosen for one drawn tile. */
struct TextureAssignment {
    TileKey wanted;     ///< the level the tau_tex criterion asks for
    TileKey key;        ///< the tile actually used (wanted or its nearest drawable ancestor)
    TileHandle handle;  ///< invalid if nothing of this layer is drawable here yet
    bool fromAncestor = false;  ///< key != wanted because wanted is not resident
    glm::dvec2 boundsMin{0.0};  ///< world (CRS) extent of `key`'s image, for texture coords
    glm::dvec2 boundsMax{0.0};
};

/**
 * @brief One tile to draw. The drawn tiles partition the visible extent: no two overlap, and
 * every visible part of the terrain (where elevation exists) is covered exactly once.
 */
struct DrawTile {
    TileId id;          ///< selected quadtree node (the region to draw)
    TileKey geometry;   ///< payload whose mesh is drawn: id itself or an ancestor
    TileHandle handle;  ///< handle of `geometry` (always valid for entries in the list)
    /** @brief Mesh is an ancestor's because `id`'s own mesh is not resident (loading). */
    bool fromAncestor = false;
    /**
     * @brief geometry.id != id (fallback, or the node is finer than the elevation pyramid):
     * draw only the part of the mesh inside [clipMin, clipMax] (e.g. fragment discard).
     */
    bool clipped = false;
    /**
     * @brief World (CRS) xy rectangle the node covers: its share of the planned geometry tile
     * G's mesh (level `domainLevel`), i.e. its tile bounds shifted east/south by half a post of
     * G's level (posts sit at pixel centres, see TileMesh); sides on G's border are opened by a
     * post of G so that G's skirts are kept when G's own mesh is drawn.
     */
    glm::dvec2 clipMin{0.0};
    glm::dvec2 clipMax{0.0};
    /** @brief Level of the planned geometry tile G whose post grid the clip edges lie on. */
    int domainLevel = 0;
    double distance = 0.0;           ///< eye to the node's bounding box (sort front to back)
    double geometricErrorPx = 0.0;   ///< projected error of the drawn mesh at `distance`
    std::uint32_t firstTexture = 0;  ///< into SelectionResult::textures
    std::uint32_t textureCount = 0;
};

/** @brief A payload the loader should fetch; larger priority first (pixels of error it fixes). */
struct TileRequest {
    TileKey key;
    double priority = 0.0;
};

struct SelectionCounters {
    std::uint32_t tilesDrawn = 0;
    std::uint32_t tilesFromAncestor = 0;  ///< geometry or any texture from an ancestor (loading)
    std::uint32_t geometryFromAncestor = 0;
    std::uint32_t texturesFromAncestor = 0;
    std::uint32_t tilesMissing = 0;  ///< selected but nothing (not even the root) resident
    std::uint32_t culled = 0;        ///< nodes rejected by the view frustum
    std::uint32_t requested = 0;
    std::uint32_t nodesVisited = 0;
};

/** @brief Reused every frame (clear() keeps capacity): no allocation once warm. */
struct SelectionResult {
    std::vector<DrawTile> tiles;
    std::vector<TextureAssignment> textures;
    std::vector<TileRequest> requests;
    SelectionCounters counters;
};

/**
 * @brief Quadtree tile selection with a guaranteed screen-space error (Döllner 2000, Wahl 2004).
 *
 * A node N at distance d (eye to its bounding box) is refined while
 *   gamma(N) = (e(N) + tinTolerance(e(N))) * pixelsPerMetreAt(d) > tauGeom,  e = stored error
 * or, for any texture layer with a finer level, while postSpacing(level) * ppm(d) > tauTex.
 * The node whose mesh meets tauGeom also picks its mesh's tolerance tier: the coarsest tier k
 * with (e + tinTolerance(e, k)) * ppm(d) <= tauGeom (key frame k of the elevation layer).
 * Each layer's texture level is then chosen independently: the coarsest ancestor level whose
 * texel still projects to <= tauTex px. Nodes outside the frustum are culled. If the wanted
 * payload is not drawable, the nearest drawable ancestor is drawn (clipped) and a request is
 * emitted. See docs/terrain.md for the formulas.
 *
 * Threads: render thread. select() does not allocate once its vectors have grown.
 */
class TileSelector {
public:
    /**
     * @brief Take a grid and layers (allocates). The grid must be a quadtree: level 0 first,
     * each level's post spacing half the previous one and at most twice as many tiles per axis.
     * Otherwise TERRAIN_GRID_NOT_QUADTREE (naming the level) and select() draws nothing.
     */
    Diagnostics configure(SelectorSetup setup);
    const SelectorSetup& setup() const noexcept { return mSetup; }
    /** @brief Change quality knobs without reconfiguring (e.g. a scenario edit); a change of
     * textureLevelsBeyondGeometry takes effect at the next configure(). */
    void setOptions(const TerrainOptions& options) { mSetup.options = options; }
    /** @brief Switch a sequence layer to another frame (no allocation). */
    void setTextureFrame(std::size_t textureIndex, std::int32_t frame);

    /** @brief Select for `camera`; the returned reference stays valid until the next call. */
    const SelectionResult& select(const math::Camera& camera, const TileStatsTable& stats,
                                  TileResidency& residency);

    /** @brief The bounding box the selector uses for a node (exposed for tests/debug draw). */
    math::Aabb nodeBounds(const TileId& id, double minZ, double maxZ) const;
    /** @brief DrawTile::clipMin/clipMax of node `id` under the planned geometry tile. */
    void nodeDomain(const TileId& id, const TileId& geometry, bool meshIsGeometry, glm::dvec2& min,
                    glm::dvec2& max) const;

private:
    struct NodeInfo {
        double minZ = 0, maxZ = 0, error = 0;
        bool known = false;
        /** Level of the ancestor whose mesh already meets tauGeom (-1: none yet). Nodes below it
         *  are refined for texture detail only and draw that ancestor's mesh, clipped. */
        int geometryLevel = -1;
        /** Tolerance tier of that ancestor's mesh (TerrainOptions::toleranceTiers). */
        int geometryTier = 0;
    };
    /** Mesh of `wanted` (frame = tier): that tier, a finer one, a coarser one, else the
     *  nearest drawable ancestor's tier-0 mesh. */
    bool findGeometry(TileKey& key, TileHandle& handle);
    void visit(const TileId& id, const NodeInfo& parent);
    void emit(const TileId& id, const NodeInfo& info, double distance, double ppm);
    bool findDrawable(TileKey& key, TileHandle& handle);
    void request(const TileKey& key, double priority);
    bool inMatrix(const TileId& id) const;
    double levelError(const TileId& geometryTile, int tier = 0) const;

    SelectorSetup mSetup;
    int mMaxDepth = 0;
    SelectionResult mResult;
    // Per-frame state (valid during select()).
    const math::Camera* mCamera = nullptr;
    const TileStatsTable* mStats = nullptr;
    TileResidency* mResidency = nullptr;
    math::Frustum mFrustum;
    std::vector<std::uint8_t> mRootRequested;  // per level-0 tile and layer, reset per frame
};

}  // namespace kiosk::terrain
