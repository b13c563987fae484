#include "config/DocumentLoader.h"

#include "config/Limits.h"
#include "config/PathPolicy.h"
#include "config/ScenarioReader.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>

namespace kiosk::config {

namespace {

using nlohmann::json;
using OriginMap = std::map<std::string, int, std::less<>>;  // pointer prefix -> file index

// Captures nlohmann's parse error (byte offset + message) when the DOM parse failed; the DOM
// parser with allow_exceptions=false only says "discarded".
class ErrorCatcher : public nlohmann::json_sax<json> {
public:
    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override { return true; }
    bool key(string_t&) override { return true; }
    bool end_object() override { return true; }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    bool parse_error(std::size_t position, const std::string& lastToken,
                     const nlohmann::detail::exception& ex) override {
        failed = true;
        // Characters read up to and including the offending one (the token's last character).
        offset = position > 0 ? position - 1 : 0;
        (void)lastToken;
        // The message quotes the whole token read (an unclosed comment: the rest of the file);
        // keep its head and tail only, which is all cleanParseMessage shows.
        const std::string_view what = ex.what();
        message = what.size() <= 1024 ? std::string(what)
                                      : std::string(what.substr(0, 512)) +
                                            std::string(what.substr(what.size() - 512));
        return false;
    }

    bool failed = false;
    std::size_t offset = 0;
    std::string message;
};

TextIndex::Pos positionOf(std::string_view text, std::size_t offset) {
    TextIndex::Pos p{1, 1};
    for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
        if (text[i] == '\n') {
            ++p.line;
            p.column = 1;
        } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
            ++p.column;
        }
    }
    return p;
}

// "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error ..." ->
// "syntax error ..."; the position is reported separately in our own format. nlohmann echoes
// the token it stopped in ("last read: '...'"), which for an unclosed comment or string is the
// rest of the file and for a non-JSON include is that file's content: keep a short fragment.
std::string cleanParseMessage(const std::string& what) {
    std::string out = what;
    const auto column = what.find("column ");
    const auto bracket = what.find("] ");
    if (column != std::string::npos && what.find(": ", column) != std::string::npos)
        out = what.substr(what.find(": ", column) + 2);
    else if (bracket != std::string::npos)
        out = what.substr(bracket + 2);
    constexpr std::size_t kFragment = 24;
    const std::string lastRead = "last read: '";
    const auto lr = out.find(lastRead);
    if (lr != std::string::npos) {
        const std::size_t start = lr + lastRead.size();
        const std::size_t end = out.rfind('\'');
        if (end != std::string::npos && end > start && end - start > kFragment) {
            std::size_t cut = start + kFragment;
            while (cut > start && (static_cast<unsigned char>(out[cut]) & 0xC0) == 0x80) --cut;
            out = out.substr(0, cut) + "\u2026" + out.substr(end);
        }
    }
    return out;
}

// A UTF-16 or UTF-32 file starts with a byte-order mark or has NUL bytes in its first
// characters; JSON parsers then report a baffling "invalid literal" at 1:1.
bool looksUtf16or32(std::string_view text) {
    if (text.size() >= 2 &&
        ((text[0] == '\xFF' && text[1] == '\xFE') || (text[0] == '\xFE' && text[1] == '\xFF')))
        return true;
    const std::size_t n = std::min<std::size_t>(text.size(), 8);
    return n >= 2 && text.substr(0, n).find('\0') != std::string_view::npos;
}

int originOf(const OriginMap& origin, std::string_view pointer) {
    std::string p(pointer);
    for (;;) {
        auto it = origin.find(p);
        if (it != origin.end()) return it->second;
        if (p.empty()) return 0;
        const std::size_t slash = p.rfind('/');
        p.resize(slash == std::string::npos ? 0 : slash);
    }
}

bool under(std::string_view pointer, std::string_view prefix) {
    return pointer == prefix ||
           (pointer.size() > prefix.size() && pointer.substr(0, prefix.size()) == prefix &&
            pointer[prefix.size()] == '/');
}

void replaceOrigin(OriginMap& dst, const OriginMap& src, const std::string& pointer) {
    for (auto it = dst.lower_bound(pointer);
         it != dst.end() && it->first.compare(0, pointer.size(), pointer) == 0;) {
        if (under(it->first, pointer))
            it = dst.erase(it);
        else
            ++it;
    }
    dst[pointer] = originOf(src, pointer);
    for (auto it = src.lower_bound(pointer);
         it != src.end() && it->first.compare(0, pointer.size(), pointer) == 0; ++it)
        if (under(it->first, pointer)) dst[it->first] = it->second;
}

