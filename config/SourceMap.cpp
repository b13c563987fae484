#include "config/SourceMap.h"

#include <algorithm>
#include <cstdint>

namespace kiosk::config {

std::string escapePointerToken(std::string_view token) {
    std::string out;
    out.reserve(token.size());
    for (char c : token) {
        if (c == '~')
            out += "~0";
        else if (c == '/')
            out += "~1";
        else
            out += c;
    }
    return out;
}

std::string childPointer(std::string_view parent, std::string_view token) {
    std::string out(parent);
    out += '/';
    out += escapePointerToken(token);
    return out;
}

namespace {

// A forgiving recursive-descent walk over JSON text. It only records positions: the text has
// already been validated by nlohmann, but the scanner still bounds-checks everything so that it
// can never crash on whatever it is given.
class Scanner {
public:
    Scanner(std::string_view text, int depthLimit, TextIndex& out)
        : mText(text), mLimit(depthLimit), mOut(out) {
        mLineStarts.push_back(0);
        for (std::size_t i = 0; i < text.size(); ++i)
            if (text[i] == '\n') mLineStarts.push_back(i + 1);
    }

    void run() {
        if (mText.substr(0, 3) == "\xEF\xBB\xBF") mPos = 3;  // UTF-8 BOM, as nlohmann skips it
        skipSpace();
        if (mPos < mText.size() && !value("", 0)) mOut.complete = false;
    }

private:
    TextIndex::Pos posOf(std::size_t offset) const {
        auto it = std::upper_bound(mLineStarts.begin(), mLineStarts.end(), offset);
        const std::size_t line = std::size_t(it - mLineStarts.begin());  // 1-based
        const std::size_t start = mLineStarts[line - 1];
        int column = 1;
        for (std::size_t i = start; i < offset && i < mText.size(); ++i)
            if ((static_cast<unsigned char>(mText[i]) & 0xC0) != 0x80) ++column;
        return {int(line), column};
    }

    bool more() const { return mPos < mText.size(); }
    char peek() const { return more() ? mText[mPos] : '\0'; }

    void skipSpace() {
        while (more()) {
            const char c = mText[mPos];
            if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
                ++mPos;
            } else if (c == '/' && mPos + 1 < mText.size() && mText[mPos + 1] == '/') {
                while (more() && mText[mPos] != '\n') ++mPos;
            } else if (c == '/' && mPos + 1 < mText.size() && mText[mPos + 1] == '*') {
                const std::size_t end = mText.find("*/", mPos + 2);
                mPos = end == std::string_view::npos ? mText.size() : end + 2;
            } else {
                return;
            }
        }
    }

    static void appendUtf8(std::string& s, std::uint32_t cp) {
        if (cp < 0x80) {
            s += char(cp);
        } else if (cp < 0x800) {
            s += char(0xC0 | (cp >> 6));
            s += char(0x80 | (cp & 0x3F));
        } else if (cp < 0x10000) {
            s += char(0xE0 | (cp >> 12));
            s += char(0x80 | ((cp >> 6) & 0x3F));
            s += char(0x80 | (cp & 0x3F));
        } else {
            s += char(0xF0 | (cp >> 18));
            s += char(0x80 | ((cp >> 12) & 0x3F));
            s += char(0x80 | ((cp >> 6) & 0x3F));
            s += char(0x80 | (cp & 0x3F));
        }
    }

    bool hex4(std::uint32_t& cp) {
        if (mPos + 4 > mText.size()) return false;
        cp = 0;
        for (int i = 0; i < 4; ++i) {
            const char c = mText[mPos++];
            cp <<= 4;
            if (c >= '0' && c <= '9')
                cp |= std::uint32_t(c - '0');
            else if (c >= 'a' && c <= 'f')
                cp |= std::uint32_t(c - 'a' + 10);
            else if (c >= 'A' && c <= 'F')
                cp |= std::uint32_t(c - 'A' + 10);
            else
                return false;
        }
        return true;
    }

