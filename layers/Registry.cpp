#include "layers/Registry.h"

#include "layers/arrival/Arrival.h"
#include "layers/data/Data.h"
#include "layers/difference/Difference.h"
#include "layers/duration/Duration.h"
#include "layers/hazard/Hazard.h"
#include "layers/luminance/Luminance.h"
#include "layers/maximum/Maximum.h"
#include "layers/normals/Normals.h"
#include "layers/sequence/Sequence.h"
#include "layers/thematic/Thematic.h"
#include "layers/topographic/Topographic.h"
#include "layers/visibility/Visibility.h"

namespace kiosk::layers {

void Registry::add(std::string name, std::unique_ptr<Kind> kind) {
    if (auto section = kind->section()) config::kindSections().add(name, std::move(section));
    mKinds[std::move(name)] = std::move(kind);
}

const Kind* Registry::find(std::string_view name) const {
    auto it = mKinds.find(name);
    return it == mKinds.end() ? nullptr : it->second.get();
}

Registry& registry() {
    // Explicit registration (not static initialisers): objects of a static library that nothing
    // references are dropped by the linker, and their registration with them.
    static Registry r = [] {
        Registry k;
        k.add("thematic", std::make_unique<ThematicKind>());
        k.add("luminance", std::make_unique<LuminanceKind>());
        k.add("topographic", std::make_unique<TopographicKind>());
        k.add("normals", std::make_unique<NormalsKind>());
        k.add("visibility", std::make_unique<VisibilityKind>());
        k.add("data", std::make_unique<DataKind>());
        k.add("sequence", std::make_unique<SequenceKind>());
        k.add("maximum", std::make_unique<MaximumKind>());
        k.add("arrival", std::make_unique<ArrivalKind>());
        k.add("duration", std::make_unique<DurationKind>());
        k.add("hazard", std::make_unique<HazardKind>());
        k.add("difference", std::make_unique<DifferenceKind>());
        return k;
    }();
    return r;
}

}  // namespace kiosk::layers
