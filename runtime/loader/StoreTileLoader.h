#pragma once

#include "runtime/core/Result.h"
#include "runtime/io/StoreReader.h"
#include "runtime/loader/DerivedTiles.h"
#include "runtime/loader/TileLoader.h"
#include "runtime/terrain/RtinMesher.h"
#include "runtime/terrain/StoredMesh.h"
#include "runtime/terrain/TerrainOptions.h"
#include "runtime/terrain/TinTileMesh.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace kiosk::loader {

/** @brief Which store table a key's layer index names (index in the vector == TileKey::layer). */
struct LayerBinding {
    std::string name;  ///< layer table or sequence name in the store
    io::LayerKind kind = io::LayerKind::Elevation;
    /**
     * @brief Sequence only: load the arrival thresholds of the pair (key.frame, key.frame + 1)
     * instead of a frame (anim::computeArrivalThresholds on this thread; the last frame gives
     * thresholds 0). Posts as the frame's raster, values in [0, 1].
     */
    bool arrivalThresholds = false;
    std::optional<float> nodataAs = std::nullopt;  ///< arrival: the class nodata counts as
    int store = 0;  ///< which of the loader's stores holds the table (index into its openers)
    /**
     * @brief Sequence only: load values derived from the stored frames instead of a frame
     * (derived products, loader/Derivation.h); null: the stored frame.
     */
    std::shared_ptr<const Derivation> derivation = nullptr;
};

/** @brief Opens this thread's own StoreReader, e.g. `[p] { return io::StoreReader::open(p); }`. */
using StoreOpener = std::function<Result<std::unique_ptr<io::StoreReader>>()>;

/**
 * @brief The standard LoadFunction: reads a tile from the store with a StoreReader owned by the
 * loader thread and, for elevation, decodes the mesh stored at import for the tile's tolerance
 * (kiosk_tile_meshes) or, where the store has none, builds its RTIN mesh from the posts; skirts
 * either way (TerrainOptions must equal the selector's). Imagery gives an RGBA image, sequences a
 * float raster of frame `key.frame`.
 *
 * Bad data never throws: STORE_TILE_MISSING gives an Absent payload, any other error a Failed
 * one with the reader's diagnostics (naming layer and tile); a store that cannot be opened fails
 * every request with the open diagnostics. Loader thread only (after construction).
 */
class StoreTileLoader final : public LoadFunction {
public:
    StoreTileLoader(StoreOpener opener, std::vector<LayerBinding> layers,
                    terrain::TerrainOptions options);
    /**
     * @brief Several stores on one loader thread (layers from other stores of the same tile
     * grid): LayerBinding::store indexes `openers`; one reader each, opened on the thread. A
     * store that cannot be opened fails only the requests for its layers.
     */
    StoreTileLoader(std::vector<StoreOpener> openers, std::vector<LayerBinding> layers,
                    terrain::TerrainOptions options);

    void threadStarted() override;
    terrain::TilePayload load(const LoadRequest& request) override;
    void threadStopping() override;
    /**
     * @brief Test hook: every load() first sleeps this long (a slow disk or network share); with
     * `store` >= 0 only the loads from that store (index into the openers) do.
     */
    void setArtificialDelay(double seconds, int store = -1) noexcept {
        mDelaySeconds = seconds;
        mDelayStore = store;
    }
    /** @brief Bytes the running states of derived products may hold at least (any thread). */
    void setDerivedBudget(std::size_t bytes) noexcept { mDerived.setBudget(bytes); }
    /** @brief (tile, product layer) pairs in view, whose states are kept (any thread). */
    void setDerivedTracksInView(std::size_t tracks) noexcept { mDerived.setTracksInView(tracks); }
    /** @brief Bytes the running states hold (any thread; as of the last derivation). */
    std::size_t derivedBytes() const noexcept { return mDerived.bytesHeld(); }
    /**
     * @brief Imagery tiles as the GPU blocks of `format` where the store holds them
     * (kiosk_tile_textures; the PNG otherwise); None (default): always the PNG. Before start.
     */
    void setTextureFormat(io::TextureFormat format) noexcept { mTextureFormat = format; }

private:
    void loadArrivalThresholds(const LayerBinding& layer, int frame, terrain::TilePayload& p);
    /** @brief A derived product's tile (binding.derivation set) into `p`. */
    void loadDerived(int binding, const LayerBinding& layer, const terrain::TileKey& key,
                     terrain::TilePayload& p);
    /**
     * @brief The tile's mesh from kiosk_tile_meshes when the store has one as fine as `tier`
     * asks (true); false to mesh the posts (none stored, or a corrupt one: then a warning
     * naming the tile is in `p`).
     */
    bool loadStoredMesh(const LayerBinding& layer, const TileId& id, int tier,
                        terrain::TilePayload& p);

    /**
     * @brief The tile's local TIN (kiosk_tile_tins) when it has one built at least as fine as
     * `tier` asks (true); false for the grid mesh (no TIN, a full-resolution run, or a corrupt
     * TIN: then a warning naming the tile is in `p`).
     */
    bool loadTin(const LayerBinding& layer, const TileId& id, int tier, terrain::TilePayload& p);
    /**
     * @brief The imagery tile's stored GPU blocks (true); false to read the PNG (none stored,
     * or a damaged row: then a warning naming the tile is in `p`).
     */
    bool loadCompressed(const LayerBinding& layer, const TileId& id, terrain::TilePayload& p);

    std::vector<StoreOpener> mOpeners;
    std::vector<LayerBinding> mLayers;
    terrain::TerrainOptions mOptions;
    std::vector<std::unique_ptr<io::StoreReader>> mReaders;  ///< per opener; null: failed
    std::vector<Diagnostics> mOpenDiagnostics;               ///< per opener
    io::StoreReader* mReader = nullptr;  ///< the store of the request being loaded
    terrain::RtinMesher mMesher;
    terrain::StoredMeshBuilder mStoredMeshes;
    io::TileMeshRow mMeshRow;  // decoded stored mesh, buffers reused from tile to tile
    terrain::TinMeshBuilder mTins;
    io::TileTinRow mTinRow;
    double mDelaySeconds = 0.0;
    int mDelayStore = -1;  ///< -1: every store is slow
    io::TextureFormat mTextureFormat = io::TextureFormat::None;
    DerivedTiles mDerived;  ///< running states of cumulative products, per tile
};

}  // namespace kiosk::loader
