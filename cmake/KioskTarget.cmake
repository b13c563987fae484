# One place for the policy every geokiosk target gets (cesium-native's configure_cesium_library idea).
function(kiosk_configure_target tgt)
    target_compile_features(${tgt} PUBLIC cxx_std_20)
    set_target_properties(${tgt} PROPERTIES CXX_EXTENSIONS OFF)
    target_compile_options(${tgt} PRIVATE -Wall -Wextra -Wconversion -Wshadow -Wpedantic
                                          -Wno-sign-conversion)
    target_compile_definitions(${tgt} PUBLIC GLM_FORCE_EXPLICIT_CTOR)
    target_include_directories(${tgt} PUBLIC ${PROJECT_SOURCE_DIR})
    if(KIOSK_WERROR)
        set_target_properties(${tgt} PROPERTIES COMPILE_WARNING_AS_ERROR ON)
    endif()
    if(KIOSK_SANITIZE)
        target_compile_options(${tgt} PRIVATE -fsanitize=${KIOSK_SANITIZE} -fno-omit-frame-pointer)
        target_link_options(${tgt} PUBLIC -fsanitize=${KIOSK_SANITIZE})
    endif()
endfunction()

# A module library: kiosk_module(core SOURCES a.cpp b.cpp) -> target kiosk_core, alias kiosk::core.
function(kiosk_module name)
    cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
    add_library(kiosk_${name} STATIC ${ARG_SOURCES})
    add_library(kiosk::${name} ALIAS kiosk_${name})
    kiosk_configure_target(kiosk_${name})
endfunction()

# A GoogleTest executable registered with CTest; LABELS unit|gl|scenario|platform.
function(kiosk_test name)
    cmake_parse_arguments(ARG "" "LABEL" "SOURCES;LIBS" ${ARGN})
    add_executable(${name} ${ARG_SOURCES})
    kiosk_configure_target(${name})
    # kiosk_test_main sets the driver pins and data paths (gtest_discover_tests cannot pass a
    # multi-variable ENVIRONMENT list through its PROPERTIES).
    target_link_libraries(${name} PRIVATE ${ARG_LIBS} kiosk_test_main GTest::gtest)
    gtest_discover_tests(${name}
        WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
        PROPERTIES LABELS "${ARG_LABEL}"
        DISCOVERY_TIMEOUT 60)
endfunction()

# A benchmark executable in BUILD/bench (bench/run.sh runs it; never part of ctest):
# kiosk_bench(bench-x SOURCES x/XBench.cpp LIBS kiosk::app ...).
function(kiosk_bench name)
    cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
    add_executable(${name} ${ARG_SOURCES})
    kiosk_configure_target(${name})
    target_link_libraries(${name} PRIVATE ${ARG_LIBS})
    set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/bench)
endfunction()
