#pragma once

#include <cstdlib>

#include "runtime/core/Log.h"

/**
 * Programmer errors (violated preconditions): abort in debug and tests, log and carry on in
 * release builds so a kiosk keeps showing something. Bad *data* never goes through here; it
 * becomes a Diagnostic.
 */
#ifdef NDEBUG
#define KIOSK_ASSERT(cond)                                                                    \
    do {                                                                                      \
        if (!(cond)) KIOSK_LOG_ERROR("assert", "%s:%d: %s", __FILE__, __LINE__, #cond);       \
    } while (0)
#else
#define KIOSK_ASSERT(cond)                                                                    \
    do {                                                                                      \
        if (!(cond)) {                                                                        \
            KIOSK_LOG_ERROR("assert", "%s:%d: %s", __FILE__, __LINE__, #cond);                \
            std::abort();                                                                     \
        }                                                                                     \
    } while (0)
#endif
