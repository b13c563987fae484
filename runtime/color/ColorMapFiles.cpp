#include "runtime/color/ColorMapFiles.h"

#include "runtime/color/ColorImport.h"
#include "runtime/color/ColorText.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

namespace kiosk::color {

namespace {

using detail::readText;
using detail::toNumber;

std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

/** @brief Lines of a text with their 1-based numbers; `#` starts a comment line. */
struct Line {
    int number = 0;
    std::string text;     ///< without the comment part
    std::string comment;  ///< after a leading '#', for "# COLOR_MODEL = ..."
};

std::vector<Line> lines(std::string_view text) {
    std::vector<Line> out;
    std::size_t pos = 0;
    int n = 0;
    while (pos < text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        Line l;
        l.number = ++n;
        l.text = std::string(text.substr(pos, end - pos));
        pos = end + 1;
        if (!l.text.empty() && l.text.back() == '\r') l.text.pop_back();
        const auto first = l.text.find_first_not_of(" \t");
        if (first != std::string::npos && l.text[first] == '#') {
            l.comment = l.text.substr(first + 1);
            l.text.clear();
        }
        out.push_back(std::move(l));
    }
    return out;
}

std::vector<std::string> tokens(std::string s, const char* separators) {
    for (char& c : s)
        if (std::strchr(separators, c)) c = ' ';
    std::vector<std::string> out;
    std::istringstream ls(s);
    for (std::string t; ls >> t;) out.push_back(t);
    return out;
}

Rgba rgb255(double r, double g, double b) {
    return Rgba{float(r / 255.0), float(g / 255.0), float(b / 255.0), 1.0f};
}

// One problem per file: the first, with its line.
Result<TransferFunction> failAt(const char* code, const std::string& file, int line,
                                const std::string& message) {
    Diagnostics d;
    d.error(code, file, "", message).line = line;
    return d;
}

}  // namespace

Result<TransferFunction> parseFloatRgbList(std::string_view text, const std::string& file) {
    std::vector<Rgba> colours;
    for (const Line& l : lines(text)) {
        const auto tok = tokens(l.text, ",;\t");
        if (tok.empty()) continue;
        if (tok.size() != 3)
            return failAt("COLOR_RGB_SYNTAX", file, l.number,
                          "expected three numbers `r g b` in 0..1, got " +
                              std::to_string(tok.size()) + " fields");
        double c[3];
        for (int k = 0; k < 3; ++k) {
            auto n = toNumber(tok[std::size_t(k)]);
            if (!n)
                return failAt("COLOR_RGB_SYNTAX", file, l.number,
                              "\"" + tok[std::size_t(k)] + "\" is not a number");
            if (*n < 0 || *n > 1)
                return failAt("COLOR_RGB_RANGE", file, l.number,
                              "component " + tok[std::size_t(k)] +
                                  " is outside 0..1 (a float RGB list; 0..255 colours belong in "
                                  "a GRASS rules or .cpt file)");
            c[k] = *n;
        }
        colours.push_back(Rgba{float(c[0]), float(c[1]), float(c[2]), 1.0f});
    }
    Diagnostics d;
    if (colours.size() < 2) {
        d.error("COLOR_RGB_EMPTY", file, "", "needs at least two colours");
        return d;
    }
    TransferFunction tf;
    tf.name = std::filesystem::path(file).stem().string();
    tf.space = Space::Srgb;
    const double n = double(colours.size() - 1);
    for (std::size_t i = 0; i < colours.size(); ++i)
        tf.stops.push_back({double(i) / n, colours[i]});
    d.append(tf.finalize(false, false, false, file, ""));
    if (d.hasErrors()) return d;
    return {std::move(tf), std::move(d)};
}

namespace {

// A GMT colour starting at tok[i]: `r g b` (3 tokens), `r/g/b`, `#hex`, grey, or a name.
// Advances i past it; nullopt with `error` set otherwise.
std::optional<Rgba> cptColour(const std::vector<std::string>& tok, std::size_t& i,
                              std::string& error) {
    if (i >= tok.size()) {
        error = "a colour is missing";
        return std::nullopt;
    }
    const std::string& t = tok[i];
    auto component = [&](const std::string& s) -> std::optional<double> {
        auto n = toNumber(s);
        if (!n) {
            error = "colour component \"" + s + "\" is not a number";
            return std::nullopt;
        }
        if (*n < 0 || *n > 255) {
            error = "colour component " + s + " is outside 0..255";
            return std::nullopt;
        }
        return n;
    };
    if (t.find('/') != std::string::npos) {
        const auto parts = tokens(t, "/");
        if (parts.size() != 3) {
            error = "colour \"" + t + "\" is not r/g/b";
            return std::nullopt;
        }
        auto r = component(parts[0]), g = component(parts[1]), b = component(parts[2]);
        if (!r || !g || !b) return std::nullopt;
        ++i;
        return rgb255(*r, *g, *b);
    }
    if (t.find('-') != std::string::npos && t.front() != '-') {
        error = "h-s-v colour \"" + t + "\" is not supported (use r/g/b or # COLOR_MODEL = RGB)";
        return std::nullopt;
    }
    if (toNumber(t)) {
        // Three numbers are r g b; a lone number before the next z (or the end) is a grey.
        if (i + 2 < tok.size() && toNumber(tok[i + 1]) && toNumber(tok[i + 2]) &&
            tok.size() - i != 4) {
            auto r = component(tok[i]), g = component(tok[i + 1]), b = component(tok[i + 2]);
            if (!r || !g || !b) return std::nullopt;
            i += 3;
            return rgb255(*r, *g, *b);
        }
        auto v = component(t);
        if (!v) return std::nullopt;
        ++i;
        return rgb255(*v, *v, *v);
    }
    if (auto c = parseColor(t)) {
        ++i;
        return c;
    }
    error = "unknown colour \"" + t + "\"";
    return std::nullopt;
}

}  // namespace

Result<TransferFunction> parseCpt(std::string_view text, const std::string& file) {
    TransferFunction tf;
    tf.name = std::filesystem::path(file).stem().string();
    tf.space = Space::Srgb;  // GMT interpolates r, g, b linearly in the RGB model
    bool continuous = false, categorical = false;
    for (const Line& l : lines(text)) {
        if (!l.comment.empty()) {
            auto c = tokens(l.comment, "=");
            if (c.size() == 2 && c[0] == "COLOR_MODEL" && lower(c[1]) != "rgb" &&
                lower(c[1]) != "+rgb")
                return failAt("COLOR_CPT_UNSUPPORTED", file, l.number,
                              "colour model " + c[1] + " is not supported (only RGB)");
            continue;
        }
        std::string body = l.text, label;
        if (auto semi = body.find(';'); semi != std::string::npos) {
            label = body.substr(semi + 1);
            body = body.substr(0, semi);
            label.erase(0, label.find_first_not_of(" \t"));
            while (!label.empty() && std::isspace(static_cast<unsigned char>(label.back())))
                label.pop_back();
        }
        auto tok = tokens(body, "\t,");
        if (tok.empty()) continue;
        // Annotation flags at the end of a slice (L, U, B) are about labels on a colour bar.
        if (tok.size() > 2 && (tok.back() == "L" || tok.back() == "U" || tok.back() == "B"))
            tok.pop_back();
        std::string error;
        const std::string key = tok[0];
        if (key == "B" || key == "F" || key == "N") {
            std::size_t i = 1;
            auto c = cptColour(tok, i, error);
            if (!c || i != tok.size())
                return failAt("COLOR_CPT_SYNTAX", file, l.number,
                              error.empty() ? "expected `" + key + " colour`" : error);
            if (key == "B") {
                tf.below = *c;
                tf.belowGiven = true;
            } else if (key == "F") {
                tf.above = *c;
                tf.aboveGiven = true;
            } else {
                tf.nodata = *c;
            }
            continue;
        }
        auto z0 = toNumber(key);
        if (!z0)
            return failAt("COLOR_CPT_SYNTAX", file, l.number,
                          "\"" + key + "\" is not a z value (nor B, F or N)");
        std::size_t i = 1;
        auto c0 = cptColour(tok, i, error);
        if (!c0) return failAt("COLOR_CPT_SYNTAX", file, l.number, error);
        if (i == tok.size()) {  // `key colour [;label]`: a categorical entry
            categorical = true;
            tf.classes.push_back({*z0, *c0, label});
        } else {
            continuous = true;
            auto z1 = toNumber(tok[i++]);
            auto c1 = z1 ? cptColour(tok, i, error) : std::nullopt;
            if (!z1 || !c1 || i != tok.size())
                return failAt("COLOR_CPT_SYNTAX", file, l.number,
                              !error.empty() ? error : "expected `z0 colour z1 colour`");
            if (!(*z1 > *z0))
                return failAt("COLOR_CPT_RANGE", file, l.number,
                              "slice end " + tok[i - 2] + " is not above its start " + key);
            if (!tf.stops.empty() && *z0 < tf.stops.back().value)
                return failAt("COLOR_CPT_RANGE", file, l.number,
                              "slices must increase (" + key + " after " +
                                  std::to_string(tf.stops.back().value) + ")");
            tf.stops.push_back({*z0, *c0});
            tf.stops.push_back({*z1, *c1});
        }
        if (continuous && categorical)
            return failAt("COLOR_CPT_SYNTAX", file, l.number,
                          "mixes categorical `key colour` lines with `z0 colour z1 colour` slices");
    }
    Diagnostics d;
    if (tf.stops.empty() && tf.classes.empty()) {
        d.error("COLOR_CPT_EMPTY", file, "", "no colour slices");
        return d;
    }
    // Categorical keys become classes: each key covers [key, next key) (finalize's domain).
    d.append(tf.finalize(false, false, false, file, ""));
    if (d.hasErrors()) return d;
    return {std::move(tf), std::move(d)};
}

ColorFileFormat sniffColorFile(const std::filesystem::path& file, std::string_view text) {
    const std::string ext = lower(file.extension().string());
    if (ext == ".json") return ColorFileFormat::ParaView;
    if (ext == ".cpt") return ColorFileFormat::Cpt;
    // Most data lines being three numbers in 0..1 (never a valid colour rule, which needs a
    // value and a colour) makes a float list: one broken line is then reported in the format
    // the file evidently is, once.
    std::size_t dataLines = 0, triplets = 0;
    for (const Line& l : lines(text)) {
        if (l.comment.find("COLOR_MODEL") != std::string::npos) return ColorFileFormat::Cpt;
        const auto tok = tokens(l.text, ",;\t");
        if (tok.empty()) continue;
        if (tok[0] == "B" || tok[0] == "F" || tok[0] == "N") return ColorFileFormat::Cpt;
        if (l.text.find('/') != std::string::npos) return ColorFileFormat::Cpt;
        bool unit = tok.size() == 3;
        for (const auto& t : tok) {
            auto n = toNumber(t);
            unit = unit && n && *n >= 0 && *n <= 1;
        }
        ++dataLines;
        triplets += unit;
    }
    if (dataLines > 0 && triplets * 2 >= dataLines) return ColorFileFormat::FloatRgb;
    return ColorFileFormat::ColorRules;
}

Result<TransferFunction> importColorMapFile(const std::filesystem::path& file,
                                            std::optional<std::pair<double, double>> range,
                                            ColorFileFormat* format) {
    auto text = readText(file);
    if (!text) {
        Diagnostics d;
        d.error("COLOR_FILE", file.string(), "", "cannot read the colour map file");
        return d;
    }
    const ColorFileFormat f = sniffColorFile(file, *text);
    if (format) *format = f;
    switch (f) {
        case ColorFileFormat::Cpt:
            return parseCpt(*text, file.string());
        case ColorFileFormat::FloatRgb:
            return parseFloatRgbList(*text, file.string());
        case ColorFileFormat::ColorRules:
            return parseColorRelief(*text, file.string(), range);
        case ColorFileFormat::ParaView:
            break;
    }
    // ParaView: usable by file alone when it holds exactly one preset.
    std::string cleaned = *text;
    stripTrailingCommas(cleaned);
    const auto doc = nlohmann::json::parse(cleaned, nullptr, false, true);
    std::vector<std::string> names;
    if (doc.is_array())
        for (const auto& p : doc)
            if (p.is_object() && p.contains("Name") && p["Name"].is_string())
                names.push_back(p["Name"].get<std::string>());
    if (doc.is_object() && doc.contains("Name") && doc["Name"].is_string())
        names.push_back(doc["Name"].get<std::string>());
    if (names.size() != 1) {
        Diagnostics d;
        d.error("COLOR_PARAVIEW_UNKNOWN_PRESET", file.string(), "",
                names.empty() ? "not a ParaView preset file (expected a JSON array of presets)"
                              : "holds " + std::to_string(names.size()) +
                                    " presets; name one with \"paraview\": {\"file\", \"name\"}");
        return d;
    }
    return importParaView(*text, names[0], file.string());
}

}  // namespace kiosk::color
