#include "runtime/color/ColorImport.h"
#include "runtime/color/ColorText.h"

#include "runtime/core/Strings.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace kiosk::color {

namespace {

using detail::readText;
using detail::toNumber;

using nlohmann::json;

std::optional<double> channel(const json& j) {
    if (!j.is_number()) return std::nullopt;
    const double v = j.get<double>();
    if (!std::isfinite(v) || v < 0 || v > 1) return std::nullopt;
    return v;
}

Rgba rgb255(int r, int g, int b, int a = 255) {
    return Rgba{float(r) / 255.0f, float(g) / 255.0f, float(b) / 255.0f, float(a) / 255.0f};
}

Rgba hex(const char* h) {
    return parseColor(h).value_or(Rgba{});
}

}  // namespace

std::size_t stripTrailingCommas(std::string& text) {
    std::size_t removed = 0;
    bool inString = false;
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            out += c;
            if (c == '\\' && i + 1 < text.size())
                out += text[++i];
            else if (c == '"')
                inString = false;
            continue;
        }
        if (c == '"') inString = true;
        if (c == ',') {
            std::size_t j = i + 1;
            while (j < text.size() && std::isspace(static_cast<unsigned char>(text[j]))) ++j;
            if (j < text.size() && (text[j] == ']' || text[j] == '}')) {
                ++removed;
                continue;
            }
        }
        out += c;
    }
    text.swap(out);
    return removed;
}

Result<TransferFunction> importParaView(std::string_view text, std::string_view presetName,
                                        const std::string& file) {
    Diagnostics d;
    std::string cleaned(text);
    stripTrailingCommas(cleaned);
    const json doc = json::parse(cleaned, nullptr, /*allow_exceptions=*/false,
                                 /*ignore_comments=*/true);
    if (doc.is_discarded() || !(doc.is_array() || doc.is_object())) {
        d.error("COLOR_PARAVIEW_PARSE", file, "",
                "not a ParaView preset file (expected a JSON array of presets)");
        return d;
    }
    const json* preset = nullptr;
    std::vector<std::string> names;
    auto consider = [&](const json& p) {
        if (!p.is_object()) return;
        auto n = p.find("Name");
        if (n == p.end() || !n->is_string()) return;
        names.push_back(n->get<std::string>());
        if (!preset && names.back() == presetName) preset = &p;
    };
    if (doc.is_array())
        for (const auto& p : doc) consider(p);
    else
        consider(doc);
    if (!preset) {
        auto& e = d.error("COLOR_PARAVIEW_UNKNOWN_PRESET", file, "",
                          "no preset named \"" + std::string(presetName) + "\"");
        if (auto m = closestMatch(presetName, names)) e.hint = "did you mean \"" + *m + "\"?";
        return d;
    }
    const std::string where = "preset \"" + std::string(presetName) + "\"";
    TransferFunction tf;
    tf.name = std::string(presetName);
    tf.space = Space::Lab;
    if (auto nan = preset->find("NanColor");
        nan != preset->end() && nan->is_array() && nan->size() >= 3) {
        auto r = channel((*nan)[0]), g = channel((*nan)[1]), b = channel((*nan)[2]);
        if (r && g && b) tf.nodata = Rgba{float(*r), float(*g), float(*b), 1.0f};
    }
    const std::string space = preset->contains("ColorSpace") && (*preset)["ColorSpace"].is_string()
                                  ? (*preset)["ColorSpace"].get<std::string>()
                                  : std::string("Lab");
    if (space == "RGB")
        tf.space = Space::Srgb;
    else if (space == "Diverging")
        tf.space = Space::Msh;
    else if (space == "Lab" || space == "CIELAB" || space == "Step")
        tf.space = Space::Lab;
    else
        d.warning("COLOR_PARAVIEW_SPACE", file, where,
                  "colour space \"" + space + "\" is not supported; interpolating in lab");

    auto points = preset->find("RGBPoints");
    auto indexed = preset->find("IndexedColors");
    if (points != preset->end()) {
        if (!points->is_array() || points->size() < 8 || points->size() % 4 != 0) {
            d.error("COLOR_PARAVIEW_POINTS", file, where,
                    "RGBPoints must hold at least two [x, r, g, b] quadruples");
            return d;
        }
        for (std::size_t i = 0; i < points->size(); i += 4) {
            const json& x = (*points)[i];
            auto r = channel((*points)[i + 1]), g = channel((*points)[i + 2]),
                 b = channel((*points)[i + 3]);
            if (!x.is_number() || !std::isfinite(x.get<double>()) || !r || !g || !b) {
                d.error("COLOR_PARAVIEW_POINTS", file, where,
                        "RGBPoints entry " + std::to_string(i / 4) +
                            " is not [x, r, g, b] with r, g, b in 0..1");
                return d;
            }
            const Rgba c{float(*r), float(*g), float(*b), 1.0f};
            if (space == "Step")
                tf.classes.push_back({x.get<double>(), c, {}});
            else
                tf.stops.push_back({x.get<double>(), c});
        }
        bool explicitDomain = false;
        if (space == "Step") {
            // Step presets end at their last point: that point's colour is the top class.
            tf.domainMin = tf.classes.front().from;
            tf.domainMax = tf.classes.back().from;
            explicitDomain = tf.domainMax > tf.domainMin;
            if (explicitDomain && tf.classes.size() > 1) tf.classes.pop_back();
        }
        d.append(tf.finalize(explicitDomain, false, false, file, where));
    } else if (indexed != preset->end() && indexed->is_array() && indexed->size() >= 3 &&
               indexed->size() % 3 == 0) {
        std::vector<std::string> labels;
        if (auto ann = preset->find("Annotations"); ann != preset->end() && ann->is_array())
            for (std::size_t i = 1; i < ann->size(); i += 2)
                labels.push_back((*ann)[i].is_string() ? (*ann)[i].get<std::string>() : "");
        for (std::size_t i = 0; i < indexed->size(); i += 3) {
            auto r = channel((*indexed)[i]), g = channel((*indexed)[i + 1]),
                 b = channel((*indexed)[i + 2]);
            if (!r || !g || !b) {
                d.error("COLOR_PARAVIEW_POINTS", file, where,
                        "IndexedColors entry " + std::to_string(i / 3) + " is not r, g, b in 0..1");
                return d;
            }
            const std::size_t k = i / 3;
            tf.classes.push_back({double(k), Rgba{float(*r), float(*g), float(*b), 1.0f},
                                  k < labels.size() ? labels[k] : std::string()});
        }
        d.append(tf.finalize(false, false, false, file, where));
    } else {
        d.error("COLOR_PARAVIEW_POINTS", file, where, "has neither RGBPoints nor IndexedColors");
    }
    if (d.hasErrors()) return d;
    return {std::move(tf), std::move(d)};
}

