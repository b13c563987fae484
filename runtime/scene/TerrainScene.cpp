#include "runtime/scene/TerrainScene.h"

#include "runtime/color/TransferFunction.h"
#include "runtime/core/Log.h"
#include "runtime/loader/StoreTileLoader.h"
#include "runtime/render/Textures.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace kiosk::scene {
namespace {

constexpr const char* kTag = "scene::TerrainScene";
constexpr std::uint32_t kCacheSlots = 4096;
/** Levels whose tile statistics are read up front so the error bound holds from frame one. */
constexpr int kPrefetchedStatLevels = 4;

glm::vec4 toVec4(const color::Rgba& c) { return {c.r, c.g, c.b, c.a}; }

}  // namespace

const char* layerStateName(LayerState s) noexcept {
    switch (s) {
        case LayerState::Ready: return "OK";
        case LayerState::Degraded: return "DEGRADED";
        case LayerState::Failed: return "FAILED";
    }
    return "?";
}

TerrainScene::~TerrainScene() {
    // Join the loader before GL objects and the reader go away.
    if (mLoader) mLoader->shutdown();
}

Result<std::unique_ptr<TerrainScene>> TerrainScene::create(const config::Scenario& scenario,
                                                           const gl::Caps& caps) {
    Diagnostics diags;
    const std::string scenarioFile =
        scenario.sourceFiles.empty() ? std::string() : scenario.sourceFiles.front().string();
    auto storeIt = scenario.stores.find(scenario.terrain.store);
    if (storeIt == scenario.stores.end()) {
        diags.error("SCENE_NO_STORE", scenarioFile, scenario.terrain.pointer + "/store",
                    "terrain store \"" + scenario.terrain.store + "\" is not declared under /stores");
        return diags;
    }
    std::unique_ptr<TerrainScene> s(new TerrainScene());
    s->mScenario = &scenario;
    s->mStorePath = storeIt->second.path;
    auto reader = io::StoreReader::open(s->mStorePath);
    if (!reader) return reader.diagnostics;
    s->mReader = std::move(*reader.value);
    const io::StoreInfo& info = s->mReader->info();
    s->mGrid = info.grid;
    s->mElevation = info.findLayer(scenario.terrain.elevation);
    if (!s->mElevation || s->mElevation->kind != io::LayerKind::Elevation) {
        diags.error("SCENE_NO_ELEVATION", s->mStorePath.string(), scenario.terrain.pointer + "/elevation",
                    "store has no elevation layer \"" + scenario.terrain.elevation + "\"");
        return diags;
    }
    if (s->mGrid.levels.empty()) {
        diags.error("SCENE_EMPTY_GRID", s->mStorePath.string(), "", "store has no tile matrix");
        return diags;
    }
    const glm::dvec3 lo(s->mElevation->dataMinX, s->mElevation->dataMinY, s->mElevation->minValue);
    const glm::dvec3 hi(s->mElevation->dataMaxX, s->mElevation->dataMaxY, s->mElevation->maxValue);
    s->mBounds = {lo, hi};
    s->mSceneOrigin = glm::dvec3(s->mGrid.minX, s->mGrid.minY, 0.0);

    // Tile statistics of the upper levels (a few dozen rows) make the screen-space bound hold
    // before any tile arrives; deeper levels fill in as payloads land.
    const int statLevels = std::min(kPrefetchedStatLevels, s->mElevation->levels);
    for (int level = 0; level < statLevels; ++level) {
        const auto& m = s->mGrid.levels[std::size_t(level)];
        for (int row = 0; row < m.matrixHeight; ++row)
            for (int col = 0; col < m.matrixWidth; ++col) {
                const TileId id{level, col, row};
                if (auto st = s->mReader->tileStats(s->mElevation->name, id))
                    s->mStats.set(id, *st);
                else
                    s->mStats.markAbsent(id);
            }
    }

    if (scenario.terrain.reference == config::TerrainReference::Full)
        s->mOptions = terrain::TerrainOptions::fullResolutionReference();
    else {
        s->mOptions.tauGeom = scenario.terrain.tauGeom;
        s->mOptions.tauTex = scenario.terrain.tauTex;
    }
    io::TileStats rootStats;
    if (s->mStats.lookup({0, 0, 0}, rootStats) == terrain::TileState::Known)
        s->mOptions.neighbourErrorBound =
            rootStats.geometricError + s->mOptions.tinTolerance(rootStats.geometricError);

    // The layer stack: key layer 0 is the elevation mesh; every textured layer gets its own.
    std::vector<loader::LayerBinding> bindings{{s->mElevation->name, io::LayerKind::Elevation}};
    terrain::SelectorSetup setup;
    setup.grid = s->mGrid;
    setup.geometryLayer = 0;
    setup.geometryMaxLevel = s->mElevation->levels - 1;
    render::CompositeProgramDesc desc;
    s->mLayerStores.push_back({scenario.terrain.store, s->mStorePath, s->mReader.get(), nullptr});
    s->buildLayerStack(bindings, setup, desc);

    // The scene's elevation LUT is a flat grey and Session draws with elevationLutWeight 0
    // (hypsometric tint comes from data layers): skip that fetch per pixel.
    desc.elevationTint = false;
    desc.detailHole = scenario.terrain.proceduralDetail;  // the detail grid draws inside a hole
    s->mDesc = desc;
    s->mMaxTextureUnits = caps.maxTextureUnits;
    if (Diagnostics d = s->setupMappings(caps); d.hasErrors()) return d;
    for (SceneLut& lut : s->mLuts) {
        std::vector<std::uint8_t> rgba;
        if (lut.function) {
            rgba = color::buildLut(*lut.function, color::kMinLutSize);
        } else {
            rgba = {40, 40, 40, 255, 230, 230, 230, 255};
        }
        lut.size = int(rgba.size() / 4);
        lut.texture = render::makeLutTexture(lut.size, rgba.data());
        const render::LutBinding b = s->lutBinding(std::size_t(&lut - s->mLuts.data()));
        lut.edged = render::makeEdgedLutTexture(lut.size, rgba.data(), b.below, b.above, b.nodata);
    }
    if (Diagnostics d = s->buildRenderer(); d.hasErrors()) return d;

    // 0 (unset): sized to the view's working set from the first frame on (sizeBudgetsToView).
    s->mAutoCpu = scenario.terrain.cacheBytes <= 0;
    s->mAutoGpu = scenario.terrain.gpuBytes <= 0;
    terrain::CacheBudget budget{
        s->mAutoCpu ? CacheDefaults::kFloorCpuBytes
                    : std::size_t(std::max<std::int64_t>(scenario.terrain.cacheBytes, 1 << 20)),
        s->mAutoGpu ? CacheDefaults::kFloorGpuBytes
                    : std::size_t(std::max<std::int64_t>(scenario.terrain.gpuBytes, 1 << 20))};
    s->mCache = std::make_unique<terrain::TerrainTileCache>(budget, kCacheSlots);
    s->mResidency = std::make_unique<terrain::CacheResidency>(*s->mCache, true);
    s->mGpu.resize(kCacheSlots);
    // Imagery imported finer than the elevation grid (ImageryResolution.h) has levels below the
    // grid's finest: the selector's grid continues the pyramid so tauTex can reach them.
    int finestTexture = setup.grid.maxLevel();
    for (const auto& t : setup.textures) {
        s->mOptions.textureLevelsBeyondGeometry =
            std::max(s->mOptions.textureLevelsBeyondGeometry, t.maxLevel - setup.geometryMaxLevel);
        finestTexture = std::max(finestTexture, t.maxLevel);
    }
    if (finestTexture > setup.grid.maxLevel() && !setup.grid.levels.empty()) {
        const io::TileMatrix& f = setup.grid.levels.back();
        const int extra = finestTexture - setup.grid.maxLevel();
        setup.grid.setPyramid(finestTexture + 1, f.tileWidth, f.tileHeight,
                              f.pixelXSize / double(1 << extra));
        // Clip margins of texture-only nodes are a quarter of *their* level's pixel.
        s->mGrid = setup.grid;
    }
    setup.options = s->mOptions;
    setup.heightMin = s->mElevation->minValue;
    setup.heightMax = s->mElevation->maxValue;
    if (Diagnostics d = s->mSelector.configure(setup); d.hasErrors()) return d;
    // The prefetch selector looks at a future camera; it neither pins tiles nor needs GPU copies.
    s->mPrefetchSelector.configure(setup);
    s->mPrefetchResidency = std::make_unique<terrain::CacheResidency>(*s->mCache, false, false);
    // One loader for every store the layers read: the same queue, cache and budgets.
    std::vector<loader::StoreOpener> openers;
    for (const auto& st : s->mLayerStores)
        openers.push_back([path = st.path] { return io::StoreReader::open(path); });
    auto fn = std::make_unique<loader::StoreTileLoader>(std::move(openers), bindings, s->mOptions);
    // Running states of derived products (loader thread): at least a quarter of the CPU tile
    // budget, and always those of the tiles in view (sizeDerivedStatesToView).
    fn->setDerivedBudget(budget.cpuBytes / 4);
    s->mStoreLoader = fn.get();
    // Imagery as stored GPU blocks where the context has the format (docs/terrain.md §11).
    s->mTextureChoice = chooseTextureFormat(scenario.terrain.textureCompression, caps);
    fn->setTextureFormat(s->mTextureChoice.format);
    // Said at info level only when it changes something or a forced choice could not be
    // honoured: the uncompressed default is the quiet case (a valid store gives no message).
    const bool compressed = s->mTextureChoice.format != io::TextureFormat::None;
    const bool forcedButNot =
        !compressed && scenario.terrain.textureCompression == config::TextureCompression::Astc;
    log::write(compressed || forcedButNot ? log::Level::Info : log::Level::Debug, kTag,
               "imagery textures: %s (%s)", io::textureFormatName(s->mTextureChoice.format),
               s->mTextureChoice.reason.c_str());
    // Test hook (atomic-step tests): a slow disk, in milliseconds per tile.
    if (const char* delay = std::getenv("GEOKIOSK_TEST_LOAD_DELAY_MS"))
        fn->setArtificialDelay(std::atof(delay) / 1000.0, s->testDelayedStore());
    s->mLoader = std::make_unique<loader::TileLoader>(loader::LoaderOptions{}, std::move(fn));
    s->setOcclusionCulling(scenario.terrain.occlusionCulling);
    return s;
}

