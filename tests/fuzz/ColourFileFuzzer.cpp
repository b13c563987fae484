// libFuzzer target: colour files. The first byte picks the reader (even: gdaldem .clr, odd:
// ParaView JSON presets), the rest is the file; both go through the file readers a scenario
// uses, so size limits and file handling are covered too. A transfer function that reads must
// have an increasing domain and build a LUT.
#include "runtime/color/ColorImport.h"
#include "runtime/color/TransferFunction.h"
#include "tests/fuzz/FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const bool paraview = data[0] & 1;
    const std::string file =
        kiosk::fuzz::scratchFile(data + 1, size - 1, paraview ? ".json" : ".clr");
    const auto tf = paraview ? kiosk::color::importParaViewFile(file, "fuzz")
                             : kiosk::color::importColorReliefFile(file, std::pair{0.0, 100.0});
    kiosk::fuzz::checkContract(tf);
    if (tf.ok()) {
        if (!(tf.value->domainMin < tf.value->domainMax)) __builtin_trap();
        (void)kiosk::color::buildLut(*tf.value, 1024);
    }
    return 0;
}
