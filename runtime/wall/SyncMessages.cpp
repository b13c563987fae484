#include "runtime/wall/SyncMessages.h"

#include <bit>
#include <cstring>

namespace kiosk::wall {
namespace {

constexpr std::uint8_t kVersion = 2;  // 2: FrameState.chapter
constexpr std::size_t kMaxIdBytes = 255;

class Writer {
public:
    explicit Writer(MessageType t) { mOut = {std::uint8_t(t), kVersion}; }
    void u8(std::uint8_t v) { mOut.push_back(v); }
    void u32(std::uint32_t v) {
        for (int i = 0; i < 4; ++i) mOut.push_back(std::uint8_t(v >> (8 * i)));
    }
    void u64(std::uint64_t v) {
        for (int i = 0; i < 8; ++i) mOut.push_back(std::uint8_t(v >> (8 * i)));
    }
    void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
    void str(const std::string& s) {
        const std::size_t n = std::min(s.size(), kMaxIdBytes);
        u8(std::uint8_t(n));
        mOut.insert(mOut.end(), s.begin(), s.begin() + std::ptrdiff_t(n));
    }
    std::vector<std::uint8_t> take() { return std::move(mOut); }

private:
    std::vector<std::uint8_t> mOut;
};

/** Bounds-checked reads: a short or foreign message fails instead of reading past the end. */
class ReaderBytes {
public:
    ReaderBytes(std::span<const std::uint8_t> b, MessageType t) : mB(b) {
        mOk = b.size() >= 2 && b[0] == std::uint8_t(t) && b[1] == kVersion;
        mPos = 2;
    }
    bool ok() const { return mOk && mPos == mB.size(); }
    std::uint8_t u8() { return need(1) ? mB[mPos++] : 0; }
    std::uint32_t u32() {
        std::uint32_t v = 0;
        if (need(4))
            for (int i = 0; i < 4; ++i) v |= std::uint32_t(mB[mPos++]) << (8 * i);
        return v;
    }
    std::uint64_t u64() {
        std::uint64_t v = 0;
        if (need(8))
            for (int i = 0; i < 8; ++i) v |= std::uint64_t(mB[mPos++]) << (8 * i);
        return v;
    }
    double f64() { return std::bit_cast<double>(u64()); }
    std::string str() {
        const std::size_t n = u8();
        if (!need(n)) return {};
        std::string s(reinterpret_cast<const char*>(mB.data() + mPos), n);
        mPos += n;
        return s;
    }

private:
    bool need(std::size_t n) {
        if (!mOk || mB.size() - mPos < n) mOk = false;
        return mOk;
    }
    std::span<const std::uint8_t> mB;
    std::size_t mPos = 0;
    bool mOk = false;
};

}  // namespace

std::vector<std::uint8_t> encode(const FrameState& m) {
    Writer w(MessageType::State);
    w.u64(m.frame);
    w.f64(m.dataTime);
    w.f64(m.stepTime);
    w.f64(m.camera.target.x);
    w.f64(m.camera.target.y);
    w.f64(m.camera.target.z);
    w.f64(m.camera.headingDeg);
    w.f64(m.camera.pitchDeg);
    w.f64(m.camera.range);
    w.u64(m.scenarioHash);
    w.str(m.scenarioId);
    w.f64(m.rate);
    w.f64(m.rangeStart);
    w.f64(m.rangeEnd);
    w.u64(m.seekSerial);
    w.u8(m.rangeMode);
    w.u8(m.paused ? 1 : 0);
    w.u32(std::uint32_t(m.chapter));
    return w.take();
}

std::vector<std::uint8_t> encode(const Ready& m) {
    Writer w(MessageType::Ready);
    w.u32(m.screen);
    w.u64(m.frame);
    w.u8(std::uint8_t((m.resident ? 1 : 0) | (m.stepResident ? 2 : 0)));
    w.u64(m.scenarioHash);
    return w.take();
}

std::vector<std::uint8_t> encode(const Release& m) {
    Writer w(MessageType::Release);
    w.u64(m.frame);
    w.u8(m.byDeadline ? 1 : 0);
    w.u32(m.readyNodes);
    return w.take();
}

std::vector<std::uint8_t> encodeStop() {
    return Writer(MessageType::Stop).take();
}

std::optional<MessageType> messageType(std::span<const std::uint8_t> b) {
    if (b.size() < 2 || b[1] != kVersion || b[0] < 1 || b[0] > 4) return std::nullopt;
    return MessageType(b[0]);
}

std::optional<FrameState> decodeState(std::span<const std::uint8_t> b) {
    ReaderBytes r(b, MessageType::State);
    FrameState m;
    m.frame = r.u64();
    m.dataTime = r.f64();
    m.stepTime = r.f64();
    m.camera.target.x = r.f64();
    m.camera.target.y = r.f64();
    m.camera.target.z = r.f64();
    m.camera.headingDeg = r.f64();
    m.camera.pitchDeg = r.f64();
    m.camera.range = r.f64();
    m.scenarioHash = r.u64();
    m.scenarioId = r.str();
    m.rate = r.f64();
    m.rangeStart = r.f64();
    m.rangeEnd = r.f64();
    m.seekSerial = r.u64();
    m.rangeMode = r.u8();
    m.paused = r.u8() != 0;
    m.chapter = std::int32_t(r.u32());
    if (!r.ok()) return std::nullopt;
    return m;
}

std::optional<Ready> decodeReady(std::span<const std::uint8_t> b) {
    ReaderBytes r(b, MessageType::Ready);
    Ready m;
    m.screen = r.u32();
    m.frame = r.u64();
    const std::uint8_t flags = r.u8();
    m.resident = flags & 1;
    m.stepResident = flags & 2;
    m.scenarioHash = r.u64();
    if (!r.ok()) return std::nullopt;
    return m;
}

std::optional<Release> decodeRelease(std::span<const std::uint8_t> b) {
    ReaderBytes r(b, MessageType::Release);
    Release m;
    m.frame = r.u64();
    m.byDeadline = r.u8() != 0;
    m.readyNodes = r.u32();
    if (!r.ok()) return std::nullopt;
    return m;
}

}  // namespace kiosk::wall
