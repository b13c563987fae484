#include "config/ScenarioReader.h"
#include "tests/unit/config/ConfigTestSupport.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace kiosk::config {
namespace {

using test::configData;

bool hasFile(const Scenario& s, const std::string& name) {
    return std::any_of(s.sourceFiles.begin(), s.sourceFiles.end(),
                       [&](const auto& p) { return p.filename() == name; });
}

TEST(ScenarioReader, MinimalScenarioAndDefaults) {
    auto r = readScenario(configData("minimal.json"));
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    const Scenario& s = *r.value;
    EXPECT_TRUE(r.diagnostics.empty()) << r.diagnostics.format();
    EXPECT_EQ(s.title, "Minimal");
    ASSERT_EQ(s.stores.count("valley"), 1u);
    EXPECT_EQ(s.stores.at("valley").path, configData("stores/valley.gpkg"));
    EXPECT_EQ(s.terrain.store, "valley");
    EXPECT_EQ(s.terrain.elevation, "elevation");
    EXPECT_EQ(s.terrain.tauGeom, 2.0);
    EXPECT_EQ(s.terrain.cacheBytes, 0);  // unset: sized to the view's working set
    EXPECT_EQ(s.terrain.gpuBytes, 0);
    ASSERT_EQ(s.layers.size(), 1u);
    EXPECT_EQ(s.layers[0].kind, LayerKind::Thematic);
    EXPECT_EQ(s.layers[0].operation.type, OperationType::Opacity);
    EXPECT_FALSE(s.clock);
    ASSERT_EQ(s.sourceFiles.size(), 1u);
    EXPECT_EQ(s.sourceMap.value("/layers/0/kind").line, 8);
}

TEST(ScenarioReader, FloodScenarioWithIncludeAndEveryFeature) {
    auto r = readScenario(configData("flood.json"));
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_FALSE(r.diagnostics.hasErrors());
    const Scenario& s = *r.value;

    // Include merge: terrain members merge, the including file wins where both speak.
    EXPECT_EQ(s.terrain.store, "valley");          // from common.json
    EXPECT_EQ(s.terrain.tauGeom, 2.0);             // flood.json overrides 3
    EXPECT_EQ(s.terrain.tauTex, 1.5);              // common.json
    EXPECT_EQ(s.terrain.cacheBytes, 384ll << 20);  // "384 MiB"
    EXPECT_EQ(s.stores.size(), 2u);
    EXPECT_EQ(s.overlays.timeLabel.enabled, true);   // common.json
    EXPECT_EQ(s.overlays.legends.at(0).transfer, "depth");  // flood.json
    EXPECT_EQ(s.overlays.legends.at(0).position, Corner::BottomRight);
    EXPECT_TRUE(s.overlays.progress.enabled);
    EXPECT_FALSE(s.overlays.status.enabled);
    EXPECT_EQ(s.lighting.sunAltitude, 40.0);  // common.json, merged with keys below
    ASSERT_EQ(s.lighting.keys.size(), 2u);
    EXPECT_EQ(s.lighting.keys[1].sunAzimuth, 180.0);

    // Every file hot reload must watch.
    EXPECT_EQ(s.sourceFiles.front(), configData("flood.json"));
    EXPECT_TRUE(hasFile(s, "common.json"));
    EXPECT_TRUE(hasFile(s, "presets.json"));
    EXPECT_TRUE(hasFile(s, "depth.clr"));

    // Values keep the file and line they came from, across the include.
    const Location tauTex = s.sourceMap.value("/terrain/tauTex");
    EXPECT_EQ(tauTex.file, configData("common.json").string());
    EXPECT_EQ(tauTex.line, 9);  // line 1 of common.json is a comment
    EXPECT_EQ(s.sourceMap.value("/terrain/tauGeom").file, configData("flood.json").string());

    // Clock.
    ASSERT_TRUE(s.clock);
    EXPECT_EQ(s.clock->start, *parseIso8601("2026-03-14T00:00:00Z"));
    EXPECT_EQ(s.clock->end - s.clock->start, 12 * 3600.0);
    EXPECT_EQ(s.clock->rate, 600.0);
    EXPECT_EQ(s.clock->range, RangeBehaviour::Loop);

    // Layers and operations.
    ASSERT_EQ(s.layers.size(), 6u);
    EXPECT_EQ(s.layers[1].kind, LayerKind::Topographic);
    EXPECT_EQ(s.layers[1].operation.type, OperationType::Modulate);
    EXPECT_FALSE(s.layers[2].enabled);
    const Layer& depth = s.layers[3];
    EXPECT_EQ(depth.kind, LayerKind::Sequence);
    EXPECT_EQ(depth.source.sequence, "flood_depth");
    EXPECT_EQ(depth.interpolate, SequenceInterpolation::Data);
    EXPECT_EQ(depth.nodataAs, 0.0);
    EXPECT_EQ(depth.operation.opacity, 0.85);
    EXPECT_EQ(s.layers[4].operation.type, OperationType::Blend);
    EXPECT_EQ(s.layers[4].operation.visibility, "focus");
    EXPECT_EQ(s.layers[5].operation.type, OperationType::Add);
    EXPECT_EQ(s.layers[5].operation.weight, 0.3);
    EXPECT_EQ(s.findLayer("relief")->transfer, "relief");

    // Transfer functions from every origin.
    ASSERT_EQ(s.transferFunctions.size(), 5u);
    const auto& d = s.findTransfer("depth")->function;
    EXPECT_EQ(d.units, "m");
    EXPECT_EQ(d.space, color::Space::Lab);
    EXPECT_EQ(d.domainMax, 5.0);
    EXPECT_EQ(d.below.a, 0.0f);
    EXPECT_EQ(d.opacity.size(), 2u);
    EXPECT_EQ(s.findTransfer("depth")->label, "Water depth");
    const auto& burn = s.findTransfer("burn")->function;
    EXPECT_TRUE(burn.discrete());
    EXPECT_EQ(burn.classes[2].label, "burned");
    EXPECT_EQ(burn.domainMax, 3.0);
    const auto* relief = s.findTransfer("relief");
    EXPECT_EQ(relief->origin, TransferFunctionDef::Origin::Gdal);
    EXPECT_EQ(relief->function.stops.size(), 4u);
    EXPECT_EQ(relief->function.space, color::Space::Srgb);
    EXPECT_EQ(relief->function.units, "m");
    const auto* div = s.findTransfer("diverging");
    EXPECT_EQ(div->origin, TransferFunctionDef::Origin::ParaView);
    EXPECT_EQ(div->function.space, color::Space::Msh);
    EXPECT_EQ(div->function.domainMin, -2.0);  // 0..1 preset rescaled onto the domain
    EXPECT_EQ(div->function.stops[1].value, 0.0);
    EXPECT_EQ(s.findTransfer("intensity")->function.units, "kW/m");

    // Lenses.
    ASSERT_EQ(s.lenses.size(), 2u);
    EXPECT_EQ(s.lenses[0].shape, LensShape::Circle);
    EXPECT_EQ(s.lenses[0].radii, (Vec2{800, 800}));
    ASSERT_EQ(s.lenses[0].keys.size(), 2u);
    EXPECT_TRUE(s.lenses[0].keys[1].time.isOffset);
    EXPECT_EQ(s.lenses[0].keys[1].time.seconds, 6 * 3600.0);
    EXPECT_EQ(s.lenses[0].keys[1].radii, (Vec2{1200, 1200}));
    EXPECT_EQ(s.lenses[1].kind, LensKind::Visibility);
    EXPECT_EQ(s.lenses[1].shape, LensShape::Ellipse);
    EXPECT_EQ(s.lenses[1].inside, "relief");

    // Projective mapping.
    ASSERT_EQ(s.projectiveMappings.size(), 1u);
    const auto& pm = s.projectiveMappings[0];
    EXPECT_EQ(pm.u, (Vec3{4000, 0, 0}));
    EXPECT_EQ(pm.textureMatrix[4], 1.0);
    EXPECT_EQ(pm.src, BlendFactor::SrcAlpha);
    EXPECT_EQ(pm.dst, BlendFactor::OneMinusSrcAlpha);
    ASSERT_EQ(pm.keys.size(), 1u);
    EXPECT_EQ(pm.keys[0].opacity, 1.0);

    // Camera: named keys resolved to the viewpoint they name, inline keys kept.
    EXPECT_EQ(s.camera.viewpoint, "overview");
    const CameraPath& tour = s.cameraPaths.at("tour");
    ASSERT_EQ(tour.keys.size(), 3u);
    EXPECT_EQ(tour.keys[1].view.range, 2500.0);
    EXPECT_EQ(tour.keys[2].view.heading, 200.0);
    EXPECT_EQ(tour.keys[2].viewpoint, "");
}

// The example message of issue 5, character for character (plus the stable code).
TEST(ScenarioReader, MessageFormat) {
    const std::string text = R"({
  "version": 1,
  "stores": { "v": "v.gpkg" },
  "terrain": { "store": "v" },
  "transferFunctions": { "depth": { "preset": "flood-depth" } },
  "layers": [
    { "id": "a", "kind": "thematic", "source": { "store": "v", "layer": "imagery" } },
    { "id": "b", "kind": "thematic", "source": { "store": "v", "layer": "imagery" } },
    { "id": "c", "kind": "data", "source": { "store": "v", "layer": "elevation" },
      "transfer": "depht" }
  ]
})";
    auto r = parseScenario(text, "scenario.json");
    ASSERT_FALSE(r.ok());
    ASSERT_EQ(r.diagnostics.size(), 1u);
    EXPECT_EQ(r.diagnostics.items()[0].format(),
              "scenario.json:10:19: /layers/2/transfer: unknown transfer function \"depht\" (did "
              "you mean \"depth\"?) [SCENARIO_UNKNOWN_REFERENCE]");
}

