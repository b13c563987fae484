// Procedural detail (issue 21) on llvmpipe: the displaced surface stays within its stated bound
// of the data, data layers keep their exact colours, no cracks where the warped grid hands over
// to the quadtree, and the detail is off by default and labelled when on.
#include "runtime/app/Session.h"
#include "runtime/import/Importer.h"
#include "runtime/io/StoreReader.h"
#include "runtime/terrain/DetailSketch.h"
#include "tests/support/EglTestContext.h"
#include "tests/support/GoldenImage.h"
#include "tests/support/SettleView.h"

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

namespace kiosk::app {
namespace {

namespace fs = std::filesystem;

constexpr int kN = 400;         // posts per side
constexpr double kPost = 20.0;  // metres
constexpr double kWest = 600000.0, kNorth = 5200000.0;
constexpr double kWetBelowColumn = 200;  // the depth layer is valid west of this column

// Relief with post-scale roughness (so the detail has an amplitude) on larger ridges.
double demHeight(double col, double row) {
    return 800.0 + 250.0 * std::sin(col * 0.02) * std::cos(row * 0.015) +
           60.0 * std::sin(col * 0.11 + row * 0.07) +
           6.0 * std::sin(col * 1.3) * std::cos(row * 1.1);
}

bool isSky(const std::uint8_t* p) {
    return std::abs(p[0] - 158) <= 2 && std::abs(p[1] - 181) <= 2 && std::abs(p[2] - 204) <= 2;
}

void settle(Session& s, const math::Camera& cam) {
    test::settleView(s, cam, s.startTime());
}

class ProceduralDetail : public test::EglTest {
protected:
    static void SetUpTestSuite() {
        sDir = fs::temp_directory_path() / ("kiosk-detail-" + std::to_string(::getpid()));
        fs::create_directories(sDir);
        GDALAllRegister();
        double geo[6] = {kWest, kPost, 0.0, kNorth, 0.0, -kPost};
        OGRSpatialReference srs;
        srs.importFromEPSG(32610);
        auto write = [&](const fs::path& f, const std::function<float(int, int)>& v) {
            GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(
                f.c_str(), kN, kN, 1, GDT_Float32, nullptr);
            ds->SetGeoTransform(geo);
            ds->SetSpatialRef(&srs);
            ds->GetRasterBand(1)->SetNoDataValue(-9999.0);
            std::vector<float> z(std::size_t(kN) * kN);
            for (int y = 0; y < kN; ++y)
                for (int x = 0; x < kN; ++x) z[std::size_t(y) * kN + std::size_t(x)] = v(x, y);
            if (ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, kN, kN, z.data(), kN, kN,
                                               GDT_Float32, 0, 0) != CE_None)
                sProblem = "cannot write " + f.string();
            GDALClose(ds);
        };
        write(sDir / "dem.tif", [](int x, int y) { return float(demHeight(x, y)); });
        import::ImportOptions o;
        o.store = sDir / "detail.gpkg";
        o.name = "elevation";
        o.quiet = true;
        if (sProblem.empty())
            sProblem = import::importElevation((sDir / "dem.tif").string(), o).format();
        // Two frames of a depth layer valid in the west part only (nodata elsewhere).
        std::ofstream csv(sDir / "times.csv");
        std::vector<std::string> frames;
        for (int k = 0; k < 2; ++k) {
            const fs::path f = sDir / ("depth_" + std::to_string(k) + ".tif");
            write(f, [k](int x, int) { return x < kWetBelowColumn ? float(3 + 4 * k) : -9999.0f; });
            csv << f.filename().string() << ",2026-03-14T0" << k << ":00:00Z\n";
            frames.push_back(f.string());
        }
        csv.close();
        import::ImportOptions so = o;
        so.name = "depth";
        so.timesCsv = (sDir / "times.csv").string();
        so.units = "m";
        if (sProblem.empty()) sProblem = import::importSequence(frames, so).format();
        std::ofstream(sDir / "scene.json")
            << R"({ "version": 1, "title": "", "stores": { "s": "detail.gpkg" },
            "terrain": { "store": "s", "tauGeom": 1, "tauTex": 1 },
            "transferFunctions": { "depth": { "stops": [ { "value": 0, "color": "#c6ecf5" },
                { "value": 10, "color": "#08306b" } ], "nodata": "transparent" } },
            "layers": [ { "id": "depth", "kind": "sequence", "source": { "store": "s", "sequence": "depth" },
                          "transfer": "depth" } ] })";
    }
    static void TearDownTestSuite() {
        std::error_code ec;
        fs::remove_all(sDir, ec);
    }

    std::unique_ptr<Session> open(bool detail) {
        EXPECT_EQ(sProblem, "");
        auto s = Session::open(sDir / "scene.json", mCaps, [detail](config::Scenario& sc) {
            sc.terrain.proceduralDetail = detail;
        });
        EXPECT_TRUE(s.ok()) << s.diagnostics.format();
        return s ? std::move(*s.value) : nullptr;
    }

    static inline fs::path sDir;
    static inline std::string sProblem;
};

