#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

// A display wall: screens on a grid, their physical sizes and bezels, which node drives which
// screen, where the sync sockets are and where the overlays go. Plain data; any thread.
// Read with readWall() (WallReader.h); docs/wall.md describes the file.
namespace kiosk::wall {

/** @brief One screen (one output). Millimetres on the wall plane, x right, y down. */
struct Screen {
    std::string id;
    int row = 0;
    int column = 0;
    int pixelsX = 0;
    int pixelsY = 0;
    double activeMmX = 0;  ///< physical size of the picture area (inside the bezels)
    double activeMmY = 0;
    /** @brief Top-left of the active area on the wall plane (from the grid, or given). */
    double xMm = 0;
    double yMm = 0;
    /** @brief Angled screens: rotation about the active area's centre, degrees. */
    double yawDeg = 0;    ///< about the wall's up axis (positive: the right edge moves away)
    double pitchDeg = 0;  ///< about the wall's horizontal axis (positive tilts the top back)
    double rollDeg = 0;   ///< about the screen normal (positive counter-clockwise)
    int node = -1;        ///< index into Wall::nodes
};

struct Node {
    std::string id;
    std::vector<int> screens;  ///< indices into Wall::screens
};

/**
 * @brief Where an overlay goes: on one screen (laid out as on a single display), or anchored at
 * a point of the virtual canvas (fractions 0..1 of its width and height) on the screen that
 * holds the point (the nearest one when it falls on a bezel). Neither: the leader's screen.
 */
struct OverlayPlacement {
    int screen = -1;
    std::optional<std::array<double, 2>> canvas;
};

struct WallOverlays {
    OverlayPlacement legend;
    OverlayPlacement timeLabel;
    OverlayPlacement title;
};

struct SyncSettings {
    std::string stateEndpoint;  ///< leader PUB (frame state and swap release); followers SUB
    std::string readyEndpoint;  ///< leader PULL (ready reports); followers PUSH
    double deadlineMs = 100.0;  ///< a swap waits at most this long for slow nodes
};

struct Wall {
    std::string file;
    int rows = 0;
    int columns = 0;
    double mullionMmX = 0;  ///< gap between the active areas of horizontally adjacent screens
    double mullionMmY = 0;  ///< gap between the active areas of vertically adjacent screens
    std::vector<Screen> screens;
    std::vector<Node> nodes;
    int leader = -1;  ///< index into nodes
    SyncSettings sync;
    WallOverlays overlays;

    /** @brief Bounding box of every active area (mm): the virtual canvas. */
    double canvasMmX = 0;
    double canvasMmY = 0;

    int findScreen(const std::string& id) const;
    /** @brief The screen that runs the leader's sync role: the leader node's first screen. */
    int leaderScreen() const { return leader >= 0 ? nodes[leader].screens.front() : -1; }
};

}  // namespace kiosk::wall
