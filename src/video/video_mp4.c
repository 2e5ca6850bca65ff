/* H.264 in MP4 through libavcodec (libx264) and libavformat; RGB to YUV
 * 4:2:0 through libswscale. Where the distribution's libavcodec was built
 * without libx264, MPEG-4 part 2 (libavcodec's own encoder) is used. */
#include <stdio.h>
#include <stdlib.h>

#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/error.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>

#include "video_internal.h"

typedef struct mp4 {
    AVFormatContext *fmt;
    AVCodecContext *enc;
    AVStream *st;
    AVFrame *frame;
    AVPacket *pkt;
    struct SwsContext *sws;
    int w, h; /* the RGB frames' size; the encoded one is even (4:2:0) */
    int64_t pts;
    bool header;
} mp4;

static void say_av(char *err, size_t n, const char *what, int rc)
{
    char buf[AV_ERROR_MAX_STRING_SIZE] = "";
    av_strerror(rc, buf, sizeof buf);
    snprintf(err, n, "%s: %s", what, buf);
}

static void mp4_free(mp4 *m)
{
    if (!m) return;
    sws_freeContext(m->sws);
    av_packet_free(&m->pkt);
    av_frame_free(&m->frame);
    avcodec_free_context(&m->enc);
    if (m->fmt) {
        if (m->fmt->pb) avio_closep(&m->fmt->pb);
        avformat_free_context(m->fmt);
    }
    free(m);
}

/* Sends frame (NULL: flush) and writes every packet the encoder returns. */
static bool mp4_encode(mp4 *m, AVFrame *frame, char *err, size_t n)
{
    int rc = avcodec_send_frame(m->enc, frame);
    if (rc < 0) {
        say_av(err, n, "encoding", rc);
        return false;
    }
    for (;;) {
        rc = avcodec_receive_packet(m->enc, m->pkt);
        if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF) return true;
        if (rc < 0) {
            say_av(err, n, "encoding", rc);
            return false;
        }
        /* each frame lasts one tick: without it the MP4's edit list ends
         * before the last frame and players drop it */
        if (m->pkt->duration <= 0) m->pkt->duration = 1;
        av_packet_rescale_ts(m->pkt, m->enc->time_base, m->st->time_base);
        m->pkt->stream_index = m->st->index;
        rc = av_interleaved_write_frame(m->fmt, m->pkt);
        if (rc < 0) {
            say_av(err, n, "writing", rc);
            return false;
        }
    }
}

