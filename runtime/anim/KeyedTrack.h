#pragma once

#include <algorithm>
#include <cstddef>

namespace kiosk::anim {

/**
 * @brief The value of a keyed track at `time`: keys in time order, the value held before the
 * first key and after the last, piecewise linear between neighbours. Serves every keyed
 * parameter of a scenario (sun keys, lens keys, mapping keys) so they cannot disagree at a key.
 *
 * A key may set only some fields: `apply(state, key)` overlays a key's fields on the value
 * reached at the previous key (starting from `base`), `timeOf(key)` gives its time in seconds
 * and `mix(a, b, t)` interpolates two values. Two keys at the same time are a jump: the later
 * one applies from that time on.
 */
template <class State, class Keys, class TimeOf, class Apply, class Mix>
State keyedTrack(State base, const Keys& keys, double time, TimeOf timeOf, Apply apply, Mix mix) {
    State at = base;
    double atTime = 0.0;
    bool first = true;
    for (const auto& key : keys) {
        State next = at;
        apply(next, key);
        const double t = timeOf(key);
        if (first || t <= time) {  // held before the first key; passed keys are reached
            at = next;
            atTime = t;
            first = false;
            continue;
        }
        const double a = t > atTime ? std::clamp((time - atTime) / (t - atTime), 0.0, 1.0) : 0.0;
        return mix(at, next, a);
    }
    return at;
}

}  // namespace kiosk::anim
