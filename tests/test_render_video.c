/* Videos (render --video, the window's record key), the run-wide colour
 * range and --range, and render's deterministic overlays. The videos are
 * read back with the libraries that play them: libavformat/libavcodec for
 * MP4, giflib for GIF. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gif_lib.h>
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <stb_image.h>

#include "test_util.h"
#include "video.h"

static const char *scene_2d = "[scene]\nname=video test\neffects=gravity pressure viscosity walls\nsteps=4\n"
                              "[domain]\nmin=0 0\nmax=0.4 0.3\n[fluid a]\nmin=0 0\nmax=0.2 0.2\nspacing=0.02\n"
                              "[kernels]\nh=0.04\n[time]\ndt=0.0002\ncfl=0\n[search]\ntable_size=37\n";

/* An MP4's video streams, size and decoded frames (every packet decoded: the
 * container's own count may be absent). */
static void mp4_read(const char *path, int *streams, int *w, int *h, long *frames, char *codec, size_t n)
{
    AVFormatContext *fmt = NULL;
    cr_assert_eq(avformat_open_input(&fmt, path, NULL, NULL), 0, "libavformat cannot open %s", path);
    cr_assert_geq(avformat_find_stream_info(fmt, NULL), 0);
    *streams = (int)fmt->nb_streams;
    int vs = av_find_best_stream(fmt, AVMEDIA_TYPE_VIDEO, -1, -1, NULL, 0);
    cr_assert_geq(vs, 0, "no video stream in %s", path);
    const AVCodecParameters *par = fmt->streams[vs]->codecpar;
    *w = par->width;
    *h = par->height;
    snprintf(codec, n, "%s", avcodec_get_name(par->codec_id));
    const AVCodec *dec = avcodec_find_decoder(par->codec_id);
    cr_assert_not_null(dec);
    AVCodecContext *ctx = avcodec_alloc_context3(dec);
    avcodec_parameters_to_context(ctx, par);
    cr_assert_eq(avcodec_open2(ctx, dec, NULL), 0);
    AVPacket *pkt = av_packet_alloc();
    AVFrame *fr = av_frame_alloc();
    *frames = 0;
    for (bool flushing = false;;) {
        if (!flushing) {
            if (av_read_frame(fmt, pkt) < 0) {
                flushing = true;
                avcodec_send_packet(ctx, NULL);
            } else {
                if (pkt->stream_index == vs) avcodec_send_packet(ctx, pkt);
                av_packet_unref(pkt);
            }
        }
        int rc;
        while ((rc = avcodec_receive_frame(ctx, fr)) == 0) (*frames)++;
        if (flushing && rc == AVERROR_EOF) break;
    }
    av_frame_free(&fr);
    av_packet_free(&pkt);
    avcodec_free_context(&ctx);
    avformat_close_input(&fmt);
}

static void gif_read(const char *path, int *frames, int *w, int *h)
{
    int err = 0;
    GifFileType *g = DGifOpenFileName(path, &err);
    cr_assert_not_null(g, "giflib cannot open %s: %s", path, GifErrorString(err));
    cr_assert_eq(DGifSlurp(g), GIF_OK, "giflib cannot read %s", path);
    *frames = g->ImageCount;
    *w = g->SWidth;
    *h = g->SHeight;
    DGifCloseFile(g, &err);
}

