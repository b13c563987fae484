#pragma once

#include "config/MemoryBudgets.h"
#include "config/SourceMap.h"
#include "runtime/color/TransferFunction.h"
#include "runtime/core/TimeParse.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

// The typed scenario (docs/scenario-format.md). Plain data: built once by the reader on any
// thread, then read-only (safe to share between threads as const). Every element keeps the JSON
// pointer it was read from so later checks (store metadata, hot reload) can point at it.
namespace kiosk::config {

using Vec2 = std::array<double, 2>;
using Vec3 = std::array<double, 3>;
using Mat3 = std::array<double, 9>;   ///< row-major
using Mat4 = std::array<double, 16>;  ///< row-major

inline constexpr int kScenarioVersion = 1;

/** @brief A store declared under "stores": id -> path (resolved against the declaring file). */
struct StoreRef {
    std::string id;
    std::filesystem::path path;
    std::string pointer;
};

/** @brief Which store layer or sequence a layer / mapping reads. */
struct SourceRef {
    std::string store;
    std::string layer;     ///< a raster layer of the store, or empty
    std::string sequence;  ///< a time-keyed sequence of the store, or empty
};

/** @brief What the terrain draws: the error-bounded LOD, or every post (fidelity checks). */
enum class TerrainReference { Lod, Full };

/**
 * @brief Imagery tiles as GPU blocks stored at import (docs/terrain.md §11). Auto: where the
 * context has the format natively (never on a software rasterizer, which decompresses on
 * upload); Astc: wherever the context lists KHR_texture_compression_astc_ldr, software too
 * (tests, benchmarks); Off: the PNG tiles always.
 */
enum class TextureCompression { Auto, Astc, Off };

struct Terrain {
    std::string store;
    std::string elevation = "elevation";
    double tauGeom = 2.0;  ///< screen-space geometric error threshold, pixels
    double tauTex = 1.0;   ///< texture error threshold, pixels
    double verticalExaggeration = 1.0;
    /** @brief Full: the finest level everywhere with exact meshes (tauGeom/tauTex unused). */
    TerrainReference reference = TerrainReference::Lod;
    /// CPU tile cache budget; 0 (unset) = sized to the view's working set
    /// (runtime/scene/CacheBudgets.h)
    std::int64_t cacheBytes = 0;
    /// resident texture/mesh budget; 0 (unset) = sized to the view's working set
    std::int64_t gpuBytes = 0;
    /** @brief Procedural detail near the camera (decoration, labelled; docs/terrain.md §7). */
    bool proceduralDetail = false;
    /** @brief Skip tiles hidden behind nearer terrain (docs/terrain.md §10); false: draw all. */
    bool occlusionCulling = true;
    TextureCompression textureCompression = TextureCompression::Auto;
    std::string pointer = "/terrain";
};

/// Normals: a normal-map layer lit by the scenario's (moving) sun, hybrid with mesh shading.
enum class LayerKind {
    Thematic,
    Luminance,
    Topographic,
    Visibility,
    Data,
    Sequence,
    Normals,
    // Derived products of a sequence (layers/products/, docs/products.md).
    Maximum,
    Arrival,
    Duration,
    Hazard,
    Difference,  ///< A - B of two scalar layers of the stack (layers/difference/)
    /// A kind registered at run time (layers::Registry::add), named by Layer::kindName.
    Registered,
};
/** @brief The kinds computed from a sequence's stored steps while replaying. */
inline bool isProductKind(LayerKind k) noexcept {
    return k == LayerKind::Maximum || k == LayerKind::Arrival || k == LayerKind::Duration ||
           k == LayerKind::Hazard;
}
/** @brief How a layer combines with the result of the layers below it (Döllner's operations). */
enum class OperationType {
    Opacity,   ///< alpha-over with a constant opacity (the default)
    Blend,     ///< mix(previous, this, alpha of the referenced visibility layer)
    Add,       ///< previous + weight * this
    Modulate,  ///< previous * this
    Mask,      ///< previous alpha *= this layer's alpha
    Replace,   ///< this, ignoring what is below
};
enum class SequenceInterpolation { Data, None, Arrival };

struct Operation {
    OperationType type = OperationType::Opacity;
    double weight = 1.0;     ///< for Add
    double opacity = 1.0;    ///< for Opacity (and a global factor for the others)
    std::string visibility;  ///< for Blend: id of a visibility layer
};

/**
 * @brief One entry of the ordered layer stack. Layers are applied bottom (index 0) to top; each
 * operation takes the result of all layers below it (chaining).
 */
/** @brief A derived product's options (the layer's "product" object, docs/products.md). */
struct ProductOptions {
    double threshold = 0;  ///< arrival, duration: in the sequence's units
    bool hasThreshold = false;
    std::string units;            ///< units the threshold is stated in ("": the sequence's)
    std::string timeUnits = "h";  ///< arrival, duration: "h", "min" or "s"
    std::string velocity;         ///< hazard: velocity sequence of the same store ("": depth only)
    double isochrones = 0;        ///< arrival: draw only lines every this many time units (0: fill)
    std::string pointer;          ///< "/layers/3/product" (or the layer's pointer when absent)
    /** @brief Seconds per time unit (h 3600, min 60, s 1). */
    double unitSeconds() const noexcept {
        return timeUnits == "s" ? 1.0 : timeUnits == "min" ? 60.0 : 3600.0;
    }
};

/**
 * @brief A kind's own options, as its scenario reader read them (config/KindSection.h); a
 * registered kind derives its own and finds them again with dynamic_cast in plan().
 */
struct KindOptions {
    virtual ~KindOptions() = default;
};

struct Layer {
    std::string id;
    LayerKind kind = LayerKind::Thematic;
    /** @brief The kind as the scenario names it: the layers registry's key ("" = `kind`'s). */
    std::string kindName;
    /** @brief Options read by the kind's own reader beyond the fields below (may be null). */
    std::shared_ptr<const KindOptions> options;
    SourceRef source;
    std::string transfer;  ///< transfer function name (data, sequence)
    Operation operation;
    bool enabled = true;
    SequenceInterpolation interpolate = SequenceInterpolation::Data;  ///< sequence only
    std::optional<double> nodataAs;  ///< sequence: nodata counts as this value when blending
    /** @brief difference: the ids of the layers A and B (value = A - B), JSON "of". */
    std::vector<std::string> operands;
    ProductOptions product;          ///< product kinds (isProductKind) only
    std::string pointer;             ///< e.g. "/layers/2"
};

/** @brief A named transfer function and where it came from. */
struct TransferFunctionDef {
    enum class Origin { Stops, Classes, Preset, ParaView, Gdal, File };
    std::string name;
    std::string label;  ///< human title for the legend ("Water depth"); may be empty
    Origin origin = Origin::Stops;
    std::filesystem::path file;        ///< ParaView / gdal / colour-map file, resolved
    bool explicitDomain = false;       ///< the author fixed "domain"
    color::TransferFunction function;  ///< finalized: sorted, domain set
    std::string pointer;               ///< "/transferFunctions/depth"
};

enum class RangeBehaviour { Loop, Clamp, Unbounded };

struct Clock {
    double start = 0;  ///< UTC epoch seconds
    double end = 0;
    double rate = 1.0;  ///< data seconds per wall second; negative plays backwards
    RangeBehaviour range = RangeBehaviour::Loop;
    bool paused = false;
    bool waitForData = true;  ///< hold the clock until every needed tile of a step is resident
    std::string pointer = "/clock";
};

/** @brief Comparison: another layer stack (run B, forecast, a difference) inside the lens. */
enum class LensKind { Highlight, Visibility, Comparison };
/** @brief Swipe: a straight line through `center`; the inside is the side `rotation` points to. */
enum class LensShape { Circle, Ellipse, Swipe };

/** @brief Lens parameters at a time; absent fields keep the lens's base value. */
struct LensKey {
    TimeSpec time;
    std::optional<Vec2> center;
    std::optional<Vec2> radii;
    std::optional<double> rotation;
    std::string pointer;
};

struct Lens {
    std::string id;
    LensKind kind = LensKind::Highlight;
    LensShape shape = LensShape::Circle;
    Vec2 center{0, 0};    ///< map coordinates (store CRS metres)
    Vec2 radii{0, 0};     ///< metres; equal for a circle
    double rotation = 0;  ///< degrees, counter-clockwise, ellipse only
    double softEdge = 0;  ///< metres of smooth transition at the border
    double raise = 0.25;  ///< highlight: luminance added inside
    double lower = 0.25;  ///< highlight: luminance removed outside
    std::string inside;   ///< visibility: layer shown inside
    std::string outside;  ///< visibility: layer shown outside
    /** @brief comparison: the layers drawn only inside (B's stack) and only outside (A's). */
    std::vector<std::string> insideStack, outsideStack;
    bool enabled = true;
    std::vector<LensKey> keys;  ///< sorted by time as written
    std::string pointer;
};

enum class BlendFactor {
    Zero,
    One,
    SrcColor,
    OneMinusSrcColor,
    DstColor,
    OneMinusDstColor,
    SrcAlpha,
    OneMinusSrcAlpha,
    DstAlpha,
    OneMinusDstAlpha,
};

struct MappingKey {
    TimeSpec time;
    std::optional<Vec3> origin, u, v;
    std::optional<Mat3> textureMatrix;
    std::optional<Mat4> colorMatrix;
    std::optional<double> opacity;
    std::string pointer;
};

/**
 * @brief A route of way points expanded into the paper's edge and way-point mappings (§5.1);
 * replaces origin/u/v and the data layer (the textures are procedural line profiles).
 */
struct MappingRoute {
    std::vector<Vec2> points;  ///< store CRS metres
    double width = 30;         ///< edge width, metres
    double pointRadius = 0;    ///< way-point disc radius, metres (0: no points)
    std::string pointer;
};

/** @brief A projective mapping (Trapp & Döllner): PM = (O, U, V, M_T, data, LUT, M_C, blend). */
struct ProjectiveMapping {
    std::string id;
    Vec3 origin{0, 0, 0};  ///< store CRS metres
    Vec3 u{1, 0, 0};       ///< in-plane axis spanning texture s in [0,1]
    Vec3 v{0, 1, 0};       ///< in-plane axis spanning texture t in [0,1]
    Mat3 textureMatrix{1, 0, 0, 0, 1, 0, 0, 0, 1};
    SourceRef data;
    /**
     * @brief A scalar layer of the stack (its id) instead of `data`: the mapping shows that
     * layer's value at each point, live (data time, seeks, atomic steps), through `transfer`.
     */
    std::string layer;
    std::string transfer;  ///< optional: scalar data through a transfer function
    Mat4 colorMatrix{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    BlendFactor src = BlendFactor::SrcAlpha;
    BlendFactor dst = BlendFactor::OneMinusSrcAlpha;
    double opacity = 1.0;
    bool enabled = true;
    std::vector<MappingKey> keys;
    std::string pointer;
    std::filesystem::path image;  ///< RGBA image file as the data layer (instead of `data`)
    std::optional<MappingRoute> route;
    /** @brief Focus+context: applied to (rgb, 1) of the terrain outside every such mapping. */
    std::optional<Mat4> contextMatrix;
};

struct Viewpoint {
    Vec3 target{0, 0, 0};  ///< store CRS metres (z above the datum)
    double heading = 0;    ///< degrees clockwise from north
    double pitch = -45;    ///< degrees; negative looks down
    double range = 1000;   ///< metres from target to eye
    std::string pointer;
};

struct CameraKey {
    TimeSpec time;
    std::string viewpoint;  ///< name, when the key refers to a named viewpoint
    Viewpoint view;         ///< resolved (copied from the named viewpoint or given inline)
    std::string pointer;
};

enum class CameraInterpolation { Smooth, Linear, Step };

struct CameraPath {
    std::vector<CameraKey> keys;
    CameraInterpolation interpolation = CameraInterpolation::Smooth;
    std::string pointer;
};

struct Camera {
    std::string viewpoint;  ///< initial named viewpoint (empty: fit the terrain)
    std::string path;       ///< camera path played with the clock (empty: none)
    bool interactive = true;
    double fovY = 45;  ///< degrees
};

enum class Corner { TopLeft, TopRight, BottomLeft, BottomRight, Top, Bottom };

struct LegendOverlay {
    bool enabled = false;
    std::string transfer;
    Corner position = Corner::BottomRight;
    std::string title;  ///< empty: the transfer function's label
    /** @brief A layer's own legend: its transfer function, its kind's title (products). */
    std::string layer;
    std::string pointer;  ///< "/overlays/legend" or "/overlays/legend/<i>" (messages)
};
struct TimeLabelOverlay {
    bool enabled = false;
    std::string format = "%Y-%m-%d %H:%M";  ///< strftime-style
    std::string timeZone = "UTC";           ///< "UTC" or "+hh:mm" / "-hh:mm"
    int utcOffsetMinutes = 0;               ///< parsed from timeZone
    bool showOffset = true;                 ///< append "(T+6 h 40 min)" from the clock start
    Corner position = Corner::TopRight;
};
struct SimpleOverlay {
    bool enabled = false;
    Corner position = Corner::TopLeft;
};
struct Overlays {
    /**
     * @brief `overlays.legend`: one object or an array of them, drawn in that order (legends at
     * the same position stack), e.g. a product's legend next to another product's.
     */
    std::vector<LegendOverlay> legends;
    TimeLabelOverlay timeLabel;
    SimpleOverlay title{false, Corner::TopLeft};
    SimpleOverlay status{false, Corner::BottomLeft};
    SimpleOverlay progress{false, Corner::Bottom};
};

struct LightingKey {
    TimeSpec time;
    double sunAzimuth = 315;
    double sunAltitude = 45;
    std::string pointer;
};
struct Lighting {
    double sunAzimuth = 315;  ///< degrees clockwise from north
    double sunAltitude = 45;  ///< degrees above the horizon
    double ambient = 0.25;
    std::vector<LightingKey> keys;
    /**
     * @brief The sun where it is at the data time (NOAA solar position) over latitude/longitude,
     * by default the centre of the terrain's data; replaces sunAzimuth/sunAltitude and keys.
     */
    bool solar = false;
    std::optional<double> latitude, longitude;  ///< degrees, north / east positive
};

/** @brief A chapter's override of one layer of the stack (briefing). */
struct ChapterLayer {
    std::string layer;              ///< id of a layer of the stack
    std::optional<bool> enabled;    ///< false hides it for the chapter
    std::optional<double> opacity;  ///< replaces the layer's operation opacity
    std::string pointer;
};

/** @brief One chapter of a briefing: what data time it shows, from where, with which layers. */
struct Chapter {
    std::string title;
    TimeSpec from, to;              ///< equal for a chapter showing a single time
    bool span = false;              ///< given as "from"/"to" (else "time")
    std::optional<double> duration; ///< playback seconds (default: the span at the clock rate, or 5)
    std::string viewpoint;          ///< a named viewpoint, or
    std::string path;               ///< a named camera path (tour); neither: the scenario camera
    std::vector<ChapterLayer> layers;
    std::string caption;            ///< may hold several lines ("\n")
    bool pause = false;             ///< play holds at the chapter's end until "next"
    std::string pointer;
};

/** @brief Ordered chapters played by `play` and exported back to back by `render`. */
struct Briefing {
    std::vector<Chapter> chapters;
};

/** @brief A whole scenario after includes were merged and every reference resolved. */
/**
 * @brief The frame-rate governor of `play` (docs/animation.md): holds `targetFps` by raising
 * tauGeom/tauTex up to `maxTauFactor` times the scenario's, then lowering the render scale down
 * to `minRenderScale`. `render` never uses it. targetFps 0 = off.
 */
struct Governor {
    double targetFps = 0.0;
    double maxTauFactor = 4.0;
    double minRenderScale = 0.5;
};

struct Scenario {
    int version = kScenarioVersion;
    std::string title;
    std::string caption;
    std::map<std::string, StoreRef> stores;
    Terrain terrain;
    std::vector<Layer> layers;
    std::map<std::string, TransferFunctionDef> transferFunctions;
    std::optional<Clock> clock;
    std::vector<Lens> lenses;
    std::vector<ProjectiveMapping> projectiveMappings;
    std::map<std::string, Viewpoint> viewpoints;
    std::map<std::string, CameraPath> cameraPaths;
    Camera camera;
    Overlays overlays;
    Lighting lighting;
    std::optional<Briefing> briefing;
    Governor governor;
    /** @brief Set by the kiosk file playing this scenario (KioskPlaylist), never by the file. */
    MemoryBudgets memoryBudgets;

    /** @brief The scenario file first, then every included or referenced file (hot reload). */
    std::vector<std::filesystem::path> sourceFiles;
    /** @brief JSON pointer -> file:line:col of the merged document, for later diagnostics. */
    SourceMap sourceMap;

    const Layer* findLayer(const std::string& id) const {
        for (const auto& l : layers)
            if (l.id == id) return &l;
        return nullptr;
    }
    const TransferFunctionDef* findTransfer(const std::string& name) const {
        auto it = transferFunctions.find(name);
        return it == transferFunctions.end() ? nullptr : &it->second;
    }
};

const char* layerKindName(LayerKind k) noexcept;
const char* operationName(OperationType t) noexcept;

}  // namespace kiosk::config
