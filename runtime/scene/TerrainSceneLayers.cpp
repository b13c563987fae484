// The layer stack of a scene: every enabled layer of the scenario planned by its kind
// (layers/Registry.h) and served from the store it names. The scene knows no kind: it turns a
// kind's SourcePlan into store bindings and texture specs and runs the frame-pair service for
// sequences (TerrainScene.cpp update()).
#include "config/StoreGrids.h"
#include "layers/Registry.h"
#include "layers/products/ProductSource.h"
#include "runtime/core/Log.h"
#include "runtime/loader/StoreTileLoader.h"
#include "runtime/scene/TerrainScene.h"

#include <algorithm>
#include <cstdlib>

namespace kiosk::scene {
namespace {

constexpr const char* kTag = "scene::TerrainScene";

render::LayerOp compositeOp(config::OperationType t) {
    switch (t) {
        case config::OperationType::Opacity:
        case config::OperationType::Replace:
            return render::LayerOp::Over;
        case config::OperationType::Blend:
            return render::LayerOp::Blend;
        case config::OperationType::Add:
            return render::LayerOp::Add;
        case config::OperationType::Modulate:
            return render::LayerOp::Modulate;
        case config::OperationType::Mask:
            return render::LayerOp::Mask;
    }
    return render::LayerOp::Over;
}

}  // namespace

int TerrainScene::layerStore(const std::string& id, std::string& problem) {
    for (std::size_t i = 0; i < mLayerStores.size(); ++i)
        if (mLayerStores[i].id == id) {
            if (mLayerStores[i].reader) return int(i);
            problem = "store \"" + id + "\" cannot serve layers (reported with its first layer)";
            return -1;
        }
    auto it = mScenario->stores.find(id);
    if (it == mScenario->stores.end()) {
        problem = "store \"" + id + "\" is not declared under /stores";
        return -1;
    }
    // Opened once on the render thread for its metadata; the loader opens its own reader.
    LayerStore st{id, it->second.path, nullptr, nullptr};
    auto reader = io::StoreReader::open(st.path);
    if (!reader) {
        problem = reader.diagnostics.format();
    } else {
        const io::TileGrid& grid = (*reader.value)->info().grid;
        // Tiles of every layer are requested by the terrain's tile ids (validate says the same).
        if (!config::sameCrs(mGrid, grid))
            problem = "store \"" + id + "\" is in " + config::crsText(grid) + ", the terrain in " +
                      config::crsText(mGrid) + "; a layer's store must share the terrain's CRS";
        else if (std::string why = config::tileGridDifference(mReader->info().grid, grid);
                 !why.empty())
            problem = "store \"" + id + "\" does not share the terrain's tile grid (" + why + ")";
        else
            st.owned = std::move(*reader.value);
    }
    st.reader = st.owned.get();
    mLayerStores.push_back(std::move(st));
    return problem.empty() ? int(mLayerStores.size()) - 1 : -1;
}

void TerrainScene::buildLayerStack(std::vector<loader::LayerBinding>& bindings,
                                   terrain::SelectorSetup& setup,
                                   render::CompositeProgramDesc& desc) {
    mLayers.reserve(mScenario->layers.size());
    mStatus.push_back({"terrain", LayerState::Ready, {}, 0});
    mKeyLayerStatus.push_back(0);
    // A sequence layer drawn with a product of the same frames reads the product's texel (it
    // holds the frame pair, docs/products.md): (stack index, product id).
    std::vector<std::pair<int, std::string>> framesFromProduct;
    // Benchmark hook (bench-products measures both in one run): 0 turns the sharing off.
    const char* sharing = std::getenv("GEOKIOSK_PRODUCT_FRAME_SHARING");
    const bool share = !sharing || std::string(sharing) != "0";
    // Not a difference's operand nor a comparison side: those keep their own frames and steps.
    const auto stepsWithOthers = [&](const std::string& id) {
        const auto named = [&](const std::vector<std::string>& ids) {
            return std::find(ids.begin(), ids.end(), id) != ids.end();
        };
        for (const auto& l : mScenario->layers)
            if (named(l.operands)) return true;
        for (const auto& lens : mScenario->lenses)
            if (named(lens.insideStack) || named(lens.outsideStack)) return true;
        return false;
    };
    for (const auto& cl : mScenario->layers) {
        if (!cl.enabled) continue;
        LayerStatus status{cl.id, LayerState::Ready, {}, 0};
        StackLayer sl;
        sl.config = &cl;
        sl.strength =
            float(cl.operation.opacity *
                  (cl.operation.type == config::OperationType::Add ? cl.operation.weight : 1.0));
        sl.nodataAs = cl.nodataAs ? std::optional<float>(float(*cl.nodataAs)) : std::nullopt;
        render::CompositeLayer comp;
        comp.op = compositeOp(cl.operation.type);
        // The kind plans its sources (layers/) in the store the layer names; the scene serves
        // them whatever the kind.
        const std::string kindName =
            cl.kindName.empty() ? config::layerKindName(cl.kind) : cl.kindName;
        const layers::Kind* kind = layers::registry().find(kindName);
        layers::SourcePlan plan;
        std::string problem;
        const int store = layerStore(
            cl.source.store.empty() ? mScenario->terrain.store : cl.source.store, problem);
        const std::filesystem::path storePath =
            store >= 0 ? mLayerStores[std::size_t(store)].path : mStorePath;
        if (store >= 0 && !kind) {
            problem = "no layer kind \"" + kindName + "\" is registered";
        } else if (store >= 0) {
            const io::StoreInfo& info = mLayerStores[std::size_t(store)].reader->info();
            layers::StoreView view{info, mElevation->name};
            if (mScenario->clock) view.timeOrigin = mScenario->clock->start;
            problem = kind->plan(cl, view, plan);
        }
        if (problem.empty() && plan.source == layers::SourceKind::Imagery) {
            sl.keyLayer = int(bindings.size());
            bindings.push_back({plan.table, io::LayerKind::Imagery, false, std::nullopt, store});
            sl.specA = int(setup.textures.size());
            setup.textures.push_back({std::uint16_t(sl.keyLayer), 0, plan.maxLevel});
        } else if (problem.empty() && plan.source == layers::SourceKind::Sequence) {
            sl.sequence = plan.sequence;
            sl.keyLayer = int(bindings.size());
            bindings.push_back(
                {plan.table, io::LayerKind::Sequence, false, std::nullopt, store, plan.frames});
            sl.interpolation = plan.interpolation;
            sl.specA = int(setup.textures.size());
            setup.textures.push_back({std::uint16_t(sl.keyLayer), 0, plan.maxLevel});
            if (plan.framePair) {
                sl.specB = int(setup.textures.size());
                setup.textures.push_back({std::uint16_t(sl.keyLayer), 0, plan.maxLevel});
            }
            sl.productClock = plan.productClock;
            sl.timeOrigin = plan.timeOrigin;
            sl.timeUnit = plan.timeUnit;
            if (plan.thresholds) {
                // Per-pixel thresholds of each frame pair, computed by the loader thread.
                sl.keyLayerT = int(bindings.size());
                bindings.push_back({plan.table, io::LayerKind::Sequence, true, sl.nodataAs, store});
                sl.specT = int(setup.textures.size());
                setup.textures.push_back({std::uint16_t(sl.keyLayerT), 0, plan.maxLevel});
            }
        }
        // MeshElevation and None load nothing: the layer samples the mesh (or nothing).
        if (!problem.empty()) {
            status.state = LayerState::Failed;
            status.message = storePath.string() + ": " + cl.pointer + ": " + problem;
            KIOSK_LOG_WARN(kTag, "layer \"%s\" FAILED: %s", cl.id.c_str(), status.message.c_str());
            mStatus.push_back(status);
            continue;
        }
        comp.shader = kind->shader(plan);
        if (plan.source == layers::SourceKind::Sequence &&
            plan.interpolation == anim::Interpolation::Data && share && !stepsWithOthers(cl.id)) {
            for (const auto& other : mScenario->layers) {
                if (&other == &cl || !layers::products::ProductSource::carriesFramesOf(
                                         other, cl, mScenario->terrain.store))
                    continue;
                // Loads and samples nothing of its own: no binding, no texture spec.
                bindings.pop_back();
                setup.textures.resize(std::size_t(sl.specA));
                StackLayer plain;
                plain.config = sl.config;
                plain.strength = sl.strength;
                plain.nodataAs = sl.nodataAs;
                sl = std::move(plain);
                comp.shader = layers::products::ProductSource::sequenceFromProduct();
                framesFromProduct.emplace_back(int(mLayers.size()), other.id);
                break;
            }
        }
        sl.legendTitle = kind->legendTitle(cl, plan);
        if (comp.shader->usesLut()) {
            const auto* tf = mScenario->findTransfer(plan.transfer);
            SceneLut lut;
            lut.name = plan.transfer;
            lut.function = tf ? &tf->function : nullptr;
            if (!tf) {
                status.state = LayerState::Degraded;
                status.message = cl.pointer + "/transfer: unknown transfer function \"" +
                                 plan.transfer + "\"; drawn in grey";
            }
            mLuts.push_back(std::move(lut));
            ++desc.lutCount;
        }
        if (sl.keyLayer >= 0) {
            mKeyLayerStatus.resize(std::size_t(sl.keyLayer) + 1, -1);
            mKeyLayerStatus[std::size_t(sl.keyLayer)] = int(mStatus.size());
        }
        if (sl.keyLayerT >= 0) {
            mKeyLayerStatus.resize(std::size_t(sl.keyLayerT) + 1, -1);
            mKeyLayerStatus[std::size_t(sl.keyLayerT)] = int(mStatus.size());
        }
        mStatus.push_back(status);
        desc.layers.push_back(comp);
        mLayers.push_back(std::move(sl));
    }
    for (std::size_t i = 0; i < mLayers.size(); ++i)
        if (mLayers[i].sequence && mLayers[i].specB >= 0 && mFirstSequenceLayer == SIZE_MAX)
            mFirstSequenceLayer = i;
    // A stack of products only (their frame pair is inside one derived tile): the first of them.
    for (std::size_t i = 0; i < mLayers.size(); ++i)
        if (mLayers[i].sequence && mLayers[i].productClock && mFirstSequenceLayer == SIZE_MAX)
            mFirstSequenceLayer = i;
    // Blend references and lenses name layers by id; resolve to stack indices.
    auto stackIndex = [&](const std::string& id) {
        for (std::size_t i = 0; i < mLayers.size(); ++i)
            if (mLayers[i].config->id == id) return int(i);
        return -1;
    };
    for (std::size_t i = 0; i < mLayers.size(); ++i) {
        if (desc.layers[i].op != render::LayerOp::Blend) continue;
        desc.layers[i].visibilityLayer = stackIndex(mLayers[i].config->operation.visibility);
        if (desc.layers[i].visibilityLayer < 0) desc.layers[i].op = render::LayerOp::Over;
    }
    for (std::size_t i = 0; i < mLayers.size(); ++i)  // a difference's A and B
        for (const auto& id : mLayers[i].config->operands) {
            desc.layers[i].operands.push_back(stackIndex(id));
            if (desc.layers[i].operands.back() >= 0) continue;
            // Drawn transparent (the compositor's rule for an absent operand), said once here.
            for (auto& st : mStatus)
                if (st.id == mLayers[i].config->id && st.state != LayerState::Failed) {
                    st.state = LayerState::Failed;
                    st.message = mLayers[i].config->pointer + "/of: layer \"" + id +
                                 "\" is not drawn (disabled or FAILED): nothing to subtract";
                    KIOSK_LOG_WARN(kTag, "layer \"%s\" FAILED: %s", st.id.c_str(),
                                   st.message.c_str());
                }
        }
    for (const auto& lens : mScenario->lenses) {
        render::CompositeLens cl{lens.kind == config::LensKind::Highlight
                                     ? render::LensKind::Highlight
                                     : render::LensKind::Visibility,
                                 stackIndex(lens.inside), stackIndex(lens.outside)};
        if (lens.kind == config::LensKind::Comparison) {
            cl.kind = render::LensKind::Comparison;
            for (const auto& id : lens.insideStack) cl.insideLayers.push_back(stackIndex(id));
            for (const auto& id : lens.outsideStack) cl.outsideLayers.push_back(stackIndex(id));
        }
        if (lens.shape == config::LensShape::Swipe) cl.shape = render::LensShape::Swipe;
        desc.lenses.push_back(cl);
    }
    for (const auto& [i, id] : framesFromProduct)
        desc.layers[std::size_t(i)].operands = {stackIndex(id)};
    buildSyncGroups(desc);
}

std::string TerrainScene::legendTitle(const std::string& id) const {
    for (const auto& l : mLayers)
        if (l.config->id == id) return l.legendTitle;
    return {};
}

}  // namespace kiosk::scene