bool replacesWhole(std::string_view parent) {
    return parent == "/stores" || parent == "/transferFunctions" || parent == "/viewpoints" ||
           parent == "/cameraPaths";
}

void merge(json& dst, OriginMap& dstOrigin, const json& src, const OriginMap& srcOrigin,
           const std::string& pointer) {
    for (auto it = src.begin(); it != src.end(); ++it) {
        if (pointer.empty() && it.key() == "include") continue;
        const std::string child = childPointer(pointer, it.key());
        auto existing = dst.find(it.key());
        if (existing != dst.end() && existing->is_object() && it->is_object() &&
            !replacesWhole(pointer)) {
            merge(*existing, dstOrigin, *it, srcOrigin, child);
        } else {
            dst[it.key()] = *it;
            replaceOrigin(dstOrigin, srcOrigin, child);
        }
    }
}

struct SourceFile {
    std::filesystem::path path;
    TextIndex index;
};

class Loader {
public:
    Loader(Diagnostics& diags, const std::filesystem::path& root)
        : mDiags(diags), mRoots(allowedRoots(root)) {}

    struct Doc {
        json value;
        OriginMap origin;
    };

    std::optional<Doc> load(std::string_view text, const std::filesystem::path& name) {
        const int self = int(mFiles.size());
        mFiles.push_back({name, {}});
        mTotalBytes += text.size();
        if (looksUtf16or32(text)) {
            auto& e = mDiags.error("SCENARIO_ENCODING", name.string(), "",
                                   "the file is UTF-16 or UTF-32; scenarios are UTF-8");
            e.line = 1;
            e.column = 1;
            e.hint = "save it as UTF-8, e.g. iconv -f UTF-16 -t UTF-8";
            return std::nullopt;
        }
        // A UTF-8 byte-order mark is harmless: skip it, so columns stay those an editor shows.
        if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
        TextIndex index = indexJsonText(text, kMaxScenarioDepth);
        if (!index.complete && index.maxDepth > kMaxScenarioDepth) {
            auto& e =
                mDiags.error("SCENARIO_PARSE", name.string(), "",
                             "nested deeper than " + std::to_string(kMaxScenarioDepth) + " levels");
            e.line = 1;
            e.column = 1;
            return std::nullopt;
        }
        json value = json::parse(text, nullptr, /*allow_exceptions=*/false,
                                 /*ignore_comments=*/true);
        if (value.is_discarded()) {
            reportParseError(text, name);
            return std::nullopt;
        }
        for (const auto& dup : index.duplicateKeys) {
            auto pos = index.keys[dup];
            auto& w = mDiags.warning("SCENARIO_DUPLICATE_KEY", name.string(), dup,
                                     "property given twice; the last one wins");
            w.line = pos.line;
            w.column = pos.column;
        }
        mFiles[std::size_t(self)].index = std::move(index);
        if (!value.is_object()) {
            auto& e = mDiags.error("SCENARIO_TYPE", name.string(), "",
                                   "a scenario must be a JSON object");
            e.line = 1;
            e.column = 1;
            return std::nullopt;
        }

        Doc doc{json::object(), OriginMap{{"", self}}};
        auto inc = value.find("include");
        if (inc != value.end()) {
            std::vector<std::pair<std::string, std::string>> paths;  // (path, pointer)
            if (inc->is_string()) {
                paths.push_back({inc->get<std::string>(), "/include"});
            } else if (inc->is_array()) {
                for (std::size_t i = 0; i < inc->size(); ++i) {
                    const std::string ptr = childPointer("/include", i);
                    if ((*inc)[i].is_string())
                        paths.push_back({(*inc)[i].get<std::string>(), ptr});
                    else
                        error(self, "SCENARIO_TYPE", ptr, "expected a file name (string)");
                }
            } else {
                error(self, "SCENARIO_TYPE", "/include", "expected an array of file names");
            }
            bool includesOk = true;
            for (const auto& [rel, ptr] : paths) {
                if (auto sub = include(self, name, rel, ptr)) {
                    merge(doc.value, doc.origin, sub->value, sub->origin, "");
                } else {
                    includesOk = false;
                    if (mOverLimit) break;  // one message for an include bomb, not thousands
                }
            }
            // A missing include would cascade into "missing stores"-style noise: stop here.
            if (!includesOk) return std::nullopt;
        }
        merge(doc.value, doc.origin, value, OriginMap{{"", self}}, "");
        return doc;
    }

