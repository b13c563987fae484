// Overlay settings that the scenario parses do what they say (issue 18): the legend goes where
// `position` puts it, `title.enabled: false` leaves no title pixels, `timeLabel.position` moves
// the time label, and a projective mapping's transfer function gets its legend. Each case draws
// the same frame with and without the overlay and looks at where the pictures differ.
#include "runtime/app/Session.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/SettleView.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;
constexpr int kW = 480, kH = 270;

/** Bounding box of the pixels where two images differ; empty (w == 0) if none. */
struct DiffBox {
    int x0 = kW, y0 = kH, x1 = -1, y1 = -1;
    int count = 0;
    bool empty() const { return count == 0; }
};

DiffBox diff(const gl::Image& a, const gl::Image& b) {
    DiffBox d;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const auto *p = a.pixel(x, y), *q = b.pixel(x, y);
            if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) continue;
            ++d.count;
            d.x0 = std::min(d.x0, x);
            d.y0 = std::min(d.y0, y);
            d.x1 = std::max(d.x1, x);
            d.y1 = std::max(d.y1, y);
        }
    return d;
}

class OverlaySettings : public test::EglTest {
protected:
    /** The frame of `scenario` at +3 h from `viewpoint`, after `adjust` changed the scenario. */
    gl::Image frame(const std::string& scenario, const std::string& viewpoint,
                    const std::function<void(config::Scenario&)>& adjust) {
        auto rt = gl::RenderTarget::create(kW, kH);
        EXPECT_TRUE(rt.ok());
        auto s = Session::open(scenario, mCaps, adjust);
        EXPECT_TRUE(s.ok()) << s.diagnostics.format();
        if (!s.ok() || !rt.ok()) return {};
        Session& session = **s;
        const double t = session.startTime() + 900;
        auto vp = session.viewpointAt(t, viewpoint);
        EXPECT_TRUE(vp.ok());
        const math::Camera cam = makeCamera(*vp, session.terrain().bounds(), kW, kH, 45);
        test::settleView(session, cam, t);
        rt->bind();
        session.drawFrame(cam, t, kW, kH);
        return rt->readColor();
    }
    void SetUp() override {
        test::EglTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        if (!fs::exists("data/generated/rainier.gpkg"))
            KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_DATA",
                               "demo store missing: run tools/prepare-demo.sh");
    }
    const std::string kDemo = "scenarios/demo/rainier.json";
};

TEST_F(OverlaySettings, LegendPositionMovesTheLegend) {
    const gl::Image none =
        frame(kDemo, "overview", [](config::Scenario& s) { s.overlays.legends.clear(); });
    const gl::Image bottomRight = frame(kDemo, "overview", [](config::Scenario& s) {
        s.overlays.legends.at(0).position = config::Corner::BottomRight;
    });
    const gl::Image topLeft = frame(kDemo, "overview", [](config::Scenario& s) {
        s.overlays.legends.at(0).position = config::Corner::TopLeft;
    });
    const DiffBox br = diff(none, bottomRight), tl = diff(none, topLeft);
    ASSERT_FALSE(br.empty());
    ASSERT_FALSE(tl.empty());
    EXPECT_GT(br.x0, kW / 2);
    EXPECT_GT(br.y0, kH / 2);
    EXPECT_LT(tl.x1, kW / 2);
    // At top-left it stacks below the title panel (itself below the time label at this width)
    // rather than covering it.
    EXPECT_GT(tl.y0, 90);
    EXPECT_LT(tl.y1, kH * 2 / 3);
}

TEST_F(OverlaySettings, DisabledTitleHasNoTitlePixels) {
    const gl::Image shown = frame(kDemo, "overview", nullptr);
    const gl::Image disabled =
        frame(kDemo, "overview", [](config::Scenario& s) { s.overlays.title.enabled = false; });
    const gl::Image untitled = frame(kDemo, "overview", [](config::Scenario& s) {
        s.title.clear();
        s.caption.clear();
    });
    // Disabled is exactly the picture of a scenario without any title or caption ...
    EXPECT_TRUE(diff(disabled, untitled).empty());
    // ... and the title panel (top-left) is what disabling removed.
    const DiffBox d = diff(shown, disabled);
    ASSERT_FALSE(d.empty());
    EXPECT_LT(d.x0, 20);
    EXPECT_LT(d.x1, kW * 3 / 4);
    EXPECT_LT(d.y1, kH / 2);
    EXPECT_GT(d.count, 3000);  // a panel with two lines of text
}

TEST_F(OverlaySettings, TimeLabelPositionMovesTheLabel) {
    const gl::Image none =
        frame(kDemo, "overview", [](config::Scenario& s) { s.overlays.timeLabel.enabled = false; });
    const gl::Image bottomLeft = frame(kDemo, "overview", [](config::Scenario& s) {
        s.overlays.timeLabel.position = config::Corner::BottomLeft;
    });
    const DiffBox d = diff(none, bottomLeft);
    ASSERT_FALSE(d.empty());
    EXPECT_LT(d.x1, kW / 2 + 40);  // the label is about 200 px wide at this size
    EXPECT_GT(d.y0, kH / 2);
}

