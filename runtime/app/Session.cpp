#include "runtime/app/Session.h"
#include "runtime/app/SolarLighting.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>

#include "config/MeaningCheck.h"
#include "config/ScenarioReader.h"
#include "runtime/color/Legend.h"
#include "runtime/core/Log.h"
#include "runtime/core/Strings.h"
#include "runtime/io/StoreReader.h"

namespace kiosk::app {
namespace {

constexpr const char* kTag = "app::Session";
const glm::vec4 kPanel(0.05f, 0.07f, 0.1f, 0.72f);
const glm::vec4 kText(1.0f, 1.0f, 1.0f, 1.0f);
const glm::vec4 kDim(0.8f, 0.84f, 0.9f, 1.0f);
const glm::vec4 kWarn(1.0f, 0.75f, 0.3f, 1.0f);

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
    auto scenario = config::readScenario(scenarioPath);
    if (!scenario) return scenario.diagnostics;
    std::unique_ptr<Session> s(new Session());
    s->mScenario = std::make_unique<config::Scenario>(std::move(*scenario.value));
    Diagnostics diags = scenario.diagnostics;  // warnings

    // Meaning checks need every store's metadata.
    std::map<std::string, std::unique_ptr<io::StoreReader>> readers;
    for (const auto& [id, ref] : s->mScenario->stores) {
        auto r = io::StoreReader::open(ref.path);
        if (!r) {
            diags.append(r.diagnostics);
            return diags;
        }
        readers[id] = std::move(*r.value);
    }
    Diagnostics meaning = config::checkMeaning(*s->mScenario, [&](const std::string& id) {
        auto it = readers.find(id);
        return it == readers.end() ? nullptr : &it->second->info();
    });
    diags.append(meaning);
    if (diags.hasErrors()) return diags;
    if (adjust) adjust(*s->mScenario);
    for (const auto& d : diags.items()) KIOSK_LOG_WARN(kTag, "%s", d.format().c_str());

    auto scene = scene::TerrainScene::create(*s->mScenario, caps);
    if (!scene) return scene.diagnostics;
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
    if (!sc.camera.path.empty()) {
        auto it = sc.cameraPaths.find(sc.camera.path);
        if (it != sc.cameraPaths.end()) {
            std::vector<anim::CameraKey> keys;
            for (const auto& k : it->second.keys)
                keys.push_back({k.time.resolve(s->mStart), toViewpoint(k.view)});
            auto path = anim::CameraPath::create(std::move(keys), sc.sourceFiles.front().string(),
                                                 it->second.pointer);
            if (path)
                s->mPath = std::move(*path.value);
            else
                for (const auto& d : path.diagnostics.items())
                    KIOSK_LOG_WARN(kTag, "%s", d.format().c_str());
        }
    }
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
        const auto& keys = sc.lighting.keys;
        std::size_t i = 0;
        while (i + 1 < keys.size() && keys[i + 1].time.resolve(mStart) <= time) ++i;
        az = keys[i].sunAzimuth;
        alt = keys[i].sunAltitude;
        if (i + 1 < keys.size()) {
            const double t0 = keys[i].time.resolve(mStart), t1 = keys[i + 1].time.resolve(mStart);
            const double a = t1 > t0 ? std::clamp((time - t0) / (t1 - t0), 0.0, 1.0) : 0.0;
            az += a * (keys[i + 1].sunAzimuth - az);
            alt += a * (keys[i + 1].sunAltitude - alt);
        }
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

