// A projective mapping of a layer of the stack (issue 19: "the hazard projective-mapping example
// uses the live product"): the mapping shows the product's value at the data time, through its
// own transfer function, and follows seeks. A synthetic run on a flat bed whose value is uniform
// per frame and NOT monotonic (1, 4, 2, 5, 3, 0 at hours 0..5), so a maximum so far differs from
// the frame on screen and from the last frame (what the mapping used to show); the value a pixel
// must show is computed independently from the frame values (brute-force walk of the
// piecewise-linear series), and the colour from the transfer function.
#include "runtime/color/TransferFunction.h"
#include "tests/scenario/ComparisonFixture.h"

#include <cstdlib>
#include <cstring>

namespace kiosk::test {
namespace {

using namespace compare;

constexpr float kValues[kFrames] = {1, 4, 2, 5, 3, 0};

/** The maximum of the linearly interpolated series over [0, hours] (brute force). */
double maximumSoFar(double hours) {
    double best = -1e30;
    for (int i = 0; i <= 6000; ++i) {
        const double t = hours * i / 6000.0;
        const int k = std::min(int(std::floor(t)), kFrames - 2);
        const double a = std::clamp(t - k, 0.0, 1.0);
        best = std::max(best, (1 - a) * kValues[k] + a * kValues[k + 1]);
    }
    return best;
}

// The mapping covers the middle half of the data; the layer itself is drawn at opacity 0.
std::string mappedScenario() {
    const std::string text = scenario(
        R"({ "id": "max", "kind": "maximum", "source": { "store": "m", "sequence": "run" },
             "transfer": "reds", "operation": { "type": "opacity", "opacity": 0 } })",
        "");
    std::string s = text;
    s.replace(s.find(R"("stores": { "a": "a.gpkg", "b": "b.gpkg" })"),
              std::string(R"("stores": { "a": "a.gpkg", "b": "b.gpkg" })").size(),
              R"("stores": { "a": "a.gpkg", "b": "b.gpkg", "m": "m.gpkg" })");
    const std::string mapping = R"(, "projectiveMappings": [ { "id": "live", "layer": "max",
        "transfer": "reds", "origin": [500960, 4999040, 0], "u": [960, 0, 0], "v": [0, 960, 0] } ] })";
    s.replace(s.rfind('}'), 1, mapping);
    return s;
}

class MappingLiveLayer : public ComparisonTest {
protected:
    static void SetUpTestSuite() {
        ComparisonTest::SetUpTestSuite();
        if (sImport.empty()) sImport = makeRun(sDir, "m", [](int k) { return kValues[k]; });
    }
    gl::Image at(app::Session& s, double hours) {
        gl::Image image = settled(s, hours);
        EXPECT_FALSE(s.terrain().frameInfo().mixedSequenceFrames);
        return image;
    }
};

int maxDiff(const gl::Image& a, const gl::Image& b) {
    int worst = 0;
    for (std::size_t i = 0; i < std::min(a.rgba.size(), b.rgba.size()); ++i)
        worst = std::max(worst, std::abs(int(a.rgba[i]) - int(b.rgba[i])));
    return a.rgba.size() == b.rgba.size() ? worst : 255;
}

TEST_F(MappingLiveLayer, ShowsTheProductAtTheDataTimeInsideItsRectangle) {
    auto s = open("mapped.json", mappedScenario());
    ASSERT_TRUE(s);
    for (const auto& st : s->terrain().layerStatus())
        ASSERT_EQ(st.state, scene::LayerState::Ready) << st.id << ": " << st.message;
    const auto* tf = s->scenario().findTransfer("reds");
    ASSERT_NE(tf, nullptr);
    const math::Camera cam = camera(*s);
    const glm::ivec2 in = project(cam, kCentreX + 150, kCentreY - 200, kW, kH);
    const glm::ivec2 out = project(cam, kCentreX + 700, kCentreY - 700, kW, kH);  // outside
    // 0.5 h: the value on screen (2.5) is the maximum; 2 h: frame 2 shows 2, the maximum is 4;
    // 4.5 h: 5 (frame 3); the last frame, 0, is what a mapping of the sequence used to show.
    const double hours[] = {0.5, 2.0, 4.5};
    std::vector<gl::Image> images;
    for (double h : hours) {
        images.push_back(at(*s, h));
        const double want = maximumSoFar(h);
        const color::Rgba c = tf->function.evaluate(want);
        const std::uint8_t* got = images.back().pixel(in.x, in.y);
        const double rgb[3] = {c.r * 255.0, c.g * 255.0, c.b * 255.0};
        for (int k = 0; k < 3; ++k)
            EXPECT_LE(std::abs(double(got[k]) - rgb[k]), 1.5)
                << "at " << h << " h channel " << k << ": maximum so far " << want;
    }
    for (std::size_t i = 1; i < images.size(); ++i) {
        const std::uint8_t* a = images[i - 1].pixel(in.x, in.y);
        const std::uint8_t* b = images[i].pixel(in.x, in.y);
        EXPECT_GT(std::abs(int(a[0]) - int(b[0])), 20) << "the mapped product did not change";
        // Outside the rectangle the mapping draws nothing: the bed's colour, whatever the time.
        EXPECT_EQ(std::memcmp(images[i - 1].pixel(out.x, out.y), images[i].pixel(out.x, out.y), 3),
                  0);
    }
    int apart = 0;  // inside the rectangle the mapping draws, outside the bare bed
    for (int c = 0; c < 3; ++c)
        apart = std::max(apart, std::abs(int(images[2].pixel(in.x, in.y)[c]) -
                                         int(images[2].pixel(out.x, out.y)[c])));
    EXPECT_GT(apart, 40);
}

TEST_F(MappingLiveLayer, SeekBackShowsTheStraightReplayPixels) {
    gl::Image straight;
    {
        auto s = open("mapped.json", mappedScenario());
        ASSERT_TRUE(s);
        straight = at(*s, 2.5);
    }
    auto s = open("mapped.json", mappedScenario());
    ASSERT_TRUE(s);
    const gl::Image later = at(*s, 4.5);
    const gl::Image back = at(*s, 2.5);
    EXPECT_GT(maxDiff(later, straight), 20) << "the two times look alike: the test proves nothing";
    EXPECT_EQ(maxDiff(back, straight), 0) << "a seek back shows another product than a replay";
}

}  // namespace
}  // namespace kiosk::test
