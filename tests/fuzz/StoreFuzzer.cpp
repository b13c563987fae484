// libFuzzer target: the store reader on mutated stores. At start-up a small valid store is
// written (elevation, imagery, a two-frame sequence; 16 x 16 tiles, two levels); each input is a
// list of 5-byte patches (little-endian offset into the file, new byte) applied to a copy of it.
// The patched file is opened, every tile read, and the deep integrity check run. Contract: never
// crash, hang or overrun; ok() exactly when there is no error; messages one line.
#include "runtime/io/ImageCodec.h"
#include "runtime/io/StoreIntegrity.h"
#include "runtime/io/StoreReader.h"
#include "runtime/io/StoreWriter.h"
#include "tests/fuzz/FuzzSupport.h"

#include <fstream>
#include <iterator>
#include <vector>

namespace {

using namespace kiosk::io;
using kiosk::TileId;
constexpr int kT = 16;
std::vector<std::uint8_t> gBase;

EncodedScalarTile scalarTile(float base) {
    std::vector<float> posts(std::size_t((kT + 1) * (kT + 1)));
    for (std::size_t i = 0; i < posts.size(); ++i) posts[i] = base + float(i % 23);
    quantizePosts(posts, 0.125);
    auto enc = encodeScalarTile(posts, kT, kT, 0.125, 6);
    if (!enc) __builtin_trap();
    return *enc;
}

std::vector<std::uint8_t> buildBase() {
    const std::string path = kiosk::fuzz::scratchFile(nullptr, 0, ".base.gpkg");
    std::filesystem::remove(path);
    auto w = StoreWriter::open(path, true);
    if (!w) __builtin_trap();
    TileGrid g;
    g.srsId = 32610;
    g.crsName = "WGS 84 / UTM zone 10N";
    g.crsWkt = "PROJCS[\"WGS 84 / UTM zone 10N\"]";
    g.minX = 500000;
    g.maxY = 5200000;
    g.maxX = g.minX + 10.0 * kT * 2;
    g.minY = g.maxY - 10.0 * kT * 2;
    g.setPyramid(2, kT, kT, 10.0);
    StoreWriter& s = **w;
    if (s.defineGrid(g).hasErrors()) __builtin_trap();
    ScalarLayerSpec elevation;
    elevation.table = "elevation";
    s.createScalarLayer(elevation);
    s.createImageryLayer("hillshade", "fuzz");
    SequenceSpec seq;
    seq.name = "depth";
    seq.units = "m";
    s.createSequence(seq);
    std::vector<std::uint8_t> rgb(std::size_t(kT * kT * 3), 128);
    const auto png = encodePng8(rgb.data(), kT, kT, 3, 6);
    for (const TileId id : {TileId{0, 0, 0}, TileId{1, 0, 0}, TileId{1, 1, 1}}) {
        s.putScalarTile("elevation", id, scalarTile(100));
        s.putImageTile("hillshade", id, *png);
    }
    s.finishLayer("elevation", 100, 130, g.minX, g.minY, g.maxX, g.maxY);
    s.finishLayer("hillshade", 0, 255, g.minX, g.minY, g.maxX, g.maxY);
    for (int f = 0; f < 2; ++f) {
        ScalarLayerSpec frame;
        frame.table = "depth_f000" + std::to_string(f);
        frame.kind = LayerKind::Sequence;
        s.createScalarLayer(frame);
        s.putScalarTile(frame.table, TileId{0, 0, 0}, scalarTile(float(f)));
        s.finishLayer(frame.table, 0, 30, g.minX, g.minY, g.maxX, g.maxY);
        s.addSequenceFrame("depth", f, 1.7e9 + 3600.0 * f, frame.table, 0, 30);
    }
    if (s.commit().hasErrors()) __builtin_trap();
    w.value->reset();
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gBase = buildBase();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::uint8_t> image = gBase;
    for (std::size_t i = 0; i + 5 <= size; i += 5) {
        const std::uint32_t offset = std::uint32_t(data[i]) | std::uint32_t(data[i + 1]) << 8 |
                                     std::uint32_t(data[i + 2]) << 16 |
                                     std::uint32_t(data[i + 3]) << 24;
        image[offset % image.size()] = data[i + 4];
    }
    const std::string path = kiosk::fuzz::scratchFile(image.data(), image.size(), ".gpkg");
    auto reader = StoreReader::open(path);
    kiosk::fuzz::checkContract(reader);
    if (reader.ok()) {
        StoreReader& r = **reader.value;
        for (const auto& layer : r.info().layers) {
            for (const TileId id : {TileId{0, 0, 0}, TileId{1, 0, 0}, TileId{1, 1, 1}}) {
                if (layer.kind == LayerKind::Imagery)
                    kiosk::fuzz::checkContract(r.readImagery(layer.name, id));
                else if (layer.kind == LayerKind::Elevation)
                    kiosk::fuzz::checkContract(r.readElevation(layer.name, id));
                (void)r.tileStats(layer.name, id);
            }
        }
        for (const auto& seq : r.info().sequences)
            for (int f = 0; f < int(seq.frameTimes.size()); ++f)
                kiosk::fuzz::checkContract(r.readSequenceFrame(seq.name, f, TileId{0, 0, 0}));
    }
    const kiosk::Diagnostics integrity = checkStoreIntegrity(path, IntegrityLevel::Deep);
    for (const auto& d : integrity.items())
        if (d.format().find('\n') != std::string::npos) __builtin_trap();
    return 0;
}
