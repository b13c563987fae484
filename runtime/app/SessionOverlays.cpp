// Session's 2D overlays: title, time label, progress bar, legend, chapter caption, status lines,
// each at the position the scenario gives it (docs/scenario-format.md, "Overlays").
#include "runtime/app/Session.h"
#include "runtime/color/Legend.h"
#include "runtime/core/Log.h"
#include "runtime/render/Textures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace kiosk::app {
namespace {

constexpr const char* kTag = "app::Session";
const glm::vec4 kPanel(0.05f, 0.07f, 0.1f, 0.72f);
const glm::vec4 kText(1.0f, 1.0f, 1.0f, 1.0f);
const glm::vec4 kDim(0.8f, 0.84f, 0.9f, 1.0f);
const glm::vec4 kWarn(1.0f, 0.75f, 0.3f, 1.0f);
constexpr float kMargin = 12.0f;  // panels from the frame's edges
constexpr float kGap = 8.0f;      // between panels sharing an edge
/** Captions stay inside the title-safe area (5 % of each side, SMPTE RP 2046-1). */
constexpr float kSafeFraction = 0.05f;
/** A caption wraps at this share of the width, so the corners stay free for the other panels. */
constexpr float kCaptionWidthFraction = 0.6f;

render::Anchor anchorOf(config::Corner c) {
    switch (c) {
        case config::Corner::TopLeft:
            return render::Anchor::TopLeft;
        case config::Corner::TopRight:
            return render::Anchor::TopRight;
        case config::Corner::BottomLeft:
            return render::Anchor::BottomLeft;
        case config::Corner::BottomRight:
            return render::Anchor::BottomRight;
        case config::Corner::Top:
            return render::Anchor::Top;
        case config::Corner::Bottom:
            return render::Anchor::Bottom;
    }
    return render::Anchor::TopLeft;
}

}  // namespace

