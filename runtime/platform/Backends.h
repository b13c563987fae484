#pragma once

#include "runtime/platform/Display.h"

// Factories of the compiled-in backends; only Display.cpp calls them. Each lives in its own file
// (SurfacelessDisplay.cpp, X11Display.cpp, KmsDisplay.cpp, WaylandDisplay.cpp), chosen in CMake.
namespace kiosk::platform {

Result<std::unique_ptr<Display>> createSurfacelessDisplay(const DisplayOptions& options);
Result<std::unique_ptr<Display>> createX11Display(const DisplayOptions& options);
Result<std::unique_ptr<Display>> createKmsDisplay(const DisplayOptions& options);
Result<std::unique_ptr<Display>> createWaylandDisplay(const DisplayOptions& options);

/** @brief First /dev/dri/cardN that opens, or empty. Used by `auto` and the KMS backend. */
std::string findDrmDevice();

}  // namespace kiosk::platform
