#pragma once

#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace kiosk::app {

/**
 * @brief Minimal command-line reader for one sub-command: positionals plus `--name value` and
 * `--flag` options declared up front. Unknown options and missing values are usage errors
 * (exit 2) with a did-you-mean hint.
 */
class Args {
public:
    Args(std::string command, std::vector<std::string> valueOptions,
         std::vector<std::string> flagOptions);

    /** @brief Parse; false with `error()` set on a usage error. `--help` / `-h` anywhere wins:
     *  parse() returns true with help() set and reads nothing else. */
    bool parse(const std::vector<std::string>& argv);
    bool help() const noexcept { return mHelp; }
    const std::string& error() const noexcept { return mError; }

    const std::vector<std::string>& positionals() const noexcept { return mPositionals; }
    std::optional<std::string> value(const std::string& name) const;
    bool flag(const std::string& name) const;

private:
    std::string mCommand;
    std::vector<std::string> mValueOptions, mFlagOptions;
    std::vector<std::string> mPositionals;
    std::map<std::string, std::string> mValues;
    std::vector<std::string> mFlags;
    std::string mError;
    bool mHelp = false;
};

/** @brief True when `--help` or `-h` is among the arguments (header-only: the import and info
 *  commands are also compiled into tests that do not link the app library). */
inline bool wantsHelp(const std::vector<std::string>& argv) {
    return std::any_of(argv.begin(), argv.end(),
                       [](const std::string& a) { return a == "--help" || a == "-h"; });
}

/** @brief `--help`: the usage text on stdout, exit status 0 (docs/cli.md). */
inline int showHelp(const char* usageText) {
    std::fputs(usageText, stdout);
    return 0;
}

}  // namespace kiosk::app
