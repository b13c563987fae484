// Occlusion culling (issue 20, Wahl et al. 2004 §5; docs/terrain.md §10) on llvmpipe: from a
// low camera in front of a ridge the tiles behind it are not drawn, and the picture is the
// same as with every tile drawn (a wrongly culled tile would be a hole or a changed pixel).
// CrackCensus.* and ReferenceFidelity.* run with culling on (the default) as well.
#include "runtime/app/Session.h"
#include "runtime/import/Importer.h"
#include "tests/support/CrackCensus.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/FloatTiff.h"
#include "tests/support/GoldenImage.h"
#include "tests/support/SettleView.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;

constexpr int kN = 1024;        // posts per side: 4x4 tiles of 256 at the finest level
constexpr double kPost = 10.0;  // metres
constexpr double kWest = 600000.0, kNorth = 5200000.0;
constexpr double kRidgeRow = 420;  // a 2 km high ridge runs west-east along this row

double demHeight(int col, int row) {
    const double ridge = 2000.0 * std::exp(-std::pow((row - kRidgeRow) / 45.0, 2.0));
    // Rough enough at post scale that the error bound wants the finest tiles near the camera.
    return 300.0 + 60.0 * std::sin(col * 0.03) * std::cos(row * 0.021) +
           25.0 * std::sin(col * 0.9) * std::cos(row * 0.7) + ridge;
}

class OcclusionCulling : public test::EglTest {
protected:
    static void SetUpTestSuite() {
        sDir = fs::temp_directory_path() / ("kiosk-occlusion-" + std::to_string(::getpid()));
        fs::create_directories(sDir);
        const fs::path tif = sDir / "dem.tif";
        sProblem = test::writeFloatTiff(tif.string(), kN, kWest, kNorth, kPost,
                                        [](int x, int y) { return float(demHeight(x, y)); });
        import::ImportOptions o;
        o.store = sDir / "ridge.gpkg";
        o.name = "elevation";
        o.quiet = true;
        if (sProblem.empty()) sProblem = import::importElevation(tif.string(), o).format();
        std::ofstream(sDir / "scene.json")
            << R"({ "version": 1, "title": "", "stores": { "s": "ridge.gpkg" },
            "terrain": { "store": "s", "tauGeom": 1, "tauTex": 1 }, "layers": [] })";
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        fs::remove_all(sDir, ec);
    }

    struct Frame {
        gl::Image image;
        scene::SceneFrameInfo info;
    };
    Frame draw(Session& s, gl::RenderTarget& rt, const math::Camera& cam) {
        rt.bind();
        EXPECT_TRUE(test::settleView(s, cam, s.startTime()));
        s.drawFrame(cam, s.startTime(), rt.width(), rt.height());
        return {rt.readColor(), s.terrain().frameInfo()};
    }

    static inline fs::path sDir;
    static inline std::string sProblem;
};

/** Pixels whose colour differs by more than `tolerance` in some channel. */
int differingPixels(const gl::Image& a, const gl::Image& b, int tolerance) {
    int n = 0;
    for (std::size_t i = 0; i + 3 < a.rgba.size() && i + 3 < b.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c)
            if (std::abs(int(a.rgba[i + std::size_t(c)]) - int(b.rgba[i + std::size_t(c)])) >
                tolerance) {
                ++n;
                break;
            }
    return n;
}

