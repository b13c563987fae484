#pragma once

#include <string>
#include <vector>

#include "runtime/core/Result.h"
#include "runtime/gl/GlObject.h"

namespace kiosk::gl {

/**
 * @brief Compile and link a program from two library shaders. Compile/link failures come back as
 * one diagnostic per driver message, each naming the shader file and line
 * (`terrain.frag:12: 'foo' : undeclared identifier`). Render thread only.
 */
Result<Program> buildProgram(const std::string& vertexName, const std::string& fragmentName,
                             const std::vector<std::string>& defines = {});

/**
 * @brief Same, with the fragment stage given as complete generated text (including
 * `#version`); `fragmentName` names it in diagnostics.
 */
Result<Program> buildProgramWithFragmentText(const std::string& vertexName,
                                             const std::string& fragmentName,
                                             const std::string& fragmentText);

/**
 * @brief Rewrite a driver info log ("0:12(5): error: ..." from Mesa, "ERROR: 0:12: ..." from
 * others) so source-string numbers become file names. Pure, unit-tested.
 */
std::vector<std::string> mapInfoLog(const std::string& log,
                                    const std::vector<std::string>& fileNames);

}  // namespace kiosk::gl