Diagnostics TerrainScene::buildRenderer() {
    auto renderer = render::TerrainRenderer::create(mDesc, mMaxTextureUnits);
    if (!renderer) return renderer.diagnostics;
    mRenderer = std::make_unique<render::TerrainRenderer>(std::move(*renderer.value));
    mRenderer->setMappings(mMappingSet.get());
    for (std::size_t k = 0; k < mLuts.size(); ++k) mRenderer->setLut(int(k), lutBinding(k));
    // Without a hypsometric layer the terrain base is a neutral grey.
    const std::uint8_t base[8] = {200, 200, 195, 255, 200, 200, 195, 255};
    mRenderer->setElevationLut(2, base, 0.0f, 1.0f);
    return buildDetailRenderer();
}

render::LutBinding TerrainScene::lutBinding(std::size_t k) const {
    const SceneLut& lut = mLuts[k];
    render::LutBinding b;
    if (lut.function) {
        b.domainMin = float(lut.function->domainMin);
        b.domainMax = float(lut.function->domainMax);
        b.nodata = toVec4(lut.function->nodata);
        b.below = toVec4(lut.function->below);
        b.above = toVec4(lut.function->above);
    }
    b.texture = lut.edged.id();
    b.size = lut.size;
    return b;
}

bool TerrainScene::setPositionOutput(bool on) {
    mDesc.outputPosition = on;
    return !buildRenderer().hasErrors();
}

