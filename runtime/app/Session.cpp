#include "runtime/app/Session.h"

#include "config/DataUnits.h"
#include "config/ScenarioReader.h"
#include "runtime/anim/KeyedTrack.h"
#include "runtime/app/MemoryBudgets.h"
#include "runtime/app/ScenarioStores.h"
#include "runtime/app/SolarLighting.h"
#include "runtime/color/Legend.h"
#include "runtime/core/Log.h"
#include "runtime/core/Strings.h"
#include "runtime/io/StoreReader.h"
#include "runtime/platform/CompilerPages.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <malloc.h>
#include <map>

namespace kiosk::app {
namespace {

constexpr const char* kTag = "app::Session";
/** Shader compiles come in bursts (start-up, a new layer or state): between them llvmpipe's
 * compiler code goes back to the kernel at most this often (platform/CompilerPages.h). */
constexpr double kCompilerPagesEverySeconds = 2.0;

math::Viewpoint toViewpoint(const config::Viewpoint& v) {
    return {glm::dvec3(v.target[0], v.target[1], v.target[2]), v.heading, v.pitch, v.range};
}


}  // namespace

math::Camera makeCamera(const math::Viewpoint& vp, const math::Aabb& bounds, int width, int height,
                        double fovY) {
    math::Camera cam = math::Camera::fromViewpoint(vp, width, height, fovY);
    // Include the skirts' depth below the data minimum.
    glm::dvec3 lo = bounds.min, hi = bounds.max;
    lo.z -= std::max(100.0, (hi.z - lo.z) * 0.1);
    cam.fitClipPlanes(lo, hi);
    return cam;
}

Result<std::unique_ptr<Session>> Session::open(const std::filesystem::path& scenarioPath,
                                               const gl::Caps& caps) {
    return open(scenarioPath, caps, nullptr);
}

Result<std::unique_ptr<Session>> Session::open(
    const std::filesystem::path& scenarioPath, const gl::Caps& caps,
    const std::function<void(config::Scenario&)>& adjust) {
    auto checked = readChecked(scenarioPath);
    if (!checked) return checked.diagnostics;
    sayWarnings(checked.diagnostics);
    return create(std::move(*checked.value), caps, adjust);
}

void Session::sayWarnings(const Diagnostics& warnings) {
    for (const auto& d : warnings.items()) KIOSK_LOG_WARN(kTag, "%s", d.format().c_str());
}

Result<std::unique_ptr<config::Scenario>> Session::readChecked(
    const std::filesystem::path& scenarioPath) {
    auto scenario = config::readScenario(scenarioPath);
    if (!scenario) return scenario.diagnostics;
    auto checked = std::make_unique<config::Scenario>(std::move(*scenario.value));
    Diagnostics diags = scenario.diagnostics;  // warnings
    // Meaning checks need every store's metadata; store errors name the scenario's line.
    OpenedStores readers;
    diags.append(openScenarioStores(*checked, readers));
    if (diags.hasErrors()) return diags;
    // Legends of transfer functions without units show the units the stores record.
    config::adoptDataUnits(*checked, [&](const std::string& id) -> const io::StoreInfo* {
        auto it = readers.find(id);
        return it == readers.end() ? nullptr : &it->second->info();
    });
    return {std::move(checked), std::move(diags)};
}

Result<std::unique_ptr<Session>> Session::create(
    std::unique_ptr<config::Scenario> scenario, const gl::Caps& caps,
    const std::function<void(config::Scenario&)>& adjust) {
    std::unique_ptr<Session> s(new Session());
    s->mScenario = std::move(scenario);
    if (adjust) adjust(*s->mScenario);
    // LUTs and mapping arrays over budget: refused before anything is allocated.
    if (Diagnostics d = checkMemoryBudgets(*s->mScenario); d.hasErrors()) return d;

    auto scene = scene::TerrainScene::create(*s->mScenario, caps);
    if (!scene) {
        // Renderer errors (e.g. more texture units than this GPU has) still name the scenario.
        Diagnostics named;
        for (Diagnostic d : scene.diagnostics.items()) {
            if (d.file.empty()) d.file = s->mScenario->sourceFiles.front().string();
            named.add(std::move(d));
        }
        return named;
    }
    s->mScene = std::move(*scene.value);


    const auto& sc = *s->mScenario;
    if (sc.clock) {
        s->mStart = sc.clock->start;
        s->mEnd = sc.clock->end;
    } else if (auto times = s->mScene->sequenceKeyTimes(); !times.empty()) {
        s->mStart = times.front();
        s->mEnd = times.back();
    }
    auto tz = anim::parseTimeZone(sc.overlays.timeLabel.timeZone);
    if (tz) s->mZone = *tz;
    if (!sc.camera.path.empty())
        if (auto path = s->buildPath(sc.camera.path)) s->mPath = std::move(*path);
    s->setupBriefing();
    return s;
}

Result<math::Viewpoint> Session::viewpointAt(double time, const std::string& viewpoint) const {
    const auto& sc = *mScenario;
    if (!viewpoint.empty()) {
        auto it = sc.viewpoints.find(viewpoint);
        if (it == sc.viewpoints.end()) {
            Diagnostics d;
            std::vector<std::string> names;
            for (const auto& [n, v] : sc.viewpoints) names.push_back(n);
            auto& e = d.error("SCENARIO_UNKNOWN_VIEWPOINT", sc.sourceFiles.front().string(),
                              "/viewpoints", "no viewpoint named \"" + viewpoint + "\"");
            if (auto m = closestMatch(viewpoint, names)) e.hint = "did you mean \"" + *m + "\"?";
            return d;
        }
        return toViewpoint(it->second);
    }
    if (auto v = chapterViewpoint(time)) return *v;
    if (!mPath.empty()) return mPath.sample(time);
    if (!sc.camera.viewpoint.empty()) {
        auto it = sc.viewpoints.find(sc.camera.viewpoint);
        if (it != sc.viewpoints.end()) return toViewpoint(it->second);
    }
    return mScene->overviewViewpoint();
}

void Session::setRenderScale(double scale) {
    mRenderScale = std::clamp(scale, 0.1, 1.0);
}

bool Session::bindScaledTarget(int width, int height, int& outFbo) {
    const int w = std::max(1, int(std::lround(width * mRenderScale)));
    const int h = std::max(1, int(std::lround(height * mRenderScale)));
    if (w == width && h == height) return false;
    if (!mScaled || mScaled->width() != w || mScaled->height() != h) {
        auto rt = gl::RenderTarget::create(w, h);
        if (!rt) return false;  // no smaller target: render at full size
        mScaled.emplace(std::move(*rt.value));
    }
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &outFbo);
    mScaled->bind();
    glViewport(0, 0, w, h);
    return true;
}