    const auto& f = mScene->frameInfo();
    FrameRecord r;
    r.tilesDrawn = f.tilesDrawn;
    r.triangles = f.triangles;
    r.tilesFromAncestor = f.tilesFromAncestor;
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

void Session::drawOverlays(double time, int width, int height) {
    // Text scales with the output: legible on a wall at 4K, not covering a 320-pixel preview.
    const int fontPx = std::clamp((mOverlayFontHeight > 0 ? mOverlayFontHeight : height) / 40, 10, 40);
    if (fontPx != mOverlayFontPx) {
        mOverlayFontPx = fontPx;
        mOverlay.reset();
        auto overlay = render::OverlayRenderer::create(render::FontAtlas::defaultFontPath(), fontPx);
        if (overlay)
            mOverlay.emplace(std::move(*overlay.value));
        else  // no text is no reason to leave the display dark
            KIOSK_LOG_WARN(kTag, "overlays disabled: %s", overlay.diagnostics.format().c_str());
    }
    if (!mOverlay) return;
    auto& o = *mOverlay;
    const auto& sc = *mScenario;
    const float line = float(o.font().lineHeight());
    o.begin(width, height);
    // The time label is laid out first: when it and the title do not fit side by side (narrow
    // previews, long titles), the title moves below it rather than being overdrawn.
    std::string label;
    float labelW = 0.0f;
    // Tiles late: a sequence holds an older step. Label the time actually drawn and say so.
    const auto& frameInfo = mScene->frameInfo();
    const bool buffering = frameInfo.holdingSequence;
    if (buffering && !std::isnan(frameInfo.heldDataTime)) time = frameInfo.heldDataTime;
    if ((mOverlayOnly & kOverlayTimeLabel) && sc.overlays.timeLabel.enabled && mEnd > mStart) {
        char buf[128];
        anim::formatTimeLabel(buf, sizeof buf, time, mStart, sc.overlays.timeLabel.format, mZone);
        label = buf;
        if (buffering) label += "  buffering";
        if (sc.overlays.timeLabel.showOffset && label.find("T+") == std::string::npos &&
            label.find("T-") == std::string::npos)
            label += "  (" + anim::formatElapsed(time - mStart) + ")";
        labelW = o.measure(label) + 24.0f;
    }
    if ((mOverlayOnly & kOverlayTitle) && (!sc.title.empty() || !sc.caption.empty())) {
        const float w = std::max(o.measure(sc.title), o.measure(sc.caption)) + 24.0f;
        const float h = (sc.caption.empty() ? 1.0f : 2.0f) * line + 16.0f;
        const bool stacked = labelW > 0.0f && 12 + w + 12 + labelW + 12 > float(width);
        const float y = stacked ? 12 + line + 16 + 8 : 12;
        o.rect(12, y, w, h, kPanel);
        o.text(24, y + 8 + float(o.font().ascent()), sc.title, kText);
        if (!sc.caption.empty()) o.text(24, y + 8 + line + float(o.font().ascent()), sc.caption, kDim);
    }
    if (labelW > 0.0f) {
        o.rect(float(width) - labelW - 12, 12, labelW, line + 16, kPanel);
        o.text(float(width) - labelW, 12 + 8 + float(o.font().ascent()), label, kText);
        if (sc.overlays.progress.enabled) {
            const float frac = float(std::clamp((time - mStart) / (mEnd - mStart), 0.0, 1.0));
            o.rect(12, float(height) - 10, float(width) - 24, 4, glm::vec4(1, 1, 1, 0.3f));
            o.rect(12, float(height) - 10, (float(width) - 24) * frac, 4, kText);
        }
    }
    if ((mOverlayOnly & kOverlayLegend) && sc.overlays.legend.enabled) drawLegend(sc.overlays.legend, width, height);
    // Layer problems are always shown: an operator must see why a layer is missing.
    if (!(mOverlayOnly & kOverlayStatus)) {  // a wall box of one overlay only
        o.end();
        return;
    }
    float y = float(height) - 24;
    if (!mNotice.empty()) {
        const std::string text = mNotice.size() > 160 ? mNotice.substr(0, 157) + "..." : mNotice;
        const float w = o.measure(text) + 16;
        o.rect(12, y - line, w, line + 6, kPanel);
        o.text(20, y - 4, text, kWarn);
        y -= line + 8;
    }
    // The frame-rate governor at work (play): say what it trades, so nobody mistakes the
    // coarser picture for the scenario's.
    const bool governed = sc.terrain.reference == config::TerrainReference::Lod &&
                          (mScene->tauGeom() != sc.terrain.tauGeom ||
                           mScene->tauTex() != sc.terrain.tauTex || mRenderScale < 1.0);
    if (governed) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "frame-rate governor: tauGeom %.3g px (scenario %.3g), tauTex %.3g px (%.3g), "
                      "render scale %.2f",
                      mScene->tauGeom(), sc.terrain.tauGeom, mScene->tauTex(), sc.terrain.tauTex,
                      mRenderScale);
        const float w = o.measure(text) + 16;
        o.rect(12, y - line, w, line + 6, kPanel);
        o.text(20, y - 4, text, kDim);
        y -= line + 8;
    }
    for (const auto& st : mScene->layerStatus()) {
        if (st.state == scene::LayerState::Ready && !sc.overlays.status.enabled) continue;
        std::string text = st.id + ": " + scene::layerStateName(st.state);
        if (!st.message.empty()) text += " - " + st.message;
        if (text.size() > 140) text = text.substr(0, 137) + "...";
        const float w = o.measure(text) + 16;
        o.rect(12, y - line, w, line + 6, kPanel);
        o.text(20, y - 4, text, st.state == scene::LayerState::Ready ? kDim : kWarn);
        y -= line + 8;
    }
    if (mCurtain > 0.0f) o.rect(0, 0, float(width), float(height), glm::vec4(0, 0, 0, mCurtain));
    o.end();
}

