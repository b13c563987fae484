#pragma once

#include "config/Scenario.h"
#include "runtime/core/Diagnostics.h"
#include "runtime/io/StoreIntegrity.h"
#include "runtime/io/StoreReader.h"

#include <map>
#include <memory>
#include <string>

// The step `validate`, `render` and `play` share after a scenario has been read: open its stores
// and run the meaning checks. A store that cannot be opened is reported once, in the scenario's
// terms (`scenario.json:6:30: /stores/valley: store "v.gpkg": <why> [STORE_...]`), so that a user
// sees which line of which file to fix whichever command found it.
namespace kiosk::app {

using OpenedStores = std::map<std::string, std::unique_ptr<io::StoreReader>>;

/**
 * @brief Open every store of `scenario` into `opened` (by store id) and check the scenario
 * against them (config::checkMeaning) and each store's tables (io::checkStoreIntegrity at
 * `check`: Core for render and play, Tables or Deep for validate). Returns the errors and warnings,
 * each one line; store open problems carry the scenario file, line:col and `/stores/<id>` pointer,
 * integrity problems the store file and table or tile. Never throws.
 */
Diagnostics openScenarioStores(const config::Scenario& scenario, OpenedStores& opened,
                               io::IntegrityLevel check = io::IntegrityLevel::Core);

}  // namespace kiosk::app
