#include "runtime/export/StreamModule.h"

#include "runtime/core/SelfPath.h"

#include <dlfcn.h>
#include <filesystem>
#include <mutex>
#include <string>

namespace kiosk::video {
namespace {

struct Loaded {
    MakeStreamFn make = nullptr;
    std::string error;  ///< why it could not be loaded (when make is null)
};

Loaded load() {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path exeDir = core::executableDir();
    // Beside the executable (the build folder's geokiosk), the installed layout
    // (bin/ -> lib/<arch>/geokiosk/), the build folder (tests and benchmarks in subfolders).
    const fs::path candidates[] = {exeDir / kAvModuleFile,
                                   exeDir / KIOSK_AV_MODULE_RELDIR / kAvModuleFile,
                                   fs::path(KIOSK_AV_MODULE_BUILD_DIR) / kAvModuleFile};
    Loaded out;
    for (const fs::path& p : candidates) {
        if (!fs::exists(p, ec)) {
            out.error = p.lexically_normal().string() + ": not found";
            continue;
        }
        // Never unloaded: encoders may run again in the same process.
        void* handle = ::dlopen(p.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* why = ::dlerror();
            out.error = why ? why : p.string() + ": cannot be loaded";
            continue;
        }
        if (void* entry = ::dlsym(handle, kAvModuleEntry)) {
            out.make = reinterpret_cast<MakeStreamFn>(entry);
            return out;
        }
        out.error = p.string() + ": no entry point " + kAvModuleEntry;
    }
    return out;
}

}  // namespace

std::unique_ptr<EncoderStream> makeEncoderStream(Diagnostics& diags) {
    static std::once_flag once;
    static Loaded loaded;
    std::call_once(once, [] { loaded = load(); });
    if (!loaded.make) {
        diags.error("EXPORT_MODULE", "", "",
                    "video export needs the FFmpeg module " + std::string(kAvModuleFile) +
                        " (installed with geokiosk): " + loaded.error);
        return nullptr;
    }
    return std::unique_ptr<EncoderStream>(loaded.make());
}

}  // namespace kiosk::video
