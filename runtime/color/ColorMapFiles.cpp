#include "runtime/color/ColorMapFiles.h"

#include "runtime/color/ColorImport.h"
#include "runtime/color/ColorText.h"
#include "runtime/color/GmtColorNames.h"

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

// GMT's HSV convention: h in degrees 0..360, s and v in 0..1.
struct Hsv {
    double h = 0, s = 0, v = 0;
};

Rgba hsvToRgb(const Hsv& c) {
    if (c.s == 0) return Rgba{float(c.v), float(c.v), float(c.v), 1.0f};
    const double h = 6.0 * std::fmod(c.h, 360.0) / 360.0;
    const int sextant = int(std::floor(h));
    const double f = h - sextant;
    const double p = c.v * (1 - c.s), q = c.v * (1 - c.s * f), t = c.v * (1 - c.s * (1 - f));
    double r = c.v, g = t, b = p;
    switch (sextant) {
        case 1:
            r = q, g = c.v, b = p;
            break;
        case 2:
            r = p, g = c.v, b = t;
            break;
        case 3:
            r = p, g = q, b = c.v;
            break;
        case 4:
            r = t, g = p, b = c.v;
            break;
        case 5:
            r = c.v, g = p, b = q;
            break;
        default:
            break;
    }
    return Rgba{float(r), float(g), float(b), 1.0f};
}

Hsv rgbToHsv(const Rgba& c) {
    const double rgb[3] = {c.r, c.g, c.b};
    int hi = 0, lo = 0;
    for (int k = 1; k < 3; ++k) {
        if (rgb[k] > rgb[hi]) hi = k;
        if (rgb[k] < rgb[lo]) lo = k;
    }
    const double range = rgb[hi] - rgb[lo];
    Hsv out{0, rgb[hi] == 0 ? 0 : range / rgb[hi], rgb[hi]};
    if (out.s == 0) return out;  // grey: hue undefined, GMT takes 0
    out.h = 120.0 * hi + 60.0 * (rgb[(hi + 1) % 3] - rgb[(hi + 2) % 3]) / range;
    if (out.h < 0) out.h += 360;
    return out;
}

/** @brief A colour of a .cpt: its RGB, and its HSV when the table's model is HSV. */
struct CptColour {
    Rgba rgb;
    Hsv hsv;
};

// A GMT colour starting at tok[i]: `r g b` (3 tokens; `h s v` in the HSV model), `r/g/b`,
// `h-s-v`, `#hex`, grey, or a name. Advances i past it; nullopt with `error` set otherwise.
std::optional<CptColour> cptColour(const std::vector<std::string>& tok, std::size_t& i,
                                   bool hsvModel, std::string& error) {
    if (i >= tok.size()) {
        error = "a colour is missing";
        return std::nullopt;
    }
    const std::string& t = tok[i];
    auto number = [&](const std::string& s, int max) -> std::optional<double> {
        auto n = toNumber(s);
        if (!n) {
            error = "colour component \"" + s + "\" is not a number";
            return std::nullopt;
        }
        if (*n < 0 || *n > max) {
            error = "colour component " + s + " is outside 0.." + std::to_string(max);
            return std::nullopt;
        }
        return n;
    };
    auto fromHsv = [&](const std::string& h, const std::string& s,
                       const std::string& v) -> std::optional<CptColour> {
        auto hh = number(h, 360), ss = number(s, 1), vv = number(v, 1);
        if (!hh || !ss || !vv) return std::nullopt;
        const Hsv c{*hh, *ss, *vv};
        return CptColour{hsvToRgb(c), c};
    };
    auto fromRgb = [&](const Rgba& c) { return CptColour{c, rgbToHsv(c)}; };
    if (t.find('/') != std::string::npos) {
        const auto parts = tokens(t, "/");
        if (parts.size() != 3) {
            error = "colour \"" + t + "\" is not r/g/b";
            return std::nullopt;
        }
        auto r = number(parts[0], 255), g = number(parts[1], 255), b = number(parts[2], 255);
        if (!r || !g || !b) return std::nullopt;
        ++i;
        return fromRgb(rgb255(*r, *g, *b));
    }
    if (toNumber(t)) {
        // Three numbers are r g b (h s v); a lone number before the next z (or the end) is a
        // grey 0..255 in either model, as in GMT.
        if (i + 2 < tok.size() && toNumber(tok[i + 1]) && toNumber(tok[i + 2]) &&
            tok.size() - i != 4) {
            i += 3;
            if (hsvModel) return fromHsv(tok[i - 3], tok[i - 2], tok[i - 1]);
            auto r = number(tok[i - 3], 255), g = number(tok[i - 2], 255),
                 b = number(tok[i - 1], 255);
            if (!r || !g || !b) return std::nullopt;
            return fromRgb(rgb255(*r, *g, *b));
        }
        auto v = number(t, 255);
        if (!v) return std::nullopt;
        ++i;
        return fromRgb(rgb255(*v, *v, *v));
    }
    if (t.find('-') != std::string::npos && t.front() != '-' && t.front() != '#') {
        const auto parts = tokens(t, "-");
        if (parts.size() != 3) {
            error = "colour \"" + t + "\" is not h-s-v";
            return std::nullopt;
        }
        ++i;
        return fromHsv(parts[0], parts[1], parts[2]);
    }
    // GMT's names first: they are X11's, which differ from CSS's for gray, green, maroon and
    // purple. The few names only parseColor knows (transparent, indigo, teal, ...) still read.
    if (auto c = t.front() == '#' ? std::nullopt : gmtNamedColor(t)) {
        ++i;
        return fromRgb(*c);
    }
    if (auto c = parseColor(t)) {
        ++i;
        return fromRgb(*c);
    }
    error = "unknown colour \"" + t + "\"";
    return std::nullopt;
}

