#pragma once

namespace kiosk {

/** @brief Process exit status, the contract of docs/cli.md. */
enum ExitCode : int {
    kExitOk = 0,
    kExitBadInput = 1,   ///< scenario, data or store is wrong; a message says where
    kExitUsage = 2,      ///< command line is wrong
    kExitCannotRun = 3,  ///< no display, no GLES 3 context, no DRM device
};

}  // namespace kiosk
