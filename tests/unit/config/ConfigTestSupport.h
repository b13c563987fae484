#pragma once

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

}  // namespace kiosk::test
