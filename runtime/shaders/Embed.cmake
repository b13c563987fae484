# Writes OUTPUT: a C++ file with every shader in SOURCES as a raw string (osgEarth/tangram idea:
# no external tool). Run at build time so editing a shader re-generates.
string(REPLACE "|" ";" SOURCES "${SOURCES}")
set(entries "")
foreach(src IN LISTS SOURCES)
    file(READ "${SHADER_DIR}/${src}" text)
    string(FIND "${text}" ")glsl\"" bad)
    if(NOT bad EQUAL -1)
        message(FATAL_ERROR "${src} contains the raw-string terminator )glsl\"")
    endif()
    string(APPEND entries "    {\"${src}\", R\"glsl(${text})glsl\"},\n")
endforeach()
file(WRITE "${OUTPUT}.tmp" "// Generated from runtime/shaders by Embed.cmake; do not edit.\n#include \"runtime/shaders/EmbeddedShaders.h\"\n\nnamespace kiosk::shaders {\nnamespace {\nconstexpr EmbeddedShader kShaders[] = {\n${entries}};\n}  // namespace\n\nstd::span<const EmbeddedShader> embedded() { return kShaders; }\n\n}  // namespace kiosk::shaders\n")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
