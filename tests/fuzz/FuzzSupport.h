#pragma once

// Shared by the libFuzzer targets in this folder: readers that take a path get the input
// through one scratch file per process, and every reader's contract is checked the same way.
#include "runtime/core/Diagnostics.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace kiosk::fuzz {

/** @brief Write `data` to this process's scratch file (suffix chosen by the caller). */
inline std::string scratchFile(const std::uint8_t* data, std::size_t size, const char* suffix) {
    const std::string path = (std::filesystem::temp_directory_path() /
                              ("kiosk-fuzz-" + std::to_string(::getpid()) + suffix))
                                 .string();
    if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
        if (size) std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    return path;
}

/** @brief The contract of every reader: ok() exactly when there is no error, messages one line. */
template <class R>
void checkContract(const R& result) {
    if (result.ok() == result.diagnostics.hasErrors()) __builtin_trap();
    for (const auto& d : result.diagnostics.items())
        if (d.format().find('\n') != std::string::npos) __builtin_trap();
}

}  // namespace kiosk::fuzz
