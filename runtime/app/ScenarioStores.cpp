#include "runtime/app/ScenarioStores.h"

#include "config/MeaningCheck.h"
#include "runtime/io/StoreIntegrity.h"

#include <set>

namespace kiosk::app {

Diagnostics openScenarioStores(const config::Scenario& scenario, OpenedStores& opened,
                               io::IntegrityLevel check) {
    Diagnostics out;
    std::set<std::string> reported;
    for (const auto& [id, ref] : scenario.stores) {
        auto reader = io::StoreReader::open(ref.path);
        if (reader.ok() && *reader.value) {
            for (const auto& d : reader.diagnostics.items()) out.add(d);  // warnings
            opened.emplace(id, std::move(*reader.value));
            out.append(io::checkStoreIntegrity(ref.path, check));
            continue;
        }
        const config::Location at = scenario.sourceMap.value(ref.pointer);
        for (const auto& d : reader.diagnostics.items()) {
            if (d.severity != Severity::Error) {
                out.add(d);
                continue;
            }
            Diagnostic e = d;
            e.file = at.file;
            e.line = at.line;
            e.column = at.column;
            e.where = ref.pointer;
            e.message = "store \"" + ref.path.string() +
                        "\": " + (d.where.empty() ? "" : d.where + ": ") + d.message;
            out.add(std::move(e));
            reported.insert(id);
            break;  // the first error says why; the rest follow from it
        }
    }
    const Diagnostics meaning =
        config::checkMeaning(scenario, [&](const std::string& id) -> const io::StoreInfo* {
            auto it = opened.find(id);
            return it == opened.end() ? nullptr : &it->second->info();
        });
    for (const auto& d : meaning.items()) {
        // Already said, with the store's own reason, above.
        if (d.code == "SCENARIO_STORE_UNAVAILABLE" && !reported.empty()) {
            bool mine = false;
            for (const auto& id : reported)
                if (d.where == scenario.stores.at(id).pointer) mine = true;
            if (mine) continue;
        }
        out.add(d);
    }
    return out;
}

}  // namespace kiosk::app