void Session::drawOverlays(double time, int width, int height) {
    // Text scales with the output: legible on a wall at 4K, not covering a 320-pixel preview.
    const int fontPx =
        std::clamp((mOverlayFontHeight > 0 ? mOverlayFontHeight : height) / 40, 10, 40);
    if (fontPx != mOverlayFontPx) {
        mOverlayFontPx = fontPx;
        mOverlay.reset();
        const int px = budgetedFontPx(fontPx);  // budgets.fontAtlasBytes
        if (px <= 0) return;
        auto overlay = render::OverlayRenderer::create(render::FontAtlas::defaultFontPath(), px);
        if (overlay)
            mOverlay.emplace(std::move(*overlay.value));
        else  // no text is no reason to leave the display dark
            KIOSK_LOG_WARN(kTag, "overlays disabled: %s", overlay.diagnostics.format().c_str());
    }
    if (!mOverlay) return;
    auto& o = *mOverlay;
    const auto& sc = *mScenario;
    const auto& ov = sc.overlays;
    const float line = float(o.font().lineHeight());
    const float ascent = float(o.font().ascent());
    o.begin(width, height);
    mLayout.begin(width, height, kMargin, kGap);
    // The time label is placed first: when it and the title share an edge and do not fit side
    // by side (narrow previews, long titles), the title moves clear of it.
    // Tiles late: a sequence holds an older step. Label the time actually drawn and say so.
    const auto& frameInfo = mScene->frameInfo();
    const bool buffering = frameInfo.holdingSequence;
    if (buffering && !std::isnan(frameInfo.heldDataTime)) time = frameInfo.heldDataTime;
    // On a wall, drawWallOverlays() draws each overlay in its own box (mOverlayOnly bits).
    const auto at = [&](config::Corner c) { return anchorOf(mOverlayCorner.value_or(c)); };
    if ((mOverlayOnly & kOverlayTimeLabel) && ov.timeLabel.enabled && mEnd > mStart) {
        // Formatted into fixed buffers: the label changes every frame and the frame loop must
        // not allocate (tests/scenario/FrameAllocGLTest.cpp).
        char label[192];
        const std::size_t n =
            anim::formatTimeLabel(label, 128, time, mStart, ov.timeLabel.format, mZone);
        std::size_t len = std::min<std::size_t>(n, 127);
        if (buffering)
            len += std::size_t(std::snprintf(label + len, sizeof label - len, "  buffering"));
        const std::string_view shown(label, len);
        if (ov.timeLabel.showOffset && shown.find("T+") == std::string_view::npos &&
            shown.find("T-") == std::string_view::npos) {
            char elapsed[64];
            anim::formatElapsed(elapsed, sizeof elapsed, time - mStart);
            std::snprintf(label + len, sizeof label - len, "  (%s)", elapsed);
        }
        const float w = o.measure(label) + 24.0f;
        const render::Box b = mLayout.place(at(ov.timeLabel.position), w, line + 16);
        o.rect(b.x, b.y, b.w, b.h, kPanel);
        o.text(b.x + 12, b.y + 8 + ascent, label, kText);
    }
    if ((mOverlayOnly & kOverlayTitle) && ov.title.enabled &&
        (!sc.title.empty() || !sc.caption.empty())) {
        const float w = std::max(o.measure(sc.title), o.measure(sc.caption)) + 24.0f;
        const float h = (sc.caption.empty() ? 1.0f : 2.0f) * line + 16.0f;
        const render::Box b = mLayout.place(at(ov.title.position), w, h);
        o.rect(b.x, b.y, b.w, b.h, kPanel);
        o.text(b.x + 12, b.y + 8 + ascent, sc.title, kText);
        if (!sc.caption.empty()) o.text(b.x + 12, b.y + 8 + line + ascent, sc.caption, kDim);
    }
    if ((mOverlayOnly & kOverlayTimeLabel) && ov.progress.enabled && mEnd > mStart) {
        // A thin bar along the top or bottom edge (its position's vertical half).
        const bool top = ov.progress.position == config::Corner::Top ||
                         ov.progress.position == config::Corner::TopLeft ||
                         ov.progress.position == config::Corner::TopRight;
        const float y = top ? 6.0f : float(height) - 10.0f;
        const float frac = float(std::clamp((time - mStart) / (mEnd - mStart), 0.0, 1.0));
        o.rect(12, y, float(width) - 24, 4, glm::vec4(1, 1, 1, 0.3f));
        o.rect(12, y, (float(width) - 24) * frac, 4, kText);
    }
    if (mOverlayOnly & kOverlayLegend)
        for (std::size_t i = 0; i < ov.legends.size(); ++i)
            if (ov.legends[i].enabled) drawLegend(ov.legends[i], i);
    if (!(mOverlayOnly & kOverlayStatus)) {  // a wall box of one overlay only
        // The chapter caption goes with the title (on a wall: once, in the title's box).
        if (mOverlayOnly & kOverlayTitle) drawCaption(width, height);
        o.end();
        return;
    }
    // Layer problems are always shown: an operator must see why a layer is missing.
    const render::Anchor statusAt = anchorOf(ov.status.position);
    auto statusLine = [&](std::string_view text, const glm::vec4& color) {
        const render::Box b = mLayout.place(statusAt, o.measure(text) + 16, line + 6);
        o.rect(b.x, b.y, b.w, b.h, kPanel);
        o.text(b.x + 8, b.y + line - 4, text, color);
    };
    // Status texts go through fixed buffers (no allocation per frame), long ones shortened.
    char text[192];
    if (!mNotice.empty()) {
        const bool cut = mNotice.size() > 160;
        std::snprintf(text, sizeof text, "%.*s%s", cut ? 157 : 160, mNotice.c_str(),
                      cut ? "..." : "");
        statusLine(text, kWarn);
    }
    // Procedural detail is decoration: labelled whenever it is on screen (docs/terrain.md §7).
    if (mScene->frameInfo().proceduralDetail)
        statusLine("procedural detail: decoration below the data's resolution", kText);
    // The frame-rate governor at work (play): say what it trades, so nobody mistakes the
    // coarser picture for the scenario's.
    const bool governed = sc.terrain.reference == config::TerrainReference::Lod &&
                          (mScene->tauGeom() != sc.terrain.tauGeom ||
                           mScene->tauTex() != sc.terrain.tauTex || mRenderScale < 1.0);
    if (governed) {
        std::snprintf(text, sizeof text,
                      "frame-rate governor: tauGeom %.3g px (scenario %.3g), tauTex %.3g px (%.3g), "
                      "render scale %.2f",
                      mScene->tauGeom(), sc.terrain.tauGeom, mScene->tauTex(), sc.terrain.tauTex,
                      mRenderScale);
        statusLine(text, kDim);
    }
    for (const auto& st : mScene->layerStatus()) {
        if (st.state == scene::LayerState::Ready && !ov.status.enabled) continue;
        const int n = std::snprintf(text, sizeof text, "%s: %s%s%s", st.id.c_str(),
                                    scene::layerStateName(st.state),
                                    st.message.empty() ? "" : " - ", st.message.c_str());
        if (n > 140) std::snprintf(text + 137, sizeof text - 137, "...");
        statusLine(text, st.state == scene::LayerState::Ready ? kDim : kWarn);
    }
    if (mOverlayOnly & kOverlayTitle) drawCaption(width, height);
    if (mCurtain > 0.0f) o.rect(0, 0, float(width), float(height), glm::vec4(0, 0, 0, mCurtain));
    o.end();
}

void Session::drawCaption(int width, int height) {
    const config::Chapter* c = chapter();
    if (!c) return;
    auto& o = *mOverlay;
    const float line = float(o.font().lineHeight());
    const float ascent = float(o.font().ascent());
    const float maxText = float(width) * kCaptionWidthFraction - 24.0f;
    // Greedy word wrap of each caption line at the caption width, once per chapter and size.
    if (mCaptionChapter != mChapter || mCaptionWidth != width || mCaptionFontPx != mOverlayFontPx) {
        mCaptionChapter = mChapter;
        mCaptionWidth = width;
        mCaptionFontPx = mOverlayFontPx;
        wrapCaption(c->caption, maxText);
    }
    float w = o.measure(c->title);
    for (const auto& l : mCaptionLines) w = std::max(w, o.measure(l));
    w = std::min(w, maxText) + 24.0f;
    const float h = line * float(1 + mCaptionLines.size()) + 16.0f;
    const float safe = float(height) * kSafeFraction;
    const render::Box b = mLayout.place(render::Anchor::Bottom, w, h, std::max(safe, kMargin));
    o.rect(b.x, b.y, b.w, b.h, kPanel);
    o.text(b.x + 12, b.y + 8 + ascent, c->title, kText);
    float y = b.y + 8 + line + ascent;
    for (const auto& l : mCaptionLines) {
        o.text(b.x + 12, y, l, kDim);
        y += line;
    }
}