bool TerrainScene::sequenceFrameComplete(const StackLayer& layer, bool useA) const {
    return specComplete(useA ? layer.specA : layer.specB);
}

void TerrainScene::update(const math::Camera& camera, double time) {
    ++mFrameNumber;
    mTime = time;
    mFrame = {};
    mCache->beginFrame(mFrameNumber);
    mBudget.beginFrame();
    releaseEvicted();
    drainCompletions();
    mFrame.uploadMs = mBudget.msUsed();

    bool reselect = false;
    std::vector<anim::FrameBracket>& wanted = mWanted;  // reused: no allocation per frame
    wanted.assign(mLayers.size(), anim::FrameBracket{});
    for (std::size_t i = 0; i < mLayers.size(); ++i) {
        StackLayer& l = mLayers[i];
        if (!l.sequence || l.specA < 0) continue;
        wanted[i] = anim::bracketFrames(l.sequence->frameTimes, time, l.interpolation);
        mSelector.setTextureFrame(std::size_t(l.specA), std::int32_t(wanted[i].i0));
        if (l.specB >= 0) mSelector.setTextureFrame(std::size_t(l.specB), std::int32_t(wanted[i].i1));
        if (l.specT >= 0)
            mSelector.setTextureFrame(std::size_t(l.specT), std::int32_t(wanted[i].i0));
    }
    mSelection = &mSelector.select(camera, mStats, *mResidency);
    mFrame.requests = std::uint32_t(mSelection->requests.size());
    // Submitted at the end of update() together with the sequences' frames ahead.
    for (const auto& r : mSelection->requests) mLoader->request(r.key, r.priority);
    if (!mSelection->requests.empty() && log::threshold() == log::Level::Debug) {
        const auto& k = mSelection->requests.front().key;
        KIOSK_LOG_DEBUG(kTag, "%zu requests, first layer %u frame %d tile %d/%d/%d", mSelection->requests.size(),
                        unsigned(k.layer), k.frame, k.id.level, k.id.column, k.id.row);
    }
    const bool requestsPending = !mSelection->requests.empty();
    // Display walls: the pair shown is the one at the wall's step time (TerrainSceneWall.cpp).
    applyStepGate(camera, time, wanted);
    syncGroupsComplete(wanted);  // comparison sides and difference operands step together

    for (std::size_t i = 0; i < mLayers.size(); ++i) {
        StackLayer& l = mLayers[i];
        if (!l.sequence || l.specA < 0) continue;
        const anim::FrameBracket& w = wanted[i];
        const bool completeA = sequenceFrameComplete(l, true);
        const bool completeB = l.specB < 0 || w.i1 == w.i0 ? completeA : sequenceFrameComplete(l, false);
        const bool completeT = l.specT < 0 || specComplete(l.specT);  // arrival thresholds
        for (const auto& t : mSelection->tiles) {
            for (int spec : {l.specA, l.specB, l.specT}) {
                if (spec < 0 || int(t.textureCount) <= spec) continue;
                const auto& a = mSelection->textures[t.firstTexture + std::uint32_t(spec)];
                mFrame.sequenceTilesMissing += (!a.handle.valid() || a.fromAncestor) ? 1u : 0u;
            }
        }
        // Atomic steps: a new frame pair becomes visible only when every tile of the view has
        // both its frames; until then the last complete pair stays (never a mix of times).
        l.shown = l.pair.update(w, l.sequence->frameTimes, time, [&](std::size_t frame) {
            return (frame == w.i0 ? completeA : completeB) && completeT &&
                   (l.syncGroup < 0 || mGroupComplete[std::size_t(l.syncGroup)]);
        });
        if (l.shown.hasPair && (l.shown.i0 != w.i0 || l.shown.i1 != w.i1)) {
            mSelector.setTextureFrame(std::size_t(l.specA), std::int32_t(l.shown.i0));
            if (l.specB >= 0) mSelector.setTextureFrame(std::size_t(l.specB), std::int32_t(l.shown.i1));
            if (l.specT >= 0)
                mSelector.setTextureFrame(std::size_t(l.specT), std::int32_t(l.shown.i0));
            reselect = true;
        }
        if (!l.shown.hasPair) {
            l.shown.i0 = w.i0;
            l.shown.i1 = w.i1;
            l.shown.alpha = w.alpha;
        }
        mFrame.holdingSequence = mFrame.holdingSequence || l.shown.holding;
        // The picture never lies about time: the label shows the held pair's time, not the clock's.
        if (l.shown.holding && l.shown.hasPair && std::isnan(mFrame.heldDataTime)) {
            const auto& ft = l.sequence->frameTimes;
            mFrame.heldDataTime = ft[l.shown.i0] + l.shown.alpha * (ft[l.shown.i1] - ft[l.shown.i0]);
        }
        countPrefetchHits(l, i == mFirstSequenceLayer);
    }
    if (reselect) mSelection = &mSelector.select(camera, mStats, *mResidency);

    mFrame.tilesFromAncestor = mSelection->counters.tilesFromAncestor;
    mFrame.residentBytes = mCache->cpuBytes() + mCache->gpuBytes();
    mSettled = !requestsPending && mLoader->inFlight() == 0 && !mFrame.holdingSequence &&
               mSelection->counters.tilesFromAncestor == 0;
    sizeBudgetsToView();  // before the prefetch below touches frames ahead
    sizeDerivedStatesToView();
    planSequencePrefetch();
    for (const auto& r : mSequencePrefetch) mLoader->request(r.key, r.priority);
    mLoader->submit();
    sendPrefetch();
}