Result<TransferFunction> importParaViewFile(const std::filesystem::path& file,
                                            std::string_view presetName) {
    auto text = readText(file);
    if (!text) {
        Diagnostics d;
        d.error("COLOR_FILE", file.string(), "", "cannot read the ParaView preset file");
        return d;
    }
    return importParaView(*text, presetName, file.string());
}

Result<TransferFunction> parseColorRelief(std::string_view text, const std::string& file,
                                          std::optional<std::pair<double, double>> range) {
    Diagnostics d;
    TransferFunction tf;
    tf.name = std::filesystem::path(file).filename().string();
    tf.space = Space::Srgb;  // gdaldem interpolates the 0..255 components linearly
    int lineNo = 0;
    std::size_t pos = 0;
    // One error per file: the first, with its line (a file in the wrong format would otherwise
    // give one error per line).
    auto fail = [&](const char* code, const std::string& msg) {
        auto& e = d.error(code, file, "", msg);
        e.line = lineNo;
        pos = text.size() + 1;
    };
    while (pos <= text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        std::string line(text.substr(pos, end - pos));
        pos = end + 1;
        ++lineNo;
        if (auto hash = line.find('#'); hash != std::string::npos && hash == 0) continue;
        for (char& c : line)
            if (c == ',' || c == '\t' || c == ':' || c == '\r') c = ' ';
        std::vector<std::string> tok;
        std::istringstream ls(line);
        for (std::string t; ls >> t;) tok.push_back(t);
        if (tok.empty()) continue;
        if (tok[0] == "%") continue;  // GRASS rules: "% min max", the range r.colors saw
        if (tok.size() != 2 && tok.size() != 4 && tok.size() != 5) {
            fail("COLOR_CLR_SYNTAX", "expected `value r g b [a]` or `value colorname`, got " +
                                         std::to_string(tok.size()) + " fields");
            continue;
        }
        Rgba color;
        if (tok.size() == 2) {
            auto c = parseColor(tok[1]);
            if (!c || tok[1][0] == '#') {
                fail("COLOR_CLR_SYNTAX", "unknown colour name \"" + tok[1] + "\"");
                continue;
            }
            color = *c;
        } else {
            int v[4] = {0, 0, 0, 255};
            bool ok = true;
            for (std::size_t k = 1; k < tok.size(); ++k) {
                auto n = toNumber(tok[k]);
                if (!n || *n != std::floor(*n)) {
                    fail("COLOR_CLR_SYNTAX",
                         "colour component \"" + tok[k] + "\" is not an integer");
                    ok = false;
                    break;
                }
                if (*n < 0 || *n > 255) {
                    fail("COLOR_CLR_RANGE", "colour component " + tok[k] + " is outside 0..255");
                    ok = false;
                    break;
                }
                v[k - 1] = int(*n);
            }
            if (!ok) continue;
            color = rgb255(v[0], v[1], v[2], v[3]);
        }
        std::string key = tok[0];
        for (char& c : key) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (key == "nv") {
            tf.nodata = color;
            continue;
        }
        if (key == "default") {  // GRASS: the colour of values outside the rules
            tf.below = tf.above = color;
            tf.belowGiven = tf.aboveGiven = true;
            continue;
        }
        double value = 0;
        if (key.back() == '%') {
            auto pct = toNumber(std::string_view(key).substr(0, key.size() - 1));
            if (!pct) {
                fail("COLOR_CLR_SYNTAX", "bad percentage \"" + tok[0] + "\"");
                continue;
            }
            if (!range) {
                fail("COLOR_CLR_PERCENT",
                     "percentage \"" + tok[0] + "\" needs the data range (give a domain)");
                continue;
            }
            value = range->first + *pct / 100.0 * (range->second - range->first);
        } else {
            auto n = toNumber(key);
            if (!n) {
                fail("COLOR_CLR_SYNTAX", "bad value \"" + tok[0] + "\" (number, N% or nv)");
                continue;
            }
            value = *n;
        }
        tf.stops.push_back({value, color});
    }
    if (d.hasErrors()) return d;
    if (tf.stops.size() < 2) {
        d.error("COLOR_CLR_EMPTY", file, "", "needs at least two colour entries");
        return d;
    }
    d.append(tf.finalize(false, false, false, file, ""));
    if (d.hasErrors()) return d;
    return {std::move(tf), std::move(d)};
}