Test(video, render_writes_mp4_and_gif_that_read_back_with_every_frame)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d = test_temp_dir("video");
    char args[1024], out[4096], mp4[128], gif[128];
    snprintf(mp4, sizeof mp4, "%s/run.mp4", d);
    snprintf(gif, sizeof gif, "%s/run.gif", d);
    /* 12 steps every 2: frames at steps 0, 2, ..., 12 = 7 */
    snprintf(args, sizeof args, "render %s --steps 12 --every 2 --size 160x120 --out %s --video %s", scene, d, mp4);
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    cr_expect(strstr(out, "7 frames (160x120) at 25 frames/s"), "%s", out);
    snprintf(args, sizeof args, "render %s --steps 12 --every 2 --size 160x120 --video %s --fps 10", scene, gif);
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    int streams, w, h, gf;
    long frames;
    char codec[64];
    mp4_read(mp4, &streams, &w, &h, &frames, codec, sizeof codec);
    cr_expect_eq(streams, 1);
    cr_expect_eq(frames, 7, "%ld frames decoded", frames);
    cr_expect(w == 160 && h == 120, "%dx%d", w, h);
    cr_expect(strcmp(codec, "h264") == 0 || strcmp(codec, "mpeg4") == 0, "codec %s", codec);
    gif_read(gif, &gf, &w, &h);
    cr_expect_eq(gf, 7, "%d GIF frames", gf);
    cr_expect(w == 160 && h == 120, "%dx%d", w, h);
    /* no temporary left beside them */
    snprintf(args, sizeof args, "%s/run.part.mp4", d);
    cr_expect(access(args, F_OK) != 0, "temporary left: %s", args);
    test_remove_dir(d);
    remove(scene);
}

Test(video, bad_video_paths_are_refused_naming_the_value)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    char args[1024], out[4096];
    snprintf(args, sizeof args, "render %s --steps 2 --video /tmp/sphlab-video-x.avi", scene);
    cr_expect_eq(test_sphlab(args, out, sizeof out), 2, "%s", out);
    cr_expect(strstr(out, "'/tmp/sphlab-video-x.avi'") && strstr(out, "unknown extension"), "%s", out);
    snprintf(args, sizeof args, "render %s --steps 2 --video /proc/sphlab-no/x.mp4", scene);
    cr_expect_eq(test_sphlab(args, out, sizeof out), 1, "%s", out);
    cr_expect(strstr(out, "/proc/sphlab-no/x.mp4") && strstr(out, "cannot create"), "%s", out);
    snprintf(args, sizeof args, "view %s --frames 1 --video x.webm", scene);
    cr_expect_eq(test_sphlab_env("SDL_VIDEODRIVER=offscreen", args, out, sizeof out), 2, "%s", out);
    cr_expect(strstr(out, "'x.webm'"), "%s", out);
    /* the library's own check, without the command line */
    char err[256];
    cr_expect_null(sph_video_open("a.mov", 64, 64, 25, err, sizeof err));
    cr_expect(strstr(err, "a.mov"), "%s", err);
    remove(scene);
}

/* Under SDL's offscreen driver with scripted keys, as the other window
 * tests: v starts a recording after the first frame, v again stops it
 * three frames later. */
Test(video, window_record_key_writes_a_video)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d = test_temp_dir("video");
    char args[1024], out[8192], gif[128];
    snprintf(gif, sizeof gif, "%s/rec.gif", d);
    snprintf(args, sizeof args, "view %s --frames 6 --keys '.v...v' --size 240x180 --video %s", scene, gif);
    int rc = test_sphlab_env("SDL_VIDEODRIVER=offscreen", args, out, sizeof out);
    cr_assert_eq(rc, 0, "view exit %d: %s", rc, out);
    cr_expect(strstr(out, "recording ") && strstr(out, "recorded "), "%s", out);
    int frames, w, h;
    gif_read(gif, &frames, &w, &h);
    cr_expect_eq(frames, 4, "%d frames recorded (keys before frames 2..5: 4 frames drawn)", frames);
    cr_expect(w == 240 && h == 180, "%dx%d", w, h);
    test_remove_dir(d);
    remove(scene);
}

/* The legend column (the right part of the frame with only the legend on). */
static unsigned char *legend_of(const char *path, int *w, int *h)
{
    int n;
    unsigned char *img = stbi_load(path, w, h, &n, 3);
    cr_assert_not_null(img, "cannot read %s", path);
    return img;
}

