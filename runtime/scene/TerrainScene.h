#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "config/Scenario.h"
#include "runtime/anim/FrameBracket.h"
#include "runtime/anim/PrefetchPlanner.h"
#include "runtime/anim/VisiblePair.h"
#include "runtime/core/Result.h"
#include "runtime/gl/Context.h"
#include "runtime/gl/GlObject.h"
#include "runtime/io/StoreReader.h"
#include "runtime/loader/TileLoader.h"
#include "runtime/loader/UploadBudget.h"
#include "runtime/math/Camera.h"
#include "runtime/math/Frustum.h"
#include "runtime/render/GpuMesh.h"
#include "runtime/render/MappingSet.h"
#include "runtime/render/OcclusionQueries.h"
#include "runtime/render/TerrainRenderer.h"
#include "runtime/render/WarpedGridRenderer.h"
#include "runtime/scene/CacheBudgets.h"
#include "runtime/scene/Playback.h"
#include "runtime/scene/TextureChoice.h"
#include "runtime/terrain/MeshCells.h"
#include "runtime/terrain/MeshPosts.h"
#include "runtime/terrain/TilePayload.h"
#include "runtime/terrain/TileSelector.h"
#include "runtime/terrain/TileStatsTable.h"

namespace kiosk::loader {
struct LayerBinding;    // runtime/loader/StoreTileLoader.h
class StoreTileLoader;  // runtime/loader/StoreTileLoader.h
}