Result<TransferFunction> importColorReliefFile(const std::filesystem::path& file,
                                               std::optional<std::pair<double, double>> range) {
    auto text = readText(file);
    if (!text) {
        Diagnostics d;
        d.error("COLOR_FILE", file.string(), "", "cannot read the colour file");
        return d;
    }
    return parseColorRelief(*text, file.string(), range);
}

std::vector<std::string> namedMapNames() {
    return {"viridis", "cividis", "flood-depth", "fire-intensity", "grayscale"};
}

std::optional<TransferFunction> namedMap(std::string_view name) {
    TransferFunction tf;
    tf.name = std::string(name);
    tf.space = Space::Lab;
    auto evenly = [&](std::initializer_list<const char*> colors) {
        const double n = double(colors.size() - 1);
        double i = 0;
        for (const char* c : colors) tf.stops.push_back({i++ / n, hex(c)});
    };
    if (name == "viridis") {
        // matplotlib's viridis (van der Walt & Smith, CC0) sampled at k/32 from its published
        // 256-entry table; Lab interpolation between these stays within 2 DN of the table.
        evenly({"#440154", "#470d60", "#48186a", "#482374", "#472d7b", "#453781", "#424086",
                "#3e4989", "#3b528b", "#375b8d", "#33638d", "#2f6b8e", "#2c728e", "#297a8e",
                "#26828e", "#23898e", "#21918c", "#1f978b", "#1f9f88", "#21a685", "#27ad81",
                "#31b57b", "#3dbc74", "#4cc26c", "#5cc863", "#6ece58", "#81d34d", "#95d840",
                "#aadc32", "#c0df25", "#d5e21a", "#eae51a", "#fde725"});
    } else if (name == "cividis") {
        // cividis (Nuñez, Anderton & Renslow 2018) sampled the same way; within 5 DN.
        evenly({"#00204d", "#00265a", "#002c69", "#00306f", "#06366e", "#1f3c6d", "#2d426c",
                "#38486b", "#414d6b", "#4a536b", "#52596c", "#595f6d", "#61646f", "#686a71",
                "#6f7073", "#767676", "#7d7c78", "#848179", "#8b8779", "#938e78", "#9b9477",
                "#a39a76", "#aca174", "#b4a872", "#bcaf6f", "#c5b56c", "#cebc68", "#d7c463",
                "#e0cb5e", "#e9d358", "#f2da50", "#fbe248", "#ffea46"});
    } else if (name == "grayscale") {
        tf.space = Space::Srgb;
        evenly({"#000000", "#ffffff"});
    } else if (name == "flood-depth") {
        tf.units = "m";
        tf.stops = {{0.0, hex("#d4f4fa")}, {0.25, hex("#9be0f0")}, {0.75, hex("#4eb3de")},
                    {1.5, hex("#2171b5")}, {3.0, hex("#0c4a97")},  {5.0, hex("#08205e")}};
        // Dry cells (depth 0) vanish; a few centimetres already show full colour.
        tf.opacity = {{0.0, 0.0}, {0.02, 1.0}};
        tf.below = Rgba{0, 0, 0, 0};
        tf.finalize(false, true, false);
        return tf;
    } else if (name == "fire-intensity") {
        tf.units = "kW/m";
        // Breaks follow common fireline-intensity classes (350 kW/m: hand tools; 1700: machinery;
        // 3500: aerial; 7000+: crown fire).
        tf.stops = {{0, hex("#ffffb2")},    {350, hex("#fed976")},  {1700, hex("#feb24c")},
                    {3500, hex("#fd8d3c")}, {7000, hex("#f03b20")}, {10000, hex("#bd0026")}};
        tf.opacity = {{0.0, 0.0}, {50.0, 1.0}};
        tf.below = Rgba{0, 0, 0, 0};
        tf.finalize(false, true, false);
        return tf;
    } else {
        return std::nullopt;
    }
    tf.finalize(false, false, false);
    return tf;
}

}  // namespace kiosk::color
