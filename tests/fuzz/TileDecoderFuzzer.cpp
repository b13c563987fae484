// libFuzzer target: arbitrary bytes as a stored tile, through the header peek and both decoders
// exactly as the store reader calls them (scalar 16 x 16 posts, imagery RGBA). Contract: never
// crash, never allocate beyond the decode budget, errors name the tile.
#include "runtime/io/ImageCodec.h"
#include "runtime/io/ImageHeader.h"
#include "runtime/io/ScalarTileCodec.h"
#include "tests/fuzz/FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace kiosk::io;
    (void)peekImageHeader(data, size);
    const auto scalar =
        decodeScalarTile(data, size, nullptr, 0, 0.125, 10.0, 65535.0, 16, 16, "elevation/0/0/0");
    kiosk::fuzz::checkContract(scalar);
    if (scalar.ok() && scalar.value->values.size() != 17u * 17u) __builtin_trap();
    const auto header = checkTileHeader(data, size, {16, 16, false}, "hillshade/0/0/0");
    if (!header.hasErrors()) {
        const auto rgba = decodeRgba8(data, size, "hillshade/0/0/0");
        kiosk::fuzz::checkContract(rgba);
        if (rgba.ok() && rgba.value->samples8.size() !=
                             std::size_t(rgba.value->width) * std::size_t(rgba.value->height) * 4)
            __builtin_trap();
    }
    return 0;
}
