#include "runtime/export/VideoEncoder.h"

#include "runtime/export/AvStream.h"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <thread>

namespace kiosk::video {

std::optional<VideoFormat> videoFormatForPath(const std::filesystem::path& path) {
    const std::string ext = path.extension().string();
    if (ext == ".mp4") return VideoFormat::H264Mp4;
    if (ext == ".mkv") return VideoFormat::Ffv1Mkv;
    if (ext == ".webm") return VideoFormat::Vp9Webm;
    return std::nullopt;
}

const char* videoFormatName(VideoFormat f) noexcept {
    switch (f) {
        case VideoFormat::H264Mp4:
            return "H.264 MP4";
        case VideoFormat::Ffv1Mkv:
            return "FFV1 Matroska (lossless RGB)";
        case VideoFormat::Vp9Webm:
            return "VP9 WebM";
    }
    return "?";
}

int defaultCrf(VideoFormat f) noexcept {
    // H.264 18 keeps the overlays' text and the legend's thin ticks clean (PSNR ~45 dB on the
    // demo); VP9's scale differs, 31 is libvpx's recommended 1080p quality.
    return f == VideoFormat::Vp9Webm ? 31 : 15;
}

int maxCrf(VideoFormat f) noexcept {
    return f == VideoFormat::Vp9Webm ? 63 : 51;
}

/**
 * The encoder thread's side: a fixed pool of frame buffers moves between `free` and `ready`;
 * the render thread fills a free one, the encoder thread converts, encodes and returns it.
 */
struct VideoEncoder::Impl {
    AvStream stream;
    std::size_t frameBytes = 0;
    std::vector<std::vector<std::uint8_t>> pool;
    std::deque<std::size_t> freeSlots, ready;
    std::mutex mutex;
    std::condition_variable changed;
    bool closing = false;
    bool finished = false;
    Diagnostics error;  // first failure of the encoder thread
    bool failed = false;
    std::int64_t encoded = 0;
    std::thread worker;

    void run() {
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
            const bool ok = failed || stream.encode(pool[slot].data(), d);
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
        if (!failed && !stream.close(d)) {
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
    if (!impl->stream.open(options, d)) {
        impl->stream.abandon();
        return d;
    }
    impl->frameBytes = std::size_t(options.width) * std::size_t(options.height) * 4;
    const int slots = std::max(1, options.queueFrames);
    impl->pool.resize(std::size_t(slots));
    for (std::size_t i = 0; i < impl->pool.size(); ++i) {
        impl->pool[i].resize(impl->frameBytes);
        impl->freeSlots.push_back(i);
    }
    Impl* raw = impl.get();
    impl->worker = std::thread([raw] { raw->run(); });
    return std::unique_ptr<VideoEncoder>(new VideoEncoder(std::move(impl)));
}

VideoEncoder::~VideoEncoder() {
    if (mImpl && !mImpl->finished) {
        Diagnostics ignored;  // an abandoned export (an error elsewhere) still stops its thread
        finish(ignored);
    }
}

bool VideoEncoder::push(const std::uint8_t* rgba, Diagnostics& diags) {
    Impl& m = *mImpl;
    std::size_t slot = 0;
    {
        std::unique_lock lock(m.mutex);
        m.changed.wait(lock, [&] { return !m.freeSlots.empty() || m.failed; });
        if (m.failed) {
            diags.append(m.error);
            return false;
        }
        slot = m.freeSlots.front();
        m.freeSlots.pop_front();
    }
    std::memcpy(m.pool[slot].data(), rgba, m.frameBytes);
    std::lock_guard lock(m.mutex);
    m.ready.push_back(slot);
    m.changed.notify_all();
    return true;
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
        m.stream.abandon();
        return false;
    }
    return true;
}

std::int64_t VideoEncoder::framesEncoded() const noexcept {
    std::lock_guard lock(mImpl->mutex);
    return mImpl->encoded;
}

}  // namespace kiosk::video
