#include "runtime/app/ValidateCommand.h"

#include "config/ScenarioReader.h"
#include "runtime/app/ScenarioStores.h"
#include "runtime/core/ExitCode.h"
#include "runtime/core/Strings.h"

#include <iostream>
#include <map>
#include <memory>
#include <optional>

namespace kiosk::app {

namespace {

const char* const kUsage =
    "usage: geokiosk validate [--no-stores] [--deep] [--quiet] [--allow-path DIR] SCENARIO...\n"
    "  check scenarios (schema, references, includes) and, unless --no-stores, their stores'\n"
    "  tables (--deep: and every tile)\n";

struct Options {
    bool noStores = false;
    bool deep = false;
    bool quiet = false;
    std::vector<std::string> scenarios;
};

// nullopt to go on, else the status to exit with (after --help, or a usage error).
std::optional<int> parseOptions(const std::vector<std::string>& args, Options& o, std::ostream& out,
                                std::ostream& err) {
    const std::vector<std::string> known = {"--no-stores", "--deep", "--quiet", "--help"};
    bool positionalOnly = false;
    for (const auto& a : args) {
        if (positionalOnly || a.empty() || a[0] != '-' || a == "-") {
            o.scenarios.push_back(a);
        } else if (a == "--") {
            positionalOnly = true;
        } else if (a == "--no-stores") {
            o.noStores = true;
        } else if (a == "--deep") {
            o.deep = true;
        } else if (a == "--quiet" || a == "-q") {
            o.quiet = true;
        } else if (a == "--help" || a == "-h") {
            out << kUsage;
            return kExitOk;
        } else {
            err << "geokiosk validate: unknown option '" << a << "'";
            if (auto m = closestMatch(a, known)) err << " (did you mean '" << *m << "'?)";
            err << "\n" << kUsage;
            return kExitUsage;
        }
    }
    if (o.scenarios.empty()) {
        err << "geokiosk validate: give at least one SCENARIO\n" << kUsage;
        return kExitUsage;
    }
    return std::nullopt;
}

// One scenario; true when valid. Every message goes to `err` as it is found.
bool validateOne(const std::string& path, const Options& o, std::ostream& out, std::ostream& err) {
    auto scenario = config::readScenario(path);
    err << scenario.diagnostics.format();
    if (!scenario.ok()) return false;

    bool valid = true;
    std::size_t storesOpened = 0;
    if (!o.noStores) {
        OpenedStores opened;
        const Diagnostics stores = openScenarioStores(
            *scenario, opened, o.deep ? io::IntegrityLevel::Deep : io::IntegrityLevel::Tables);
        storesOpened = opened.size();
        err << stores.format();
        valid = !stores.hasErrors();
    }
    if (valid && !o.quiet) {
        out << path << ": ok (" << scenario->layers.size() << " layers, "
            << scenario->transferFunctions.size() << " transfer functions, "
            << scenario->sourceFiles.size() << " files";
        if (o.noStores)
            out << ", stores not checked";
        else
            out << ", " << storesOpened << " stores checked";
        out << ")\n";
    }
    return valid;
}

}  // namespace

int runValidateCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    Options o;
    if (const auto status = parseOptions(args, o, out, err)) return *status;
    bool allValid = true;
    for (const auto& path : o.scenarios) {
        try {
            if (!validateOne(path, o, out, err)) allValid = false;
        } catch (const std::exception& e) {
            // The readers do not throw; this guards the store layer and allocation failures so
            // one bad file never stops the others being checked.
            err << path << ": internal error: " << e.what() << " [VALIDATE_INTERNAL]\n";
            allValid = false;
        }
    }
    return allValid ? kExitOk : kExitBadInput;
}

int runValidateCommand(const std::vector<std::string>& args) {
    return runValidateCommand(args, std::cout, std::cerr);
}

}  // namespace kiosk::app
