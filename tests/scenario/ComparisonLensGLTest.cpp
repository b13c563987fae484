// The comparison lens (issue 19): inside a circle, an ellipse or on one side of a swipe line the
// screen shows run B's layer stack, elsewhere run A's, at the same data time; and a difference
// layer (A - B) draws the diverging transfer function's LUT colour of A - B within 1 DN.
#include "runtime/color/TransferFunction.h"
#include "tests/scenario/ComparisonFixture.h"

#include <cstdlib>

namespace kiosk::test {
namespace {

using namespace compare;

int maxDiff(const std::uint8_t* a, const std::uint8_t* b) {
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a[c]) - int(b[c])));
    return d;
}

class ComparisonLens : public ComparisonTest {
protected:
    /**
     * Render `lens` over both runs at step 2 and check a 15 x 15 grid of scene points over the
     * data: where `inside(x, y)` (signed distance in metres, > 0 inside) is clearly positive the
     * pixel is the B-only render's, clearly negative the A-only render's.
     */
    template <class Inside>
    void check(const std::string& lens, Inside inside) {
        auto a = open("a-only.json", scenario(runLayer("A", "a", "reds"), ""));
        auto b = open("b-only.json", scenario(runLayer("B", "b", "blues"), ""));
        auto l = open("lens.json", scenario(kRuns, lens));
        ASSERT_TRUE(a && b && l);
        const gl::Image ia = settled(*a, 2), ib = settled(*b, 2), il = settled(*l, 2);
        for (const auto& st : l->terrain().layerStatus())
            EXPECT_EQ(st.state, scene::LayerState::Ready) << st.id << ": " << st.message;
        const math::Camera cam = camera(*l);
        int in = 0, out = 0;
        for (int i = 0; i < 15; ++i)
            for (int j = 0; j < 15; ++j) {
                const double x = kWest + kSize * (i + 0.5) / 15,
                             y = kNorth - kSize * (j + 0.5) / 15;
                const double d = inside(x, y);
                if (std::abs(d) < 60) continue;  // the edge: a few pixels either way
                const glm::ivec2 p = project(cam, x, y, kW, kH);
                ASSERT_TRUE(p.x >= 0 && p.x < kW && p.y >= 0 && p.y < kH);
                const auto* want = (d > 0 ? ib : ia).pixel(p.x, p.y);
                const auto* other = (d > 0 ? ia : ib).pixel(p.x, p.y);
                ASSERT_GT(maxDiff(want, other), 40) << "A and B must look different";
                EXPECT_LE(maxDiff(il.pixel(p.x, p.y), want), 1)
                    << (d > 0 ? "inside" : "outside") << " at " << x << ", " << y;
                ++(d > 0 ? in : out);
            }
        EXPECT_GT(in, 10);
        EXPECT_GT(out, 10);
    }
};

TEST_F(ComparisonLens, CircleShowsRunBInsideRunAOutside) {
    check(R"({ "id": "cmp", "kind": "comparison", "center": [500960, 4999040], "radius": 500,
               "inside": ["B"], "outside": ["A"] })",
          [](double x, double y) { return 500 - std::hypot(x - kCentreX, y - kCentreY); });
}

TEST_F(ComparisonLens, EllipseShowsRunBInsideRunAOutside) {
    const double a = 30.0 * M_PI / 180.0;
    check(R"({ "id": "cmp", "kind": "comparison", "shape": "ellipse", "center": [500700, 4999300],
               "radii": [700, 300], "rotation": 30, "inside": ["B"], "outside": ["A"] })",
          [a](double x, double y) {
              const double dx = x - 500700, dy = y - 4999300;
              const double u = std::cos(a) * dx + std::sin(a) * dy;
              const double v = -std::sin(a) * dx + std::cos(a) * dy;
              // Approximate metres from the border along the minor axis scale.
              return 300.0 * (1.0 - std::hypot(u / 700.0, v / 300.0));
          });
}

TEST_F(ComparisonLens, SwipeShowsRunBOnOneSideRunAOnTheOther) {
    const double a = 20.0 * M_PI / 180.0;
    check(R"({ "id": "cmp", "kind": "comparison", "shape": "swipe", "center": [501100, 4999040],
               "rotation": 20, "inside": ["B"], "outside": ["A"] })",
          [a](double x, double y) {
              return std::cos(a) * (x - 501100) + std::sin(a) * (y - 4999040);
          });
}

/** The colour the GPU draws for value v: the LUT (linear filtering between texel centres). */
glm::dvec3 lutColour(const color::TransferFunction& tf, double v) {
    const auto lut = color::buildLut(tf, color::kMinLutSize);
    const int n = int(lut.size() / 4);
    const double u = std::clamp((v - tf.domainMin) / (tf.domainMax - tf.domainMin), 0.0, 1.0);
    const double texel = std::clamp(u * (n - 1), 0.0, double(n - 1));
    const int i0 = int(std::floor(texel)), i1 = std::min(i0 + 1, n - 1);
    const double f = texel - i0;
    glm::dvec3 c;
    for (int k = 0; k < 3; ++k)
        c[k] = (1 - f) * lut[std::size_t(i0 * 4 + k)] + f * lut[std::size_t(i1 * 4 + k)];
    return c;
}

TEST_F(ComparisonLens, DifferenceIsTheDivergingLutOfAMinusB) {
    // A and B drawn at opacity 0 (sources of the difference only); the difference everywhere.
    const std::string hidden = R"(, "operation": { "type": "opacity", "opacity": 0 })";
    auto s =
        open("diff.json", scenario(runLayer("A", "a", "reds", hidden) + ", " +
                                       runLayer("B", "b", "blues", hidden) +
                                       R"(, { "id": "A-B", "kind": "difference", "of": ["A", "B"],
                                      "transfer": "diff" })",
                                   ""));
    ASSERT_TRUE(s);
    const auto* tf = s->scenario().findTransfer("diff");
    ASSERT_NE(tf, nullptr);
    const math::Camera cam = camera(*s);
    const glm::ivec2 p = project(cam, kCentreX + 200, kCentreY - 300, kW, kH);
    int distinct = 0;
    glm::dvec3 previous(-1.0);
    for (int k = 0; k < kFrames; ++k) {
        const gl::Image img = settled(*s, k);
        const glm::dvec3 want = lutColour(tf->function, double(valueA(k)) - double(valueB(k)));
        const auto* got = img.pixel(p.x, p.y);
        for (int c = 0; c < 3; ++c)
            EXPECT_LE(std::abs(double(got[c]) - want[c]), 1.0 + 1e-9)
                << "step " << k << " channel " << c << ": A - B = " << valueA(k) - valueB(k);
        distinct += glm::length(want - previous) > 8 ? 1 : 0;
        previous = want;
    }
    EXPECT_GE(distinct, 4) << "the steps must cover several colours of the diverging LUT";
}

}  // namespace
}  // namespace kiosk::test
