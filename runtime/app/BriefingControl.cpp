#include "runtime/app/BriefingControl.h"

#include <atomic>

namespace kiosk::app {
namespace {
std::atomic<int> gPendingSteps{0};
}

void requestChapterStep(int delta) noexcept {
    gPendingSteps.fetch_add(delta, std::memory_order_relaxed);
}

int takeChapterSteps() noexcept {
    return gPendingSteps.exchange(0, std::memory_order_relaxed);
}

}  // namespace kiosk::app