struct BadCase {
    const char* name;
    const char* json;  ///< members added to a valid minimal scenario (or a whole document)
    const char* code;
    const char* where;
    const char* message;
};

std::string withBase(const std::string& members) {
    return "{\"version\": 1, \"stores\": {\"v\": \"v.gpkg\"}, \"terrain\": {\"store\": \"v\"}, "
           "\"layers\": [{\"id\": \"a\", \"kind\": \"thematic\", \"source\": {\"store\": \"v\", "
           "\"layer\": \"imagery\"}}]" +
           (members.empty() ? std::string() : ", " + members) + "}";
}

const BadCase kBad[] = {
    {"layer not object", R"("caption": "x", "lenses": [3])", "SCENARIO_TYPE", "/lenses/0",
     "expected object, got number"},
    {"title not string", R"("title": 1)", "SCENARIO_TYPE", "/title", "expected string, got number"},
    {"ambient range", R"("lighting": {"ambient": 2})", "SCENARIO_RANGE", "/lighting/ambient",
     "ambient must be in [0, 1], got 2"},
    {"solar latitude range", R"("lighting": {"solar": true, "latitude": 91, "longitude": 0})",
     "SCENARIO_RANGE", "/lighting/latitude", "latitude must be in [-90, 90], got 91"},
    {"solar site needs both", R"("lighting": {"solar": true, "latitude": 46})", "SCENARIO_MISSING",
     "/lighting/latitude", "\"latitude\" and \"longitude\" go together"},
    {"solar is a boolean", R"("lighting": {"solar": "yes"})", "SCENARIO_TYPE", "/lighting/solar",
     "expected boolean, got string"},
    {"fov range", R"("camera": {"fovY": 0})", "SCENARIO_RANGE", "/camera/fovY", "in [1, 170]"},
    {"clock order", R"("clock": {"start": "2026-03-14T06:00:00Z", "end": "2026-03-14T05:00:00Z"})",
     "SCENARIO_RANGE", "/clock/end", "clock end must be after its start"},
    {"clock without zone", R"("clock": {"start": "2026-03-14T06:00:00", "end": "2026-03-15"})",
     "SCENARIO_BAD_TIME", "/clock/start", "bad time \"2026-03-14T06:00:00\""},
    {"clock needs end", R"("clock": {"start": "2026-03-14T06:00:00Z"})", "SCENARIO_MISSING",
     "/clock", "missing required property \"end\""},
    {"unbounded clock ok but bad rate",
     R"("clock": {"start": "2026-03-14T06:00:00Z", "range": "unbounded", "rate": "fast"})",
     "SCENARIO_TYPE", "/clock/rate", "expected number, got string"},
    {"range typo",
     R"("clock": {"start": "2026-03-14T06:00:00Z", "end": "2026-03-15T00:00:00Z", "range": "lop"})",
     "SCENARIO_BAD_VALUE", "/clock/range", "(did you mean \"loop\"?)"},
    {"lens radius and radii",
     R"("lenses": [{"id": "l", "kind": "highlight", "center": [0, 0], "radius": 1, "radii": [1, )"
     R"(2]}])",
     "SCENARIO_CONFLICT", "/lenses/0", "not both"},
    {"lens center size",
     R"("lenses": [{"id": "l", "kind": "highlight", "center": [0], "radius": 1}])", "SCENARIO_TYPE",
     "/lenses/0/center", "expected an array of 2 numbers, got an array of 1"},
    {"visibility lens needs layers",
     R"("lenses": [{"id": "l", "kind": "visibility", "center": [0, 0], "radius": 1}])",
     "SCENARIO_MISSING", "/lenses/0", "needs \"inside\" and/or \"outside\""},
    {"lens layer ref",
     R"("lenses": [{"id": "l", "kind": "visibility", "center": [0, 0], "radius": 1, )"
     R"("inside": "b"}])",
     "SCENARIO_UNKNOWN_REFERENCE", "/lenses/0/inside", "unknown layer \"b\""},
    {"mapping parallel axes",
     R"("projectiveMappings": [{"id": "m", "origin": [0,0,0], "u": [1,0,0], "v": [2,0,0], )"
     R"("data": {"store": "v", "layer": "x"}}])",
     "SCENARIO_RANGE", "/projectiveMappings/0/v", "not parallel"},
    {"mapping blend typo",
     R"("projectiveMappings": [{"id": "m", "origin": [0,0,0], "u": [1,0,0], "v": [0,1,0], )"
     R"("data": {"store": "v", "layer": "x"}, "blend": {"src": "srcAlfa"}}])",
     "SCENARIO_BAD_VALUE", "/projectiveMappings/0/blend/src", "did you mean \"srcAlpha\"?"},
    {"mapping matrix size",
     R"("projectiveMappings": [{"id": "m", "origin": [0,0,0], "u": [1,0,0], "v": [0,1,0], )"
     R"("data": {"store": "v", "layer": "x"}, "colorMatrix": [1,0,0]}])",
     "SCENARIO_TYPE", "/projectiveMappings/0/colorMatrix", "array of 16 numbers"},
    {"mapping route one point",
     R"("projectiveMappings": [{"id": "r", "route": {"points": [[0, 0]]}}])", "SCENARIO_RANGE",
     "/projectiveMappings/0/route/points", "at least 2 way points"},
    {"mapping route point size",
     R"("projectiveMappings": [{"id": "r", "route": {"points": [[0, 0], [1, 2, 3]]}}])",
     "SCENARIO_TYPE", "/projectiveMappings/0/route/points/1", "array of 2 numbers"},
    {"mapping route width",
     R"("projectiveMappings": [{"id": "r", "route": {"points": )"
     R"([[0, 0], [1, 1]], "width": 0}}])",
     "SCENARIO_RANGE", "/projectiveMappings/0/route/width", "width"},
    {"mapping image missing",
     R"("projectiveMappings": [{"id": "m", "origin": [0,0,0], "u": [1,0,0], "v": [0,1,0], )"
     R"("image": "no-such-atlas.png"}])",
     "SCENARIO_FILE", "/projectiveMappings/0/image", "does not exist"},
    {"mapping without data",
     R"("projectiveMappings": [{"id": "m", "origin": [0,0,0], )"
     R"("u": [1,0,0], "v": [0,1,0]}])",
     "SCENARIO_MISSING", "/projectiveMappings/0", "data"},
    {"mapping context matrix size",
     R"("projectiveMappings": [{"id": "r", "route": {"points": [[0, 0], [1, 1]]}, )"
     R"("contextMatrix": [1, 0]}])",
     "SCENARIO_TYPE", "/projectiveMappings/0/contextMatrix", "array of 16 numbers"},
    {"camera unknown viewpoint",
     R"("viewpoints": {"home": {"target": [0,0,0]}}, "camera": {"viewpoint": "hom"})",
     "SCENARIO_UNKNOWN_REFERENCE", "/camera/viewpoint",
     "unknown viewpoint \"hom\" (did you mean \"home\"?)"},
    {"camera key needs view",
     R"("cameraPaths": {"p": {"keys": [{"time": "2026-03-14T00:00:00Z"}]}})", "SCENARIO_MISSING",
     "/cameraPaths/p/keys/0", "needs \"viewpoint\" or \"target\""},
    {"keys out of order",
     R"("clock": {"start": "2026-03-14T00:00:00Z", "end": "2026-03-15T00:00:00Z"}, )"
     R"("lighting": {"keys": [{"time": "+2h", "sunAzimuth": 1, "sunAltitude": 2}, )"
     R"({"time": "2026-03-14T01:00:00Z", "sunAzimuth": 1, "sunAltitude": 2}]})",
     "SCENARIO_RANGE", "/lighting/keys/1/time", "keys must be in time order"},
    {"pitch range", R"("viewpoints": {"a": {"target": [0,0,0], "pitch": -100}})", "SCENARIO_RANGE",
     "/viewpoints/a/pitch", "pitch must be in [-90, 90], got -100"},
    {"time zone", R"("overlays": {"timeLabel": {"timeZone": "CET"}})", "SCENARIO_BAD_VALUE",
     "/overlays/timeLabel/timeZone", "time zone \"CET\" is not supported"},
    {"legend without transfer", R"("overlays": {"legend": {}})", "SCENARIO_MISSING",
     "/overlays/legend", "the legend needs \"transfer\""},
    {"second legend's layer",
     R"("overlays": {"legend": [{"transfer": "t"}, {"layer": "b"}]}, )"
     R"("transferFunctions": {"t": {"preset": "viridis"}})",
     "SCENARIO_UNKNOWN_REFERENCE", "/overlays/legend/1/layer", "unknown layer \"b\""},
    {"legend array item type",
     R"("overlays": {"legend": [{"transfer": "t"}, 3]}, )"
     R"("transferFunctions": {"t": {"preset": "viridis"}})",
     "SCENARIO_TYPE", "/overlays/legend/1", "expected object, got number"},
    {"overlay typo", R"("overlays": {"legnd": {}})", "SCENARIO_UNKNOWN_PROPERTY", "/overlays/legnd",
     "unknown property \"legnd\" (did you mean \"legend\"?)"},
    {"cache bytes unit", R"("terrain": {"store": "v", "cacheBytes": "12 parsecs"})",
     "SCENARIO_BAD_VALUE", "/terrain/cacheBytes", "bad size \"12 parsecs\""},
    {"gpu bytes too small", R"("terrain": {"store": "v", "gpuBytes": 1000})", "SCENARIO_RANGE",
     "/terrain/gpuBytes", "between 1 MiB and 1 TiB"},
    {"tf no source", R"("transferFunctions": {"t": {"units": "m"}})", "SCENARIO_MISSING",
     "/transferFunctions/t", "needs one of \"stops\""},
    {"tf one stop", R"("transferFunctions": {"t": {"stops": [{"value": 1, "color": "red"}]}})",
     "SCENARIO_RANGE", "/transferFunctions/t/stops", "at least two stops"},
    {"tf stop missing color",
     R"("transferFunctions": {"t": {"stops": [{"value": 1}, {"value": 2, "color": "red"}]}})",
     "SCENARIO_MISSING", "/transferFunctions/t/stops/0", "missing required property \"color\""},
    {"tf stop colour typo",
     R"("transferFunctions": {"t": {"stops": [{"value": 1, "colour": "red"}, {"value": 2, )"
     R"("color": "red"}]}})",
     "SCENARIO_UNKNOWN_PROPERTY", "/transferFunctions/t/stops/0/colour",
     "(did you mean \"color\"?)"},
    {"tf colour array range",
     R"("transferFunctions": {"t": {"preset": "viridis", "nodata": [0, 0, 2]}})",
     "SCENARIO_BAD_COLOR", "/transferFunctions/t/nodata/2", "in 0..1"},
    {"tf domain order", R"("transferFunctions": {"t": {"preset": "viridis", "domain": [5, 1]}})",
     "SCENARIO_RANGE", "/transferFunctions/t/domain", "min < max"},
    {"tf space typo", R"("transferFunctions": {"t": {"preset": "viridis", "space": "cielab"}})",
     "SCENARIO_BAD_VALUE", "/transferFunctions/t/space", "unknown space \"cielab\""},
    {"tf paraview missing file",
     R"("transferFunctions": {"t": {"paraview": {"file": "nope.json", "name": "x"}}})",
     "SCENARIO_FILE", "/transferFunctions/t/paraview/file", "does not exist"},
    {"tf class order",
     R"("transferFunctions": {"t": {"classes": [{"from": 1, "color": "red"}, {"from": 1, )"
     R"("color": "blue"}]}})",
     "SCENARIO_RANGE", "/transferFunctions/t/classes/1/from", "strictly increasing"},
    {"interactive must be boolean",
     R"("transferFunctions": {"t": {"preset": "viridis"}}, "caption": "c", "lenses": [], )"
     R"("camera": {"interactive": "yes"})",
     "SCENARIO_TYPE", "/camera/interactive", "expected boolean, got string"},
    {"include not array", R"("include": 5)", "SCENARIO_TYPE", "/include",
     "expected an array of file names"},
    {"schema must be string", R"("$schema": 1)", "SCENARIO_TYPE", "/$schema", "expected string"},
    {"version must be an integer", R"("version": "1")", "SCENARIO_TYPE", "/version",
     "expected integer, got string"},
};

