// How long would a far-terrain impostor stay valid (issue 20, Wahl et al. 2004 §5;
// docs/terrain.md §12)? Plays a scenario's camera path at a kiosk's frame rate and, per far
// tile, tracks an impostor as W04 describe it: the tile rendered into a texture once, drawn as a
// quad (through the tile's centre, facing the eye it was rendered from) until its error exceeds
// the bound, then rendered again. Error of an impostor rendered from eye e0, seen from eye e:
// the parallax of the tile's surface points against their place on the quad (projected with the
// camera of the frame, in pixels) plus the resampling of the impostor's texels (half a texel,
// texels magnified by d0 / d when the eye comes closer). Budget: 1 pixel (terrain.tauTex),
// as W04 sum the errors. No GL drawing: the cameras and the store's elevation posts only.
// Prints ONE JSON object: per far distance D (tiles whose every point is farther than D), far
// tiles per frame, impostor re-renders per frame, how many frames an impostor lasts.
//
// usage: bench-impostor-validity SCENARIO [--far M,...] [--fps N] [--size WxH] [--level L]
#include "runtime/app/Session.h"
#include "runtime/io/StoreReader.h"

#include "bench/common/BenchArgs.h"
#include "bench/common/HeadlessGl.h"
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

using namespace kiosk;

