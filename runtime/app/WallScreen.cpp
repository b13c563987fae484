#include "runtime/app/WallScreen.h"

#include "runtime/app/Report.h"
#include "runtime/core/ExitCode.h"
#include "runtime/core/Strings.h"
#include "runtime/wall/ScreenFrustum.h"
#include "runtime/wall/WallReader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace kiosk::app {

std::optional<WallScreen> wallScreenFromArgs(const Args& args, int& exitCode) {
    exitCode = -1;
    const auto file = args.value("wall");
    const auto id = args.value("screen");
    if (!file && !id) return std::nullopt;
    if (!file || !id) {
        std::fprintf(stderr, "--wall and --screen go together\n");
        exitCode = kExitUsage;
        return std::nullopt;
    }
    auto w = wall::readWall(*file);
    if (!w) {
        printDiagnostics(w.diagnostics);
        exitCode = kExitBadInput;
        return std::nullopt;
    }
    WallScreen ws{std::move(*w.value), -1};
    ws.screen = ws.wall.findScreen(*id);
    if (ws.screen < 0) {
        std::vector<std::string> ids;
        for (const auto& s : ws.wall.screens) ids.push_back(s.id);
        std::string msg = *file + ": --screen \"" + *id + "\": no such screen in the wall file";
        if (auto m = closestMatch(*id, ids)) msg += " (did you mean \"" + *m + "\"?)";
        std::fprintf(stderr, "%s\n", msg.c_str());
        exitCode = kExitUsage;
        return std::nullopt;
    }
    return ws;
}

math::Camera WallScreen::camera(const math::Viewpoint& vp, const math::Aabb& bounds,
                                double fovY) const {
    const glm::ivec2 canvas = wall::canvasPixels(wall, screen);
    return wall::screenCamera(makeCamera(vp, bounds, canvas.x, canvas.y, fovY), wall, screen);
}

namespace {

/** Distance (mm) from a canvas point to a screen's active area (0 inside). */
double distanceMm(const wall::Screen& s, double x, double y) {
    const double dx = std::max({s.xMm - x, 0.0, x - (s.xMm + s.activeMmX)});
    const double dy = std::max({s.yMm - y, 0.0, y - (s.yMm + s.activeMmY)});
    return std::hypot(dx, dy);
}

}  // namespace

Session::OverlayLayout WallScreen::overlayLayout() const {
    // Boxes follow how Session lays each overlay out: the legend in the bottom-right corner of
    // its box, the time label top-right, the title top-left. A canvas anchor becomes that corner.
    enum class Corner { BottomRight, TopRight, TopLeft };
    auto place = [&](const wall::OverlayPlacement& p, Corner corner) {
        Session::OverlayBox box;
        if (!p.canvas) {
            box.shown = (p.screen >= 0 ? p.screen : wall.leaderScreen()) == screen;
            return box;
        }
        const double x = (*p.canvas)[0] * wall.canvasMmX, y = (*p.canvas)[1] * wall.canvasMmY;
        int owner = 0;
        for (std::size_t i = 1; i < wall.screens.size(); ++i)
            if (distanceMm(wall.screens[i], x, y) <
                distanceMm(wall.screens[std::size_t(owner)], x, y))
                owner = int(i);
        box.shown = owner == screen;
        if (!box.shown) return box;
        const wall::Screen& s = self();
        // The anchor in this screen's pixels, clamped inside it (a point on a bezel moves onto
        // the nearest screen: the overlay is never cut).
        const int ax =
            std::clamp(int(std::lround((x - s.xMm) * s.pixelsX / s.activeMmX)), 1, s.pixelsX);
        const int ay =
            std::clamp(int(std::lround((y - s.yMm) * s.pixelsY / s.activeMmY)), 1, s.pixelsY);
        switch (corner) {
            case Corner::BottomRight:
                box = {true, 0, 0, ax, ay, config::Corner::BottomRight};
                break;
            case Corner::TopRight:
                box = {true, 0, ay - 1, ax, s.pixelsY - ay + 1, config::Corner::TopRight};
                break;
            case Corner::TopLeft:
                box = {true,
                       ax - 1,
                       ay - 1,
                       s.pixelsX - ax + 1,
                       s.pixelsY - ay + 1,
                       config::Corner::TopLeft};
                break;
        }
        return box;
    };
    Session::OverlayLayout l;
    l.legend = place(wall.overlays.legend, Corner::BottomRight);
    l.timeLabel = place(wall.overlays.timeLabel, Corner::TopRight);
    l.title = place(wall.overlays.title, Corner::TopLeft);
    return l;
}

}  // namespace kiosk::app