static bool legends_equal(const char *p1, const char *p2)
{
    int w1, h1, w2, h2;
    unsigned char *a = legend_of(p1, &w1, &h1), *b = legend_of(p2, &w2, &h2);
    cr_assert(w1 == w2 && h1 == h2);
    bool same = true;
    for (int y = 0; y < h1; y++)
        same &= memcmp(a + ((size_t)y * w1 + w1 * 3 / 4) * 3, b + ((size_t)y * w1 + w1 * 3 / 4) * 3,
                       (size_t)(w1 - w1 * 3 / 4) * 3) == 0;
    stbi_image_free(a);
    stbi_image_free(b);
    return same;
}

Test(video, frames_of_one_run_share_one_colour_range)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d = test_temp_dir("video");
    char args[1024], out[4096], f0[128], f3[128];
    const char *opts = "--steps 300 --every 100 --size 320x240 --overlay none --overlay legend --color speed";
    snprintf(f0, sizeof f0, "%s/frame_00000.png", d);
    snprintf(f3, sizeof f3, "%s/frame_00003.png", d);
    /* each frame's own range: the legend changes (speed 0 everywhere at step 0) */
    snprintf(args, sizeof args, "render %s --out %s %s --range frame --quiet", scene, d, opts);
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    cr_expect(!legends_equal(f0, f3), "per-frame ranges drew the same legend");
    /* the default: the run's range, the same legend in every frame */
    snprintf(args, sizeof args, "render %s --out %s %s", scene, d, opts);
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    cr_expect(strstr(out, "colour range over the run: speed 0 to "), "%s", out);
    cr_expect(legends_equal(f0, f3), "frames 0 and 3 of one run have different legends");
    char keep[128];
    snprintf(keep, sizeof keep, "%s/run0.png", d);
    cr_assert_eq(rename(f0, keep), 0);
    /* --range LO,HI: honoured (another legend than the run's), one for all frames */
    snprintf(args, sizeof args, "render %s --out %s %s --range 0,2.5 --quiet", scene, d, opts);
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    cr_expect(legends_equal(f0, f3));
    cr_expect(!legends_equal(f0, keep), "--range 0,2.5 drew the run's legend");
    /* bad values */
    const char *bad[] = {"1,0", "2,2", "a,b", "nan,1", "0,inf", "1", "0,1,2", "runs"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        snprintf(args, sizeof args, "render %s --out %s --steps 1 --range '%s'", scene, d, bad[k]);
        cr_expect_eq(test_sphlab(args, out, sizeof out), 2, "--range %s: %s", bad[k], out);
        char want[64];
        snprintf(want, sizeof want, "--range '%s'", bad[k]);
        cr_expect(strstr(out, want), "--range %s: %s", bad[k], out);
    }
    /* the window cannot know its run's range beforehand */
    snprintf(args, sizeof args, "view %s --frames 1 --range run", scene);
    cr_expect_eq(test_sphlab_env("SDL_VIDEODRIVER=offscreen", args, out, sizeof out), 2, "%s", out);
    test_remove_dir(d);
    remove(scene);
}

Test(video, render_overlay_all_gives_the_same_bytes_every_run)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d1 = test_temp_dir("video"), *d2 = test_temp_dir("video");
    char args[1024], out[4096];
    for (int k = 0; k < 2; k++) {
        snprintf(args, sizeof args, "render %s --out %s --steps 4 --every 2 --size 320x240 --overlay all --quiet", scene,
                 k ? d2 : d1);
        cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    }
    for (int f = 0; f < 3; f++) {
        char p1[128], p2[128], cmd[300];
        snprintf(p1, sizeof p1, "%s/frame_%05d.png", d1, f);
        snprintf(p2, sizeof p2, "%s/frame_%05d.png", d2, f);
        snprintf(cmd, sizeof cmd, "cmp -s %s %s", p1, p2);
        cr_expect_eq(system(cmd), 0, "frame %d differs between two runs with --overlay all", f);
    }
    test_remove_dir(d1);
    test_remove_dir(d2);
    remove(scene);
}
