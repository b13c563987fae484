#pragma once

#include "runtime/color/TransferFunction.h"
#include "runtime/core/Result.h"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

// Colour-map files users already have, beside ParaView presets and gdaldem colour relief
// (ColorImport.h): matplotlib/cmocean float RGB lists, GMT colour palette tables, and the
// format-sniffing entry point behind a transfer function's `"file": PATH`. Every parser stops
// at the first problem of a file and reports it once, with its line. No throw, any thread.
namespace kiosk::color {

/**
 * @brief A matplotlib / cmocean style list (cmocean's `rgb/NAME-rgb.txt`, `np.savetxt` of a
 * colormap): one colour per line as three numbers `r g b` in 0..1 (spaces, tabs or commas),
 * `#` comments allowed. The N colours sit evenly on the domain 0..1 (matplotlib's
 * ListedColormap sampling), interpolated in sRGB. Codes: COLOR_RGB_SYNTAX, COLOR_RGB_RANGE,
 * COLOR_RGB_EMPTY, naming file:line.
 */
Result<TransferFunction> parseFloatRgbList(std::string_view text, const std::string& file);

/**
 * @brief A GMT colour palette table (`.cpt`, GMT 4 to 6): slices `z0 C0 z1 C1 [L|U|B] [;label]`
 * where a colour C is `r g b`, `r/g/b`, `h-s-v`, `#rrggbb`, a grey `0..255` or one of GMT's
 * colour names (GmtColorNames.h); `B`, `F` and `N` lines give the colours below the range, above
 * it and for nodata; `#` comments. `# COLOR_MODEL = RGB` (the default) interpolates slices in
 * RGB; `# COLOR_MODEL = HSV` reads `h s v` triplets (h 0..360, s and v 0..1) and interpolates
 * slices in HSV as GMT does (CMYK is refused). Each RGB slice becomes two stops (a colour jump
 * between slices is a step). A categorical table (`key C [;label]` lines, GMT 5+) becomes
 * classes with the labels. Codes: COLOR_CPT_SYNTAX, COLOR_CPT_RANGE, COLOR_CPT_UNSUPPORTED,
 * COLOR_CPT_EMPTY, naming file:line.
 */
Result<TransferFunction> parseCpt(std::string_view text, const std::string& file);

/** @brief The colour-map formats parseColorMapFile() tells apart. */
enum class ColorFileFormat { ParaView, Cpt, FloatRgb, ColorRules };

/**
 * @brief The format of a colour-map file from its extension and content: `.json` ParaView;
 * `.cpt` (or a COLOR_MODEL comment, B/F/N lines, `r/g/b` colours) GMT; mostly lines of three
 * numbers within 0..1 a float RGB list; anything else GRASS colour rules / gdaldem colour relief.
 */
ColorFileFormat sniffColorFile(const std::filesystem::path& file, std::string_view text);

/**
 * @brief Read any supported colour-map file (`"file": PATH` in a transfer function). ParaView
 * files must hold exactly one preset here (name others with `"paraview": {"file", "name"}`);
 * GRASS rules / colour relief percentages use `dataRange`. COLOR_FILE when unreadable.
 */
Result<TransferFunction> importColorMapFile(
    const std::filesystem::path& file,
    std::optional<std::pair<double, double>> dataRange = std::nullopt,
    ColorFileFormat* format = nullptr);

/** @brief GMT tables and colour rules are in data units; float lists and ParaView presets are
 *  relative (0..1, the preset's x) and are rescaled onto a transfer function's domain. */
constexpr bool hasDataUnits(ColorFileFormat f) {
    return f == ColorFileFormat::Cpt || f == ColorFileFormat::ColorRules;
}

}  // namespace kiosk::color