void Session::drawLegend(const config::LegendOverlay& legend, int width, int height) {
    auto& o = *mOverlay;
    const scene::SceneLut* lut = mScene->lut(legend.transfer);
    const config::TransferFunctionDef* def = mScenario->findTransfer(legend.transfer);
    if (!lut || !def) return;
    const color::TransferFunction& tf = *lut->function;
    std::string title = !legend.title.empty() ? legend.title : !def->label.empty() ? def->label : def->name;
    if (!tf.units.empty()) title += " (" + tf.units + ")";
    const float line = float(o.font().lineHeight());
    const float barW = line * 12.0f, barH = line * 0.8f;
    if (tf.discrete()) {
        auto patches = color::legendPatches(tf);
        float w = o.measure(title);
        for (const auto& p : patches) w = std::max(w, 28 + o.measure(p.label));
        const float h = line * float(patches.size() + 1) + 20;
        const float x = float(width) - w - 36, y = float(height) - h - 12;
        o.rect(x, y, w + 24, h, kPanel);
        o.text(x + 12, y + 8 + float(o.font().ascent()), title, kText);
        float py = y + 8 + line;
        for (const auto& p : patches) {
            o.rect(x + 12, py + 3, 18, line - 6, glm::vec4(p.color.r, p.color.g, p.color.b, 1.0f));
            o.text(x + 40, py + float(o.font().ascent()), p.label, kText);
            py += line;
        }
        return;
    }
    const float w = std::max(barW, o.measure(title)) + 24;
    const float h = line * 2 + barH + 28;
    const float x = float(width) - w - 12, y = float(height) - h - 12;
    o.rect(x, y, w, h, kPanel);
    o.text(x + 12, y + 8 + float(o.font().ascent()), title, kText);
    const float barX = x + 12, barY = y + 12 + line;
    o.image(barX, barY, barW, barH, lut->texture.id());
    for (const auto& t : color::legendTicks(tf)) {
        const float tx = barX + float(t.position) * barW;
        o.rect(tx - 0.5f, barY + barH, 1, 5, kText);
        const float tw = o.measure(t.label);
        o.text(std::clamp(tx - tw / 2, barX - 6, barX + barW - tw + 6),
               barY + barH + 6 + float(o.font().ascent()), t.label, kText);
    }
}

}  // namespace kiosk::app
