// Session's briefing chapters: which chapter is on, its camera, its layer overrides, and the
// chapters in numbers for `play` (BriefingPlayer) and `render` (briefingFrames).
#include "runtime/app/Session.h"
#include "runtime/core/Log.h"

#include <cmath>

namespace kiosk::app {
namespace {

constexpr const char* kTag = "app::Session";
/** Playback seconds of a chapter showing a single time when it gives no duration. */
constexpr double kDefaultChapterSeconds = 5.0;

math::Viewpoint toViewpoint(const config::Viewpoint& v) {
    return {glm::dvec3(v.target[0], v.target[1], v.target[2]), v.heading, v.pitch, v.range};
}

}  // namespace

std::optional<anim::CameraPath> Session::buildPath(const std::string& name) const {
    const auto& sc = *mScenario;
    auto it = sc.cameraPaths.find(name);
    if (it == sc.cameraPaths.end()) return std::nullopt;
    std::vector<anim::CameraKey> keys;
    for (const auto& k : it->second.keys)
        keys.push_back({k.time.resolve(mStart), toViewpoint(k.view)});
    auto path = anim::CameraPath::create(std::move(keys), sc.sourceFiles.front().string(),
                                         it->second.pointer);
    if (!path) {
        for (const auto& d : path.diagnostics.items())
            KIOSK_LOG_WARN(kTag, "%s", d.format().c_str());
        return std::nullopt;
    }
    return std::move(*path.value);
}

void Session::setupBriefing() {
    mChapterSpans = computeChapterSpans();
    if (!mScenario->briefing) return;
    for (const auto& c : mScenario->briefing->chapters)
        if (!c.path.empty() && !mChapterPaths.count(c.path))
            if (auto p = buildPath(c.path)) mChapterPaths.emplace(c.path, std::move(*p));
}

const config::Chapter* Session::chapter() const noexcept {
    const auto& b = mScenario->briefing;
    if (!b || mChapter < 0 || std::size_t(mChapter) >= b->chapters.size()) return nullptr;
    return &b->chapters[std::size_t(mChapter)];
}

void Session::setChapter(int index) {
    mChapter = index;
    mScene->clearLayerOverrides();
    if (const config::Chapter* c = chapter())
        for (const auto& l : c->layers)
            mScene->setLayerOverride(l.layer, l.enabled.value_or(true), l.opacity);
}

std::optional<math::Viewpoint> Session::chapterViewpoint(double time) const {
    const config::Chapter* c = chapter();
    if (!c) return std::nullopt;
    if (!c->viewpoint.empty()) {
        auto it = mScenario->viewpoints.find(c->viewpoint);
        if (it != mScenario->viewpoints.end()) return toViewpoint(it->second);
    }
    if (!c->path.empty()) {
        auto it = mChapterPaths.find(c->path);
        if (it != mChapterPaths.end()) return it->second.sample(time);
    }
    return std::nullopt;  // the scenario's own camera
}

std::vector<anim::ChapterSpan> Session::computeChapterSpans() const {
    std::vector<anim::ChapterSpan> out;
    if (!mScenario->briefing) return out;
    const double rate =
        mScenario->clock && mScenario->clock->rate != 0 ? std::fabs(mScenario->clock->rate) : 1.0;
    for (const auto& c : mScenario->briefing->chapters) {
        anim::ChapterSpan s;
        s.from = c.from.resolve(mStart);
        s.to = c.to.resolve(mStart);
        s.pause = c.pause;
        // A span plays at the clock's rate unless the chapter says how long it takes.
        const double natural = std::fabs(s.to - s.from) / rate;
        s.seconds = c.duration ? *c.duration : natural > 0 ? natural : kDefaultChapterSeconds;
        out.push_back(s);
    }
    return out;
}

}  // namespace kiosk::app
