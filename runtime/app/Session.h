#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "config/Scenario.h"
#include "runtime/anim/BriefingTimeline.h"
#include "runtime/anim/CameraPath.h"
#include "runtime/anim/ScenarioClock.h"
#include "runtime/anim/TimeLabel.h"
#include "runtime/app/FrameStats.h"
#include "runtime/color/Legend.h"
#include "runtime/core/Result.h"
#include "runtime/gl/Context.h"
#include "runtime/render/OverlayLayout.h"
#include "runtime/gl/RenderTarget.h"
#include "runtime/render/OverlayRenderer.h"
#include "runtime/scene/TerrainScene.h"

namespace kiosk::app {

/**
 * @brief One loaded scenario ready to draw: the typed scenario, its terrain scene, overlays and
 * camera. Shared by `render` and `play`. Render thread only.
 */
class Session {
public:
    /** @brief Read and check the scenario, open its stores, build GL resources. */
    static Result<std::unique_ptr<Session>> open(const std::filesystem::path& scenarioPath,
                                                 const gl::Caps& caps);
    /** @brief Same, letting a caller adjust the checked scenario first (benchmarks, tests). */
    static Result<std::unique_ptr<Session>> open(
        const std::filesystem::path& scenarioPath, const gl::Caps& caps,
        const std::function<void(config::Scenario&)>& adjust);
    /**
     * @brief The first half of open(), any thread and no GL: read the scenario and check it
     * against its stores (play's reload worker runs this off the frame loop).
     */
    static Result<std::unique_ptr<config::Scenario>> readChecked(
        const std::filesystem::path& scenarioPath);
    /** @brief Log the warnings readChecked() returned with its scenario, as open() says them. */
    static void sayWarnings(const Diagnostics& warnings);
    /** @brief The second half, render thread: GL resources for a scenario readChecked passed. */
    static Result<std::unique_ptr<Session>> create(
        std::unique_ptr<config::Scenario> scenario, const gl::Caps& caps,
        const std::function<void(config::Scenario&)>& adjust = nullptr);

    const config::Scenario& scenario() const noexcept { return *mScenario; }
    scene::TerrainScene& terrain() noexcept { return *mScene; }

    /** @brief Scenario start/end in epoch seconds (from the clock, else the sequences). */
    double startTime() const noexcept { return mStart; }
    double endTime() const noexcept { return mEnd; }
    /** @brief The scenario's clock (rate, range, wait, paused) over [startTime, endTime]. */
    anim::ClockSettings clockSettings() const;

    /**
     * @brief The camera at data time `time`: `viewpoint` if named, else the scenario's camera
     * path, else its initial viewpoint, else an overview of the data.
     */
    Result<math::Viewpoint> viewpointAt(double time, const std::string& viewpoint) const;

    /** @brief A line shown on screen until replaced (e.g. why a scenario edit was refused). */
    void setNotice(std::string notice) { mNotice = std::move(notice); }
    /** @brief Black drawn over everything with this opacity (playlist fades; 0: none). */
    void setCurtain(float alpha) { mCurtain = alpha; }

    /** @brief Select and load tiles for the view without drawing (render waits with this). */
    void prepare(const math::Camera& camera, double time) {
        mScene->update(camera, time, mPlayback);
    }
    /** @brief How the clock plays (rate, range, seeks): sizes the sequences' prefetch. */
    void setPlayback(const scene::Playback& playback) { mPlayback = playback; }

    /**
     * @brief Display walls (runtime/app/WallScreen): which of the legend, time label and title
     * this output draws, each laid out in its own box (pixels, top-left origin; w == 0: the
     * whole output), so no overlay straddles a bezel. nullopt: all, over the whole output.
     * `corner`: the box's anchor corner (a canvas anchor), in place of the scenario's position.
     */
    struct OverlayBox {
        bool shown = true;
        int x = 0, y = 0, w = 0, h = 0;
        std::optional<config::Corner> corner;
    };
    struct OverlayLayout {
        OverlayBox legend, timeLabel, title;
    };
    void setOverlayLayout(std::optional<OverlayLayout> layout) { mOverlayLayout = layout; }