    LoadedDocument finish(std::optional<Doc> doc) {
        LoadedDocument out;
        for (const auto& f : mFiles) out.files.push_back(f.path);
        if (!doc) return out;
        out.value = std::move(doc->value);
        walk(out.value, "", doc->origin, out.sourceMap, 0);
        return out;
    }

private:
    void error(int file, const char* code, const std::string& ptr, std::string message,
               std::string hint = {}) {
        const auto& f = mFiles[std::size_t(file)];
        auto& e = mDiags.error(code, f.path.string(), ptr, std::move(message));
        e.hint = std::move(hint);
        auto it = f.index.values.find(ptr);
        if (it != f.index.values.end()) {
            e.line = it->second.line;
            e.column = it->second.column;
        }
    }

    std::optional<Doc> include(int self, const std::filesystem::path& from, const std::string& rel,
                               const std::string& ptr) {
        if (mOverLimit) return std::nullopt;
        const std::filesystem::path target = (from.parent_path() / rel).lexically_normal();
        if (auto why = checkContained(target, mRoots)) {
            error(self, "SCENARIO_PATH", ptr, "included file \"" + rel + "\" " + *why);
            return std::nullopt;
        }
        // Counted before reading: ten includes per level nested eight deep would otherwise be
        // 10^8 file loads (the limits are in config/Limits.h).
        if (++mIncludes > kMaxIncludeFiles) {
            mOverLimit = true;
            error(self, "SCENARIO_LIMIT", ptr,
                  "more than " + std::to_string(kMaxIncludeFiles) +
                      " included files (each inclusion counts)",
                  "see \"Limits\" in docs/scenario-format.md");
            return std::nullopt;
        }
        std::error_code ec;
        std::filesystem::path canon = std::filesystem::weakly_canonical(target, ec);
        if (ec) canon = target;
        if (mStack.empty()) {
            std::filesystem::path rootCanon = std::filesystem::weakly_canonical(from, ec);
            mStack.push_back(ec ? from.lexically_normal() : rootCanon);
        }
        for (const auto& s : mStack) {
            if (s == canon) {
                std::string chain;
                for (const auto& c : mStack) chain += c.filename().string() + " -> ";
                chain += canon.filename().string();
                error(self, "SCENARIO_INCLUDE_CYCLE", ptr, "include cycle: " + chain);
                return std::nullopt;
            }
        }
        // mStack holds the root and the includes being read: its size is this include's depth.
        if (int(mStack.size()) > kMaxIncludeDepth) {
            mOverLimit = true;
            error(self, "SCENARIO_LIMIT", ptr,
                  "includes nested deeper than " + std::to_string(kMaxIncludeDepth) + " files",
                  "see \"Limits\" in docs/scenario-format.md");
            return std::nullopt;
        }
        std::string why;
        auto text = readTextFile(target, kMaxScenarioFileBytes, why);
        if (!text) {
            mFiles.push_back({target, {}});  // still worth watching: it may appear
            error(self, "SCENARIO_INCLUDE_MISSING", ptr,
                  "included file \"" + target.string() + "\" " + why);
            return std::nullopt;
        }
        if (mTotalBytes + text->size() > kMaxScenarioTotalBytes) {
            mOverLimit = true;
            error(self, "SCENARIO_LIMIT", ptr,
                  "the scenario and its includes exceed " +
                      std::to_string(kMaxScenarioTotalBytes >> 20) + " MiB together",
                  "see \"Limits\" in docs/scenario-format.md");
            return std::nullopt;
        }
        mStack.push_back(canon);
        const std::size_t firstDiag = mDiags.size();
        auto doc = load(*text, target);
        mStack.pop_back();
        // A problem inside the include also names where it was included from (one line: hint).
        if (!doc) {
            const auto& f = mFiles[std::size_t(self)];
            std::string includedBy = f.path.string();
            if (auto it = f.index.values.find(ptr); it != f.index.values.end())
                includedBy +=
                    ":" + std::to_string(it->second.line) + ":" + std::to_string(it->second.column);
            Diagnostics annotated;
            for (std::size_t i = 0; i < mDiags.size(); ++i) {
                Diagnostic d = mDiags.items()[i];
                if (i >= firstDiag && d.file == target.string() &&
                    d.hint.find("included by ") == std::string::npos)
                    d.hint +=
                        (d.hint.empty() ? "" : "; ") + ("included by " + includedBy + " " + ptr);
                annotated.add(std::move(d));
            }
            mDiags = std::move(annotated);
        }
        return doc;
    }

