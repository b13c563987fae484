#include "runtime/loader/StoreTileLoader.h"

#include "runtime/anim/ArrivalThresholds.h"
#include "runtime/io/MipChain.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <utility>

namespace kiosk::loader {

namespace {

using terrain::TilePayload;

std::string tileName(const std::string& layer, const TileId& id) {
    return layer + " tile " + std::to_string(id.level) + "/" + std::to_string(id.column) + "/" +
           std::to_string(id.row);
}

// Missing tiles are expected (sparse pyramids, data extents): Absent, not Failed.
void markFailure(TilePayload& p, Diagnostics d) {
    p.status =
        d.has("STORE_TILE_MISSING") ? TilePayload::Status::Absent : TilePayload::Status::Failed;
    p.diagnostics.append(d);
}

// Diagnostics of building a tile's mesh, placed in the store file and the tile.
Diagnostics namedAfter(Diagnostics d, const std::string& file, const std::string& where) {
    Diagnostics out;
    for (Diagnostic e : d.items()) {
        e.file = file;
        e.where = where;
        out.add(std::move(e));
    }
    return out;
}

// A stored form of the tile that cannot be used while the posts can: warnings, with what is
// drawn instead.
void warnInstead(const Diagnostics& d, const std::string& instead, TilePayload& p) {
    for (Diagnostic e : d.items()) {
        e.severity = Severity::Warning;
        e.message += instead;
        p.diagnostics.add(std::move(e));
    }
}

}  // namespace

void StoreTileLoader::loadArrivalThresholds(const LayerBinding& layer, int frame,
                                            terrain::TilePayload& p) {
    io::RasterTile& r0 = *p.raster;
    const io::SequenceInfo* seq = mReader->info().findSequence(layer.name);
    std::vector<float> thresholds;
    if (seq && std::size_t(frame) + 1 < seq->frameTimes.size()) {
        Result<io::RasterTile> r1 = mReader->readSequenceFrame(layer.name, frame + 1, r0.id);
        if (!r1.ok()) {
            p.raster.reset();
            markFailure(p, std::move(r1.diagnostics));
            return;
        }
        anim::computeArrivalThresholds(r0.values, r1->values, r0.postsX, r0.postsY, layer.nodataAs,
                                       thresholds);
    }
    // The last frame (or a pair of mismatched tiles) switches nowhere.
    if (thresholds.size() != r0.values.size()) thresholds.assign(r0.values.size(), 0.0f);
    r0.values = std::move(thresholds);
}

void StoreTileLoader::loadDerived(int binding, const LayerBinding& layer,
                                  const terrain::TileKey& key, terrain::TilePayload& p) {
    const Derivation& d = *layer.derivation;
    if (d.stateFloats() > 0) {
        io::RasterTile out;
        Diagnostics diags =
            mDerived.compute(binding, d, *mReader, layer.name, key.frame, key.id, out);
        if (diags.hasErrors()) return markFailure(p, std::move(diags));
        p.raster = std::move(out);
        return;
    }
    Result<io::RasterTile> r = mReader->readSequenceFrame(layer.name, key.frame, key.id);
    if (!r.ok()) return markFailure(p, std::move(r.diagnostics));
    std::vector<float> other;
    if (!d.companion().empty()) {
        Result<io::RasterTile> c = mReader->readSequenceFrame(d.companion(), key.frame, key.id);
        if (!c.ok()) return markFailure(p, std::move(c.diagnostics));
        if (c->values.size() != r->values.size()) {
            Diagnostics diags;
            diags.error("LOADER_DERIVED_FRAME", mReader->info().path, d.companion(),
                        "tile " + std::to_string(key.id.level) + "/" +
                            std::to_string(key.id.column) + "/" + std::to_string(key.id.row) +
                            " differs in size from " + layer.name + "'s");
            return markFailure(p, std::move(diags));
        }
        other = std::move(c->values);
    }
    d.combine(r->values, other);
    p.raster = std::move(*r.value);
}

bool StoreTileLoader::loadStoredMesh(const LayerBinding& layer, const TileId& id, int tier,
                                     terrain::TilePayload& p) {
    // Without stats the tile is absent or broken: readElevation says which.
    const std::optional<io::TileStats> stats = mReader->tileStats(layer.name, id);
    if (!stats) return false;
    const double error = double(stats->geometricError);
    const double tolerance = mOptions.tinTolerance(error, tier);
    const double base = mOptions.tinTolerance(error);
    Result<bool> row = mReader->readTileMesh(layer.name, id, tolerance, base, mMeshRow);
    if (row.ok() && !*row) return false;  // none stored that fine: mesh the posts
    if (row.ok()) {
        const io::TileGrid& grid = mReader->info().grid;
        const io::TileMeshRow& r = mMeshRow;
        const double skirt = mOptions.skirtDepth(grid, id.level, error, tier);
        // A coarser tier follows from tier 0's split tiers exactly (the query returned that
        // row only when it has them and no row of `tolerance` exists).
        const bool derive = std::abs(r.tolerance - tolerance) > 1e-12 * tolerance;
        Diagnostics d =
            derive
                ? mStoredMeshes.derive(r.mesh, tier, id, grid, tolerance, skirt, p.mesh.emplace())
                : mStoredMeshes.build(r.mesh, id, grid, r.tolerance, skirt, p.mesh.emplace());
        if (!d.hasErrors()) {
            p.stats = stats;
            return true;
        }
        p.mesh.reset();
        row.diagnostics.append(
            namedAfter(std::move(d), mReader->info().path, tileName(layer.name, id)));
    }
    // A corrupt stored mesh costs only the time to mesh the posts, which are intact: say so
    // once for the tile and draw it anyway.
    warnInstead(row.diagnostics, " (meshed from the posts instead)", p);
    return false;
}

bool StoreTileLoader::loadTin(const LayerBinding& layer, const TileId& id, int tier,
                              terrain::TilePayload& p) {
    if (mOptions.fullResolution) return false;  // the reference draws the posts
    const std::optional<io::TileStats> stats = mReader->tileStats(layer.name, id);
    if (!stats) return false;  // absent or broken tile: readElevation says which
    const double error = double(stats->geometricError);
    // The coarsest TIN built within the tier's tolerance (none: other TerrainOptions, the grid).
    Result<bool> row =
        mReader->readTileTin(layer.name, id, mOptions.tinTolerance(error, tier), mTinRow);
    if (row.ok() && !*row) return false;
    if (row.ok()) {
        const io::TileGrid& grid = mReader->info().grid;
        const double skirt = mOptions.skirtDepth(grid, id.level, error, tier);
        Diagnostics d =
            mTins.build(mTinRow.mesh, id, grid, mTinRow.tolerance, skirt, p.mesh.emplace());
        if (!d.hasErrors()) {
            p.stats = stats;
            // Lines can stand above or below the posts: the bounds must hold the TIN.
            p.stats->minValue = std::min(p.stats->minValue, p.mesh->minZ);
            p.stats->maxValue = std::max(p.stats->maxValue, p.mesh->maxZ);
            return true;
        }
        p.mesh.reset();
        row.diagnostics.append(
            namedAfter(std::move(d), mReader->info().path, tileName(layer.name, id)));
    }
    // The posts are intact: draw the grid mesh and say once for the tile why.
    warnInstead(row.diagnostics, " (grid mesh drawn instead)", p);
    return false;
}

bool StoreTileLoader::loadCompressed(const LayerBinding& layer, const TileId& id,
                                     terrain::TilePayload& p) {
    if (mTextureFormat == io::TextureFormat::None) return false;
    io::CompressedImage image;
    Result<bool> row = mReader->readTileTexture(layer.name, id, mTextureFormat, image);
    if (row.ok() && *row) {
        p.compressed = std::move(image);
        return true;
    }
    // The PNG is intact: draw it and say once for the tile why.
    if (!row.ok()) warnInstead(row.diagnostics, " (PNG tile drawn instead)", p);
    return false;
}

StoreTileLoader::StoreTileLoader(StoreOpener opener, std::vector<LayerBinding> layers,
                                 terrain::TerrainOptions options)
    : StoreTileLoader(std::vector<StoreOpener>{std::move(opener)}, std::move(layers), options) {}

StoreTileLoader::StoreTileLoader(std::vector<StoreOpener> openers, std::vector<LayerBinding> layers,
                                 terrain::TerrainOptions options)
    : mOpeners(std::move(openers)), mLayers(std::move(layers)), mOptions(options) {}

void StoreTileLoader::threadStarted() {
    mReaders.clear();
    mOpenDiagnostics.assign(mOpeners.size(), Diagnostics{});
    for (std::size_t i = 0; i < mOpeners.size(); ++i) {
        Diagnostics& d = mOpenDiagnostics[i];
        mReaders.emplace_back();
        if (!mOpeners[i]) {
            d.error("LOADER_NO_STORE", "", "", "no store opener configured");
            continue;
        }
        Result<std::unique_ptr<io::StoreReader>> r = mOpeners[i]();
        d = r.diagnostics;
        if (r.ok() && *r)
            mReaders.back() = std::move(*r.value);
        else if (!d.hasErrors())
            d.error("LOADER_NO_STORE", "", "", "store opener returned no reader");
    }
}

void StoreTileLoader::threadStopping() {
    mReader = nullptr;
    mReaders.clear();
}

TilePayload StoreTileLoader::load(const LoadRequest& request) {
    TilePayload p;
    p.key = request.key;
    // The store holding the request's layer (an unknown layer is reported by the first store).
    const std::size_t store = request.key.layer < mLayers.size()
                                  ? std::size_t(std::max(0, mLayers[request.key.layer].store))
                                  : 0;
    if (mDelaySeconds > 0 && (mDelayStore < 0 || std::size_t(mDelayStore) == store))
        std::this_thread::sleep_for(std::chrono::duration<double>(mDelaySeconds));
    mReader = store < mReaders.size() ? mReaders[store].get() : nullptr;
    if (!mReader) {
        p.status = TilePayload::Status::Failed;
        if (store < mOpenDiagnostics.size())
            p.diagnostics.append(mOpenDiagnostics[store]);
        else
            p.diagnostics.error("LOADER_NO_STORE", "", "",
                                "layer names store " + std::to_string(store) + " of " +
                                    std::to_string(mOpeners.size()));
        return p;
    }
    if (request.key.layer >= mLayers.size()) {
        p.status = TilePayload::Status::Failed;
        p.diagnostics.error(
            "LOADER_UNKNOWN_LAYER", mReader->info().path,
            "layer index " + std::to_string(request.key.layer),
            "no layer bound to this index (" + std::to_string(mLayers.size()) + " bound)");
        return p;
    }
    const LayerBinding& layer = mLayers[request.key.layer];
    const TileId& id = request.key.id;
    switch (layer.kind) {
        case io::LayerKind::Elevation: {
            // The elevation key's frame is the mesh's tolerance tier (TerrainOptions).
            if (loadTin(layer, id, std::max(0, int(request.key.frame)), p)) break;
            if (loadStoredMesh(layer, id, std::max(0, int(request.key.frame)), p)) break;
            Result<io::RasterTile> r = mReader->readElevation(layer.name, id);
            if (!r.ok()) {
                markFailure(p, std::move(r.diagnostics));
                return p;
            }
            p.diagnostics.append(r.diagnostics);
            p.stats = r->stats;
            Result<terrain::TileMesh> mesh = terrain::buildTileMesh(
                *r, mReader->info().grid, mOptions, mMesher, std::max(0, int(request.key.frame)));
            if (!mesh.ok()) {
                p.status = TilePayload::Status::Failed;
                p.diagnostics.append(namedAfter(std::move(mesh.diagnostics), mReader->info().path,
                                                tileName(layer.name, id)));
                return p;
            }
            p.mesh = std::move(*mesh.value);
            break;
        }
        case io::LayerKind::Imagery: {
            if (loadCompressed(layer, id, p)) break;
            Result<io::ImageTile> r = mReader->readImagery(layer.name, id);
            if (!r.ok()) {
                markFailure(p, std::move(r.diagnostics));
                return p;
            }
            p.diagnostics.append(r.diagnostics);
            p.image = std::move(*r.value);
            // Its mipmaps made here, not by glGenerateMipmap on the render thread (io/MipChain.h).
            io::MipChain::append(p.image->rgba, p.image->width, p.image->height);
            break;
        }
        case io::LayerKind::Sequence: {
            if (layer.derivation) {
                loadDerived(int(request.key.layer), layer, request.key, p);
                if (!p.raster) return p;
                break;
            }
            Result<io::RasterTile> r =
                mReader->readSequenceFrame(layer.name, request.key.frame, id);
            if (!r.ok()) {
                markFailure(p, std::move(r.diagnostics));
                return p;
            }
            p.diagnostics.append(r.diagnostics);
            p.raster = std::move(*r.value);
            if (layer.arrivalThresholds) loadArrivalThresholds(layer, request.key.frame, p);
            break;
        }
    }
    p.status = TilePayload::Status::Ready;
    return p;
}

}  // namespace kiosk::loader
