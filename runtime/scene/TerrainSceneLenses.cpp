// Lenses of a scene: their placement per frame (keys, or where a user put them: keys in `play`,
// POST /control/lens) and the comparison lens's atomic steps: the sequences on its two sides
// (and a difference's operands) show a new step only when all of them have it for the view.
#include "runtime/anim/KeyedTrack.h"
#include "runtime/scene/TerrainScene.h"

#include <algorithm>
#include <cstdlib>
#include <numeric>

namespace kiosk::scene {

int TerrainScene::primaryLens() const {
    const auto& lenses = mScenario->lenses;
    for (std::size_t j = 0; j < lenses.size(); ++j)
        if (lenses[j].kind == config::LensKind::Comparison) return int(j);
    return lenses.empty() ? -1 : 0;
}

int TerrainScene::lensIndex(const std::string& id) const {
    for (std::size_t j = 0; j < mScenario->lenses.size(); ++j)
        if (mScenario->lenses[j].id == id) return int(j);
    return -1;
}

std::optional<LensPlacement> TerrainScene::lensPlacement(int index) const {
    if (index < 0 || std::size_t(index) >= mScenario->lenses.size()) return std::nullopt;
    if (mLensPut.size() > std::size_t(index) && mLensPut[std::size_t(index)])
        return mLensPut[std::size_t(index)];
    if (mLensDrawn.size() > std::size_t(index)) return mLensDrawn[std::size_t(index)];
    const config::Lens& l = mScenario->lenses[std::size_t(index)];  // before the first frame
    return LensPlacement{glm::dvec2(l.center[0], l.center[1]), glm::dvec2(l.radii[0], l.radii[1]),
                         l.rotation, l.enabled};
}

bool TerrainScene::placeLens(int index, const LensPlacement& p) {
    if (index < 0 || std::size_t(index) >= mScenario->lenses.size()) return false;
    mLensPut.resize(mScenario->lenses.size());
    LensPlacement q = p;
    q.radii = glm::max(q.radii, glm::dvec2(1e-3));
    mLensPut[std::size_t(index)] = q;
    return true;
}

void TerrainScene::bindLenses() {
    const double start = mScenario->clock ? mScenario->clock->start : 0.0;
    mLensDrawn.resize(mScenario->lenses.size());
    for (std::size_t j = 0; j < mScenario->lenses.size(); ++j) {
        const config::Lens& lens = mScenario->lenses[j];
        // Keyed positions: hold before the first key, piecewise linear between keys.
        struct Place {
            glm::dvec2 centre, radii;
            double rotation;
        };
        Place place = anim::keyedTrack(
            Place{glm::dvec2(lens.center[0], lens.center[1]),
                  glm::dvec2(lens.radii[0], lens.radii[1]), lens.rotation},
            lens.keys, mTime, [start](const config::LensKey& k) { return k.time.resolve(start); },
            [](Place& p, const config::LensKey& k) {
                if (k.center) p.centre = glm::dvec2((*k.center)[0], (*k.center)[1]);
                if (k.radii) p.radii = glm::dvec2((*k.radii)[0], (*k.radii)[1]);
                if (k.rotation) p.rotation = *k.rotation;
            },
            [](const Place& a, const Place& b, double t) {
                return Place{glm::mix(a.centre, b.centre, t), glm::mix(a.radii, b.radii, t),
                             a.rotation + (b.rotation - a.rotation) * t};
            });
        bool enabled = lens.enabled;
        if (j < mLensPut.size() && mLensPut[j]) {  // put there at run time: keys no longer move it
            place = {mLensPut[j]->centre, mLensPut[j]->radii, mLensPut[j]->rotationDeg};
            enabled = mLensPut[j]->enabled;
        }
        mLensDrawn[j] = {place.centre, place.radii, place.rotation, enabled};
        render::LensBinding b;
        b.centre = place.centre;
        b.radii = glm::max(place.radii, glm::dvec2(1e-3));
        b.rotationDeg = place.rotation;
        // Round lenses blend over a fraction of the radius; a swipe line over metres.
        b.softEdge =
            lens.shape == config::LensShape::Swipe
                ? float(lens.softEdge)
                : float(std::clamp(lens.softEdge / std::max(b.radii.x, b.radii.y), 0.0, 1.0));
        b.insideGain = float(1.0 + lens.raise);
        b.outsideGain = float(1.0 - lens.lower);
        b.enabled = enabled;
        mRenderer->setLens(int(j), b);
        if (mDetail) setDetailLens(int(j), b);
    }
}

void TerrainScene::buildSyncGroups(const render::CompositeProgramDesc& desc) {
    // Union-find over the stack: a comparison lens joins every layer on its two sides, a
    // difference joins itself and its operands (so a lens showing a difference joins them too).
    std::vector<int> parent(mLayers.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto root = [&](int i) {
        while (parent[std::size_t(i)] != i) i = parent[std::size_t(i)];
        return i;
    };
    auto join = [&](int a, int b) {
        if (a >= 0 && b >= 0) parent[std::size_t(root(a))] = root(b);
    };
    for (std::size_t i = 0; i < desc.layers.size(); ++i)
        for (int o : desc.layers[i].operands) join(int(i), o);
    for (const auto& lens : desc.lenses) {
        if (lens.kind != render::LensKind::Comparison) continue;
        int first = -1;
        for (const auto* side : {&lens.insideLayers, &lens.outsideLayers})
            for (int i : *side) {
                if (first < 0) first = i;
                join(i, first);
            }
    }
    // A group is the sequences of one root; a sequence alone keeps its own steps (-1).
    std::vector<int> count(mLayers.size(), 0), group(mLayers.size(), -1);
    auto isSequence = [&](std::size_t i) { return mLayers[i].sequence && mLayers[i].specA >= 0; };
    for (std::size_t i = 0; i < mLayers.size(); ++i)
        if (isSequence(i)) ++count[std::size_t(root(int(i)))];
    int groups = 0;
    for (std::size_t i = 0; i < mLayers.size(); ++i) {
        const auto r = std::size_t(root(int(i)));
        if (!isSequence(i) || count[r] < 2) continue;
        if (group[r] < 0) group[r] = groups++;
        mLayers[i].syncGroup = group[r];
    }
    mGroupComplete.assign(std::size_t(groups), 1);
    mGroupTileValid.assign(std::size_t(groups), 1);
}

void TerrainScene::groupTileValidity(const terrain::DrawTile& t) {
    std::fill(mGroupTileValid.begin(), mGroupTileValid.end(), std::uint8_t(1));
    for (const StackLayer& l : mLayers) {
        if (l.syncGroup < 0) continue;
        for (int spec : {l.specA, l.specB}) {
            if (spec < 0) continue;
            if (int(t.textureCount) <= spec ||
                !mSelection->textures[t.firstTexture + std::uint32_t(spec)].handle.valid())
                mGroupTileValid[std::size_t(l.syncGroup)] = 0;
        }
    }
}

void TerrainScene::syncGroupsComplete(const std::vector<anim::FrameBracket>& wanted) {
    // No tile selected yet (no geometry resident) is not "complete": a first pair committed on
    // an empty view would let each member draw whatever arrives first.
    const std::uint8_t any = mSelection && !mSelection->tiles.empty() ? 1 : 0;
    std::fill(mGroupComplete.begin(), mGroupComplete.end(), any);
    for (std::size_t i = 0; i < mLayers.size(); ++i) {
        const StackLayer& l = mLayers[i];
        if (l.syncGroup < 0) continue;
        const anim::FrameBracket& w = wanted[i];
        // Every tile of the view has both frames of this member's wanted pair (and thresholds).
        const bool complete = w.valid && sequenceFrameComplete(l, true) &&
                              (l.specB < 0 || w.i1 == w.i0 || sequenceFrameComplete(l, false)) &&
                              (l.specT < 0 || specComplete(l.specT));
        if (!complete) mGroupComplete[std::size_t(l.syncGroup)] = 0;
    }
}

int TerrainScene::testDelayedStore() const {
    // With GEOKIOSK_TEST_LOAD_DELAY_MS: only this store's tiles are slow (-1: every store).
    const char* id = std::getenv("GEOKIOSK_TEST_LOAD_DELAY_STORE");
    if (!id) return -1;
    for (std::size_t i = 0; i < mLayerStores.size(); ++i)
        if (mLayerStores[i].id == id) return int(i);
    return -1;
}

}  // namespace kiosk::scene