namespace kiosk::scene {

/** @brief osgEarth-style layer status: a bad layer degrades itself, never the process. */
enum class LayerState { Ready, Degraded, Failed };
const char* layerStateName(LayerState s) noexcept;

struct LayerStatus {
    std::string id;
    LayerState state = LayerState::Ready;
    std::string message;  ///< why, naming file/table/tile
    std::uint32_t failedTiles = 0;
};

/** @brief What one frame did (feeds `--stats` and the status overlay). */
struct SceneFrameInfo {
    std::uint32_t tilesDrawn = 0;
    std::uint64_t triangles = 0;
    std::uint32_t tilesFromAncestor = 0;
    std::uint32_t drawCalls = 0;  ///< terrain glDrawElements calls
    std::uint32_t sequenceTilesMissing = 0;  ///< wanted sequence tiles not resident
    std::uint64_t residentBytes = 0;         ///< CPU + GPU bytes held by the tile cache
    std::uint32_t requests = 0;
    std::uint32_t uploads = 0;
    bool holdingSequence = false;  ///< a sequence shows an older complete frame pair
    /** @brief While holding with a pair on screen: the data time that pair shows (else NaN). */
    double heldDataTime = std::numeric_limits<double>::quiet_NaN();
    /** @brief Tiles of one sequence drew different frames (must never happen: atomic steps). */
    bool mixedSequenceFrames = false;
    std::int32_t shownFrameA = -1;  ///< first sequence layer: frames on screen (-1: none)
    std::int32_t shownFrameB = -1;
    /** @brief The first sequence layer shows a pair that was complete when it was committed. */
    bool sequencePairCommitted = false;
    /** @brief Drawn tiles whose shown frame came from an ancestor or was absent. */
    std::uint32_t shownTilesIncomplete = 0;
    // Prefetch ahead of the playhead (first sequence layer; docs/animation.md).
    std::uint32_t heldFrames = 0;        ///< consecutive frames the shown pair was held
    std::int32_t prefetchDepth = 0;      ///< frames ahead wanted by the deadline rule
    std::uint32_t prefetchFrames = 0;    ///< frames in this frame's plan (current pair included)
    std::uint32_t prefetchRequests = 0;  ///< sequence tiles requested ahead this frame
    /** @brief Frames that became shown this frame after being requested ahead (0, 1 or 2). */
    std::uint32_t prefetchHits = 0;
    std::uint64_t prefetchGeneration = 0;  ///< bumped on each seek (stale prefetch dropped)
    double frameLoadMs = 0;                ///< measured mean time to load one frame of the view
    /** @brief Projective mappings this frame (route pieces count one each). */
    std::uint32_t mappingsActive = 0;
    std::uint32_t mappingsCulledFrustum = 0;  ///< rectangle outside the view frustum
    std::uint32_t mappingsCulledSize = 0;     ///< screen-space size rho below the threshold
    std::uint32_t mappingsOverCapacity = 0;   ///< active but beyond the uniform block
    double uploadMs = 0;                   ///< GPU uploads (and evicted releases) this frame
    /** @brief Every sequence pair at this frame's own time is resident (a wall may step to it). */
    bool wantedSequenceResident = true;
    /** @brief The procedural detail grid drew this frame (overlay: "procedural detail"). */
    bool proceduralDetail = false;
    // Occlusion culling (docs/terrain.md §10): tiles skipped as hidden behind nearer terrain.
    std::uint32_t tilesOccluded = 0;
    std::uint32_t occlusionQueries = 0;  ///< boxes tested
    std::uint32_t occlusionRounds = 0;   ///< batches (each waits for the rasterizer once)
    double occlusionMs = 0;              ///< issuing the boxes and waiting for their results
};

/** @brief Bytes held by the tile cache by kind, and loader requests waiting (kiosk /metrics). */
struct SceneCacheUsage {
    std::uint64_t cpuTiles = 0;     ///< CPU payloads (budget terrain.cache_bytes)
    std::uint64_t gpuTextures = 0;  ///< uploaded imagery / raster textures
    std::uint64_t gpuTexturesCompressed = 0;  ///< of which imagery uploaded as GPU blocks
    std::uint64_t gpuMeshes = 0;    ///< uploaded terrain meshes
    std::uint32_t loaderQueue = 0;  ///< requests waiting for the loader thread
    std::uint64_t cpuBudget = 0;    ///< budget of cpuTiles now
    std::uint64_t gpuBudget = 0;    ///< budget of gpuTextures + gpuMeshes now
};

/** @brief Bytes of the per-scenario GPU/CPU resources outside the tile cache (kiosk budgets). */
struct SceneMemoryUsage {
    std::uint64_t lutBytes = 0;      ///< layer LUT textures and mapping LUT rows
    std::uint64_t mappingBytes = 0;  ///< projective-mapping data arrays
};

/** @brief Where a lens is (scene CRS metres), after its keys or a run-time move. */
struct LensPlacement {
    glm::dvec2 centre{0.0};
    glm::dvec2 radii{1.0};     ///< circle / ellipse; a swipe lens has none
    double rotationDeg = 0.0;  ///< ellipse axis, or the swipe line's inside direction
    bool enabled = true;
};

/** @brief A transfer function ready for the GPU and the legend. */
struct SceneLut {
    std::string name;
    const color::TransferFunction* function = nullptr;
    gl::Texture texture;  ///< the ramp alone (legends)
    gl::Texture edged;    ///< below, the ramp, above, nodata texels (the layer stack)
    int size = 0;         ///< ramp texels
};

/**
 * @brief The running terrain of one scenario: the store, tile selection with the screen-space
 * error guarantee, the loader thread, the tile cache and its GPU copies, the layer stack and
 * the sequences' atomic frame pairs.
 *
 * Render thread only (owns GL objects); the loader thread it starts reads the store with its own
 * connection. Per frame: update() then draw(). Never blocks on disk: what is not resident is
 * drawn from the nearest resident ancestor.
 */
class TerrainScene {
public:
    static Result<std::unique_ptr<TerrainScene>> create(const config::Scenario& scenario,
                                                        const gl::Caps& caps);
    ~TerrainScene();
    TerrainScene(const TerrainScene&) = delete;
    TerrainScene& operator=(const TerrainScene&) = delete;

    /**
     * @brief Select tiles for `camera` at data time `time`, submit requests, upload what arrived
     * within the per-frame budget, and pick each sequence's visible frame pair.
     */
    void update(const math::Camera& camera, double time);
    /**
     * @brief update() with the clock's playback state: sequences prefetch frames ahead of the
     * playhead sized from `playback.rate` and the measured load time, under the cache budget,
     * wrapping to the loop start. Without it the last playback given is used (initially paused:
     * the current pair and its neighbours).
     */
    void update(const math::Camera& camera, double time, const Playback& playback);
    /**
     * @brief Display walls (runtime/wall): sequences show the pair bracketing `stepTime` (which
     * every node of the wall reported resident) while the pair at the frame's own time loads;
     * nullopt (the default) shows the pair at the frame's time as soon as it is complete.
     */
    void setStepGate(std::optional<double> stepTime) { mStepGate = stepTime; }
    /** @brief Request tiles for a future view (camera path prefetch); low priority. */
    void prefetch(const math::Camera& futureCamera);
    void draw(const math::Camera& camera, const render::TerrainStyle& style);

