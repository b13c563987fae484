#include "config/PathPolicy.h"

#include "runtime/core/SelfPath.h"

#include <cstdlib>
#include <mutex>
#include <system_error>

namespace kiosk::config {

namespace {

std::mutex gMutex;
std::vector<std::filesystem::path> gAllowed;  // guarded by gMutex

// Absolute, `..` and symbolic links resolved as far as the path exists (a missing file still
// has a place: its existing parent decides).
std::filesystem::path canonicalOf(const std::filesystem::path& p) {
    std::error_code ec;
    std::filesystem::path abs = std::filesystem::absolute(p, ec);
    if (ec) abs = p;
    std::filesystem::path c = std::filesystem::weakly_canonical(abs, ec);
    return ec ? abs.lexically_normal() : c;
}

bool isUnder(const std::filesystem::path& file, const std::filesystem::path& root) {
    auto f = file.begin();
    for (auto r = root.begin(); r != root.end(); ++r, ++f) {
        if (r->empty()) continue;  // trailing separator of "dir/"
        if (f == file.end() || *f != *r) return false;
    }
    return true;
}

void addUnique(std::vector<std::filesystem::path>& roots, const std::filesystem::path& p) {
    if (p.empty()) return;
    const auto c = canonicalOf(p);
    for (const auto& r : roots)
        if (r == c) return;
    roots.push_back(c);
}

}  // namespace

void allowPath(const std::filesystem::path& folder) {
    std::lock_guard lock(gMutex);
    gAllowed.push_back(folder);
}

void clearAllowedPaths() {
    std::lock_guard lock(gMutex);
    gAllowed.clear();
}

std::vector<std::filesystem::path> allowedRoots(const std::filesystem::path& rootScenario) {
    std::vector<std::filesystem::path> roots;
    const auto folder = canonicalOf(rootScenario).parent_path();
    addUnique(roots, folder);
    std::error_code ec;
    const auto cwd = std::filesystem::current_path(ec);
    // A service started in `/` would otherwise allow every file on the machine.
    if (!ec && canonicalOf(cwd) != canonicalOf("/")) addUnique(roots, cwd);
    // The package's own read-only data (the shipped demo names ../../data from its scenario
    // folder): <prefix>/share/geokiosk beside <prefix>/bin/geokiosk, when installed.
    if (const auto exeDir = core::executableDir(); !exeDir.empty()) {
        const auto shared = exeDir.parent_path() / "share" / "geokiosk";
        if (std::filesystem::is_directory(shared, ec)) addUnique(roots, shared);
    }
    if (const char* env = std::getenv("GEOKIOSK_ALLOW_PATHS")) {
        std::string list(env);
        std::size_t start = 0;
        while (start <= list.size()) {
            const std::size_t colon = std::min(list.find(':', start), list.size());
            addUnique(roots, list.substr(start, colon - start));
            start = colon + 1;
        }
    }
    std::lock_guard lock(gMutex);
    for (const auto& a : gAllowed) addUnique(roots, a);
    return roots;
}

std::optional<std::string> checkContained(const std::filesystem::path& file,
                                          const std::vector<std::filesystem::path>& roots) {
    const auto c = canonicalOf(file);
    for (const auto& r : roots)
        if (isUnder(c, r)) return std::nullopt;
    return std::string(
        "is outside the scenario's folder and the allow-list (GEOKIOSK_ALLOW_PATHS, "
        "--allow-path)");
}

}  // namespace kiosk::config
