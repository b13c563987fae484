#include "runtime/app/AllowPath.h"

#include "config/PathPolicy.h"

#include <cstdio>
#include <filesystem>
#include <system_error>

namespace kiosk::app {

std::optional<std::vector<std::string>> takeAllowPathOptions(const std::vector<std::string>& args) {
    const std::string kOption = "--allow-path";
    std::vector<std::string> rest;
    for (std::size_t i = 0; i < args.size(); ++i) {
        std::string dir;
        if (args[i] == "--") {  // everything after is positional
            rest.insert(rest.end(), args.begin() + std::ptrdiff_t(i), args.end());
            break;
        }
        if (args[i] == kOption) {
            if (i + 1 >= args.size()) {
                std::fprintf(stderr, "geokiosk: --allow-path wants a folder\n");
                return std::nullopt;
            }
            dir = args[++i];
        } else if (args[i].rfind(kOption + "=", 0) == 0) {
            dir = args[i].substr(kOption.size() + 1);
        } else {
            rest.push_back(args[i]);
            continue;
        }
        std::error_code ec;
        if (!std::filesystem::is_directory(dir, ec)) {
            std::fprintf(stderr, "geokiosk: --allow-path %s: not a folder\n", dir.c_str());
            return std::nullopt;
        }
        config::allowPath(dir);
    }
    return rest;
}

}  // namespace kiosk::app
