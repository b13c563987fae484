#pragma once

#include <cstdio>

#include "runtime/core/Diagnostics.h"

namespace kiosk::app {

/** @brief Every diagnostic on stderr, one line each (docs/cli.md message format). */
inline void printDiagnostics(const Diagnostics& d) {
    for (const auto& item : d.items()) std::fprintf(stderr, "%s\n", item.format().c_str());
}

}  // namespace kiosk::app
