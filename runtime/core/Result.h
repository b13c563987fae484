#pragma once

#include <optional>
#include <utility>

#include "runtime/core/Diagnostics.h"

namespace kiosk {

/**
 * @brief A value that may be absent, plus the errors and warnings met producing it.
 *
 * Not std::expected: a tile or scenario can load *with* warnings (Cesium's Result<T>).
 * Invariant by convention: `value` is empty iff `diagnostics.hasErrors()`.
 */
template <class T>
struct Result {
    std::optional<T> value;
    Diagnostics diagnostics;

    Result() = default;
    Result(T v) : value(std::move(v)) {}  // NOLINT(google-explicit-constructor)
    Result(Diagnostics d) : diagnostics(std::move(d)) {}  // NOLINT
    Result(T v, Diagnostics d) : value(std::move(v)), diagnostics(std::move(d)) {}

    bool ok() const noexcept { return value.has_value(); }
    explicit operator bool() const noexcept { return ok(); }
    T& operator*() { return *value; }
    const T& operator*() const { return *value; }
    T* operator->() { return &*value; }
    const T* operator->() const { return &*value; }
};

}  // namespace kiosk