TEST_F(OverlaySettings, ProjectiveMappingTransferFunctionHasALegend) {
    const std::string hazard = "scenarios/mappings/hazard.json";
    const gl::Image with = frame(hazard, "", nullptr);
    const gl::Image without =
        frame(hazard, "", [](config::Scenario& s) { s.overlays.legends.clear(); });
    const DiffBox d = diff(without, with);
    ASSERT_FALSE(d.empty()) << "the hazard transfer function's legend is missing";
    EXPECT_GT(d.x0, kW / 2);
    EXPECT_GT(d.y0, kH / 2);
    EXPECT_GT(d.count, 2000);  // a panel, not a stray pixel
}

// A difference layer's own legend (overlays.legend.layer naming it, as the shipped difference
// scenario does): a box bottom right whose colour bar shows the diverging function's swatches,
// A < B (blue) left of A = B (white) left of A > B (red), titled by the kind ("Difference runA -
// runB (m)") instead of the function's label.
TEST_F(OverlaySettings, DifferenceLayerHasItsOwnLegend) {
    const std::string scenario = "scenarios/demo/rainier-compare-difference.json";
    const gl::Image with = frame(scenario, "flood", nullptr);
    const gl::Image without =
        frame(scenario, "flood", [](config::Scenario& s) { s.overlays.legends.clear(); });
    const gl::Image byName = frame(
        scenario, "flood", [](config::Scenario& s) { s.overlays.legends.at(0).layer.clear(); });
    const DiffBox d = diff(without, with);
    ASSERT_FALSE(d.empty()) << "the difference layer's legend is missing";
    EXPECT_GT(d.x0, kW / 2);
    EXPECT_GT(d.y0, kH / 2);
    // The swatches: on the legend's row with the most blue pixels, the first blue, white and red
    // pixels come in this order, each colour over at least 8 pixels.
    auto kindOf = [&](int x, int y) {
        const auto* p = with.pixel(x, y);
        const auto* q = without.pixel(x, y);
        if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) return 0;  // not the legend
        const int r = p[0], g = p[1], b = p[2];
        if (b > r + 60) return 1;                                             // A < B
        if (r > 170 && g > 170 && b > 170 && std::abs(r - b) < 40) return 2;  // A ~ B
        if (r > b + 60 && r > g + 60) return 3;                               // A > B
        return 0;
    };
    int barRow = -1, mostBlue = 0;
    for (int y = d.y0; y <= d.y1; ++y) {
        int blue = 0;
        for (int x = d.x0; x <= d.x1; ++x) blue += kindOf(x, y) == 1;
        if (blue > mostBlue) mostBlue = blue, barRow = y;
    }
    ASSERT_GE(barRow, 0) << "no blue swatch in the legend";
    int first[4] = {-1, -1, -1, -1}, count[4] = {0, 0, 0, 0};
    for (int x = d.x0; x <= d.x1; ++x) {
        const int k = kindOf(x, barRow);
        if (first[k] < 0) first[k] = x;
        ++count[k];
    }
    EXPECT_GE(count[1], 8);
    EXPECT_GE(count[2], 8);
    EXPECT_GE(count[3], 8);
    EXPECT_LT(first[1], first[2]);
    EXPECT_LT(first[2], first[3]);
    // The kind's title: not the function's label, exactly the legend titled by hand so.
    EXPECT_FALSE(diff(byName, with).empty()) << "the legend is titled by the function's label";
    const gl::Image titled = frame(scenario, "flood", [](config::Scenario& s) {
        s.overlays.legends.at(0).layer.clear();
        s.overlays.legends.at(0).title = "Difference runA - runB";
    });
    EXPECT_TRUE(diff(titled, with).empty());
}

