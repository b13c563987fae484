#pragma once

#include "runtime/color/ColorSpace.h"

#include <optional>
#include <string_view>

namespace kiosk::color {

/**
 * @brief A colour name as GMT reads it in a `.cpt` (its 663 documented names: X11's rgb.txt
 * names without spaces, their numbered variants `darkorange1..4`, `gray0..100` / `grey0..100`,
 * and GMT's own `lightred`, `darkyellow`, ...). Case-insensitive; nullopt for other names.
 * These are X11's values, not CSS's: `gray` is 190/190/190 and `green` 0/255/0, as in GMT.
 */
std::optional<Rgba> gmtNamedColor(std::string_view name);

}  // namespace kiosk::color
