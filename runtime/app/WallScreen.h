#pragma once

#include "runtime/app/Args.h"
#include "runtime/app/Session.h"
#include "runtime/math/Camera.h"
#include "runtime/wall/Wall.h"

#include <optional>
#include <string>

// `--wall WALL.json --screen ID` for play and render: which screen of which wall this process
// draws, its off-axis camera and where its overlays go (docs/wall.md).
namespace kiosk::app {

struct WallScreen {
    wall::Wall wall;
    int screen = -1;

    const wall::Screen& self() const { return wall.screens[std::size_t(screen)]; }
    int width() const { return self().pixelsX; }
    int height() const { return self().pixelsY; }
    bool isLeader() const { return screen == wall.leaderScreen(); }
    /** @brief This screen's off-axis part of the virtual camera for `vp` (fovY spans the canvas).
     */
    math::Camera camera(const math::Viewpoint& vp, const math::Aabb& bounds, double fovY) const;
    /** @brief Which overlays this screen draws, and in which box (never across a bezel). */
    Session::OverlayLayout overlayLayout() const;
};

/**
 * @brief Read `--wall`/`--screen` from `args`. Neither: nullopt and exit code -1. Errors print
 * one line each and return the exit code: 2 (usage: only one of the two, unknown screen id with
 * a did-you-mean), 1 (the wall file is bad).
 */
std::optional<WallScreen> wallScreenFromArgs(const Args& args, int& exitCode);

}  // namespace kiosk::app