void *sph_video_mp4_open(const char *tmp, int w, int h, int fps, const char **codec, char *err, size_t n)
{
    mp4 *m = calloc(1, sizeof *m);
    if (!m) {
        snprintf(err, n, "out of memory");
        return NULL;
    }
    m->w = w;
    m->h = h;
    av_log_set_level(AV_LOG_ERROR);
    int rc = avformat_alloc_output_context2(&m->fmt, NULL, "mp4", tmp);
    if (rc < 0 || !m->fmt) {
        say_av(err, n, "libavformat has no MP4 muxer", rc);
        goto fail;
    }
    /* H.264 where libavcodec has libx264 (Debian's does), else MPEG-4 part 2 */
    const AVCodec *c = avcodec_find_encoder_by_name("libx264");
    *codec = "libx264 (H.264)";
    if (!c) {
        c = avcodec_find_encoder(AV_CODEC_ID_MPEG4);
        *codec = "mpeg4 (MPEG-4 part 2; this libavcodec has no libx264)";
    }
    if (!c) {
        snprintf(err, n, "libavcodec has neither libx264 nor an MPEG-4 encoder");
        goto fail;
    }
    m->st = avformat_new_stream(m->fmt, NULL);
    m->enc = avcodec_alloc_context3(c);
    m->frame = av_frame_alloc();
    m->pkt = av_packet_alloc();
    if (!m->st || !m->enc || !m->frame || !m->pkt) {
        snprintf(err, n, "out of memory");
        goto fail;
    }
    m->enc->width = w & ~1;
    m->enc->height = h & ~1;
    m->enc->pix_fmt = AV_PIX_FMT_YUV420P;
    m->enc->time_base = (AVRational){1, fps};
    m->enc->framerate = (AVRational){fps, 1};
    m->enc->gop_size = 2 * fps;
    /* one thread: the same bytes on every run and machine */
    m->enc->thread_count = 1;
    m->enc->flags |= AV_CODEC_FLAG_BITEXACT;
    if (m->fmt->oformat->flags & AVFMT_GLOBALHEADER) m->enc->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    if (c->id == AV_CODEC_ID_H264) {
        /* sharp edges and text: near-lossless quality; yuv420p plays everywhere */
        av_opt_set(m->enc->priv_data, "crf", "18", 0);
        av_opt_set(m->enc->priv_data, "preset", "medium", 0);
    } else {
        m->enc->bit_rate = 4000000; /* [bit/s] */
    }
    rc = avcodec_open2(m->enc, c, NULL);
    if (rc < 0) {
        say_av(err, n, "opening the encoder", rc);
        goto fail;
    }
    rc = avcodec_parameters_from_context(m->st->codecpar, m->enc);
    if (rc < 0) {
        say_av(err, n, "stream parameters", rc);
        goto fail;
    }
    m->st->time_base = m->enc->time_base;
    m->fmt->flags |= AVFMT_FLAG_BITEXACT;
    rc = avio_open(&m->fmt->pb, tmp, AVIO_FLAG_WRITE);
    if (rc < 0) {
        say_av(err, n, "cannot create it", rc);
        goto fail;
    }
    rc = avformat_write_header(m->fmt, NULL);
    if (rc < 0) {
        say_av(err, n, "writing the header", rc);
        goto fail;
    }
    m->header = true;
    m->frame->format = m->enc->pix_fmt;
    m->frame->width = m->enc->width;
    m->frame->height = m->enc->height;
    rc = av_frame_get_buffer(m->frame, 0);
    if (rc < 0) {
        say_av(err, n, "frame buffer", rc);
        goto fail;
    }
    m->sws = sws_getContext(w, h, AV_PIX_FMT_RGB24, m->enc->width, m->enc->height, AV_PIX_FMT_YUV420P,
                            SWS_BICUBIC | SWS_ACCURATE_RND | SWS_BITEXACT, NULL, NULL, NULL);
    if (!m->sws) {
        snprintf(err, n, "libswscale cannot convert RGB to YUV 4:2:0");
        goto fail;
    }
    return m;
fail:
    mp4_free(m);
    return NULL;
}

static bool mp4_add(void *st, const uint8_t *rgb, char *err, size_t n)
{
    mp4 *m = st;
    int rc = av_frame_make_writable(m->frame);
    if (rc < 0) {
        say_av(err, n, "frame buffer", rc);
        return false;
    }
    const uint8_t *src[1] = {rgb};
    const int stride[1] = {3 * m->w};
    sws_scale(m->sws, src, stride, 0, m->h, m->frame->data, m->frame->linesize);
    m->frame->pts = m->pts++;
    return mp4_encode(m, m->frame, err, n);
}

static bool mp4_finish(void *st, char *err, size_t n)
{
    mp4 *m = st;
    bool ok = mp4_encode(m, NULL, err, n);
    if (ok && m->header) {
        int rc = av_write_trailer(m->fmt);
        if (rc < 0) {
            say_av(err, n, "writing the trailer", rc);
            ok = false;
        }
    }
    if (m->fmt && m->fmt->pb) {
        avio_flush(m->fmt->pb);
        if (m->fmt->pb->error < 0) {
            say_av(err, n, "writing", m->fmt->pb->error);
            ok = false;
        }
    }
    mp4_free(m);
    return ok;
}

static void mp4_drop(void *st)
{
    mp4_free(st);
}

const sph_video_ops sph_video_mp4_ops = {mp4_add, mp4_finish, mp4_drop};
