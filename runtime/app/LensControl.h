#pragma once

#include "runtime/platform/Display.h"
#include "runtime/scene/TerrainScene.h"
#include "runtime/service/Control.h"

#include <string>

// Moving a lens at run time (issue 19): keys in `play` and POST /control/lens. Both act on the
// frame loop's thread, between frames: the HTTP thread only queued the command.
namespace kiosk::app {

/**
 * @brief Apply one POST /control/lens command to `scene` from the next frame on. False with
 * a one-line reason (no such lens id, no lens at all) for the log.
 */
bool applyLensMove(scene::TerrainScene& scene, const service::LensMove& move, std::string& why);

/**
 * @brief The lens keys of `input` (w/a/s/d move by 1/20 of the terrain's larger side, ] and [
 * scale by 1.1, r turns 15 degrees, c toggles) on the scene's primary lens (the first comparison
 * lens, else the first lens); nothing without a lens or a lens key.
 */
void applyLensKeys(scene::TerrainScene& scene, const platform::InputState& input);

}  // namespace kiosk::app