TEST(ScenarioReader, BadInputsGiveCodeWhereAndMessage) {
    for (const BadCase& c : kBad) {
        auto r = parseScenario(withBase(c.json), "t.json");
        ASSERT_FALSE(r.ok()) << c.name;
        const Diagnostic* e = r.diagnostics.firstError();
        ASSERT_NE(e, nullptr) << c.name;
        EXPECT_EQ(e->code, c.code) << c.name << ": " << r.diagnostics.format();
        EXPECT_EQ(e->where, c.where) << c.name << ": " << r.diagnostics.format();
        EXPECT_NE(e->format().find(c.message), std::string::npos) << c.name << ": " << e->format();
        EXPECT_EQ(e->file, "t.json") << c.name;
        EXPECT_EQ(e->line, 1) << c.name;
        EXPECT_GT(e->column, 1) << c.name;
    }
}

TEST(ScenarioReader, LayerRules) {
    struct Case {
        const char* layer;
        const char* code;
        const char* message;
    };
    const Case cases[] = {
        {R"({"id": "d", "kind": "data", "source": {"store": "v", "layer": "e"}})",
         "SCENARIO_MISSING", "a data layer needs \"transfer\""},
        {R"({"id": "s", "kind": "sequence", "source": {"store": "v", "layer": "e"}, )"
         R"("transfer": "t"})",
         "SCENARIO_MISSING", "a sequence layer needs \"sequence\""},
        {R"({"id": "d", "kind": "thematic", "source": {"store": "v"}})", "SCENARIO_MISSING",
         "missing required property \"layer\""},
        {R"({"id": "d", "kind": "thematic"})", "SCENARIO_MISSING",
         "missing required property \"source\""},
        {R"({"id": "d", "kind": "thematic", "source": {"store": "v", "layer": "i"}, )"
         R"("interpolate": "none"})",
         "SCENARIO_CONFLICT", "apply to sequence layers only"},
        {R"({"id": "d", "kind": "thematic", "source": {"store": "v", "layer": "i", )"
         R"("sequence": "s"}})",
         "SCENARIO_CONFLICT", "either \"layer\" or \"sequence\""},
        {R"({"id": "d", "kind": "thematic", "source": {"store": "v", "layer": "i"}, )"
         R"("operation": "multiply"})",
         "SCENARIO_BAD_VALUE", "unknown operation \"multiply\""},
        {R"({"id": "d", "kind": "thematic", "source": {"store": "v", "layer": "i"}, )"
         R"("operation": {"type": "add", "weight": -1}})",
         "SCENARIO_RANGE", "weight must be in [0, 16], got -1"},
        {R"({"id": "", "kind": "thematic", "source": {"store": "v", "layer": "i"}})",
         "SCENARIO_BAD_VALUE", "\"id\" must not be empty"},
        {R"({"id": "d", "kind": "sequence", "source": {"store": "v", "sequence": "s"}, )"
         R"("transfer": "t", "interpolate": "linear"})",
         "SCENARIO_BAD_VALUE", "expected one of data, none, arrival"},
    };
    for (const auto& c : cases) {
        const std::string text =
            std::string(R"({"version": 1, "stores": {"v": "v.gpkg"}, "terrain": {"store": "v"},
                "transferFunctions": {"t": {"preset": "viridis"}}, "layers": [)") +
            c.layer + "]}";
        auto r = parseScenario(text, "l.json");
        ASSERT_FALSE(r.ok()) << c.layer;
        EXPECT_EQ(r.diagnostics.firstError()->code, c.code) << r.diagnostics.format();
        EXPECT_NE(r.diagnostics.format().find(c.message), std::string::npos)
            << r.diagnostics.format();
    }
}

TEST(ScenarioReader, DuplicateKeyIsAWarning) {
    auto r = parseScenario(withBase(R"("title": "a", "title": "b")"), "d.json");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_EQ(r.value->title, "b");
    ASSERT_TRUE(r.diagnostics.has("SCENARIO_DUPLICATE_KEY"));
    EXPECT_EQ(r.diagnostics.items()[0].severity, Severity::Warning);
}

TEST(ScenarioReader, CommentsAreAllowed) {
    auto r = parseScenario("// header\n" + withBase(R"(/* c */ "title": "x" // tail
)"),
                           "c.json");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    EXPECT_EQ(r.value->title, "x");
}

TEST(ScenarioReader, ByteOrderMarkAndCrLf) {
    std::string text =
        "\xEF\xBB\xBF{\r\n  \"version\": 1,\r\n  \"stores\": {\"v\": \"v.gpkg\"},\r\n"
        "  \"terrain\": {\"store\": \"v\", \"tauTex\": -1},\r\n  \"layers\": []\r\n}\r\n";
    auto r = parseScenario(text, "bom.json");
    ASSERT_FALSE(r.ok());
    const Diagnostic* e = r.diagnostics.firstError();
    EXPECT_EQ(e->code, "SCENARIO_RANGE");
    EXPECT_EQ(e->line, 4);
    EXPECT_EQ(e->column, 39);
}

TEST(ScenarioReader, MissingFile) {
    auto r = readScenario("tests/unit/config/data/nope.json");
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.diagnostics.firstError()->code, "SCENARIO_FILE");
    EXPECT_NE(r.diagnostics.format().find("nope.json: scenario file does not exist"),
              std::string::npos);
    auto dir = readScenario("tests/unit/config/data");
    EXPECT_EQ(dir.diagnostics.firstError()->code, "SCENARIO_FILE");
}

