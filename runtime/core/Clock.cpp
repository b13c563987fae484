#include "runtime/core/Clock.h"

namespace kiosk {

double RealClock::now() const {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace kiosk
