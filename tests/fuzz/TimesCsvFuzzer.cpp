// libFuzzer target: the `import sequence --times CSV` file. Contract: never crash, every failure
// one IMPORT_TIMES / IMPORT_UNREADABLE line, every time read is finite.
#include "runtime/import/Importer.h"
#include "tests/fuzz/FuzzSupport.h"

#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string file = kiosk::fuzz::scratchFile(data, size, ".csv");
    const auto times = kiosk::import::readTimesCsv(file);
    kiosk::fuzz::checkContract(times);
    if (times.ok()) {
        std::vector<double> values;
        std::vector<std::string> files;
        for (const auto& [name, t] : *times.value) {
            if (!std::isfinite(t)) __builtin_trap();
            values.push_back(t);
            files.push_back(name);
        }
        (void)kiosk::import::checkTimes(values, files);
    }
    return 0;
}
