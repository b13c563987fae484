#pragma once

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

    /** @brief Parse; false with `error()` set on a usage error. */
    bool parse(const std::vector<std::string>& argv);
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
};

}  // namespace kiosk::app
