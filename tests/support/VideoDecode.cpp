#include "tests/support/VideoDecode.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libswscale/swscale.h>
}

#include <cmath>
#include <memory>

namespace kiosk::test {
namespace {

struct Closer {
    void operator()(AVFormatContext* f) const { avformat_close_input(&f); }
    void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
    void operator()(AVFrame* f) const { av_frame_free(&f); }
    void operator()(AVPacket* p) const { av_packet_free(&p); }
    void operator()(SwsContext* s) const { sws_freeContext(s); }
};

int swsMatrix(int avcolSpace) {
    switch (avcolSpace) {
        case AVCOL_SPC_BT709:
            return SWS_CS_ITU709;
        case AVCOL_SPC_BT2020_NCL:
            return SWS_CS_BT2020;
        default:
            return SWS_CS_ITU601;  // what an untagged stream is decoded as
    }
}

}  // namespace

DecodedVideo decodeVideo(const std::filesystem::path& file) {
    DecodedVideo v;
    AVFormatContext* raw = nullptr;
    if (avformat_open_input(&raw, file.c_str(), nullptr, nullptr) < 0) {
        v.error = "cannot open " + file.string();
        return v;
    }
    std::unique_ptr<AVFormatContext, Closer> fmt(raw);
    if (avformat_find_stream_info(fmt.get(), nullptr) < 0) {
        v.error = "no stream info";
        return v;
    }
    const AVCodec* codec = nullptr;
    const int si = av_find_best_stream(fmt.get(), AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
    if (si < 0 || !codec) {
        v.error = "no video stream";
        return v;
    }
    const AVStream* st = fmt->streams[si];
    std::unique_ptr<AVCodecContext, Closer> dec(avcodec_alloc_context3(codec));
    avcodec_parameters_to_context(dec.get(), st->codecpar);
    if (avcodec_open2(dec.get(), codec, nullptr) < 0) {
        v.error = "cannot open decoder";
        return v;
    }
    v.codec = codec->name;
    v.width = st->codecpar->width;
    v.height = st->codecpar->height;
    v.fps = av_q2d(st->avg_frame_rate);
    v.colorPrimaries = st->codecpar->color_primaries;
    v.colorTrc = st->codecpar->color_trc;
    v.colorSpace = st->codecpar->color_space;
    v.colorRange = st->codecpar->color_range;
    std::unique_ptr<AVFrame, Closer> frame(av_frame_alloc());
    std::unique_ptr<AVPacket, Closer> pkt(av_packet_alloc());
    std::unique_ptr<SwsContext, Closer> sws;
    auto take = [&]() {
        while (avcodec_receive_frame(dec.get(), frame.get()) == 0) {
            const int w = frame->width, h = frame->height;
            std::vector<std::uint8_t> rgb(std::size_t(w) * std::size_t(h) * 3);
            if (!sws) {
                sws.reset(sws_getContext(w, h, AVPixelFormat(frame->format), w, h, AV_PIX_FMT_RGB24,
                                         SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INT,
                                         nullptr, nullptr, nullptr));
                const int* m = sws_getCoefficients(swsMatrix(frame->colorspace));
                const int srcFull = frame->color_range == AVCOL_RANGE_JPEG ? 1 : 0;
                sws_setColorspaceDetails(sws.get(), m, srcFull, m, 1, 0, 1 << 16, 1 << 16);
            }
            std::uint8_t* dst[1] = {rgb.data()};
            const int stride[1] = {w * 3};
            sws_scale(sws.get(), frame->data, frame->linesize, 0, h, dst, stride);
            v.frames.push_back(std::move(rgb));
        }
    };
    while (av_read_frame(fmt.get(), pkt.get()) >= 0) {
        if (pkt->stream_index == si) avcodec_send_packet(dec.get(), pkt.get());
        av_packet_unref(pkt.get());
        take();
    }
    avcodec_send_packet(dec.get(), nullptr);
    take();
    return v;
}

double clipPsnr(const std::vector<std::vector<std::uint8_t>>& a,
                const std::vector<std::vector<std::uint8_t>>& b) {
    double se = 0, n = 0;
    for (std::size_t f = 0; f < a.size() && f < b.size(); ++f)
        for (std::size_t i = 0; i < a[f].size() && i < b[f].size(); ++i) {
            const double d = double(a[f][i]) - double(b[f][i]);
            se += d * d;
            n += 1;
        }
    if (n == 0) return 0;
    if (se == 0) return INFINITY;
    return 10.0 * std::log10(255.0 * 255.0 / (se / n));
}

}  // namespace kiosk::test
