// libFuzzer target: arbitrary bytes as a scenario (and as colour files). The contract under test
// is the reader's: never crash, never throw, never hang; ok() exactly when there is no error.
// Built with clang (-fsanitize=fuzzer,address,undefined) by tests/fuzz/CMakeLists.txt.
#include "config/ScenarioReader.h"
#include "runtime/color/ColorImport.h"

#include <cstddef>
#include <cstdint>
#include <string_view>

#ifndef KIOSK_FUZZ_BASE
#define KIOSK_FUZZ_BASE "fuzz.json"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    // Named inside the config fixtures so includes and colour-file references can resolve.
    const auto scenario = kiosk::config::parseScenario(text, KIOSK_FUZZ_BASE);
    if (scenario.ok() == scenario.diagnostics.hasErrors()) __builtin_trap();
    const auto clr = kiosk::color::parseColorRelief(text, "fuzz.clr", std::pair{0.0, 1.0});
    if (clr.ok() == clr.diagnostics.hasErrors()) __builtin_trap();
    const auto pv = kiosk::color::importParaView(text, "x", "fuzz.json");
    if (pv.ok() && pv.value->domainMin >= pv.value->domainMax) __builtin_trap();
    if (pv.ok()) (void)kiosk::color::buildLut(*pv.value, 1024);
    return 0;
}
