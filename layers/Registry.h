#pragma once

#include "layers/Kind.h"

#include <map>
#include <memory>
#include <string>
#include <string_view>

namespace kiosk::layers {

/**
 * @brief Layer kinds by scenario name ("thematic", "data", ...). The built-in kinds are
 * registered on first use (Registry.cpp, one line each); a test or a plug-in adds its own with
 * add() before the scene is created. Not thread-safe for add(): register at start-up.
 */
class Registry {
public:
    /**
     * @brief Register (or replace) the kind called `name`; with its section() a scenario can
     * name it (`"kind": name`), read by that section.
     */
    void add(std::string name, std::unique_ptr<Kind> kind);
    const Kind* find(std::string_view name) const;

private:
    std::map<std::string, std::unique_ptr<Kind>, std::less<>> mKinds;
};

/** @brief The process's registry, holding the built-in kinds. */
Registry& registry();

}  // namespace kiosk::layers