    /**
     * @brief Briefing chapter `index` on (-1: none): its layer overrides apply at once, its
     * camera (viewpoint or path) replaces the scenario's in viewpointAt(), its caption shows.
     * (SessionBriefing.cpp)
     */
    void setChapter(int index);
    const config::Chapter* chapter() const noexcept;
    int chapterIndex() const noexcept { return mChapter; }
    /** @brief The briefing's chapters in numbers (data spans, playback seconds, pauses). */
    const std::vector<anim::ChapterSpan>& chapterSpans() const noexcept { return mChapterSpans; }
    /** @brief Budgets in effect (cache, uploads, prefetch, memory) for `--stats`. */
    std::vector<std::pair<std::string, double>> budgets() const;  // SessionBudgets.cpp
    /** @brief Bytes held now against the memory budgets (kiosk /metrics, `--stats`). */
    struct MemoryUsage {
        std::uint64_t lutBytes = 0, mappingBytes = 0, fontAtlasBytes = 0;
    };
    MemoryUsage memoryUsage() const;

    /** @brief Update tiles for the view and draw terrain + overlays into the bound framebuffer. */
    FrameRecord drawFrame(const math::Camera& camera, double time, int width, int height);

    /**
     * @brief Fraction of the output size (per axis) the terrain is rendered at, then stretched
     * (the frame-rate governor's last lever; `play` only). 1 = full size.
     */
    void setRenderScale(double scale);
    double renderScale() const noexcept { return mRenderScale; }

private:
    Session() = default;
    void drawOverlays(double time, int width, int height);
    void drawLegend(const config::LegendOverlay& legend, std::size_t index);
    void drawCaption(int width, int height);
    void wrapCaption(const std::string& caption, float maxText);
    std::optional<anim::CameraPath> buildPath(const std::string& name) const;
    void setupBriefing();
    std::vector<anim::ChapterSpan> computeChapterSpans() const;
    std::optional<math::Viewpoint> chapterViewpoint(double time) const;
    bool bindScaledTarget(int width, int height, int& outFbo);
    /** @brief The text size drawn for `wantedPx` under the font atlas budget (0: no text). */
    int budgetedFontPx(int wantedPx);
    /** @brief drawOverlays() once per wall overlay box (SessionWall.cpp). */
    void drawWallOverlays(double time, int width, int height);

    std::unique_ptr<config::Scenario> mScenario;
    std::unique_ptr<scene::TerrainScene> mScene;
    std::optional<render::OverlayRenderer> mOverlay;
    int mOverlayFontPx = 0;
    std::uint64_t mFontAtlasBytes = 0;  ///< atlas of mOverlay (CPU copy + GPU texture)
    int mFontWarnedPx = 0;              ///< wanted size the budget warning was logged for
    std::string mNotice;
    /** @brief A legend's title, ticks and patches: they depend only on the scenario, so they
     * are made once (per overlays.legend entry) and drawn every frame. */
    struct LegendText {
        const config::TransferFunctionDef* def = nullptr;  ///< made for this function
        std::string layer, givenTitle;                     ///< and this layer and title
        std::string title;
        std::vector<color::LegendTick> ticks;
        std::vector<color::LegendPatch> patches;
    };
    std::vector<LegendText> mLegendText;
    float mCurtain = 0.0f;
    std::optional<OverlayLayout> mOverlayLayout;
    /** @brief Which overlays drawOverlays() draws (bits below) and the output height its font
     * follows (0: the height it is given); set per box by drawWallOverlays(). */
    unsigned mOverlayOnly = ~0u;
    int mOverlayFontHeight = 0;
    std::optional<config::Corner> mOverlayCorner;  ///< replaces the scenario's position (wall box)
    static constexpr unsigned kOverlayLegend = 1, kOverlayTimeLabel = 2, kOverlayTitle = 4,
                              kOverlayStatus = 8;
    anim::CameraPath mPath;
    anim::TimeZone mZone;
    double mStart = 0, mEnd = 0;
    scene::Playback mPlayback;
    render::OverlayLayout mLayout;
    std::map<std::string, gl::Texture> mLegendLuts;  ///< mapping transfer functions' legends
    std::vector<std::string> mCaptionLines;          ///< reused by drawCaption
    std::map<std::string, anim::CameraPath> mChapterPaths;
    std::vector<anim::ChapterSpan> mChapterSpans;
    int mChapter = -1;
    int mCaptionChapter = -1, mCaptionWidth = 0, mCaptionFontPx = 0;  ///< what mCaptionLines wraps
    double mRenderScale = 1.0;
    std::optional<gl::RenderTarget> mScaled;  ///< terrain target while mRenderScale < 1
};

/** @brief Camera for a viewpoint with clip planes fitted to the scene. */
math::Camera makeCamera(const math::Viewpoint& vp, const math::Aabb& bounds, int width, int height,
                        double fovY);

}  // namespace kiosk::app
