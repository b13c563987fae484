#pragma once

#include "runtime/core/Diagnostics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace kiosk::test {

/** @brief Tests run with cwd = repo root; fixtures live beside the tests. */
inline std::filesystem::path configData(const std::string& rel) {
    return std::filesystem::path("tests/unit/config/data") / rel;
}

inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/** @brief A scratch directory under the system temp dir, removed on destruction. */
class TempDir {
public:
    explicit TempDir(const std::string& name)
        : mPath(std::filesystem::temp_directory_path() /
                ("geokiosk-config-" + name + "-" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(mPath);
        std::filesystem::create_directories(mPath);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(mPath, ec);
    }
    std::filesystem::path write(const std::string& name, const std::string& text) const {
        const auto p = mPath / name;
        std::filesystem::create_directories(p.parent_path());
        std::ofstream(p, std::ios::binary) << text;
        return p;
    }
    const std::filesystem::path& path() const { return mPath; }

private:
    std::filesystem::path mPath;
};

/**
 * @brief A scenario mistake is reported as exactly one error, on one line, with the expected
 * code, JSON pointer and a message containing `message`.
 */
inline ::testing::AssertionResult isOneErrorLine(const Diagnostics& d, const std::string& code,
                                                 const std::string& where,
                                                 const std::string& message) {
    const auto& items = d.items();
    const auto errors = std::count_if(items.begin(), items.end(), [](const Diagnostic& i) {
        return i.severity == Severity::Error;
    });
    if (errors != 1)
        return ::testing::AssertionFailure() << errors << " errors, want 1:\n" << d.format();
    const Diagnostic* e = d.firstError();
    if (e->code != code || e->where != where)
        return ::testing::AssertionFailure()
               << "want " << code << " at " << where << ", got: " << e->format();
    if (e->format().find(message) == std::string::npos)
        return ::testing::AssertionFailure() << "no \"" << message << "\" in: " << e->format();
    if (e->format().find('\n') != std::string::npos)
        return ::testing::AssertionFailure() << "not one line: " << e->format();
    return ::testing::AssertionSuccess();
}

}  // namespace kiosk::test
