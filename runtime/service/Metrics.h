#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

// Prometheus text exposition format 0.0.4
// (https://prometheus.io/docs/instrumenting/exposition_formats/): a small writer for the families
// geokiosk exports plus a fixed-bucket histogram the frame loop fills without allocating. Pure; no
// threads, no I/O.
namespace kiosk::service {

/** @brief Upper bounds (ms) of the frame-time histogram buckets; +Inf is implicit. */
inline constexpr std::array<double, 12> kFrameMsBuckets = {2,  5,   10,  16.7, 25,   33.4,
                                                           50, 100, 250, 500,  1000, 5000};

/** @brief Cumulative-on-output histogram with fixed bounds; observe() never allocates. */
template <std::size_t N>
struct Histogram {
    std::array<std::uint64_t, N + 1> counts{};  ///< per bucket (not cumulative), last is +Inf
    double sum = 0;
    std::uint64_t count = 0;

    void observe(const std::array<double, N>& bounds, double value) noexcept {
        std::size_t i = 0;
        while (i < N && value > bounds[i]) ++i;
        ++counts[i];
        sum += value;
        ++count;
    }
};
using FrameHistogram = Histogram<kFrameMsBuckets.size()>;

using Labels = std::vector<std::pair<std::string, std::string>>;

/** @brief Escape a label value: backslash, double quote and newline (0.0.4 rules). */
std::string escapeLabelValue(std::string_view value);
/** @brief A sample value as the format wants it (+Inf, -Inf, NaN, shortest round-trip). */
std::string formatValue(double value);

/**
 * @brief Builds one exposition text. Each family is announced once with HELP and TYPE before
 * its samples (the format requires all samples of a family to be contiguous).
 */
class MetricsWriter {
public:
    enum class Type { Counter, Gauge, Histogram };
    /** @brief Start a family `name` (must match [a-zA-Z_:][a-zA-Z0-9_:]*). */
    void family(std::string_view name, std::string_view help, Type type);
    /** @brief One sample of the current family (`suffix` e.g. "_bucket", "_sum"). */
    void sample(std::string_view suffix, const Labels& labels, double value);
    void sample(double value) { sample("", {}, value); }
    /** @brief A whole histogram family from bounds and per-bucket counts. */
    template <std::size_t N>
    void histogram(std::string_view name, std::string_view help,
                   const std::array<double, N>& bounds, const Histogram<N>& h) {
        family(name, help, Type::Histogram);
        std::uint64_t cumulative = 0;
        for (std::size_t i = 0; i <= N; ++i) {
            cumulative += h.counts[i];
            sample("_bucket", {{"le", i < N ? formatValue(bounds[i]) : "+Inf"}},
                   double(cumulative));
        }
        sample("_sum", {}, h.sum);
        sample("_count", {}, double(h.count));
    }
    const std::string& text() const noexcept { return mText; }

private:
    std::string mText;
    std::string mFamily;
};

/** @brief Content-Type of the 0.0.4 text format. */
inline constexpr const char* kMetricsContentType = "text/plain; version=0.0.4; charset=utf-8";

}  // namespace kiosk::service
