// libFuzzer target: ANUGA SWW (netCDF) files. Contract: never crash or overrun, refuse shapes
// that do not agree and sizes beyond the limits, read elevation and depth of the first step of
// any mesh it accepts.
#include "runtime/import/SwwMesh.h"
#include "tests/fuzz/FuzzSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string file = kiosk::fuzz::scratchFile(data, size, ".sww");
    const auto mesh = kiosk::import::SwwMesh::open(file);
    kiosk::fuzz::checkContract(mesh);
    if (!mesh.ok()) return 0;
    const auto elevation = mesh.value->elevation(0);
    kiosk::fuzz::checkContract(elevation);
    if (elevation.ok() && elevation.value->size() != mesh.value->points()) __builtin_trap();
    const auto depth = mesh.value->depth(0);
    kiosk::fuzz::checkContract(depth);
    return 0;
}