// The merge rule documented in ScenarioReader.h and docs/scenario-format.md.
TEST(ScenarioReader, IncludeMergeRule) {
    test::TempDir dir("merge");
    dir.write("lib/base.json", R"({
  "stores": { "v": "../data/v.gpkg", "w": "w.gpkg" },
  "terrain": { "store": "v", "tauGeom": 4, "tauTex": 3 },
  "transferFunctions": {
    "t": { "units": "m",
           "stops": [ { "value": 0, "color": "black" }, { "value": 1, "color": "white" } ] },
    "u": { "preset": "viridis" }
  },
  "layers": [ { "id": "base", "kind": "thematic", "source": { "store": "v", "layer": "i" } } ],
  "overlays": { "legend": { "transfer": "t", "position": "top-left" } }
})");
    dir.write("lib/mid.json", R"({ "include": "base.json", "terrain": { "tauTex": 2 } })");
    const auto main = dir.write("main.json", R"({
  "version": 1,
  "include": ["lib/mid.json"],
  "stores": { "w": "other.gpkg" },
  "terrain": { "tauGeom": 1 },
  "transferFunctions": { "t": { "preset": "cividis" } },
  "layers": [ { "id": "top", "kind": "thematic", "source": { "store": "w", "layer": "i" } } ],
  "overlays": { "legend": { "position": "bottom-left" } }
})");
    auto r = readScenario(main);
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    const Scenario& s = *r.value;
    // Objects merge member by member, recursively; nested includes apply in order.
    EXPECT_EQ(s.terrain.store, "v");
    EXPECT_EQ(s.terrain.tauGeom, 1.0);
    EXPECT_EQ(s.terrain.tauTex, 2.0);
    EXPECT_EQ(s.overlays.legends.at(0).transfer, "t");
    EXPECT_EQ(s.overlays.legends.at(0).position, Corner::BottomLeft);
    // Named entries replace whole: "t" is now a preset, not base's stops; "u" survives.
    EXPECT_EQ(s.findTransfer("t")->origin, TransferFunctionDef::Origin::Preset);
    EXPECT_EQ(s.findTransfer("t")->function.units, "");
    EXPECT_TRUE(s.findTransfer("u"));
    // Store paths resolve against the file that declares them.
    EXPECT_EQ(s.stores.at("v").path, (dir.path() / "lib/../data/v.gpkg").lexically_normal());
    EXPECT_EQ(s.stores.at("w").path, dir.path() / "other.gpkg");
    // Arrays replace.
    ASSERT_EQ(s.layers.size(), 1u);
    EXPECT_EQ(s.layers[0].id, "top");
    ASSERT_EQ(s.sourceFiles.size(), 3u);
    EXPECT_EQ(s.sourceFiles[1].filename(), "mid.json");
    EXPECT_EQ(s.sourceFiles[2].filename(), "base.json");
    // An error inside an included file names that file and its line.
    dir.write("lib/base.json", R"({
  "terrain": { "store": "v",
               "tauGoem": 4 }
})");
    auto bad = readScenario(main);
    ASSERT_FALSE(bad.ok());
    const Diagnostic* e = bad.diagnostics.firstError();
    EXPECT_EQ(e->code, "SCENARIO_UNKNOWN_PROPERTY");
    EXPECT_EQ(std::filesystem::path(e->file).filename(), "base.json");
    EXPECT_EQ(e->line, 3);
    EXPECT_EQ(e->column, 16);
}