    void reportParseError(std::string_view text, const std::filesystem::path& name) {
        ErrorCatcher catcher;
        json::sax_parse(text, &catcher, json::input_format_t::json, /*strict=*/true,
                        /*ignore_comments=*/true);
        auto& e = mDiags.error(
            "SCENARIO_PARSE", name.string(), "",
            catcher.failed ? cleanParseMessage(catcher.message) : std::string("not valid JSON"));
        std::size_t offset = std::min(catcher.offset, text.size());
        // A string token ends at its closing quote: point at its opening quote instead, which
        // is where an editor shows the unexpected token.
        if (offset < text.size() && text[offset] == '"' && offset > 0) {
            std::size_t j = offset;
            while (j > 0) {
                --j;
                if (text[j] != '"') continue;
                std::size_t backslashes = 0;
                while (j > backslashes && text[j - 1 - backslashes] == '\\') ++backslashes;
                if (backslashes % 2 == 0) break;
            }
            offset = j;
        }
        const auto pos = positionOf(text, offset);
        e.line = pos.line;
        e.column = pos.column;
        const std::size_t at = offset;
        if (at < text.size() && (text[at] == ']' || text[at] == '}')) {
            std::size_t i = at;
            while (i > 0 && std::isspace(static_cast<unsigned char>(text[i - 1]))) --i;
            if (i > 0 && text[i - 1] == ',')
                e.hint = "JSON allows no comma before a closing bracket";
        }
    }

    void walk(const json& node, const std::string& ptr, const OriginMap& origin, SourceMap& map,
              int depth) {
        const auto& f = mFiles[std::size_t(originOf(origin, ptr))];
        if (auto it = f.index.values.find(ptr); it != f.index.values.end())
            map.setValue(ptr, {f.path.string(), it->second.line, it->second.column});
        else
            map.setValue(ptr, {f.path.string(), 0, 0});
        if (auto it = f.index.keys.find(ptr); it != f.index.keys.end())
            map.setKey(ptr, {f.path.string(), it->second.line, it->second.column});
        if (depth > kMaxScenarioDepth) return;
        // As indexJsonText: past kMaxIndexedItems a container is over a limit and refused.
        if (node.is_object()) {
            std::size_t n = 0;
            for (auto it = node.begin(); it != node.end() && n < kMaxIndexedItems; ++it, ++n)
                walk(*it, childPointer(ptr, it.key()), origin, map, depth + 1);
        } else if (node.is_array()) {
            for (std::size_t i = 0; i < node.size() && i < kMaxIndexedItems; ++i)
                walk(node[i], childPointer(ptr, i), origin, map, depth + 1);
        }
    }

    Diagnostics& mDiags;
    std::vector<std::filesystem::path> mRoots;  // where included files may be (PathPolicy.h)
    std::vector<SourceFile> mFiles;
    std::vector<std::filesystem::path> mStack;
    int mIncludes = 0;
    std::uintmax_t mTotalBytes = 0;
    bool mOverLimit = false;  // a limit was hit: read nothing more
};

}  // namespace

std::optional<std::string> readTextFile(const std::filesystem::path& file, std::uintmax_t maxBytes,
                                        std::string& why) {
    std::error_code ec;
    const auto status = std::filesystem::status(file, ec);
    if (ec || !std::filesystem::exists(status)) {
        why = "does not exist";
        return std::nullopt;
    }
    if (!std::filesystem::is_regular_file(status)) {
        why = "is not a regular file";
        return std::nullopt;
    }
    const auto size = std::filesystem::file_size(file, ec);
    if (ec || size > maxBytes) {
        why = ec ? "cannot be read" : "is larger than " + std::to_string(maxBytes >> 20) + " MiB";
        return std::nullopt;
    }
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        why = "cannot be read";
        return std::nullopt;
    }
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

LoadedDocument loadDocument(std::string_view text, const std::filesystem::path& name,
                            Diagnostics& diags) {
    Loader loader(diags, name);
    auto doc = loader.load(text, name);
    return loader.finish(std::move(doc));
}

}  // namespace kiosk::config