    // Decodes the string at mPos (which is '"'); the decoded key must equal nlohmann's so that
    // pointers built from either agree.
    bool string(std::string& out) {
        ++mPos;
        while (more()) {
            const char c = mText[mPos++];
            if (c == '"') return true;
            if (c != '\\') {
                out += c;
                continue;
            }
            if (!more()) return false;
            const char e = mText[mPos++];
            switch (e) {
                case 'n':
                    out += '\n';
                    break;
                case 't':
                    out += '\t';
                    break;
                case 'r':
                    out += '\r';
                    break;
                case 'b':
                    out += '\b';
                    break;
                case 'f':
                    out += '\f';
                    break;
                case 'u': {
                    std::uint32_t cp = 0;
                    if (!hex4(cp)) return false;
                    if (cp >= 0xD800 && cp <= 0xDBFF && mPos + 1 < mText.size() &&
                        mText[mPos] == '\\' && mText[mPos + 1] == 'u') {
                        mPos += 2;
                        std::uint32_t lo = 0;
                        if (!hex4(lo)) return false;
                        cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
                    }
                    appendUtf8(out, cp);
                    break;
                }
                default:
                    out += e;
                    break;
            }
        }
        return false;
    }

    bool value(const std::string& ptr, int depth) {
        mOut.maxDepth = std::max(mOut.maxDepth, depth);
        if (depth > mLimit) {
            mOut.complete = false;
            return false;
        }
        if (mUnindexed == 0) mOut.values[ptr] = posOf(mPos);
        const char c = peek();
        if (c == '{') return object(ptr, depth);
        if (c == '[') return array(ptr, depth);
        if (c == '"') {
            std::string ignored;
            return string(ignored);
        }
        const std::size_t start = mPos;
        while (more()) {
            const char d = mText[mPos];
            if (d == ',' || d == ']' || d == '}' || d == ' ' || d == '\t' || d == '\n' ||
                d == '\r' || d == '/')
                break;
            ++mPos;
        }
        return mPos > start;
    }

    bool object(const std::string& ptr, int depth) {
        ++mPos;
        skipSpace();
        if (peek() == '}') {
            ++mPos;
            return true;
        }
        for (std::size_t member = 0; more(); ++member) {
            skipSpace();
            if (peek() != '"') return false;
            const std::size_t keyStart = mPos;
            std::string key;
            if (!string(key)) return false;
            const std::string child = childPointer(ptr, key);
            const bool indexed = mUnindexed == 0 && member < kMaxIndexedItems;
            if (indexed) {
                if (mOut.keys.count(child)) mOut.duplicateKeys.push_back(child);
                mOut.keys[child] = posOf(keyStart);
            }
            skipSpace();
            if (peek() != ':') return false;
            ++mPos;
            skipSpace();
            if (!indexedValue(indexed, child, depth + 1)) return false;
            skipSpace();
            if (peek() == ',') {
                ++mPos;
                continue;
            }
            if (peek() == '}') {
                ++mPos;
                return true;
            }
            return false;
        }
        return false;
    }

    bool array(const std::string& ptr, int depth) {
        ++mPos;
        skipSpace();
        if (peek() == ']') {
            ++mPos;
            return true;
        }
        for (std::size_t index = 0; more(); ++index) {
            skipSpace();
            if (!indexedValue(index < kMaxIndexedItems, childPointer(ptr, index), depth + 1))
                return false;
            skipSpace();
            if (peek() == ',') {
                ++mPos;
                continue;
            }
            if (peek() == ']') {
                ++mPos;
                return true;
            }
            return false;
        }
        return false;
    }

    bool indexedValue(bool indexed, const std::string& ptr, int depth) {
        mUnindexed += !indexed;
        const bool ok = value(ptr, depth);
        mUnindexed -= !indexed;
        return ok;
    }

    std::string_view mText;
    int mLimit;
    TextIndex& mOut;
    std::size_t mPos = 0;
    int mUnindexed = 0;  // > 0 inside an item past kMaxIndexedItems: scanned, not indexed
    std::vector<std::size_t> mLineStarts;
};

template <class Map>
const Location* nearest(const Map& map, std::string_view pointer) {
    std::string p(pointer);
    for (;;) {
        auto it = map.find(p);
        if (it != map.end()) return &it->second;
        if (p.empty()) return nullptr;
        const std::size_t slash = p.rfind('/');
        p.resize(slash == std::string::npos ? 0 : slash);
    }
}

}  // namespace

TextIndex indexJsonText(std::string_view text, int depthLimit) {
    TextIndex out;
    Scanner scanner(text, depthLimit, out);
    scanner.run();
    return out;
}

Location SourceMap::value(std::string_view pointer) const {
    const Location* l = nearest(mValues, pointer);
    return l ? *l : Location{};
}

Location SourceMap::key(std::string_view pointer) const {
    auto it = mKeys.find(pointer);
    return it != mKeys.end() ? it->second : value(pointer);
}

}  // namespace kiosk::config
