// libFuzzer target: colour files. The first byte picks the reader (mod 4: 0 gdaldem .clr,
// 1 ParaView JSON presets, 2 GMT .cpt, 3 matplotlib/cmocean float RGB list), the rest is the
// file. They go through the file readers a scenario uses (`"file": PATH` sniffs .cpt and float
// lists), so size limits, sniffing and file handling are covered too; the float list parser is
// also called directly, as the sniffer may send a mutated list to the colour-rules reader. A
// transfer function that reads must have an increasing domain and build a LUT.
#include "runtime/color/ColorImport.h"
#include "runtime/color/ColorMapFiles.h"
#include "runtime/color/TransferFunction.h"
#include "tests/fuzz/FuzzSupport.h"

#include <string_view>

namespace {

void checkFunction(const kiosk::Result<kiosk::color::TransferFunction>& tf) {
    kiosk::fuzz::checkContract(tf);
    if (tf.ok()) {
        if (!(tf.value->domainMin < tf.value->domainMax)) __builtin_trap();
        (void)kiosk::color::buildLut(*tf.value, 1024);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    namespace color = kiosk::color;
    static const char* const kSuffix[] = {".clr", ".json", ".cpt", ".txt"};
    const int reader = data[0] % 4;
    const std::string file = kiosk::fuzz::scratchFile(data + 1, size - 1, kSuffix[reader]);
    switch (reader) {
        case 0:
            checkFunction(color::importColorReliefFile(file, std::pair{0.0, 100.0}));
            break;
        case 1:
            checkFunction(color::importParaViewFile(file, "fuzz"));
            break;
        case 2:
        case 3: {
            color::ColorFileFormat format{};
            checkFunction(color::importColorMapFile(file, std::pair{0.0, 100.0}, &format));
            const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
            checkFunction(reader == 2 ? color::parseCpt(text, "fuzz.cpt")
                                      : color::parseFloatRgbList(text, "fuzz.txt"));
            break;
        }
    }
    return 0;
}
