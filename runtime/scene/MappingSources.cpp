#include "runtime/scene/MappingSources.h"

#include "runtime/io/ImageCodec.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>

namespace kiosk::scene {

Result<MappingImage> loadMappingImage(const std::filesystem::path& file) {
    Diagnostics d;
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        d.error("MAPPING_IMAGE", file.string(), "", "cannot open image");
        return d;
    }
    const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in),
                                          std::istreambuf_iterator<char>()};
    auto decoded = io::decodeRgba8(bytes.data(), bytes.size(), "");
    if (!decoded) {
        const Diagnostic* e = decoded.diagnostics.firstError();
        d.error("MAPPING_IMAGE", file.string(), "",
                e ? e->message : std::string("cannot decode image"));
        return d;
    }
    MappingImage img;
    img.width = decoded->width;
    img.height = decoded->height;
    img.rgba = std::move(decoded->samples8);
    return img;
}

Result<std::vector<float>> sampleStoreRaster(io::StoreReader& reader,
                                             const config::SourceRef& source,
                                             const mapping::MappingState& rect, int size) {
    Diagnostics d;
    const io::StoreInfo& info = reader.info();
    const io::TileGrid& grid = info.grid;
    int levels = 0, frame = -1;
    if (!source.sequence.empty()) {
        const io::SequenceInfo* seq = info.findSequence(source.sequence);
        if (!seq || seq->frameTimes.empty()) {
            d.error("MAPPING_SOURCE", info.path, "",
                    "store has no sequence \"" + source.sequence + "\"");
            return d;
        }
        levels = seq->levels;
        frame = int(seq->frameTimes.size()) - 1;
    } else {
        const io::LayerInfo* layer = info.findLayer(source.layer);
        if (!layer || layer->kind == io::LayerKind::Imagery) {
            d.error("MAPPING_SOURCE", info.path, "",
                    "store has no scalar layer \"" + source.layer + "\"");
            return d;
        }
        levels = layer->levels;
    }
    if (levels < 1 || grid.levels.empty()) {
        d.error("MAPPING_SOURCE", info.path, "", "the source has no pyramid levels");
        return d;
    }
    const double texel = std::max(glm::length(rect.u), glm::length(rect.v)) / size;
    int level = std::min(levels, int(grid.levels.size())) - 1;
    while (level > 0 && grid.levels[std::size_t(level - 1)].pixelXSize <= texel) --level;
    const io::TileMatrix& m = grid.levels[std::size_t(level)];
    const double tileW = m.pixelXSize * m.tileWidth, tileH = m.pixelYSize * m.tileHeight;

    std::map<std::pair<int, int>, io::RasterTile> tiles;
    std::vector<float> out(std::size_t(size) * std::size_t(size), NAN);
    for (int row = 0; row < size; ++row) {
        const double t = 1.0 - (row + 0.5) / size;  // top row at the +V edge
        for (int col = 0; col < size; ++col) {
            const double s = (col + 0.5) / size;
            const glm::dvec3 p = rect.origin + (s - 0.5) * rect.u + (t - 0.5) * rect.v;
            const int tc = int(std::floor((p.x - grid.minX) / tileW));
            const int tr = int(std::floor((grid.maxY - p.y) / tileH));
            if (tc < 0 || tr < 0 || tc >= m.matrixWidth || tr >= m.matrixHeight) continue;
            auto it = tiles.find({tc, tr});
            if (it == tiles.end()) {
                const TileId id{level, tc, tr};
                auto tile = frame >= 0 ? reader.readSequenceFrame(source.sequence, frame, id)
                                       : reader.readElevation(source.layer, id);
                // Absent tiles (outside the data) leave nodata; other failures are reported.
                io::RasterTile empty;
                if (!tile &&
                    tile.diagnostics.format().find("STORE_TILE_MISSING") == std::string::npos)
                    return tile.diagnostics;
                it = tiles.emplace(std::make_pair(tc, tr), tile ? std::move(*tile.value) : empty)
                         .first;
            }
            const io::RasterTile& r = it->second;
            if (r.postsX < 1 || r.postsY < 1) continue;
            const double x0 = grid.minX + tc * tileW, y1 = grid.maxY - tr * tileH;
            const int px = std::clamp(int(std::floor((p.x - x0) / m.pixelXSize)), 0, r.postsX - 1);
            const int py = std::clamp(int(std::floor((y1 - p.y) / m.pixelYSize)), 0, r.postsY - 1);
            out[std::size_t(row) * std::size_t(size) + std::size_t(col)] = r.at(px, py);
        }
    }
    return out;
}

}  // namespace kiosk::scene