void TerrainScene::prefetch(const math::Camera& futureCamera) {
    // Same frames as the view being drawn, so the tiles a camera path will need arrive first.
    for (const auto& l : mLayers) {
        if (!l.sequence || l.specA < 0) continue;
        mPrefetchSelector.setTextureFrame(std::size_t(l.specA), std::int32_t(l.shown.i0));
        if (l.specB >= 0) mPrefetchSelector.setTextureFrame(std::size_t(l.specB), std::int32_t(l.shown.i1));
    }
    const auto& sel = mPrefetchSelector.select(futureCamera, mStats, *mPrefetchResidency);
    mPrefetch.assign(sel.requests.begin(), sel.requests.end());
    // Sequence frames ahead of the playhead are planned in update() (planSequencePrefetch) for
    // the view now; here the same frames for the view the camera path is heading to.
    addPathFramePrefetch(sel);
    sendPrefetch();
}

void TerrainScene::setTau(double tauGeom, double tauTex) {
    if (mOptions.fullResolution || (mOptions.tauGeom == tauGeom && mOptions.tauTex == tauTex))
        return;
    mOptions.tauGeom = tauGeom;
    mOptions.tauTex = tauTex;
    mSelector.setOptions(mOptions);
    mPrefetchSelector.setOptions(mOptions);
}

math::Viewpoint TerrainScene::overviewViewpoint() const {
    const glm::dvec3 c = mBounds.center();
    const double size = std::max(mBounds.max.x - mBounds.min.x, mBounds.max.y - mBounds.min.y);
    math::Viewpoint vp;
    vp.target = glm::dvec3(c.x, c.y, mBounds.min.z + (mBounds.max.z - mBounds.min.z) * 0.3);
    vp.headingDeg = 20.0;
    vp.pitchDeg = -40.0;
    vp.range = size * 1.1;
    return vp;
}

std::vector<double> TerrainScene::sequenceKeyTimes() const {
    std::vector<double> times;
    for (const auto& l : mLayers)
        if (l.sequence) times.insert(times.end(), l.sequence->frameTimes.begin(), l.sequence->frameTimes.end());
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    return times;
}

const SceneLut* TerrainScene::lut(const std::string& transferName) const {
    for (const auto& l : mLuts)
        if (l.name == transferName && l.function) return &l;
    return nullptr;
}

}  // namespace kiosk::scene
