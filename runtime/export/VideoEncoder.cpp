#include "runtime/export/VideoEncoder.h"

#include "runtime/export/StreamModule.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <future>
#include <mutex>
#include <pthread.h>
#include <sys/resource.h>
#include <thread>
#include <unistd.h>

namespace kiosk::video {

/**
 * The encoder thread's side: a fixed pool of frame buffers moves between `free` and `ready`;
 * the render thread fills a free one, the encoder thread converts, encodes and returns it.
 */
struct VideoEncoder::Impl {
    using Opened = std::pair<bool, Diagnostics>;  ///< the stream's open, done on the worker
    std::unique_ptr<EncoderStream> stream;        ///< geokiosk-av.so's AvStream (StreamModule.cpp)
    std::size_t frameBytes = 0;
    std::vector<std::vector<std::uint8_t>> pool;
    std::deque<std::size_t> freeSlots, ready;
    std::size_t filling = 0;  ///< the slot acquire() handed out
    std::mutex mutex;
    std::condition_variable changed;
    bool closing = false;
    bool finished = false;
    Diagnostics error;  // first failure of the encoder thread
    bool failed = false;
    std::int64_t encoded = 0;
    std::thread worker;

    /** On the worker, at its lower priority: the codec's threads, started by the open, inherit
     * the worker's nice value. */
    bool openStream(const VideoOptions& options, std::promise<Opened>& opened) {
        pthread_setname_np(pthread_self(), kEncoderThreadName);
        const int step = options.encoderNice;
        // Relative to the process's own (a `nice`d batch export stays below the caller). Failing
        // to lower the priority (a seccomp profile, say) costs speed, not correctness.
        const auto self = static_cast<id_t>(gettid());
        errno = 0;
        const int current = getpriority(PRIO_PROCESS, self);
        if (errno == 0) (void)setpriority(PRIO_PROCESS, self, std::min(19, current + step));
        Diagnostics d;
        const bool ok = stream->open(options, d);
        if (!ok) stream->abandon();
        opened.set_value({ok, d});
        return ok;
    }

    void run(const VideoOptions& options, std::promise<Opened>& opened) {
        if (!openStream(options, opened)) return;
        for (;;) {
            std::size_t slot = 0;
            {
                std::unique_lock lock(mutex);
                changed.wait(lock, [&] { return !ready.empty() || closing; });
                if (ready.empty()) break;  // closing and drained
                slot = ready.front();
                ready.pop_front();
            }
            Diagnostics d;
            const bool ok = failed || stream->encode(pool[slot].data(), d);
            std::lock_guard lock(mutex);
            if (!ok && !failed) {
                failed = true;
                error = d;
            }
            if (ok && !failed) ++encoded;
            freeSlots.push_back(slot);
            changed.notify_all();
        }
        Diagnostics d;
        if (!failed && !stream->close(d)) {
            std::lock_guard lock(mutex);
            failed = true;
            error = d;
        }
    }
};

VideoEncoder::VideoEncoder(std::unique_ptr<Impl> impl) : mImpl(std::move(impl)) {}

Result<std::unique_ptr<VideoEncoder>> VideoEncoder::open(const VideoOptions& options) {
    auto impl = std::make_unique<Impl>();
    Diagnostics d;
    impl->stream = makeEncoderStream(d);
    if (!impl->stream) return d;
    Impl* raw = impl.get();
    std::promise<Impl::Opened> opened;
    auto openResult = opened.get_future();
    impl->worker =
        std::thread([raw, options, p = std::move(opened)]() mutable { raw->run(options, p); });
    const auto [ok, error] = openResult.get();
    if (!ok) {
        impl->worker.join();  // it abandoned the stream and returned
        return error;
    }
    // The queue's frames only once the codec is open (the worker waits for a submitted slot).
    impl->frameBytes = std::size_t(options.width) * std::size_t(options.height) * 4;
    const int slots = std::max(1, options.queueFrames);
    impl->pool.resize(std::size_t(slots));
    {
        std::lock_guard lock(impl->mutex);
        for (std::size_t i = 0; i < impl->pool.size(); ++i) {
            impl->pool[i].resize(impl->frameBytes);
            impl->freeSlots.push_back(i);
        }
    }
    return std::unique_ptr<VideoEncoder>(new VideoEncoder(std::move(impl)));
}

VideoEncoder::~VideoEncoder() {
    if (mImpl && !mImpl->finished) {
        Diagnostics ignored;  // an abandoned export (an error elsewhere) still stops its thread
        finish(ignored);
    }
}

std::uint8_t* VideoEncoder::acquire(Diagnostics& diags) {
    Impl& m = *mImpl;
    std::unique_lock lock(m.mutex);
    m.changed.wait(lock, [&] { return !m.freeSlots.empty() || m.failed; });
    if (m.failed) {
        diags.append(m.error);
        return nullptr;
    }
    m.filling = m.freeSlots.front();
    m.freeSlots.pop_front();
    return m.pool[m.filling].data();
}

void VideoEncoder::submit() {
    Impl& m = *mImpl;
    std::lock_guard lock(m.mutex);
    m.ready.push_back(m.filling);
    m.changed.notify_all();
}

bool VideoEncoder::finish(Diagnostics& diags) {
    Impl& m = *mImpl;
    if (m.finished) return !m.failed;
    {
        std::lock_guard lock(m.mutex);
        m.closing = true;
        m.changed.notify_all();
    }
    if (m.worker.joinable()) m.worker.join();
    m.finished = true;
    if (m.failed) {
        diags.append(m.error);
        m.stream->abandon();
        return false;
    }
    return true;
}

std::int64_t VideoEncoder::framesEncoded() const noexcept {
    std::lock_guard lock(mImpl->mutex);
    return mImpl->encoded;
}

}  // namespace kiosk::video