// Several legends (overlays.legend as an array, as the shipped products scenario shows maximum
// depth and arrival time): each is drawn with its own colour bar, stacked in the corner they
// share rather than drawn over each other.
TEST_F(OverlaySettings, LegendArrayDrawsEveryLegendStacked) {
    const std::string scenario = "scenarios/demo/rainier-products.json";
    std::size_t given = 0;
    const gl::Image both =
        frame(scenario, "flood", [&](config::Scenario& s) { given = s.overlays.legends.size(); });
    ASSERT_EQ(given, 2u) << scenario << " no longer gives two legends";
    const gl::Image none =
        frame(scenario, "flood", [](config::Scenario& s) { s.overlays.legends.clear(); });
    // The scenario lists arrival first, then maximum depth.
    const gl::Image arrivalOnly =
        frame(scenario, "flood", [](config::Scenario& s) { s.overlays.legends.resize(1); });
    const gl::Image depthOnly = frame(scenario, "flood", [](config::Scenario& s) {
        s.overlays.legends.erase(s.overlays.legends.begin());
    });
    const DiffBox all = diff(none, both), depth = diff(none, depthOnly),
                  arrival = diff(none, arrivalOnly);
    ASSERT_FALSE(depth.empty()) << "the maximum depth legend is missing";
    ASSERT_FALSE(arrival.empty()) << "the arrival legend is missing";
    EXPECT_GT(all.x0, kW / 2);
    EXPECT_GT(all.y0, kH / 4);
    // Alone, each takes the corner; together, one sits above the other.
    EXPECT_GE(all.y1 - all.y0 + 2, (depth.y1 - depth.y0) + (arrival.y1 - arrival.y0));
    // Each colour bar: a band of at least 5 equal rows (within 3 DN: the ramp's opacity lets
    // the panel through) over at least 80 columns that varies along the row (the flood and the
    // terrain seen through a panel are never so). The depth ramp (#deebf7 to #08306b) is blue
    // on average, the arrival ramp (#fde725 to #57106e) warm.
    auto near = [](const std::uint8_t* p, const std::uint8_t* q, int tol) {
        return std::abs(p[0] - q[0]) <= tol && std::abs(p[1] - q[1]) <= tol &&
               std::abs(p[2] - q[2]) <= tol;
    };
    struct Bars {
        int blue = 0, warm = 0;
    };
    auto bars = [&](const gl::Image& img) {
        Bars out;
        for (int y = all.y0; y + 4 <= all.y1; ++y) {
            int run = 0, best = 0, bestEnd = 0;
            for (int x = all.x0; x <= all.x1; ++x) {
                bool same = true;
                for (int k = 1; k <= 4 && same; ++k)
                    same = near(img.pixel(x, y), img.pixel(x, y + k), 3);
                run = same ? run + 1 : 0;
                if (run > best) best = run, bestEnd = x;
            }
            if (best < 80) continue;
            long r = 0, b = 0;
            bool varies = false;
            for (int x = bestEnd - best + 1; x <= bestEnd; ++x) {
                r += img.pixel(x, y)[0];
                b += img.pixel(x, y)[2];
                varies |= !near(img.pixel(x, y), img.pixel(bestEnd, y), 40);
            }
            if (!varies) continue;
            (b > r ? out.blue : out.warm) += 1;
            y += 4;  // one band counts once per 5 rows
        }
        return out;
    };
    const Bars inBoth = bars(both), inDepth = bars(depthOnly), inArrival = bars(arrivalOnly),
               inNone = bars(none);
    EXPECT_GE(inBoth.blue, 1) << "no depth colour bar";
    EXPECT_GE(inBoth.warm, 1) << "no arrival colour bar";
    EXPECT_GE(inDepth.blue, 1);
    EXPECT_EQ(inDepth.warm, 0);
    EXPECT_EQ(inArrival.blue, 0);
    EXPECT_GE(inArrival.warm, 1);
    EXPECT_EQ(inNone.blue + inNone.warm, 0);
}

// A transfer function without "units" shows the units the store records for the data it
// colours (the demo's flood_depth is imported with --units m): its legend is the picture of the
// one that states "m", and unlike one whose units are cleared after opening.
TEST_F(OverlaySettings, LegendShowsTheStoresUnitsWhenTheScenarioGivesNone) {
    std::ifstream in(kDemo);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    const std::string store = "../../data/generated/rainier.gpkg";
    text.replace(text.find(store), store.size(), fs::absolute("data/generated/rainier.gpkg"));
    const fs::path dir = fs::temp_directory_path() / "geokiosk-legend-units";
    fs::create_directories(dir);
    std::ofstream(dir / "stated.json") << text;
    const std::string depthUnits = R"x("label": "Water depth (SYNTHETIC)",
      "units": "m",)x";
    const auto at = text.find(depthUnits);
    ASSERT_NE(at, std::string::npos) << "the demo's depth transfer function changed";
    text.replace(at, depthUnits.size(), R"x("label": "Water depth (SYNTHETIC)",)x");
    std::ofstream(dir / "none.json") << text;

    const gl::Image stated = frame((dir / "stated.json").string(), "overview", nullptr);
    const gl::Image adopted = frame((dir / "none.json").string(), "overview", nullptr);
    const gl::Image cleared =
        frame((dir / "none.json").string(), "overview",
              [](config::Scenario& s) { s.transferFunctions["depth"].function.units.clear(); });
    EXPECT_TRUE(diff(stated, adopted).empty());
    const DiffBox d = diff(adopted, cleared);
    ASSERT_FALSE(d.empty()) << "the legend shows no units";
    EXPECT_GT(d.x0, kW / 2);  // in the legend's title, bottom right
    EXPECT_GT(d.y0, kH / 2);
}

}  // namespace
}  // namespace kiosk::app