TEST(ScenarioReader, FilesReadAreReportedEvenOnFailure) {
    std::vector<std::filesystem::path> files;
    auto bad = readScenario("scenarios/broken/missing-include.json", &files);
    ASSERT_FALSE(bad.ok());
    ASSERT_EQ(files.size(), 2u);
    EXPECT_EQ(files[0], "scenarios/broken/missing-include.json");
    EXPECT_EQ(files[1], "scenarios/broken/common-does-not-exist.json");

    auto good = readScenario(configData("flood.json"), &files);
    ASSERT_TRUE(good.ok());
    EXPECT_EQ(files, good.value->sourceFiles);

    auto unreadable = readScenario("tests/unit/config/data/nope.json", &files);
    ASSERT_EQ(files.size(), 1u);
}

TEST(ScenarioReader, AcceptedPropertiesCoverEveryKind) {
    const auto& table = acceptedProperties();
    EXPECT_EQ(table.count("Scenario"), 1u);
    EXPECT_GE(table.size(), 25u);
    for (const auto& [kind, keys] : table) EXPECT_FALSE(keys.empty()) << kind;
}

}  // namespace
}  // namespace kiosk::config

namespace kiosk::config {
namespace {

TEST(ScenarioReader, NormalsLayerAndSolarSun) {
    auto r = parseScenario(R"({"version": 1, "stores": {"v": "v.gpkg"}, "terrain": {"store": "v"},
        "layers": [{"id": "n", "kind": "normals", "source": {"store": "v", "layer": "normals"},
                    "operation": "modulate"}],
        "lighting": {"solar": true, "latitude": 46.85, "longitude": -121.76, "ambient": 0.2}})",
                           "n.json");
    ASSERT_TRUE(r.ok()) << r.diagnostics.format();
    ASSERT_EQ(r.value->layers.size(), 1u);
    EXPECT_EQ(r.value->layers[0].kind, LayerKind::Normals);
    EXPECT_STREQ(layerKindName(LayerKind::Normals), "normals");
    EXPECT_TRUE(r.value->lighting.solar);
    EXPECT_EQ(r.value->lighting.latitude, 46.85);
    EXPECT_EQ(r.value->lighting.longitude, -121.76);
    auto plain = parseScenario(withBase(R"("title": "t")"), "p.json");
    ASSERT_TRUE(plain.ok());
    EXPECT_FALSE(plain.value->lighting.solar);
    EXPECT_FALSE(plain.value->lighting.latitude.has_value());
}

}  // namespace
}  // namespace kiosk::config
