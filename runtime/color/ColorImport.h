#pragma once

#include "runtime/color/TransferFunction.h"
#include "runtime/core/Result.h"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

// Importers for transfer functions written by other tools, and the built-in named maps.
// Every importer returns a finalized TransferFunction (sorted, domain set) or diagnostics with a
// stable code naming the file (and line for text formats); none throws, any thread.
namespace kiosk::color {

/**
 * @brief One preset from ParaView's preset JSON (the "Import Preset" format: an array of objects
 * with "Name", "ColorSpace", "RGBPoints" = [x, r, g, b, ...], "NanColor", or "IndexedColors" +
 * "Annotations" for categorical presets).
 *
 * Deliberately tolerant of trailing commas before `]`/`}` (ParaView's own ColorMaps.json ends with
 * one; ParaView's reader accepts it). x values are kept in the preset's own units: the domain is
 * [first x, last x]; callers map it onto a data range with TransferFunction::rescaled().
 * ColorSpace: RGB -> srgb, Lab/CIELAB -> lab, Diverging -> msh, Step -> classes, HSV -> lab with
 * a COLOR_PARAVIEW_SPACE warning. Codes: COLOR_PARAVIEW_PARSE, COLOR_PARAVIEW_UNKNOWN_PRESET
 * (with a did-you-mean hint), COLOR_PARAVIEW_POINTS, COLOR_FILE.
 */
Result<TransferFunction> importParaView(std::string_view text, std::string_view presetName,
                                        const std::string& fileForMessages);
Result<TransferFunction> importParaViewFile(const std::filesystem::path& file,
                                            std::string_view presetName);

/**
 * @brief gdaldem color-relief text (`.clr`, `.txt`): one entry per line, `value r g b [a]` or
 * `value colorname`, separated by spaces, tabs, commas or colons. `value` is a number in data
 * units, a percentage `50%` of `dataRange` (required when percentages occur), or `nv` for the
 * nodata colour. Entries may come in any order (GDAL's own test file is descending); they are
 * interpolated in sRGB like gdaldem does. Codes: COLOR_CLR_SYNTAX, COLOR_CLR_RANGE,
 * COLOR_CLR_PERCENT, COLOR_CLR_EMPTY, COLOR_FILE; each names file:line.
 */
Result<TransferFunction> parseColorRelief(
    std::string_view text, const std::string& fileForMessages,
    std::optional<std::pair<double, double>> dataRange = std::nullopt);
Result<TransferFunction> importColorReliefFile(
    const std::filesystem::path& file,
    std::optional<std::pair<double, double>> dataRange = std::nullopt);

/**
 * @brief Built-in maps: "viridis", "cividis" (domain 0..1: 33 control points sampled from the
 * published 256-entry tables, Lab interpolation, within 2 / 5 DN of them), "flood-depth" (0..5 m,
 * light cyan to deep blue, transparent when dry), "fire-intensity" (0..10000 kW/m, pale yellow to
 * dark red), "grayscale" (0..1). nullopt for any other name.
 */
std::optional<TransferFunction> namedMap(std::string_view name);
/** @brief The names namedMap() knows, for validation and hints. */
std::vector<std::string> namedMapNames();

/**
 * @brief Remove commas that directly precede `]` or `}` outside strings (ParaView's files have
 * them). Returns the number removed.
 */
std::size_t stripTrailingCommas(std::string& json);

}  // namespace kiosk::color
