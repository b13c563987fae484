#include "runtime/core/SelfPath.h"

#include <system_error>

namespace kiosk::core {

std::filesystem::path executableDir() {
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::filesystem::path() : self.parent_path();
}

}  // namespace kiosk::core