    /** @brief Nothing wanted for the current view is missing or in flight (render waits). */
    bool settled() const noexcept { return mSettled; }
    const SceneFrameInfo& frameInfo() const noexcept { return mFrame; }
    const std::vector<LayerStatus>& layerStatus() const noexcept { return mStatus; }
    /**
     * @brief The lens a user moves (keys in `play`, POST /control/lens): the first comparison
     * lens, else the first lens; -1 without lenses (TerrainSceneLenses.cpp).
     */
    int primaryLens() const;
    /** @brief Index of the lens with this id, -1 if none. */
    int lensIndex(const std::string& id) const;
    /** @brief Where lens `index` was drawn last frame (its keys, or where it was put). */
    std::optional<LensPlacement> lensPlacement(int index) const;
    /**
     * @brief Put lens `index` at `p` from the next frame on; its keys no longer move it (until
     * the scenario is re-opened). False for an index out of range.
     */
    bool placeLens(int index, const LensPlacement& p);
    /** @brief Cache bytes by kind (TerrainSceneUsage.cpp); walks the GPU slots, no allocation. */
    SceneCacheUsage cacheUsage() const;

    /** @brief World bounds of the data: extent and min/max elevation. */
    const math::Aabb& bounds() const noexcept { return mBounds; }
    /** @brief A view of the whole extent from the south-west, for scenarios without one. */
    math::Viewpoint overviewViewpoint() const;
    /** @brief Frame times of the scenario's sequences (clock key frames). */
    std::vector<double> sequenceKeyTimes() const;
    const SceneLut* lut(const std::string& transferName) const;
    /**
     * @brief The legend title layer `id`'s kind gives (products: what and since when, hazard:
     * which curves or "depth only"); empty when the layer is not in the stack or has none.
     */
    std::string legendTitle(const std::string& id) const;
    /**
     * @brief A chapter's override of layer `id`: hidden, or drawn with `opacity` (nullopt: the
     * scenario's). False if no such layer is in the stack.
     */
    bool setLayerOverride(const std::string& id, bool visible, std::optional<double> opacity);
    void clearLayerOverrides();
    /**
     * @brief Draw scene positions and elevations instead of colours (into a float target) for
     * fidelity measurements. Rebuilds the terrain program; false if that failed.
     */
    bool setPositionOutput(bool on);
    const io::StoreInfo& storeInfo() const { return mReader->info(); }
    /**
     * @brief Every budget in effect by name (bytes, milliseconds, counts) for `--stats`:
     * cache CPU/GPU bytes (and whether sized to the view), upload limits, loader in-flight cap,
     * the sequences' prefetch bytes (TerrainSceneBudgets.cpp).
     */
    std::vector<std::pair<std::string, double>> budgets() const;
    /** @brief LUT and mapping-array bytes this scene holds (TerrainSceneMappings.cpp). */
    SceneMemoryUsage memoryUsage() const;
    /**
     * @brief Screen-space error thresholds for the next selections (the frame-rate governor's
     * lever); the loader's meshes do not depend on them. Ignored for the full-resolution reference.
     */
    void setTau(double tauGeom, double tauTex);
    double tauGeom() const noexcept { return mOptions.tauGeom; }
    double tauTex() const noexcept { return mOptions.tauTex; }
    /**
     * @brief Warp passes of the procedural detail grid per frame (default 2); 0 draws a regular
     * grid of the same vertex count (the benchmark's baseline). No effect without detail.
     */
    void setDetailWarpIterations(int iterations);
    /**
     * @brief Where the procedural detail grid drew last frame: the world rectangle only it covers
     * (the quadtree's hole), false when it did not draw.
     */
    bool detailHole(glm::dvec2& min, glm::dvec2& max) const;
    /**
     * @brief Occlusion culling (terrain.occlusionCulling, default on; TerrainSceneOcclusion.cpp):
     * tiles hidden behind nearer terrain drawn this frame are skipped. Off draws every tile.
     */
    void setOcclusionCulling(bool on);
    bool occlusionCulling() const noexcept { return mOcclusionOn; }
    /** @brief The block format imagery is uploaded in (terrain.textureCompression, the context). */
    const TextureChoice& textureChoice() const noexcept { return mTextureChoice; }

private:
    TerrainScene() = default;
    struct GpuSlot {
        render::GpuMesh mesh;
        gl::Texture texture;
        std::size_t bytes = 0;
        int postsX = 0, postsY = 0;  ///< raster textures: size in posts
        bool compressed = false;     ///< imagery uploaded as stored GPU blocks
    };
    /** @brief One composite layer of the stack and where its textures come from. */
    struct StackLayer {
        const config::Layer* config = nullptr;
        int keyLayer = -1;         ///< TileKey::layer of its payloads (-1: no texture)
        int specA = -1, specB = -1;  ///< indices into the selector's texture specs
        const io::SequenceInfo* sequence = nullptr;
        anim::Interpolation interpolation = anim::Interpolation::Data;
        anim::VisiblePair pair;
        anim::DisplayPair shown;
        float strength = 1.0f;
        std::optional<float> strengthOverride;  ///< a briefing chapter's (TerrainSceneOverrides.cpp)
        std::optional<float> nodataAs;
        anim::PrefetchPlanner planner;
        anim::PrefetchPlan plan;
        std::vector<std::uint8_t> aheadRequested;  ///< per frame: planned ahead, not yet shown
        std::size_t lastI0 = SIZE_MAX, lastI1 = SIZE_MAX;  ///< pair shown last frame
        bool lastHolding = false;
        /** @brief interpolate "arrival": key layer and texture spec of the pair thresholds. */
        int keyLayerT = -1, specT = -1;
        /** @brief Products: uLayerProduct = (first frame, interval) in timeUnit s since origin. */
        bool productClock = false;
        double timeOrigin = 0, timeUnit = 3600;
        std::string legendTitle;  ///< the kind's legend title ("" : the transfer function's)
        /**
         * @brief Sequences that step together (a comparison lens's two sides, a difference's
         * operands): index into mGroupComplete, -1 alone (TerrainSceneLenses.cpp).
         */
        int syncGroup = -1;
    };

