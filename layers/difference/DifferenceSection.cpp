// The difference kind's scenario section: "of": [A, B] and a (diverging) transfer function, no
// source of its own. Compiled into kiosk_config (config/KindSections.cpp registers it).
#include "layers/SourcedSection.h"

namespace kiosk::config::reader {
namespace {

class DifferenceSection : public KindSection {
public:
    void read(Ctx& c, const Obj& o, Layer& l) const override {
        // A - B of two scalar layers of the stack: no source of its own.
        if (o.has("source"))
            c.error("SCENARIO_CONFLICT", o.at("source"),
                    "a difference layer has no \"source\": it subtracts the layers in \"of\"");
        if (o.has("of") && l.operands.size() != 2)
            c.error("SCENARIO_BAD_VALUE", o.at("of"),
                    "\"of\" wants two layer ids [A, B] (drawn as A - B)");
        else if (!o.has("of"))
            c.error("SCENARIO_MISSING", o.ptr(),
                    "a difference layer needs \"of\": [A, B], two scalar layer ids");
        if (l.transfer.empty() && !o.has("transfer"))
            c.error("SCENARIO_MISSING", o.ptr(),
                    "a difference layer needs \"transfer\" (a diverging transfer function)");
        productOptions(c, o, l);
    }
};

}  // namespace

std::shared_ptr<const KindSection> differenceSection() {
    return std::make_shared<DifferenceSection>();
}

}  // namespace kiosk::config::reader
