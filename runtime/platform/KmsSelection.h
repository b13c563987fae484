#pragma once

#include "runtime/core/Diagnostics.h"

#include <string>
#include <vector>

// Output selection rules of the KMS backend, on plain data so they are unit-tested without a
// DRM device (KmsDisplay.cpp fills these from libdrm). Pure functions, any thread.
namespace kiosk::platform::kms {

struct ModeInfo {
    int width = 0;
    int height = 0;
    int refresh = 0;  ///< Hz
    bool preferred = false;
};

struct ConnectorInfo {
    std::string name;  ///< kernel name: "HDMI-A-1", "DP-2", "eDP-1"
    bool connected = false;
    std::vector<ModeInfo> modes;
};

/** @brief "1920x1080@60". */
std::string modeName(const ModeInfo& mode);

/**
 * @brief Pick a connector: `wanted` is a kernel name ("HDMI-A-1"), a 0-based index into
 * `connectors` ("1"), or empty for the first connected one. A connector counts as connected
 * only with at least one mode. Returns the index, or -1 with one error naming `device`:
 * PLATFORM_DRM_CONNECTOR (unknown name/index; the message lists what exists),
 * PLATFORM_DRM_DISCONNECTED (the named one has no display), PLATFORM_DRM_NO_CONNECTOR.
 */
int chooseConnector(const std::vector<ConnectorInfo>& connectors, const std::string& wanted,
                    const std::string& device, Diagnostics& diags);

/**
 * @brief Pick a mode: with width and height > 0 one of exactly that size (the preferred one
 * among equals, else the highest refresh); otherwise the preferred mode, else the largest.
 * Returns the index, or -1 with PLATFORM_DRM_MODE listing the available modes.
 */
int chooseMode(const std::vector<ModeInfo>& modes, int width, int height,
               const std::string& connectorName, Diagnostics& diags);

}  // namespace kiosk::platform::kms
