// TerrainScene's projective mappings (issue 8): data layers and LUTs built once at create,
// then per frame the keyed parameters at the clock time, culling and the uniform-block upload.
#include "runtime/color/TransferFunction.h"
#include "runtime/core/Log.h"
#include "runtime/mapping/MappingCuller.h"
#include "runtime/mapping/RouteMappings.h"
#include "runtime/scene/MappingSources.h"
#include "runtime/scene/TerrainScene.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace kiosk::scene {
namespace {

constexpr const char* kTag = "scene::mappings";
constexpr int kLayerSize = render::MappingSet::kSceneLayerSize;

glm::u8vec4 toDn(const color::Rgba& c) {
    auto q = [](float v) { return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
    return {q(c.r), q(c.g), q(c.b), q(c.a)};
}

}  // namespace

Diagnostics TerrainScene::setupMappings(const gl::Caps& caps) {
    const auto& list = mScenario->projectiveMappings;
    if (list.empty()) return {};
    render::CompositeProgramDesc probe = mDesc;
    probe.mappingCapacity = 1;
    if (render::textureUnitsNeeded(probe) > mMaxTextureUnits) {
        // Degrade, do not fail: the terrain and its layers still draw.
        KIOSK_LOG_WARN(kTag, "layer stack uses every texture unit (%d): projective mappings off",
                       mMaxTextureUnits);
        return {};
    }
    auto set = render::MappingSet::create(caps, kLayerSize);
    if (!set) return set.diagnostics;
    mMappingSet = std::make_unique<render::MappingSet>(std::move(*set.value));
    const double start = mScenario->clock ? mScenario->clock->start : 0.0;
    int edgeLayer = -1;
    std::map<std::filesystem::path, int> imageLayers;
    for (const auto& m : list) {
        SceneMapping sm;
        sm.config = &m;
        std::string problem;
        bool live = false;  // data = a layer of the stack (render input -1 - k)
        if (!m.layer.empty()) {
            live = true;
            problem = liveMapping(m, sm);
        } else if (m.route) {
            if (edgeLayer < 0) {
                const auto edge = mapping::edgeProfileImage(64);
                const auto disc = mapping::discImage(64);
                edgeLayer = mMappingSet->addImage(64, 64, edge.data());
                mRoutePointLayer = mMappingSet->addImage(64, 64, disc.data());
            }
            sm.layer = edgeLayer;
        } else if (!m.image.empty()) {
            // One array layer per file: symbols sharing an atlas share its layer.
            if (auto it = imageLayers.find(m.image); it != imageLayers.end()) {
                sm.layer = it->second;
            } else if (auto img = loadMappingImage(m.image)) {
                sm.layer = mMappingSet->addImage(img->width, img->height, img->rgba.data());
                imageLayers[m.image] = sm.layer;
            } else {
                problem = img.diagnostics.format();
            }
        } else {
            const color::TransferFunction* tf = nullptr;
            if (auto it = mScenario->transferFunctions.find(m.transfer);
                it != mScenario->transferFunctions.end())
                tf = &it->second.function;
            if (!tf) {
                problem = "scalar data needs a transfer function (\"transfer\")";
            } else {
                // The store it names, or the terrain's own reader.
                std::unique_ptr<io::StoreReader> other;
                io::StoreReader* reader = mReader.get();
                if (!m.data.store.empty() && m.data.store != mScenario->terrain.store) {
                    if (auto it = mScenario->stores.find(m.data.store);
                        it != mScenario->stores.end()) {
                        auto opened = io::StoreReader::open(it->second.path);
                        if (!opened) return opened.diagnostics;
                        other = std::move(*opened.value);
                        reader = other.get();
                    }
                }
                auto values = sampleStoreRaster(*reader, m.data, mapping::evaluate(m, start, start),
                                                kLayerSize);
                if (values) {
                    sm.layer = mMappingSet->addScalar(kLayerSize, kLayerSize, values->data(),
                                                      tf->domainMin, tf->domainMax);
                    sm.lut =
                        mMappingSet->addLut(color::buildLut(*tf, render::MappingSet::kLutEntries),
                                            toDn(tf->below), toDn(tf->above));
                } else {
                    problem = values.diagnostics.format();
                }
            }
        }
        if (problem.empty() && !live && (sm.layer < 0 || (m.route && mRoutePointLayer < 0)))
            problem = "more data layers than GL_MAX_ARRAY_TEXTURE_LAYERS";
        if (!problem.empty()) {
            // One bad mapping degrades itself, never the scene.
            KIOSK_LOG_WARN(kTag, "mapping \"%s\" not drawn: %s", m.id.c_str(), problem.c_str());
            mStatus.push_back({m.id, LayerState::Failed, problem, 0});
            continue;
        }
        mMappings.push_back(sm);
    }
    mMappingSet->commit();
    // The program's array only needs the pieces this scenario can produce: a smaller block is
    // cheaper to index on llvmpipe, and the UBO (sized for capacity()) still covers it.
    int pieces = 0;
    for (const SceneMapping& sm : mMappings) {
        const auto& r = sm.config->route;
        pieces += r ? int(r->points.size()) * 2 : 1;
    }
    mDesc.mappingCapacity = std::clamp(pieces, 1, mMappingSet->capacity());
    return {};
}

std::string TerrainScene::liveMapping(const config::ProjectiveMapping& m, SceneMapping& sm) {
    // The layer's value at each fragment, as the stack samples it (so at the data time, after
    // seeks, stepping atomically with the layer), through the mapping's own LUT.
    int index = -1;
    for (std::size_t i = 0; i < mLayers.size(); ++i)
        if (mLayers[i].config->id == m.layer) index = int(i);
    if (index < 0)
        return "layer \"" + m.layer + "\" is not drawn (disabled, or FAILED: see its status)";
    if (!render::shaderOf(mDesc.layers[std::size_t(index)])->usesLut())
        return "layer \"" + m.layer + "\" has no values (a data, sequence or product layer has)";
    const color::TransferFunction* tf = nullptr;
    if (const auto* def = mScenario->findTransfer(m.transfer)) tf = &def->function;
    if (!tf) return "a mapping of a layer needs a transfer function (\"transfer\")";
    sm.lut = mMappingSet->addLut(color::buildLut(*tf, render::MappingSet::kLutEntries),
                                 toDn(tf->below), toDn(tf->above));
    if (sm.lut < 0) return "more LUTs than GL_MAX_ARRAY_TEXTURE_LAYERS";
    sm.layer = -1 - int(mDesc.mappingInputs.size());
    mDesc.mappingInputs.push_back({index, tf->domainMin, tf->domainMax});
    return {};
}

void TerrainScene::bindMappings(const math::Camera& camera) {
    if (!mMappingSet) return;
    const double start = mScenario->clock ? mScenario->clock->start : 0.0;
    mapping::CullOptions options;
    options.zMin = mBounds.min.z;
    options.zMax = mBounds.max.z;
    options.sceneScale =
        0.5 * std::max(mBounds.max.x - mBounds.min.x, mBounds.max.y - mBounds.min.y);
    const math::Frustum frustum(camera.projection() * camera.view());
    const glm::dvec3 origin(mSceneOrigin.x, mSceneOrigin.y, 0.0);  // z stays absolute
    mapping::MappingCounts counts;
    mMappingGpu.clear();
    mMappingBoxes.clear();
    bool contextOn = false;
    glm::mat4 context(1.0f);

    auto submit = [&](const mapping::MappingState& st, const SceneMapping& sm, int layer) {
        const mapping::CullResult r = mapping::cull(st, camera, frustum, options);
        const double reach =
            4.0 * std::max(options.sceneScale, glm::length(st.u) + glm::length(st.v));
        counts.add(r);
        if (r != mapping::CullResult::Active) return;
        const auto t = mapping::textureTransform(st, origin);
        if (!t) return;
        render::MappingGpu g;
        g.rowS = glm::vec4(t->rowS);
        g.rowT = glm::vec4(t->rowT);
        g.textureMatrix = glm::mat3(t->textureMatrix);
        g.colorMatrix = glm::mat4(st.colorMatrix);
        g.layer = layer;
        g.lut = sm.lut;
        g.opacity = float(st.opacity);
        g.focus = sm.config->contextMatrix.has_value();
        g.srcFactor = int(sm.config->src);
        g.dstFactor = int(sm.config->dst);
        mMappingGpu.push_back(g);
        const math::Aabb box = mapping::footprint(st, options.zMin, options.zMax, reach);
        mMappingBoxes.emplace_back(box.min.x, box.min.y, box.max.x, box.max.y);
    };

    for (const SceneMapping& sm : mMappings) {
        const config::ProjectiveMapping& m = *sm.config;
        const mapping::MappingState st = mapping::evaluate(m, mTime, start);
        if (m.contextMatrix && st.enabled) {
            // The last declaring mapping wins; the context dims even when its focus is culled.
            contextOn = true;
            context = glm::mat4(mapping::toGlm(*m.contextMatrix));
        }
        if (!m.route) {
            submit(st, sm, sm.layer);
            continue;
        }
        std::vector<glm::dvec2> points;
        for (const auto& p : m.route->points) points.emplace_back(p[0], p[1]);
        for (const auto& piece :
             mapping::routeMappings(st, points, m.route->width, m.route->pointRadius))
            submit(piece.state, sm,
                   piece.kind == mapping::RoutePieceKind::Edge ? sm.layer : mRoutePointLayer);
    }
    const int cap = mMappingSet->capacity();
    counts.overCapacity = std::uint32_t(std::max(0, int(mMappingGpu.size()) - cap));
    mMappingSet->setMappings(mMappingGpu, contextOn, context);
    mFrame.mappingsActive = counts.active - counts.overCapacity;
    mFrame.mappingsCulledFrustum = counts.culledFrustum;
    mFrame.mappingsCulledSize = counts.culledSize;
    mFrame.mappingsOverCapacity = counts.overCapacity;
}

void TerrainScene::bindTileMappings(const TileId& id) {
    if (!mMappingSet || !mRenderer) return;
    // A per-tile list keeps the fragment loop short: a tile far from every mapping runs none.
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    mGrid.tileBounds(id, x0, y0, x1, y1);
    mTileMappings.clear();
    const std::size_t n =
        std::min(mMappingBoxes.size(), std::size_t(std::max(0, mDesc.mappingCapacity)));
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec4& b = mMappingBoxes[i];
        if (b.x <= x1 && b.z >= x0 && b.y <= y1 && b.w >= y0) mTileMappings.push_back(int(i));
    }
    mRenderer->setMappingList(mTileMappings.data(), int(mTileMappings.size()));
}

}  // namespace kiosk::scene
