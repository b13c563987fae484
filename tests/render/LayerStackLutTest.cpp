// The generator bakes each data layer's LUT index into the shader (llvmpipe samples every side
// of a run-time branch) and can drop the elevation-LUT fetch: checked on the generated text.
#include <gtest/gtest.h>

#include <string>

#include "runtime/render/LayerStack.h"

namespace kiosk::render {
namespace {

int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}

CompositeProgramDesc stack(std::initializer_list<LayerKind> kinds, int lutCount) {
    CompositeProgramDesc d;
    for (LayerKind k : kinds) d.layers.push_back({k, LayerOp::Over, -1});
    d.lutCount = lutCount;
    return d;
}

TEST(LayerStackLutTest, LutIndexIsTheRankAmongScalarLayers) {
    const auto d = stack({LayerKind::Data, LayerKind::Normals, LayerKind::Sequence,
                          LayerKind::Thematic, LayerKind::Data},
                         3);
    const struct {
        int layer, expected;
    } cases[] = {{0, 0}, {1, -1}, {2, 1}, {3, -1}, {4, 2}, {-1, -1}, {5, -1}};
    for (const auto& c : cases) EXPECT_EQ(lutIndexOf(d, c.layer), c.expected) << "layer " << c.layer;
}

TEST(LayerStackLutTest, EachDataLayerSamplesOnlyItsOwnLut) {
    const auto d = stack({LayerKind::Data, LayerKind::Normals, LayerKind::Sequence}, 2);
    auto text = generateCompositeShader(d, 16);
    ASSERT_TRUE(text.ok());
    EXPECT_EQ(count(*text, "texture(uLut0,"), 1) << *text;
    EXPECT_EQ(count(*text, "texture(uLut1,"), 1) << *text;
    EXPECT_EQ(text->find("k =="), std::string::npos) << "no run-time LUT selection";
    // Layer 0 colours with LUT 0 and layer 2 with LUT 1 (its block comes after d2).
    const auto lut0 = text->find("texture(uLut0,"), lut1 = text->find("texture(uLut1,");
    EXPECT_LT(lut0, text->find("vec2 d2"));
    EXPECT_GT(lut1, text->find("vec2 d2"));
    // Without data the coordinate moves onto LUT 1's nodata texel (render::makeEdgedLutTexture).
    EXPECT_NE(
        text->find("x = d2.g >= 0.5 ? x : 1.0;\n            L2 = texture(uLut1, vec2(x, 0.5));"),
        std::string::npos)
        << *text;
}

TEST(LayerStackLutTest, LayerBeyondTheLutCountSamplesNoLut) {
    const auto d = stack({LayerKind::Data, LayerKind::Data}, 1);
    auto text = generateCompositeShader(d, 16);
    ASSERT_TRUE(text.ok());
    EXPECT_EQ(count(*text, "texture(uLut0,"), 1);
    EXPECT_EQ(count(*text, "uLut1"), 0);
    EXPECT_NE(text->find("vec4 L1 = vec4(0.0);"), std::string::npos);  // stays transparent
}

TEST(LayerStackLutTest, ElevationTintOffSkipsTheElevationLutFetch) {
    auto d = stack({LayerKind::Thematic}, 0);
    auto tinted = generateCompositeShader(d, 16);
    ASSERT_TRUE(tinted.ok());
    EXPECT_EQ(count(*tinted, "texture(uElevLut,"), 1);
    d.elevationTint = false;
    auto plain = generateCompositeShader(d, 16);
    ASSERT_TRUE(plain.ok());
    EXPECT_EQ(count(*plain, "texture(uElevLut,"), 0);
    EXPECT_NE(plain->find("vec3 C = uBaseColor.rgb;"), std::string::npos);
}

}  // namespace
}  // namespace kiosk::render
