#include "runtime/platform/KmsSelection.h"

namespace kiosk::platform::kms {
namespace {

constexpr const char* kBackend = "kms";

bool isIndex(const std::string& s) {
    if (s.empty() || s.size() > 3) return false;
    for (char c : s)
        if (c < '0' || c > '9') return false;
    return true;
}

bool usable(const ConnectorInfo& c) {
    return c.connected && !c.modes.empty();
}

}  // namespace

std::string modeName(const ModeInfo& mode) {
    return std::to_string(mode.width) + "x" + std::to_string(mode.height) + "@" +
           std::to_string(mode.refresh);
}

int chooseConnector(const std::vector<ConnectorInfo>& connectors, const std::string& wanted,
                    const std::string& device, Diagnostics& diags) {
    std::string available;
    for (std::size_t i = 0; i < connectors.size(); ++i) {
        if (!available.empty()) available += ", ";
        available += std::to_string(i) + ":" + connectors[i].name +
                     (usable(connectors[i]) ? " (connected)" : "");
    }
    if (available.empty()) available = "none";

    if (wanted.empty()) {
        for (std::size_t i = 0; i < connectors.size(); ++i)
            if (usable(connectors[i])) return int(i);
        diags.error("PLATFORM_DRM_NO_CONNECTOR", "", kBackend,
                    "no connected display on " + device + " (connectors: " + available + ")");
        return -1;
    }
    int found = -1;
    if (isIndex(wanted)) {
        const int index = std::stoi(wanted);
        if (index < int(connectors.size())) found = index;
    } else {
        for (std::size_t i = 0; i < connectors.size() && found < 0; ++i)
            if (connectors[i].name == wanted) found = int(i);
    }
    if (found < 0) {
        diags.error(
            "PLATFORM_DRM_CONNECTOR", "", kBackend,
            "connector '" + wanted + "' not found on " + device + "; available: " + available);
        return -1;
    }
    if (!usable(connectors[std::size_t(found)])) {
        diags.error("PLATFORM_DRM_DISCONNECTED", "", kBackend,
                    "connector " + connectors[std::size_t(found)].name + " on " + device +
                        " has no display connected");
        return -1;
    }
    return found;
}

int chooseMode(const std::vector<ModeInfo>& modes, int width, int height,
               const std::string& connectorName, Diagnostics& diags) {
    int best = -1;
    const auto area = [](const ModeInfo& m) { return long(m.width) * long(m.height); };
    for (std::size_t i = 0; i < modes.size(); ++i) {
        const ModeInfo& m = modes[i];
        const ModeInfo* b = best >= 0 ? &modes[std::size_t(best)] : nullptr;
        if (width > 0 && height > 0) {
            if (m.width != width || m.height != height) continue;
            if (!b || (m.preferred && !b->preferred) ||
                (m.preferred == b->preferred && m.refresh > b->refresh))
                best = int(i);
        } else if (m.preferred) {
            return int(i);
        } else if (!b || area(m) > area(*b) || (area(m) == area(*b) && m.refresh > b->refresh)) {
            best = int(i);
        }
    }
    if (best < 0) {
        std::string list;
        for (const auto& m : modes) {
            if (!list.empty()) list += ", ";
            list += modeName(m);
        }
        diags.error("PLATFORM_DRM_MODE", "", kBackend,
                    connectorName + " has no " + std::to_string(width) + "x" +
                        std::to_string(height) +
                        " mode; available: " + (list.empty() ? std::string("none") : list));
        return -1;
    }
    return best;
}

}  // namespace kiosk::platform::kms
