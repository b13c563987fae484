#include "runtime/app/Args.h"

#include <algorithm>

#include "runtime/core/Strings.h"

namespace kiosk::app {

Args::Args(std::string command, std::vector<std::string> valueOptions,
           std::vector<std::string> flagOptions)
    : mCommand(std::move(command)),
      mValueOptions(std::move(valueOptions)),
      mFlagOptions(std::move(flagOptions)) {}

bool Args::parse(const std::vector<std::string>& argv) {
    auto contains = [](const std::vector<std::string>& v, const std::string& s) {
        return std::find(v.begin(), v.end(), s) != v.end();
    };
    if (wantsHelp(argv)) {
        mHelp = true;
        return true;
    }
    for (std::size_t i = 0; i < argv.size(); ++i) {
        std::string a = argv[i];
        if (a.size() > 2 && a.rfind("--", 0) == 0) {
            std::string name = a.substr(2), inlineValue;
            bool hasInline = false;
            if (auto eq = name.find('='); eq != std::string::npos) {
                inlineValue = name.substr(eq + 1);
                name = name.substr(0, eq);
                hasInline = true;
            }
            if (contains(mValueOptions, name)) {
                if (hasInline) {
                    mValues[name] = inlineValue;
                } else if (i + 1 < argv.size()) {
                    mValues[name] = argv[++i];
                } else {
                    mError = mCommand + ": option --" + name + " needs a value";
                    return false;
                }
            } else if (contains(mFlagOptions, name) && !hasInline) {
                mFlags.push_back(name);
            } else {
                std::vector<std::string> all = mValueOptions;
                all.insert(all.end(), mFlagOptions.begin(), mFlagOptions.end());
                mError = mCommand + ": unknown option --" + name;
                if (auto m = closestMatch(name, all)) mError += " (did you mean --" + *m + "?)";
                return false;
            }
        } else if (a.size() > 1 && a[0] == '-' && a != "-" &&
                   !(a.size() > 1 && (std::isdigit(static_cast<unsigned char>(a[1])) != 0))) {
            mError = mCommand + ": unknown option " + a;
            return false;
        } else {
            mPositionals.push_back(a);
        }
    }
    return true;
}

std::optional<std::string> Args::value(const std::string& name) const {
    auto it = mValues.find(name);
    if (it == mValues.end()) return std::nullopt;
    return it->second;
}

bool Args::flag(const std::string& name) const {
    return std::find(mFlags.begin(), mFlags.end(), name) != mFlags.end();
}

}  // namespace kiosk::app
