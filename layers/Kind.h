#pragma once

#include "config/KindSection.h"
#include "config/Scenario.h"
#include "layers/LayerShader.h"
#include "runtime/anim/FrameBracket.h"
#include "runtime/io/StoreTypes.h"
#include "runtime/loader/Derivation.h"

#include <limits>
#include <memory>
#include <string>

namespace kiosk::layers {

/** @brief Where a layer's texels come from (the scene serves each through its tile cache). */
enum class SourceKind {
    None,           ///< nothing to load (unused layer slot)
    MeshElevation,  ///< the terrain mesh's own elevation, interpolated per fragment
    Imagery,        ///< an RGBA raster layer of the store (imagery, hillshade, normal map)
    Sequence,       ///< a time-keyed sequence of scalar frames (RG16F value, validity)
};

/**
 * @brief A scenario layer's data sources as a kind planned them. The scene turns this into
 * store bindings and texture requests and runs the shared atomic frame-pair service
 * (anim::VisiblePair) for sequences; a kind never re-implements either.
 */
struct SourcePlan {
    SourceKind source = SourceKind::None;
    std::string table;  ///< store layer or sequence name
    int maxLevel = 0;   ///< finest texture level of the table
    const io::SequenceInfo* sequence = nullptr;
    /** @brief Sequences: the frame pair bracketing the data time (uLayerB), else one frame. */
    bool framePair = false;
    /** @brief Per-pixel thresholds of the pair computed by the loader (uLayerT). */
    bool thresholds = false;
    anim::Interpolation interpolation = anim::Interpolation::None;
    /** @brief Transfer function colouring the values (LUT and legend); empty: none. */
    std::string transfer;
    /**
     * @brief Derived products (layers/products/): the tiles of each frame are derived on the
     * loader thread from the stored frames (a cumulative product's state with the frame pair,
     * or a hazard class), served and committed like the frames; null: the stored frames.
     */
    std::shared_ptr<const loader::Derivation> frames;
    /**
     * @brief uLayerProduct<i> = (time of the pair's first frame, the pair's interval) in units
     * of `timeUnit` seconds since `timeOrigin` (epoch seconds).
     */
    bool productClock = false;
    double timeOrigin = 0, timeUnit = 3600;
    /** @brief A kind whose GLSL depends on the layer's options builds its piece in plan(). */
    std::shared_ptr<const LayerShader> piece;
};

/** @brief What the scene offers a kind while planning: the terrain store's metadata. */
struct StoreView {
    const io::StoreInfo& info;
    const std::string& elevation;  ///< the terrain's elevation layer name
    /** @brief Epoch seconds products count time from (the clock start); NaN: none given. */
    double timeOrigin = std::numeric_limits<double>::quiet_NaN();
};

/**
 * @brief One layer kind (thematic, data, sequence, ...): what is specific to it. Stateless and
 * shared: the per-layer state (frame pairs, prefetch) is the scene's service.
 */
class Kind {
public:
    virtual ~Kind() = default;
    /**
     * @brief Plan where `layer`'s values come from in `store`. Returns the reason when it cannot
     * be served (the layer is then FAILED with it; the others keep rendering), else empty.
     */
    virtual std::string plan(const config::Layer& layer, const StoreView& store,
                             SourcePlan& out) const = 0;
    /** @brief The compositor's piece for a layer planned as `plan`. */
    virtual std::shared_ptr<const LayerShader> shader(const SourcePlan& plan) const = 0;
    /**
     * @brief The title of the layer's own legend (overlays.legend.layer); empty: the transfer
     * function's label. Units follow from the transfer function.
     */
    virtual std::string legendTitle(const config::Layer& layer, const SourcePlan& plan) const {
        (void)layer, (void)plan;
        return {};
    }
    /**
     * @brief The kind's own scenario reader and schema fragment; Registry::add registers it
     * under the kind's name so a scenario can name the kind. Null: the built-in kinds, whose
     * sections config/KindSections.cpp registers (config reads scenarios without this library).
     */
    virtual std::shared_ptr<const config::KindSection> section() const { return nullptr; }
};

}  // namespace kiosk::layers
