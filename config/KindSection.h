#pragma once

#include "config/Scenario.h"

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace kiosk::config {
namespace reader {
class Ctx;
class Obj;
}  // namespace reader

/**
 * @brief A layer kind's own part of a scenario layer object: its reader and its schema
 * fragment. The common reader (config/LayersSection.cpp) reads what every layer has (id, kind,
 * source, transfer, operation, enabled, and the built-in kinds' properties), then hands the
 * object to the section of the kind the layer names.
 */
class KindSection {
public:
    virtual ~KindSection() = default;
    /** @brief Properties of the layer object this kind adds to the common ones. */
    virtual std::vector<std::string> properties() const { return {}; }
    /**
     * @brief Read and check the kind's own part of layer object `o` into `l` (l.kind,
     * l.kindName, the common fields are set). Each mistake is one error with its pointer.
     */
    virtual void read(reader::Ctx& c, const reader::Obj& o, Layer& l) const = 0;
    /**
     * @brief The kind's JSON Schema fragment: an object with "properties" (its own, each
     * described) and the conditions for a layer of this kind (e.g. "required"); "" when the
     * kind's conditions are in config/schema/scenario.schema.json (the built-in kinds).
     */
    virtual std::string schema() const { return {}; }
};

/**
 * @brief The kinds a scenario may name, by name, in registration order: the built-in kinds'
 * sections first (registered on first use, config/KindSections.cpp), then those added at run
 * time (layers::Registry::add adds a kind's section). Register at start-up: not thread-safe.
 */
class KindSections {
public:
    void add(std::string name, std::shared_ptr<const KindSection> section);
    const KindSection* find(std::string_view name) const;
    const std::vector<std::string>& names() const { return mNames; }

private:
    std::map<std::string, std::shared_ptr<const KindSection>, std::less<>> mSections;
    std::vector<std::string> mNames;
};

KindSections& kindSections();

/**
 * @brief `schemaText` (config/schema/scenario.schema.json) with the kinds registered beyond the
 * built-in ones: each added to the Layer's `kind` enum, its properties to the Layer's, and its
 * fragment as an if/then of the Layer's allOf. Returns `schemaText` unchanged when it is not a
 * scenario schema.
 */
std::string scenarioSchema(const std::string& schemaText);

}  // namespace kiosk::config