// The data surface the store holds: bilinear between the posts.
double dataSurface(double X, double Y) {
    const double fx = (X - kWest) / kPost - 0.5, fy = (kNorth - Y) / kPost - 0.5;
    const double x0 = std::floor(fx), y0 = std::floor(fy), ax = fx - x0, ay = fy - y0;
    return (1 - ay) * ((1 - ax) * demHeight(x0, y0) + ax * demHeight(x0 + 1, y0)) +
           ay * ((1 - ax) * demHeight(x0, y0 + 1) + ax * demHeight(x0 + 1, y0 + 1));
}

const math::Viewpoint kClose{glm::dvec3(604000, 5196000, 850), 30, -35, 1400};

TEST_F(ProceduralDetail, OffByDefaultOnOnlyCloseAndLabelled) {
    constexpr int W = 320, H = 200;
    auto rt = makeTarget(W, H);
    auto plain = Session::open(sDir / "scene.json", mCaps);
    ASSERT_TRUE(plain.ok()) << plain.diagnostics.format();
    EXPECT_FALSE((*plain)->scenario().terrain.proceduralDetail);
    const math::Camera close = makeCamera(kClose, (*plain)->terrain().bounds(), W, H, 45);
    settle(**plain, close);
    rt.bind();
    (*plain)->drawFrame(close, (*plain)->startTime(), W, H);
    EXPECT_FALSE((*plain)->terrain().frameInfo().proceduralDetail);
    auto s = open(true);
    ASSERT_TRUE(s);
    settle(*s, close);
    s->drawFrame(close, s->startTime(), W, H);
    EXPECT_TRUE(s->terrain().frameInfo().proceduralDetail) << "close-up of 20 m posts at 320x200";
    // From 60 km the posts are far below a pixel: the quadtree alone, no label.
    const math::Viewpoint far{glm::dvec3(604000, 5196000, 850), 30, -35, 60000};
    const math::Camera farCam = makeCamera(far, s->terrain().bounds(), W, H, 45);
    settle(*s, farCam);
    s->drawFrame(farCam, s->startTime(), W, H);
    EXPECT_FALSE(s->terrain().frameInfo().proceduralDetail);
}

// Position read-back (as the tau tests do): inside the grid's region, every pixel's elevation is
// within kDetailErrorFraction * E of the data surface at the same x, y, where E is the error of
// the parent of the finest tile there, plus an allowance for the data's own representation
// beyond which the surface may deviate from the data only as the quadtree's may (tauGeom on
// screen, with the tau tests' allowance).
TEST_F(ProceduralDetail, DisplacementStaysWithinTheStatedBound) {
    if (!mCaps.colorBufferFloat)
        KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_GL", "no EXT_color_buffer_float: cannot read positions");
    constexpr int W = 320, H = 200;
    auto target = gl::RenderTarget::createFloat(W, H);
    ASSERT_TRUE(target.ok()) << target.diagnostics.format();
    auto s = open(true);
    ASSERT_TRUE(s);
    ASSERT_TRUE(s->terrain().setPositionOutput(true));
    auto reader = io::StoreReader::open(sDir / "detail.gpkg");
    ASSERT_TRUE(reader.ok());
    const io::TileGrid& grid = s->terrain().storeInfo().grid;
    const int finest = grid.maxLevel();
    const auto& m = grid.levels[std::size_t(finest)];
    auto boundAt = [&](double X, double Y) {
        const TileId id{finest, int((X - grid.minX) / (m.pixelXSize * m.tileWidth)),
                        int((grid.maxY - Y) / (m.pixelYSize * m.tileHeight))};
        auto st = (*reader)->tileStats("elevation", id.parent());
        return st ? terrain::kDetailErrorFraction * double(st->geometricError) : 0.0;
    };
    const math::Viewpoint views[] = {kClose, {glm::dvec3(603000, 5194000, 800), 200, -55, 900}};
    for (const auto& vp : views) {
        const math::Camera cam = makeCamera(vp, s->terrain().bounds(), W, H, 45);
        settle(*s, cam);
        target->bind();
        s->drawFrame(cam, s->startTime(), W, H);
        glm::dvec2 holeMin, holeMax;
        ASSERT_TRUE(s->terrain().detailHole(holeMin, holeMax));
        const std::vector<float> px = target->readFloat();
        int measured = 0;
        double worstExcess = -1e9, largest = 0.0, largestBound = 0.0;
        for (int i = 0; i < W * H; ++i) {
            const float* p = &px[std::size_t(i) * 4];
            if (p[3] != 2.0f) continue;
            const double X = double(p[0]) + grid.minX, Y = double(p[1]) + grid.minY;
            if (X <= holeMin.x || Y <= holeMin.y || X >= holeMax.x || Y >= holeMax.y) continue;
            const double dz = std::fabs(double(p[2]) - dataSurface(X, Y));
            const double bound = boundAt(X, Y);
            // Beyond the decoration's bound, the surface may deviate from the data as the
            // quadtree's may: tauGeom (1 px) on screen, plus the tau tests' 0.25 px allowance.
            const double ppm =
                cam.pixelsPerMetreAt(glm::distance(cam.eye, glm::dvec3(X, Y, double(p[2]))));
            worstExcess = std::max(worstExcess, (dz - bound) * ppm);
            if (dz > largest) largest = dz, largestBound = bound;
            ++measured;
        }
        EXPECT_GT(measured, W * H / 4) << "heading " << vp.headingDeg;
        EXPECT_LE(worstExcess, 1.25) << "heading " << vp.headingDeg << ": pixels beyond the bound";
        // And the detail is really there: some pixel is displaced by a good part of its bound.
        EXPECT_GT(largest, 0.4 * largestBound) << "heading " << vp.headingDeg;
        std::printf(
            "heading %.0f: %d px in the grid, largest |dz| %.2f m (bound there %.2f m), worst "
            "excess %.3f px\n",
            vp.headingDeg, measured, largest, largestBound, worstExcess);
    }
}

