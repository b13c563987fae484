#include "config/SourceMap.h"

#include <gtest/gtest.h>

namespace kiosk::config {
namespace {

TEST(SourceMap, IndexesValuesAndKeysByPointer) {
    const std::string text =
        "{\n"
        "  \"a\": 1,\n"
        "  // comment with \"quotes\" and { braces\n"
        "  \"b\": [ true, { \"c/d\": \"x\", \"e~f\": null } ],\n"
        "  /* block\n comment */ \"g\": \"\\u00e9\\\"\"\n"
        "}\n";
    const TextIndex idx = indexJsonText(text);
    ASSERT_TRUE(idx.complete);
    auto at = [&](const std::string& p) {
        auto it = idx.values.find(p);
        return it == idx.values.end() ? std::pair{-1, -1}
                                      : std::pair{it->second.line, it->second.column};
    };
    EXPECT_EQ(at(""), (std::pair{1, 1}));
    EXPECT_EQ(at("/a"), (std::pair{2, 8}));
    EXPECT_EQ(at("/b"), (std::pair{4, 8}));
    EXPECT_EQ(at("/b/0"), (std::pair{4, 10}));
    EXPECT_EQ(at("/b/1"), (std::pair{4, 16}));
    EXPECT_EQ(at("/b/1/c~1d"), (std::pair{4, 25}));  // RFC 6901 escaping of '/'
    EXPECT_EQ(at("/b/1/e~0f"), (std::pair{4, 37}));  // and of '~'
    EXPECT_EQ(at("/g"), (std::pair{6, 18}));
    EXPECT_EQ(idx.keys.at("/g").line, 6);
    EXPECT_EQ(idx.keys.at("/g").column, 13);
    EXPECT_EQ(idx.keys.at("/b").column, 3);
}

TEST(SourceMap, ColumnsCountCodePoints) {
    const TextIndex idx = indexJsonText("{\"héhé\": 1, \"x\": 2}");
    EXPECT_EQ(idx.values.at("/x").column, 18);  // "é" is two bytes but one column
    EXPECT_EQ(idx.values.count("/h\xc3\xa9h\xc3\xa9"), 1u);
}

TEST(SourceMap, DuplicateKeysAndDepthLimit) {
    const TextIndex dup = indexJsonText("{\"a\": 1, \"a\": 2}");
    ASSERT_EQ(dup.duplicateKeys.size(), 1u);
    EXPECT_EQ(dup.duplicateKeys[0], "/a");
    EXPECT_EQ(dup.values.at("/a").column, 15);  // the last one wins, as in nlohmann

    const TextIndex deep = indexJsonText(std::string(100, '[') + std::string(100, ']'), 10);
    EXPECT_FALSE(deep.complete);
    EXPECT_EQ(deep.maxDepth, 11);
}

TEST(SourceMap, MalformedTextNeverCrashes) {
    for (const char* bad : {"", "{", "[", "\"", "{\"a\"", "{\"a\":", "[1,", "{\"\\u12", "}}}", "/*",
                            "{\"a\":1 \"b\":2}", "\\", "[\"\\uD800\\u\"]"}) {
        const TextIndex idx = indexJsonText(bad);
        (void)idx;
    }
    SUCCEED();
}

TEST(SourceMap, LookupFallsBackToNearestAncestor) {
    SourceMap m;
    m.setValue("", {"a.json", 1, 1});
    m.setValue("/layers", {"a.json", 5, 13});
    m.setValue("/layers/0", {"b.json", 2, 5});
    m.setKey("/layers", {"a.json", 5, 3});
    EXPECT_EQ(m.value("/layers/0/id").file, "b.json");
    EXPECT_EQ(m.value("/layers/0/id").line, 2);
    EXPECT_EQ(m.value("/layers/1").line, 5);
    EXPECT_EQ(m.value("/title").line, 1);
    EXPECT_EQ(m.key("/layers").column, 3);
    EXPECT_EQ(m.key("/layers/0").column, 5);  // no key entry: falls back to the value
    EXPECT_EQ(childPointer("/a", "b/c~"), "/a/b~1c~0");
    EXPECT_EQ(childPointer("/a", 3), "/a/3");
}

}  // namespace
}  // namespace kiosk::config