namespace {

struct Tile {
    std::vector<glm::dvec3> points;  ///< surface samples (every 16th post), world metres
    glm::dvec3 centre{0.0};
    // The impostor: rendered from this eye, when it exists.
    std::optional<glm::dvec3> eye;
    int renders = 0;
    int farFrames = 0;
};

/** Pixel position of `p` for camera `c`; nullopt behind the eye. */
std::optional<glm::dvec2> project(const glm::dmat4& vp, const math::Camera& c,
                                  const glm::dvec3& p) {
    const glm::dvec4 clip = vp * glm::dvec4(p, 1.0);
    if (clip.w <= 1e-9) return std::nullopt;
    return glm::dvec2((clip.x / clip.w + 1.0) * 0.5 * c.viewportWidth,
                      (clip.y / clip.w + 1.0) * 0.5 * c.viewportHeight);
}

bool onScreen(const glm::dvec2& s, const math::Camera& c) {
    return s.x >= 0 && s.y >= 0 && s.x <= c.viewportWidth && s.y <= c.viewportHeight;
}

/** Error (pixels) of the tile's impostor rendered from `e0`, seen with camera `c`; -1: off screen.
 */
double impostorError(const Tile& t, const glm::dvec3& e0, const glm::dmat4& vp,
                     const math::Camera& c) {
    const glm::dvec3 n = glm::normalize(t.centre - e0);
    const double planeT = glm::dot(t.centre - e0, n);
    double parallax = 0;
    bool visible = false;
    for (const glm::dvec3& p : t.points) {
        const auto s = project(vp, c, p);
        if (!s || !onScreen(*s, c)) continue;
        visible = true;
        const double along = glm::dot(p - e0, n);
        if (along <= 1e-6) return 1e9;  // the point was behind the impostor's eye
        const glm::dvec3 q = e0 + (p - e0) * (planeT / along);
        const auto sq = project(vp, c, q);
        if (!sq) return 1e9;
        parallax = std::max(parallax, glm::length(*s - *sq));
    }
    if (!visible) return -1;
    // Texels of an impostor rendered at screen resolution from distance d0, seen from d.
    const double magnification =
        glm::length(t.centre - e0) / std::max(1.0, glm::length(t.centre - c.eye));
    return parallax + 0.5 * std::max(1.0, magnification);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr,
                     "usage: bench-impostor-validity SCENARIO [--far M,...] [--fps N] "
                     "[--size WxH] [--level L]\n");
        return 2;
    }
    const std::string scenario = argv[1];
    std::vector<double> fars;
    double fps = 30;
    int w = 1280, h = 720, level = 2;
    for (int i = 2; i + 1 < argc; i += 2) {
        const char* opt = argv[i];
        const char* value = argv[i + 1];
        if (!std::strcmp(opt, "--far")) {
            for (const char* p = value; *p;) {
                char* end = nullptr;
                const double d = std::strtod(p, &end);
                if (end == p || !(d > 0)) return 2;
                fars.push_back(d);
                p = *end == ',' ? end + 1 : end;
            }
        } else if (!std::strcmp(opt, "--fps")) {
            fps = std::max(1.0, std::atof(value));
        } else if (!std::strcmp(opt, "--size")) {
            const auto wh = parseSize(value);
            if (!wh) return 2;
            std::tie(w, h) = *wh;
        } else if (!std::strcmp(opt, "--level")) {
            level = std::max(0, std::atoi(value));
        } else {
            return 2;
        }
    }
    if (fars.empty()) fars = {30000, 60000, 90000};
    auto headless = bench::openHeadlessGl();
    if (!headless) return 3;
    auto session = app::Session::open(scenario, headless->caps);
    if (!session) {
        std::fprintf(stderr, "%s", session.diagnostics.format().c_str());
        return 1;
    }
    app::Session& s = **session;
    const config::Scenario& sc = s.scenario();
    auto reader = io::StoreReader::open(sc.stores.at(sc.terrain.store).path);
    if (!reader) {
        std::fprintf(stderr, "%s", reader.diagnostics.format().c_str());
        return 1;
    }
    const io::TileGrid& grid = (*reader)->info().grid;
    level = std::min(level, grid.maxLevel());
    const io::TileMatrix& m = grid.levels[std::size_t(level)];
    std::vector<Tile> base;
    for (int row = 0; row < m.matrixHeight; ++row)
        for (int col = 0; col < m.matrixWidth; ++col) {
            const TileId id{level, col, row};
            auto posts = (*reader)->readElevation(sc.terrain.elevation, id);
            if (!posts) continue;
            double x0, y0, x1, y1;
            grid.tileBounds(id, x0, y0, x1, y1);
            Tile t;
            for (int y = 0; y < posts->postsY; y += 16)
                for (int x = 0; x < posts->postsX; x += 16) {
                    const float z = posts->at(x, y);
                    if (std::isnan(z)) continue;
                    t.points.push_back({x0 + (x + 0.5) * m.pixelXSize,
                                        y1 - (y + 0.5) * m.pixelYSize,
                                        double(z) * sc.terrain.verticalExaggeration});
                }
            if (t.points.empty()) continue;
            for (const auto& p : t.points) t.centre += p;
            t.centre /= double(t.points.size());
            base.push_back(std::move(t));
        }
    const anim::ClockSettings clock = s.clockSettings();
    const double rate = clock.rate != 0 ? std::abs(clock.rate) : 1.0;
    const double tourSeconds = (s.endTime() - s.startTime()) / rate;
    const int frames = std::max(2, int(std::lround(tourSeconds * fps)));
    nlohmann::json out;
    out["benchmark"] = "impostor_validity";
    out["scenario"] = scenario;
    out["size"] = std::to_string(w) + "x" + std::to_string(h);
    out["fps"] = fps;
    out["tour_seconds"] = tourSeconds;
    out["frames"] = frames;
    out["tile_level"] = level;
    out["tiles"] = base.size();
    out["error_budget_px"] = 1.0;
    for (double far : fars) {
        std::vector<Tile> tiles = base;
        long long farTileFrames = 0, renders = 0, framesWithFar = 0, framesAllValid = 0;
        for (int f = 0; f < frames; ++f) {
            const double t = s.startTime() + (s.endTime() - s.startTime()) * f / (frames - 1);
            auto vp = s.viewpointAt(t, "");
            if (!vp) continue;
            const math::Camera cam =
                app::makeCamera(*vp, s.terrain().bounds(), w, h, sc.camera.fovY);
            const glm::dmat4 viewProj = cam.projection() * cam.view();
            int farNow = 0, renderedNow = 0;
            for (Tile& tile : tiles) {
                double nearest = 1e300;
                for (const auto& p : tile.points)
                    nearest = std::min(nearest, glm::length(p - cam.eye));
                if (nearest <= far) {  // drawn as geometry: its impostor is dropped
                    tile.eye.reset();
                    continue;
                }
                const double err = tile.eye ? impostorError(tile, *tile.eye, viewProj, cam)
                                            : impostorError(tile, cam.eye, viewProj, cam);
                if (err < 0) continue;  // not on screen: nothing drawn, nothing to keep valid
                ++farNow;
                ++tile.farFrames;
                if (!tile.eye || err > 1.0) {
                    tile.eye = cam.eye;
                    ++tile.renders;
                    ++renderedNow;
                }
            }
            farTileFrames += farNow;
            renders += renderedNow;
            framesWithFar += farNow > 0 ? 1 : 0;
            framesAllValid += (farNow > 0 && renderedNow == 0) ? 1 : 0;
        }
        std::vector<double> lifetimes;
        for (const Tile& t : tiles)
            if (t.renders > 0) lifetimes.push_back(double(t.farFrames) / t.renders);
        std::sort(lifetimes.begin(), lifetimes.end());
        const double rerenderFraction = farTileFrames ? double(renders) / double(farTileFrames) : 0;
        out["far"].push_back(
            {{"far_m", far},
             {"frames_with_far_tiles", framesWithFar},
             {"far_tiles_per_frame",
              framesWithFar ? double(farTileFrames) / double(framesWithFar) : 0.0},
             {"rerenders_per_frame", framesWithFar ? double(renders) / double(framesWithFar) : 0.0},
             {"rerender_fraction", rerenderFraction},
             {"frames_without_rerender", framesAllValid},
             {"impostor_lifetime_frames_median",
              lifetimes.empty() ? 0.0 : lifetimes[lifetimes.size() / 2]},
             {"impostor_lifetime_frames_mean",
              farTileFrames && renders ? double(farTileFrames) / double(renders) : 0.0}});
    }
    std::printf("%s\n", out.dump().c_str());
    return 0;
}