    /**
     * @brief The stack: each enabled layer planned by its kind (layers/Registry.h) and served
     * from the store it names (TerrainSceneLayers.cpp).
     */
    void buildLayerStack(std::vector<loader::LayerBinding>& bindings, terrain::SelectorSetup& setup,
                         render::CompositeProgramDesc& desc);
    /**
     * @brief Index into mLayerStores of store `id` (0: the terrain's), opened on first use;
     * -1 with `problem` when it cannot be opened or does not share the terrain's CRS and grid.
     */
    int layerStore(const std::string& id, std::string& problem);
    Diagnostics buildRenderer();
    render::LutBinding lutBinding(std::size_t k) const;
    // TerrainSceneDetail.cpp: the procedural detail grid near the camera (issue 21).
    struct DetailState;
    struct DetailDeleter {
        void operator()(DetailState* d) const;
    };
    Diagnostics buildDetailRenderer();
    const terrain::MeshPosts* detailPosts(const terrain::DrawTile& t);
    /** @brief Region, sketch, warp and upload; sets the quadtree renderer's hole. */
    void planDetail(const math::Camera& camera, render::TerrainRenderer& quadtree);
    void setDetailLens(int index, const render::LensBinding& lens);
    /** @brief The sketch map over the planned region from the drawn meshes; false if incomplete. */
    bool buildDetailSketch(double postSpacing, int finestLevel);
    void recordDetailTile(const terrain::DrawTile& t, std::size_t layerIndex,
                          const render::LayerBinding& binding);
    bool detailHides(const terrain::DrawTile& t) const;
    void drawDetail(const math::Camera& camera, const render::TerrainStyle& style);
    void bindLenses();
    /** @brief Group the layers that must step together (after the stack is built). */
    void buildSyncGroups(const render::CompositeProgramDesc& desc);
    /** @brief Per group: every member's wanted pair is complete for the view this frame. */
    void syncGroupsComplete(const std::vector<anim::FrameBracket>& wanted);
    /** @brief Per group, for drawing tile `t`: every member has its frame textures there. */
    void groupTileValidity(const terrain::DrawTile& t);
    /** @brief Member `l` may draw on the current tile: its group shows a pair and has it here. */
    bool groupDrawsTile(const StackLayer& l) const {
        return l.shown.hasPair && mGroupTileValid[std::size_t(l.syncGroup)] != 0;
    }
    /** @brief GEOKIOSK_TEST_LOAD_DELAY_STORE: the store (loader index) slowed by the test hook. */
    int testDelayedStore() const;
    /** @brief Data layers and LUTs of the projective mappings (TerrainSceneMappings.cpp). */
    Diagnostics setupMappings(const gl::Caps& caps);
    /** @brief Evaluate, cull and upload the mappings for this frame. */
    void bindMappings(const math::Camera& camera);
    /** @brief Before drawing a mesh of tile `id`: only the mappings touching it. */
    void bindTileMappings(const TileId& id);
    void noteDrawnFrames(const StackLayer& layer, const terrain::DrawTile& tile);
    void drainCompletions();
    void uploadPayload(terrain::TileHandle handle, terrain::TilePayload& payload);
    void releaseEvicted();
    void noteFailure(const terrain::TilePayload& payload);
    bool sequenceFrameComplete(const StackLayer& layer, bool useA) const;
    // TerrainScenePrefetch.cpp: sequence prefetch ahead of the playhead.
    /** @brief Note whether `wanted` is resident, then retarget it to the step gate (walls). */
    void applyStepGate(const math::Camera& camera, double time,
                       std::vector<anim::FrameBracket>& wanted);
    void planSequencePrefetch();
    void countPrefetchHits(StackLayer& layer, bool reported);
    void recordLoadTime(const loader::LoadResult& result);
    // TerrainSceneBudgets.cpp: cache budgets sized to the view's working set.
    void sizeBudgetsToView();
    /** @brief Tells the loader how many product states the view draws (always kept). */
    void sizeDerivedStatesToView();
    void sendPrefetch();
    void addPathFramePrefetch(const terrain::SelectionResult& future);
    bool specComplete(int spec) const;
    void bindArrival(const StackLayer& layer, const terrain::DrawTile& tile,
                     render::LayerBinding& binding) const;
    render::LayerBinding bindingFor(const terrain::TextureAssignment& a, int postsX, int postsY) const;