// GMT interpolates an HSV table's slices in h, s and v. The slice becomes sRGB stops at every
// sextant boundary its hue crosses (between them RGB is linear in h at fixed s and v), and at
// 16 even steps when s or v change too, so the LUT follows GMT's colours within 1 DN.
void addHsvSlice(TransferFunction& tf, double z0, const Hsv& a, double z1, const Hsv& b) {
    std::vector<double> ts{0.0, 1.0};
    if (a.h != b.h) {
        const double lo = std::min(a.h, b.h), hi = std::max(a.h, b.h);
        for (double edge = std::floor(lo / 60) * 60 + 60; edge < hi; edge += 60)
            ts.push_back((edge - a.h) / (b.h - a.h));
    }
    if (a.s != b.s || a.v != b.v)
        for (int k = 1; k < 16; ++k) ts.push_back(k / 16.0);
    std::sort(ts.begin(), ts.end());
    ts.erase(std::unique(ts.begin(), ts.end()), ts.end());
    for (double t : ts) {
        const Hsv c{a.h + t * (b.h - a.h), a.s + t * (b.s - a.s), a.v + t * (b.v - a.v)};
        tf.stops.push_back({t == 1.0 ? z1 : z0 + t * (z1 - z0), hsvToRgb(c)});
    }
}

}  // namespace

Result<TransferFunction> parseCpt(std::string_view text, const std::string& file) {
    TransferFunction tf;
    tf.name = std::filesystem::path(file).stem().string();
    tf.space = Space::Srgb;  // GMT interpolates r, g, b linearly in the RGB model
    bool continuous = false, categorical = false, hsvModel = false;
    for (const Line& l : lines(text)) {
        if (!l.comment.empty()) {
            auto c = tokens(l.comment, "=");
            if (c.size() == 2 && c[0] == "COLOR_MODEL") {
                // A leading '+' (as GMT 5 writes some tables) names the same model.
                const std::string model = lower(c[1][0] == '+' ? c[1].substr(1) : c[1]);
                if (model != "rgb" && model != "hsv")
                    return failAt("COLOR_CPT_UNSUPPORTED", file, l.number,
                                  "colour model " + c[1] + " is not supported (RGB or HSV)");
                hsvModel = model == "hsv";
            }
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
            auto c = cptColour(tok, i, hsvModel, error);
            if (!c || i != tok.size())
                return failAt("COLOR_CPT_SYNTAX", file, l.number,
                              error.empty() ? "expected `" + key + " colour`" : error);
            if (key == "B") {
                tf.below = c->rgb;
                tf.belowGiven = true;
            } else if (key == "F") {
                tf.above = c->rgb;
                tf.aboveGiven = true;
            } else {
                tf.nodata = c->rgb;
            }
            continue;
        }
        auto z0 = toNumber(key);
        if (!z0)
            return failAt("COLOR_CPT_SYNTAX", file, l.number,
                          "\"" + key + "\" is not a z value (nor B, F or N)");
        std::size_t i = 1;
        auto c0 = cptColour(tok, i, hsvModel, error);
        if (!c0) return failAt("COLOR_CPT_SYNTAX", file, l.number, error);
        if (i == tok.size()) {  // `key colour [;label]`: a categorical entry
            categorical = true;
            tf.classes.push_back({*z0, c0->rgb, label});
        } else {
            continuous = true;
            auto z1 = toNumber(tok[i++]);
            auto c1 = z1 ? cptColour(tok, i, hsvModel, error) : std::nullopt;
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
            if (hsvModel) {
                addHsvSlice(tf, *z0, c0->hsv, *z1, c1->hsv);
            } else {
                tf.stops.push_back({*z0, c0->rgb});
                tf.stops.push_back({*z1, c1->rgb});
            }
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