FrameRecord Session::drawFrame(const math::Camera& camera, double time, int width, int height) {
    const auto& sc = *mScenario;
    // Render scale < 1 (the frame-rate governor): the terrain goes to a smaller target that is
    // then stretched over the output; overlays are drawn at the output's own resolution.
    GLint outFbo = 0;
    const bool scaled = bindScaledTarget(width, height, outFbo);
    if (!scaled) glViewport(0, 0, width, height);
    glClearColor(0.62f, 0.71f, 0.80f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    using PhaseClock = std::chrono::steady_clock;
    const auto msSince = [](PhaseClock::time_point t) {
        return std::chrono::duration<double, std::milli>(PhaseClock::now() - t).count();
    };
    const auto tUpdate = PhaseClock::now();
    mScene->update(camera, time, mPlayback);
    const double updateMs = msSince(tUpdate);

    render::TerrainStyle style;
    double az = sc.lighting.sunAzimuth, alt = sc.lighting.sunAltitude;
    if (!sc.lighting.keys.empty()) {
        // Piecewise-linear sun between keys (a moving sun over the scenario's clock).
        const auto sunAt = anim::keyedTrack(
            glm::dvec2(az, alt), sc.lighting.keys, time,
            [this](const config::LightingKey& k) { return k.time.resolve(mStart); },
            [](glm::dvec2& v, const config::LightingKey& k) {
                v = {k.sunAzimuth, k.sunAltitude};
            },
            [](const glm::dvec2& a, const glm::dvec2& b, double t) { return glm::mix(a, b, t); });
        az = sunAt.x;
        alt = sunAt.y;
    }
    if (auto sun = solarSun(sc.lighting, mScene->storeInfo(), sc.terrain.elevation, time)) {
        az = sun->azimuthDeg;  // lighting.solar: where the sun is at the data time
        alt = sun->altitudeDeg;
    }
    style.lightDir = render::sunDirection(az, alt);
    style.ambient = float(sc.lighting.ambient);
    style.verticalScale = float(sc.terrain.verticalExaggeration);
    style.elevationLutWeight = 0.0f;
    style.baseColor = glm::vec4(0.78f, 0.78f, 0.76f, 1.0f);
    for (const auto& l : sc.layers)
        if (l.enabled && (l.kind == config::LayerKind::Topographic || l.kind == config::LayerKind::Normals))
            style.geometryLighting = 0.0f;
    style.tauTex = float(mScene->tauTex());
    const auto tDraw = PhaseClock::now();
    mScene->draw(camera, style);
    if (scaled) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, mScaled->framebuffer());
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(outFbo));
        glBlitFramebuffer(0, 0, mScaled->width(), mScaled->height(), 0, 0, width, height,
                          GL_COLOR_BUFFER_BIT, GL_LINEAR);
        glBindFramebuffer(GL_FRAMEBUFFER, GLuint(outFbo));
        glViewport(0, 0, width, height);
    }
    const double drawMs = msSince(tDraw);
    const auto tOverlay = PhaseClock::now();
    mOverlayLayout ? drawWallOverlays(time, width, height) : drawOverlays(time, width, height);
    const double overlayMs = msSince(tOverlay);
    // Between shader-compile bursts llvmpipe's compiler code, and the allocator's free pages,
    // go back to the kernel, at most every 2 s (docs/performance.md §5).
    if (platform::releaseCompilerPages(kCompilerPagesEverySeconds)) malloc_trim(0);

    const auto& f = mScene->frameInfo();
    FrameRecord r;
    r.tilesDrawn = f.tilesDrawn;
    r.triangles = f.triangles;
    r.tilesFromAncestor = f.tilesFromAncestor;
    r.tilesOccluded = f.tilesOccluded;
    r.sequenceTilesMissing = f.sequenceTilesMissing;
    r.residentBytes = f.residentBytes;
    r.dataTime = time;
    r.holdingSequence = f.holdingSequence;
    r.heldFrames = f.heldFrames;
    r.prefetchDepth = f.prefetchDepth;
    r.prefetchHits = f.prefetchHits;
    r.mappingsActive = f.mappingsActive;
    r.mappingsCulledFrustum = f.mappingsCulledFrustum;
    r.mappingsCulledSize = f.mappingsCulledSize;
    r.updateMs = updateMs;
    r.uploadMs = f.uploadMs;
    r.uploads = f.uploads;
    r.drawMs = drawMs;
    r.overlayMs = overlayMs;
    r.tauGeom = mScene->tauGeom();
    r.tauTex = mScene->tauTex();
    r.renderScale = scaled ? double(mScaled->width()) / double(width) : 1.0;
    return r;
}

anim::ClockSettings Session::clockSettings() const {
    anim::ClockSettings cs;
    cs.start = mStart;
    cs.end = mEnd;
    if (const auto& c = mScenario->clock) {
        cs.rate = c->rate;
        cs.range = c->range == config::RangeBehaviour::Loop    ? anim::RangeMode::Loop
                   : c->range == config::RangeBehaviour::Clamp ? anim::RangeMode::Clamp
                                                               : anim::RangeMode::Unbounded;
        cs.waitForData = c->waitForData;
        cs.startPaused = c->paused;
    }
    return cs;
}

}  // namespace kiosk::app