    const config::Scenario* mScenario = nullptr;
    std::unique_ptr<io::StoreReader> mReader;
    std::filesystem::path mStorePath;
    /** @brief A store the layers read (the loader opens its own reader of each). */
    struct LayerStore {
        std::string id;
        std::filesystem::path path;
        io::StoreReader* reader = nullptr;       ///< metadata on the render thread
        std::unique_ptr<io::StoreReader> owned;  ///< other stores than the terrain's
    };
    std::vector<LayerStore> mLayerStores;  ///< [0]: the terrain store (reader = mReader)
    io::TileGrid mGrid;
    const io::LayerInfo* mElevation = nullptr;
    terrain::TerrainOptions mOptions;
    std::unique_ptr<terrain::TerrainTileCache> mCache;
    std::unique_ptr<terrain::CacheResidency> mResidency;
    terrain::TileSelector mSelector;
    terrain::TileSelector mPrefetchSelector;
    std::unique_ptr<terrain::CacheResidency> mPrefetchResidency;
    terrain::TileStatsTable mStats;
    std::unique_ptr<loader::TileLoader> mLoader;
    loader::StoreTileLoader* mStoreLoader = nullptr;  ///< mLoader's function (derived states)
    std::vector<std::uint64_t> mViewTrackIds;         ///< reused by sizeDerivedStatesToView()
    loader::UploadBudget mBudget{CacheDefaults::kUploadBytesPerFrame, CacheDefaults::kUploadMsPerFrame};
    bool mAutoCpu = false, mAutoGpu = false;       ///< scenario left the budget to the view
    std::size_t mViewCpuHigh = 0, mViewGpuHigh = 0;  ///< largest view working set so far
    std::uint64_t mAheadBytes = 0;  ///< sequences' planned frames over the view (last frame)
    std::vector<GpuSlot> mGpu;
    std::vector<StackLayer> mLayers;
    std::vector<SceneLut> mLuts;
    std::vector<LayerStatus> mStatus;
    std::vector<int> mKeyLayerStatus;  ///< key layer -> index into mStatus
    std::unique_ptr<render::TerrainRenderer> mRenderer;
    render::CompositeProgramDesc mDesc;
    int mMaxTextureUnits = 16;
    std::vector<terrain::TileRequest> mPrefetch;
    std::vector<std::uint32_t> mDrawOrder;
    std::vector<terrain::IndexRange> mCellRanges;  ///< per clipped draw, reused
    std::vector<render::IndexRun> mRuns;
    const terrain::SelectionResult* mSelection = nullptr;
    math::Aabb mBounds;
    glm::dvec3 mSceneOrigin{0.0};
    SceneFrameInfo mFrame;
    std::uint64_t mFrameNumber = 0;
    double mTime = 0;
    std::size_t mFirstSequenceLayer = SIZE_MAX;  ///< the layer whose frames frameInfo() reports
    bool mSettled = false;
    Playback mPlayback;
    std::optional<double> mStepGate;
    anim::LoadTimeEstimator mTileLoad{0.005};  ///< seconds per sequence tile on the loader
    std::vector<terrain::TileRequest> mSequencePrefetch;
    std::vector<anim::FrameBracket> mWanted;  ///< per layer: the frame pair the clock wants
    std::vector<terrain::TileRequest> mPrefetchAll;  ///< camera prefetch still missing, as sent
    /** @brief One scenario mapping and the array layers it samples. */
    struct SceneMapping {
        const config::ProjectiveMapping* config = nullptr;
        int layer = -1;  ///< data layer (route: edge profile); -1 - k: live input k
        int lut = -1;    ///< LUT row for scalar data, -1 for images
    };
    /** @brief A mapping of a stack layer (`layer`): its LUT and live input; or why not. */
    std::string liveMapping(const config::ProjectiveMapping& m, SceneMapping& sm);
    std::unique_ptr<render::MappingSet> mMappingSet;
    std::vector<SceneMapping> mMappings;
    std::vector<render::MappingGpu> mMappingGpu;
    std::vector<glm::dvec4> mMappingBoxes;  ///< xy footprint of each uploaded mapping
    std::vector<int> mTileMappings;
    int mRoutePointLayer = -1;
    std::unique_ptr<DetailState, DetailDeleter> mDetail;
    std::vector<std::uint8_t> mGroupComplete;            ///< per sync group, this frame
    std::vector<std::uint8_t> mGroupTileValid;           ///< per sync group, the tile drawn
    std::vector<std::optional<LensPlacement>> mLensPut;  ///< per lens: placed at run time
    std::vector<LensPlacement> mLensDrawn;               ///< per lens: last frame's placement
    // TerrainSceneOcclusion.cpp: occlusion culling (W04 §5, docs/terrain.md §10).
    void planOcclusion(const math::Camera& camera, float verticalScale);
    /** @brief The tile at position k of the draw order is hidden (runs the rounds due first). */
    bool occluded(std::size_t k);
    void runOcclusionRound(std::size_t first, std::size_t last);
    /** @brief World box (z as drawn) of what tile t draws; false: draw it untested. */
    bool occlusionBox(const terrain::DrawTile& t, math::Aabb& box, double& postSpacing) const;
    bool mOcclusionOn = false;
    TextureChoice mTextureChoice;  ///< imagery upload format (TextureChoice.h)
    std::unique_ptr<render::OcclusionQueries> mOcclusionQueries;
    std::vector<std::size_t> mOcclusionRounds;  ///< draw-order positions where batches start
    std::size_t mNextOcclusionRound = 0;
    std::vector<std::uint8_t> mOcclusionHidden;  ///< per draw-order position
    std::vector<std::int32_t> mOcclusionSlots;   ///< per batch position: query slot or -1
    const math::Camera* mOcclusionCamera = nullptr;
    double mOcclusionVScale = 1.0;
};

}  // namespace kiosk::scene
