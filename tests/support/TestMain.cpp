// main() of every test binary: pins the Mesa software driver and the shared-data paths before
// any test runs (unless the caller set them), so a test gives the same pixels however it is
// started (ctest, a debugger, by hand). Magnum's GLVND note: without the vendor pin a host
// with an NVIDIA EGL vendor would pick it.
#include <gtest/gtest.h>

#include <cstdlib>

int main(int argc, char** argv) {
    setenv("__EGL_VENDOR_LIBRARY_FILENAMES", "/usr/share/glvnd/egl_vendor.d/50_mesa.json", 0);
    setenv("GALLIUM_DRIVER", "llvmpipe", 0);
    setenv("LP_NUM_THREADS", "2", 0);
    setenv("KIOSK_SHARED_DATA", KIOSK_SHARED_DATA_DIR, 0);
    setenv("KIOSK_TEST_OUTPUT", KIOSK_TEST_OUTPUT_DIR, 0);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