void Session::wrapCaption(const std::string& caption, float maxText) {
    const auto& o = *mOverlay;
    mCaptionLines.clear();
    std::size_t start = 0;
    while (start <= caption.size() && !caption.empty()) {
        const std::size_t nl = std::min(caption.find('\n', start), caption.size());
        std::string current;
        std::size_t p = start;
        while (p < nl) {
            const std::size_t sp = std::min(caption.find(' ', p), nl);
            const std::string word = caption.substr(p, sp - p);
            const std::string tried = current.empty() ? word : current + " " + word;
            if (!current.empty() && o.measure(tried) > maxText) {
                mCaptionLines.push_back(current);
                current = word;
            } else {
                current = tried;
            }
            p = sp + 1;
        }
        mCaptionLines.push_back(current);
        start = nl + 1;
    }
}

void Session::drawLegend(const config::LegendOverlay& legend, std::size_t index) {
    auto& o = *mOverlay;
    const config::TransferFunctionDef* def = mScenario->findTransfer(legend.transfer);
    if (!def) return;
    // A layer's LUT texture when a layer uses the function; otherwise (a projective mapping's
    // transfer function) one built for the legend.
    GLuint texture = 0;
    if (const scene::SceneLut* lut = mScene->lut(legend.transfer)) {
        texture = lut->texture.id();
    } else {
        auto it = mLegendLuts.find(legend.transfer);
        if (it == mLegendLuts.end()) {
            const auto rgba = color::buildLut(def->function, color::kMinLutSize);
            it = mLegendLuts
                     .emplace(legend.transfer,
                              render::makeLutTexture(int(rgba.size() / 4), rgba.data()))
                     .first;
        }
        texture = it->second.id();
    }
    const color::TransferFunction& tf = def->function;
    if (mLegendText.size() <= index) mLegendText.resize(index + 1);
    LegendText& text = mLegendText[index];
    if (text.def != def || text.layer != legend.layer || text.givenTitle != legend.title) {
        text.def = def;
        text.layer = legend.layer;
        text.givenTitle = legend.title;
        const std::string kindTitle =
            legend.layer.empty() ? std::string() : mScene->legendTitle(legend.layer);
        text.title = !legend.title.empty() ? legend.title
                     : !kindTitle.empty()  ? kindTitle
                     : !def->label.empty() ? def->label
                                           : def->name;
        if (!tf.units.empty()) text.title += " (" + tf.units + ")";
        text.ticks = color::legendTicks(tf);
        text.patches = color::legendPatches(tf);
    }
    const std::string& title = text.title;
    const float line = float(o.font().lineHeight());
    const float ascent = float(o.font().ascent());
    const render::Anchor at = anchorOf(mOverlayCorner.value_or(legend.position));
    if (tf.discrete()) {
        const auto& patches = text.patches;
        float w = o.measure(title);
        for (const auto& p : patches) w = std::max(w, 28 + o.measure(p.label));
        const float h = line * float(patches.size() + 1) + 20;
        const render::Box b = mLayout.place(at, w + 24, h);
        o.rect(b.x, b.y, b.w, b.h, kPanel);
        o.text(b.x + 12, b.y + 8 + ascent, title, kText);
        float py = b.y + 8 + line;
        for (const auto& p : patches) {
            o.rect(b.x + 12, py + 3, 18, line - 6,
                   glm::vec4(p.color.r, p.color.g, p.color.b, 1.0f));
            o.text(b.x + 40, py + ascent, p.label, kText);
            py += line;
        }
        return;
    }
    const float barW = line * 12.0f, barH = line * 0.8f;
    const float w = std::max(barW, o.measure(title)) + 24;
    const float h = line * 2 + barH + 28;
    const render::Box b = mLayout.place(at, w, h);
    o.rect(b.x, b.y, b.w, b.h, kPanel);
    o.text(b.x + 12, b.y + 8 + ascent, title, kText);
    const float barX = b.x + 12, barY = b.y + 12 + line;
    o.image(barX, barY, barW, barH, texture);
    for (const auto& t : text.ticks) {
        const float tx = barX + float(t.position) * barW;
        o.rect(tx - 0.5f, barY + barH, 1, 5, kText);
        const float tw = o.measure(t.label);
        o.text(std::clamp(tx - tw / 2, barX - 6, barX + barW - tw + 6), barY + barH + 6 + ascent,
               t.label, kText);
    }
}

}  // namespace kiosk::app
