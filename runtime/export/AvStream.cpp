#include "runtime/export/AvStream.h"

#include "runtime/export/Yuv420.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libavutil/pixfmt.h>
}

#include <cstring>
#include <string>

namespace kiosk::video {
namespace {

struct CodecChoice {
    const char* encoder;
    const char* muxer;
    AVPixelFormat pixels;
};

CodecChoice choiceFor(VideoFormat f) {
    switch (f) {
        case VideoFormat::H264Mp4:
            return {"libx264", "mp4", AV_PIX_FMT_YUV420P};
        // 0RGB32 (native-endian 0x00RRGGBB words): FFV1's 8-bit RGB input, the same samples as
        // the PNG, coded losslessly (FFV1 turns them into its reversible RCT internally).
        case VideoFormat::Ffv1Mkv:
            return {"ffv1", "matroska", AV_PIX_FMT_0RGB32};
        case VideoFormat::Vp9Webm:
            return {"libvpx-vp9", "webm", AV_PIX_FMT_YUV420P};
    }
    return {"libx264", "mp4", AV_PIX_FMT_YUV420P};
}

std::string avError(int err) {
    char buf[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(err, buf, sizeof buf);
    return buf;
}

}  // namespace

AvStream::~AvStream() {
    release();
}

void AvStream::error(Diagnostics& diags, const char* code, const std::string& what, int averr) {
    diags.error(code, mOptions.path.string(), "", averr < 0 ? what + ": " + avError(averr) : what);
}

bool AvStream::open(const VideoOptions& options, Diagnostics& diags) {
    mOptions = options;
    // The libraries' banners and per-frame chatter would drown the progress bar; their errors
    // come back as return codes and are reported with the file name.
    av_log_set_level(AV_LOG_ERROR);
    mPartPath = options.path.string() + ".part";
    const CodecChoice choice = choiceFor(options.format);
    const bool yuv = choice.pixels == AV_PIX_FMT_YUV420P;
    if (yuv && (options.width % 2 || options.height % 2)) {
        error(diags, "EXPORT_OPEN",
              std::string(videoFormatName(options.format)) +
                  " needs an even width and height, got " + std::to_string(options.width) + "x" +
                  std::to_string(options.height),
              0);
        return false;
    }
    const AVCodec* codec = avcodec_find_encoder_by_name(choice.encoder);
    if (!codec) {
        error(diags, "EXPORT_CODEC",
              std::string("this FFmpeg build has no ") + choice.encoder + " encoder", 0);
        return false;
    }
    int err = avformat_alloc_output_context2(&mFormat, nullptr, choice.muxer, mPartPath.c_str());
    if (err < 0 || !mFormat) {
        error(diags, "EXPORT_OPEN", std::string("cannot set up the ") + choice.muxer + " muxer",
              err);
        return false;
    }
    mStream = avformat_new_stream(mFormat, nullptr);
    mCodec = avcodec_alloc_context3(codec);
    mFrame = av_frame_alloc();
    mPacket = av_packet_alloc();
    if (!mStream || !mCodec || !mFrame || !mPacket) {
        error(diags, "EXPORT_OPEN", "out of memory setting up the encoder", 0);
        return false;
    }
    const AVRational rate = av_d2q(options.fps, 1000000);
    mCodec->width = options.width;
    mCodec->height = options.height;
    mCodec->pix_fmt = choice.pixels;
    mCodec->time_base = av_inv_q(rate);
    mCodec->framerate = rate;
    mCodec->thread_count = 0;  // the codec's own choice (x264 frame threads, FFV1 slices)
    if (yuv) {
        // Tagged as what rgbaToYuv420Bt709 (Yuv420.h) produces, so players undo exactly that matrix
        // and range and show the PNG's colours (untagged HD video is guessed, often as BT.601).
        mCodec->color_primaries = AVCOL_PRI_BT709;
        mCodec->color_trc = AVCOL_TRC_BT709;
        mCodec->colorspace = AVCOL_SPC_BT709;
        mCodec->color_range = AVCOL_RANGE_MPEG;
        const std::string crf = std::to_string(options.crf.value_or(defaultCrf(options.format)));
        av_opt_set(mCodec->priv_data, "crf", crf.c_str(), 0);
        if (options.format == VideoFormat::H264Mp4) {
            // The preset trades encoding time for file size (defaultPreset() says why ultrafast);
            // the CRF sets the quality.
            const std::string preset = options.preset.empty() ? defaultPreset() : options.preset;
            av_opt_set(mCodec->priv_data, "preset", preset.c_str(), 0);
        } else {
            mCodec->bit_rate = 0;  // constant quality: CRF without a bitrate cap
            av_opt_set(mCodec->priv_data, "deadline", "good", 0);
            av_opt_set(mCodec->priv_data, "cpu-used", "5", 0);
            av_opt_set(mCodec->priv_data, "row-mt", "1", 0);
        }
    } else {
        mCodec->color_primaries = AVCOL_PRI_BT709;
        mCodec->color_trc = AVCOL_TRC_IEC61966_2_1;  // sRGB, what the PNG holds
        mCodec->colorspace = AVCOL_SPC_RGB;
        mCodec->color_range = AVCOL_RANGE_JPEG;
        mCodec->level =
            3;  // FFV1 version 3: slices (threads) and per-slice CRCs for the audit copy
        av_opt_set(mCodec->priv_data, "slicecrc", "1", 0);
    }
    if (mFormat->oformat->flags & AVFMT_GLOBALHEADER) mCodec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    err = avcodec_open2(mCodec, codec, nullptr);
    if (err < 0) {
        error(diags, "EXPORT_OPEN", std::string("cannot open the ") + choice.encoder + " encoder",
              err);
        return false;
    }
    avcodec_parameters_from_context(mStream->codecpar, mCodec);
    mStream->time_base = mCodec->time_base;
    mStream->avg_frame_rate = rate;

    for (std::size_t i = 0; i < options.chapters.size(); ++i) {
        // libavformat has no public chapter constructor; the context frees these with itself.
        auto* ch = static_cast<AVChapter*>(av_mallocz(sizeof(AVChapter)));
        auto** list = static_cast<AVChapter**>(
            av_realloc_array(mFormat->chapters, mFormat->nb_chapters + 1, sizeof(AVChapter*)));
        if (!ch || !list) {
            av_free(ch);
            error(diags, "EXPORT_OPEN", "out of memory for chapters", 0);
            return false;
        }
        mFormat->chapters = list;
        const auto& c = options.chapters[i];
        ch->id = std::int64_t(i + 1);
        ch->time_base = AVRational{1, 1000};
        ch->start = std::llround(c.start * 1000.0);
        ch->end = std::llround(c.end * 1000.0);
        av_dict_set(&ch->metadata, "title", c.title.c_str(), 0);
        mFormat->chapters[mFormat->nb_chapters++] = ch;
    }

    if (!(mFormat->oformat->flags & AVFMT_NOFILE)) {
        err = avio_open(&mFormat->pb, mPartPath.c_str(), AVIO_FLAG_WRITE);
        if (err < 0) {
            error(diags, "EXPORT_WRITE", "cannot create the file", err);
            return false;
        }
    }
    AVDictionary* muxOpts = nullptr;
    if (options.format == VideoFormat::H264Mp4)
        av_dict_set(&muxOpts, "movflags", "+faststart", 0);  // playable while downloading
    err = avformat_write_header(mFormat, &muxOpts);
    av_dict_free(&muxOpts);
    if (err < 0) {
        error(diags, "EXPORT_WRITE", "cannot write the file header", err);
        return false;
    }
    mHeaderWritten = true;

    mFrame->format = mCodec->pix_fmt;
    mFrame->width = options.width;
    mFrame->height = options.height;
    mFrame->color_primaries = mCodec->color_primaries;
    mFrame->color_trc = mCodec->color_trc;
    mFrame->colorspace = mCodec->colorspace;
    mFrame->color_range = mCodec->color_range;
    err = av_frame_get_buffer(mFrame, 0);
    if (err < 0) {
        error(diags, "EXPORT_OPEN", "cannot allocate a frame", err);
        return false;
    }
    return true;
}

bool AvStream::encode(const std::uint8_t* rgba, Diagnostics& diags) {
    int err = av_frame_make_writable(mFrame);
    if (err < 0) {
        error(diags, "EXPORT_ENCODE", "cannot get a writable frame", err);
        return false;
    }
    const int w = mOptions.width, h = mOptions.height;
    if (mFrame->format == AV_PIX_FMT_YUV420P) {
        rgbaToYuv420Bt709(rgba, w, h,
                          {mFrame->data[0], mFrame->data[1], mFrame->data[2], mFrame->linesize[0],
                           mFrame->linesize[1], mFrame->linesize[2]});
    } else {
        // RGBA bytes -> 0x00RRGGBB words: a plain repack of the samples (nothing to round).
        for (int y = 0; y < h; ++y) {
            const std::uint8_t* s = rgba + std::size_t(h - 1 - y) * std::size_t(w) * 4;
            auto* d = reinterpret_cast<std::uint32_t*>(mFrame->data[0] +
                                                       std::ptrdiff_t(y) * mFrame->linesize[0]);
            for (int x = 0; x < w; ++x, s += 4)
                d[x] = std::uint32_t(s[0]) << 16 | std::uint32_t(s[1]) << 8 | std::uint32_t(s[2]);
        }
    }
    mFrame->pts = mNextPts++;
    err = avcodec_send_frame(mCodec, mFrame);
    if (err < 0) {
        error(diags, "EXPORT_ENCODE", "encoding a frame failed", err);
        return false;
    }
    return drain(false, diags);
}

bool AvStream::drain(bool flushing, Diagnostics& diags) {
    for (;;) {
        int err = avcodec_receive_packet(mCodec, mPacket);
        if (err == AVERROR(EAGAIN) && !flushing) return true;
        if (err == AVERROR_EOF) return true;
        if (err < 0) {
            error(diags, "EXPORT_ENCODE", "encoding a frame failed", err);
            return false;
        }
        av_packet_rescale_ts(mPacket, mCodec->time_base, mStream->time_base);
        mPacket->stream_index = mStream->index;
        err = av_interleaved_write_frame(mFormat, mPacket);  // takes the packet's reference
        if (err < 0) {
            error(diags, "EXPORT_WRITE", "writing the video failed", err);
            return false;
        }
    }
}

bool AvStream::close(Diagnostics& diags) {
    int err = avcodec_send_frame(mCodec, nullptr);
    if (err < 0 && err != AVERROR_EOF) {
        error(diags, "EXPORT_ENCODE", "flushing the encoder failed", err);
        abandon();
        return false;
    }
    if (!drain(true, diags)) {
        abandon();
        return false;
    }
    err = av_write_trailer(mFormat);
    mHeaderWritten = false;
    if (err < 0) {
        error(diags, "EXPORT_WRITE", "cannot finish the file", err);
        abandon();
        return false;
    }
    release();
    std::error_code ec;
    std::filesystem::rename(mPartPath, mOptions.path, ec);
    if (ec) {
        diags.error("EXPORT_WRITE", mOptions.path.string(), "",
                    "cannot rename into place: " + ec.message());
        std::filesystem::remove(mPartPath, ec);
        return false;
    }
    return true;
}

void AvStream::abandon() {
    release();
    std::error_code ec;
    if (!mPartPath.empty()) std::filesystem::remove(mPartPath, ec);
}

void AvStream::release() {
    if (mFormat && mHeaderWritten) av_write_trailer(mFormat);  // lets the muxer free its state
    mHeaderWritten = false;
    if (mFormat && mFormat->pb && !(mFormat->oformat->flags & AVFMT_NOFILE))
        avio_closep(&mFormat->pb);
    avformat_free_context(mFormat);
    mFormat = nullptr;
    mStream = nullptr;
    avcodec_free_context(&mCodec);
    av_frame_free(&mFrame);
    av_packet_free(&mPacket);
}

}  // namespace kiosk::video