TEST_F(OcclusionCulling, BehindARidgeFewerTilesSamePixels) {
    ASSERT_EQ(sProblem, "");
    constexpr int W = 480, H = 270;
    auto rt = makeTarget(W, H);
    auto opened = Session::open(sDir / "scene.json", mCaps);
    ASSERT_TRUE(opened.ok()) << opened.diagnostics.format();
    Session& s = **opened;
    EXPECT_TRUE(s.scenario().terrain.occlusionCulling) << "on by default";
    ASSERT_TRUE(s.terrain().occlusionCulling());
    // Low in the valley south of the ridge, looking north at its face: the eye (about 1.9 km
    // up) is below the crest (2.3 km), so everything north of the ridge is hidden.
    const double ridgeY = kNorth - (kRidgeRow + 0.5) * kPost;
    const math::Viewpoint vp{glm::dvec3(kWest + 512 * kPost, ridgeY, 1500.0), 0.0, -5.0, 4800.0};
    const math::Camera cam = makeCamera(vp, s.terrain().bounds(), W, H, 45.0);
    const Frame on = draw(s, rt, cam);
    s.terrain().setOcclusionCulling(false);
    const Frame off = draw(s, rt, cam);

    RecordProperty("tiles_drawn_off", int(off.info.tilesDrawn));
    RecordProperty("tiles_occluded", int(on.info.tilesOccluded));
    if (const char* dir = std::getenv("KIOSK_TEST_OUTPUT")) {
        test::writeImage((fs::path(dir) / "occlusion-on.png").string(), on.image);
        test::writeImage((fs::path(dir) / "occlusion-off.png").string(), off.image);
    }
    EXPECT_GT(on.info.occlusionQueries, 0u)
        << off.info.tilesDrawn << " tiles drawn without culling";
    EXPECT_GE(on.info.tilesOccluded, 2u) << "the tiles north of the ridge should be culled";
    EXPECT_EQ(on.info.tilesDrawn + on.info.tilesOccluded, off.info.tilesDrawn);
    EXPECT_EQ(off.info.tilesOccluded, 0u);
    EXPECT_EQ(off.info.occlusionQueries, 0u);
    EXPECT_LT(on.info.triangles, off.info.triangles);
    // A wrongly culled tile would change pixels: none may differ by more than 2 levels.
    EXPECT_EQ(differingPixels(on.image, off.image, 2), 0);
    const test::CrackCount c = test::crackPixels(on.image);
    EXPECT_EQ(c.cracks, 0);
    EXPECT_GT(c.sky, 0) << "the view should show sky above the ridge";

    // Seen from high above, nothing is hidden and nothing is culled.
    const math::Viewpoint above{glm::dvec3(kWest + 512 * kPost, kNorth - 512 * kPost, 400.0), 0.0,
                                -80.0, 12000.0};
    const math::Camera top = makeCamera(above, s.terrain().bounds(), W, H, 45.0);
    s.terrain().setOcclusionCulling(true);
    const Frame seen = draw(s, rt, top);
    EXPECT_EQ(seen.info.tilesOccluded, 0u);
}

// The full-resolution reference (ReferenceFidelity's yardstick) culls too, with the same pixels:
// every post drawn, so a culled tile there would be a hole in the reference itself.
TEST_F(OcclusionCulling, FullResolutionReferenceCullsWithSamePixels) {
    ASSERT_EQ(sProblem, "");
    constexpr int W = 480, H = 270;
    auto rt = makeTarget(W, H);
    auto opened = Session::open(sDir / "scene.json", mCaps, [](config::Scenario& sc) {
        sc.terrain.reference = config::TerrainReference::Full;
    });
    ASSERT_TRUE(opened.ok()) << opened.diagnostics.format();
    Session& s = **opened;
    const double ridgeY = kNorth - (kRidgeRow + 0.5) * kPost;
    const math::Viewpoint vp{glm::dvec3(kWest + 300 * kPost, ridgeY, 1500.0), 20.0, -5.0, 4800.0};
    const math::Camera cam = makeCamera(vp, s.terrain().bounds(), W, H, 45.0);
    const Frame on = draw(s, rt, cam);
    s.terrain().setOcclusionCulling(false);
    const Frame off = draw(s, rt, cam);
    EXPECT_GE(on.info.tilesOccluded, 1u) << off.info.tilesDrawn << " tiles drawn without culling";
    EXPECT_EQ(on.info.tilesDrawn + on.info.tilesOccluded, off.info.tilesDrawn);
    EXPECT_EQ(differingPixels(on.image, off.image, 2), 0);
    EXPECT_EQ(test::crackPixels(on.image).cracks, 0);
}

}  // namespace
}  // namespace kiosk::app
