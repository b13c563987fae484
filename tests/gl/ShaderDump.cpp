// kiosk_shader_dump: expand every embedded shader stage through gl::ShaderLibrary (includes,
// #line directives, defines) into a directory and, with --validator, syntax-check each one with
// glslangValidator, reporting errors as `terrain.frag:12: ...` against the original files.
// Used by the ShaderSyntax CTest; needs no GPU.
//
//   kiosk_shader_dump --out DIR [--validator PATH] [--define NAME[=VALUE]]... [--name NAME]...
//   --name limits the check to the named stages (which may exist only in GEOKIOSK_SHADER_DIR).
//   exit 0: all stages clean; 1: a stage failed; 2: usage; 77: validator missing (CTest skip)
#include "runtime/gl/ProgramBuilder.h"
#include "runtime/gl/ShaderLibrary.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace {

constexpr int kSkip = 77;

bool isStage(const std::string& name) {
    const auto ext = std::filesystem::path(name).extension().string();
    return ext == ".vert" || ext == ".frag";
}

std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) {
        if (c == '\'')
            out += "'\\''";
        else
            out += c;
    }
    return out + "'";
}

/** @brief Run the validator on one file; returns its exit status and captured output. */
int runValidator(const std::string& validator, const std::string& file, std::string& output) {
    const std::string cmd = shellQuote(validator) + " " + shellQuote(file) + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return -1;
    char buf[512];
    while (std::fgets(buf, sizeof(buf), pipe)) output += buf;
    return pclose(pipe);
}

int usage() {
    std::fprintf(stderr,
                 "usage: kiosk_shader_dump --out DIR [--validator PATH] [--define NAME[=VALUE]]... "
                 "[--name NAME]...\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    std::string outDir, validator;
    bool validatorMissing = false;
    std::vector<std::string> defines, names;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--out" && i + 1 < argc) {
            outDir = argv[++i];
        } else if (arg == "--validator" && i + 1 < argc) {
            validator = argv[++i];
        } else if (arg == "--validator-missing") {
            validatorMissing = true;
        } else if (arg == "--name" && i + 1 < argc) {
            names.emplace_back(argv[++i]);
        } else if (arg == "--define" && i + 1 < argc) {
            std::string d = argv[++i];
            if (auto eq = d.find('='); eq != std::string::npos) d[eq] = ' ';
            defines.push_back(d);
        } else {
            return usage();
        }
    }
    if (validatorMissing) {
        std::printf(
            "glslangValidator not found: shader syntax not checked "
            "(apt-get install glslang-tools)\n");
        return kSkip;
    }
    if (outDir.empty()) return usage();

    int stages = 0, failed = 0;
    if (names.empty()) names = kiosk::gl::ShaderLibrary::embeddedNames();
    for (const auto& name : names) {
        if (!isStage(name)) continue;  // .glsl files are checked through the stages including them
        ++stages;
        auto expanded = kiosk::gl::ShaderLibrary::expand(name, defines);
        if (!expanded) {
            std::printf("%s", expanded.diagnostics.format().c_str());
            ++failed;
            continue;
        }
        const std::filesystem::path path = std::filesystem::path(outDir) / name;
        std::error_code ec;
        std::filesystem::create_directories(path.parent_path(), ec);
        std::ofstream(path) << expanded->text;
        if (validator.empty()) {
            std::printf("%s\n", path.c_str());
            continue;
        }
        std::string output;
        const int status = runValidator(validator, path.string(), output);
        if (status == 0) continue;
        ++failed;
        // glslangValidator prints "ERROR: 1:12: ..." per problem, with the #line source-string
        // number; map those back to the original file names.
        std::istringstream lines(output);
        std::string line, problems;
        while (std::getline(lines, line)) {
            while (!line.empty() && (line.back() == ' ' || line.back() == '\r')) line.pop_back();
            if (line.rfind("ERROR: ", 0) == 0 || line.rfind("WARNING: ", 0) == 0) {
                if (line.find("compilation errors") != std::string::npos) continue;
                if (line.find("compilation terminated") != std::string::npos) continue;
                problems += line + "\n";
            }
        }
        for (const auto& msg : kiosk::gl::mapInfoLog(problems, expanded->fileNames))
            std::printf("%s\n", msg.c_str());
        std::printf("  (stage %s, expanded source %s, validator exit status %d)\n", name.c_str(),
                    path.c_str(), WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    }
    if (stages == 0) {
        std::printf("no shader stages are embedded: the shader embedding step is broken\n");
        return 1;
    }
    if (failed) {
        std::printf("%d of %d shader stages failed\n", failed, stages);
        return 1;
    }
    if (!validator.empty()) std::printf("%d shader stages passed glslangValidator\n", stages);
    return 0;
}
