#pragma once

// The built-in layer kinds' scenario sections and what a kind's reader may share. Compiled
// into kiosk_config (config/CMakeLists.txt): config reads scenarios without the layers library.
#include "config/KindSection.h"
#include "config/ReaderSupport.h"

#include <memory>
#include <string>

namespace kiosk::config::reader {

/** @brief The layer's kind as the scenario names it ("sequence", a registered kind's name). */
std::string kindNameOf(const Layer& l);

/** @brief What a layer reading a store table or sequence takes and needs. */
enum class SourcedValues {
    Imagery,          ///< a store layer (thematic, luminance, visibility, normals, data)
    OptionalImagery,  ///< a store layer, or none (topographic shades the terrain itself)
    Sequence,         ///< a sequence: interpolate, nodataAs
    Product,          ///< a product of a sequence: nodataAs, product (no interpolate)
};

/** @brief `"of"` is the difference kind's: refused on any other kind. */
void refuseOperands(Ctx& c, const Obj& o);
/** @brief The `product` object (layers/products/ProductSection.cpp); refused on other kinds. */
void productOptions(Ctx& c, const Obj& o, Layer& l);
/** @brief Source, sequence, transfer and the sequence-only options, for `values`. */
void checkSourced(Ctx& c, const Obj& o, const Layer& l, SourcedValues values, bool transfer);

/** @brief The section of a kind that reads a store table or sequence (`transfer`: required). */
std::shared_ptr<const KindSection> sourcedSection(SourcedValues values, bool transfer);
/** @brief The difference kind's section (layers/difference/DifferenceSection.cpp). */
std::shared_ptr<const KindSection> differenceSection();

}  // namespace kiosk::config::reader