// Colours of the data layer with detail on equal those with detail off wherever the same ground
// point is seen (positions read back; vertical displacement moves the rest, which is masked).
TEST_F(ProceduralDetail, DataLayerPixelsAreUnchanged) {
    if (!mCaps.colorBufferFloat)
        KIOSK_SKIP_OR_FAIL("KIOSK_REQUIRE_GL", "no EXT_color_buffer_float: cannot read positions");
    constexpr int W = 320, H = 200;
    const math::Viewpoint vp{glm::dvec3(kWest + kWetBelowColumn * kPost, 5193000, 820), 0, -80,
                             1300};
    struct Frame {
        gl::Image color;
        std::vector<float> pos;
    };
    auto render = [&](bool detail) {
        Frame f;
        auto s = open(detail);
        if (!s) return f;
        const math::Camera cam = makeCamera(vp, s->terrain().bounds(), W, H, 45);
        settle(*s, cam);
        auto rt = makeTarget(W, H);
        rt.bind();
        s->drawFrame(cam, s->startTime(), W, H);
        EXPECT_EQ(s->terrain().frameInfo().proceduralDetail, detail);
        f.color = rt.readColor();
        EXPECT_TRUE(s->terrain().setPositionOutput(true));
        auto target = gl::RenderTarget::createFloat(W, H);
        EXPECT_TRUE(target.ok());
        target->bind();
        s->drawFrame(cam, s->startTime(), W, H);
        f.pos = target->readFloat();
        return f;
    };
    const Frame on = render(true), off = render(false);
    ASSERT_EQ(on.pos.size(), off.pos.size());
    ASSERT_FALSE(on.pos.empty());
    int compared = 0, differing = 0, decorated = 0, worst = 0;
    for (int y = 0; y < H * 85 / 100; ++y)  // above the overlay's label
        for (int x = 0; x < W; ++x) {
            // readFloat and readColor both return the top row first.
            const std::size_t k = (std::size_t(y) * W + std::size_t(x)) * 4;
            const float* a = &on.pos[k];
            const float* b = &off.pos[k];
            if (a[3] != 2.0f || b[3] != 2.0f) continue;
            if (std::hypot(a[0] - b[0], a[1] - b[1]) > 0.25) continue;  // geometry moved this pixel
            const double column =
                (double(a[0]) + 0.0) / kPost;  // scene x from the grid's west edge
            const std::uint8_t* ca = on.color.pixel(x, y);
            const std::uint8_t* cb = off.color.pixel(x, y);
            const int d = std::max(
                {std::abs(ca[0] - cb[0]), std::abs(ca[1] - cb[1]), std::abs(ca[2] - cb[2])});
            if (column < kWetBelowColumn - 1) {  // under the data layer
                ++compared;
                worst = std::max(worst, d);
                differing += d > 2;
            } else if (column > kWetBelowColumn + 1) {
                decorated += d > 4;
            }
        }
    EXPECT_GT(compared, W * H / 10);
    if (differing) {
        gl::Image diff = on.color;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                std::uint8_t* p = diff.pixel(x, y);
                const std::uint8_t* b = off.color.pixel(x, y);
                const int d =
                    std::max({std::abs(p[0] - b[0]), std::abs(p[1] - b[1]), std::abs(p[2] - b[2])});
                p[0] = p[1] = p[2] = std::uint8_t(std::min(255, d * 20));
            }
        test::writeImage((fs::temp_directory_path() / "detail-data-diff.png").string(), diff);
        test::writeImage((fs::temp_directory_path() / "detail-data-on.png").string(), on.color);
        test::writeImage((fs::temp_directory_path() / "detail-data-off.png").string(), off.color);
    }
    EXPECT_EQ(differing, 0) << "worst difference " << worst << " DN over " << compared
                            << " data pixels";
    EXPECT_GT(decorated, W * H / 50) << "the dry side must show the detail";
    std::printf("data pixels compared %d, worst %d DN; decorated dry pixels %d\n", compared, worst,
                decorated);
}

