// TerrainScene on a display wall: wall-wide atomic steps (docs/wall.md "Atomic steps").
#include "runtime/scene/TerrainScene.h"

namespace kiosk::scene {

void TerrainScene::applyStepGate(const math::Camera& camera, double time,
                                 std::vector<anim::FrameBracket>& wanted) {
    // What this node reports to the wall's leader: could it show the pair at its own time?
    for (const auto& l : mLayers) {
        if (!l.sequence || l.specA < 0) continue;
        mFrame.wantedSequenceResident = mFrame.wantedSequenceResident && specComplete(l.specA) &&
                                        (l.specB < 0 || specComplete(l.specB)) &&
                                        (l.specT < 0 || specComplete(l.specT));
    }
    if (!mStepGate) return;
    // The pair to show is the one at the wall's step time; the pair at `time` keeps loading (its
    // requests were sent from the first selection). The blend follows `time` within the pair.
    bool changed = false;
    for (std::size_t i = 0; i < mLayers.size(); ++i) {
        StackLayer& l = mLayers[i];
        if (!l.sequence || l.specA < 0) continue;
        anim::FrameBracket gate =
            anim::bracketFrames(l.sequence->frameTimes, *mStepGate, l.interpolation);
        gate.alpha = anim::alphaWithin(l.sequence->frameTimes, gate.i0, gate.i1, time);
        if (gate.i0 != wanted[i].i0 || gate.i1 != wanted[i].i1) {
            mSelector.setTextureFrame(std::size_t(l.specA), std::int32_t(gate.i0));
            if (l.specB >= 0)
                mSelector.setTextureFrame(std::size_t(l.specB), std::int32_t(gate.i1));
            if (l.specT >= 0)
                mSelector.setTextureFrame(std::size_t(l.specT), std::int32_t(gate.i0));
            changed = true;
        }
        wanted[i] = gate;
    }
    if (changed) mSelection = &mSelector.select(camera, mStats, *mResidency);
}

}  // namespace kiosk::scene