// Crack census (tools/crack-census.sh's method): sky pixels not connected to the image border
// through sky are holes in the terrain. Views where the grid's border is on screen.
TEST_F(ProceduralDetail, NoCracksAtTheHandOver) {
    constexpr int W = 320, H = 200;
    auto rt = makeTarget(W, H);
    auto s = open(true);
    ASSERT_TRUE(s);
    int framesWithBorder = 0;
    for (int i = 0; i < 8; ++i) {
        const math::Viewpoint vp{glm::dvec3(603000 + 150.0 * i, 5194000 + 100.0 * i, 800), 40.0 * i,
                                 -25.0 - 4 * i, 900.0 + 150.0 * i};
        const math::Camera cam = makeCamera(vp, s->terrain().bounds(), W, H, 45);
        settle(*s, cam);
        rt.bind();
        s->drawFrame(cam, s->startTime(), W, H);
        ASSERT_TRUE(s->terrain().frameInfo().proceduralDetail) << "view " << i;
        glm::dvec2 lo, hi;
        ASSERT_TRUE(s->terrain().detailHole(lo, hi));
        // Is the hand-over on screen? Points along the hole's border projected.
        const glm::dmat4 vpm = cam.projection() * cam.view();
        bool border = false;
        for (int k = 0; k <= 40 && !border; ++k) {
            const double a = k / 40.0;
            for (glm::dvec2 q : {glm::dvec2(glm::mix(lo.x, hi.x, a), lo.y),
                                 glm::dvec2(glm::mix(lo.x, hi.x, a), hi.y),
                                 glm::dvec2(lo.x, glm::mix(lo.y, hi.y, a)),
                                 glm::dvec2(hi.x, glm::mix(lo.y, hi.y, a))}) {
                const double col = (q.x - kWest) / kPost, row = (kNorth - q.y) / kPost;
                const glm::dvec4 c = vpm * glm::dvec4(q, demHeight(col, row), 1.0);
                border =
                    border || (c.w > 0 && std::fabs(c.x) < 0.9 * c.w && std::fabs(c.y) < 0.9 * c.w);
            }
        }
        framesWithBorder += border;
        const gl::Image img = rt.readColor();
        std::vector<std::uint8_t> reached(std::size_t(W) * H, 0);
        std::vector<int> stack;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                if ((x == 0 || y == 0 || x == W - 1 || y == H - 1) && isSky(img.pixel(x, y))) {
                    reached[std::size_t(y) * W + std::size_t(x)] = 1;
                    stack.push_back(y * W + x);
                }
        while (!stack.empty()) {
            const int p = stack.back();
            stack.pop_back();
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int x = p % W + dx, y = p / W + dy;
                    if (x < 0 || y < 0 || x >= W || y >= H) continue;
                    const std::size_t q = std::size_t(y) * W + std::size_t(x);
                    if (reached[q] || !isSky(img.pixel(x, y))) continue;
                    reached[q] = 1;
                    stack.push_back(int(q));
                }
        }
        int cracks = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x)
                cracks += isSky(img.pixel(x, y)) && !reached[std::size_t(y) * W + std::size_t(x)];
        EXPECT_EQ(cracks, 0) << "view " << i;
        if (cracks)
            test::writeImage(
                (fs::temp_directory_path() / ("detail-crack-" + std::to_string(i) + ".png"))
                    .string(),
                img);
    }
    EXPECT_GE(framesWithBorder, 4) << "the hand-over must be on screen in most views";
}

}  // namespace
}  // namespace kiosk::app
