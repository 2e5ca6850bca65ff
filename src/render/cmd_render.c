/* sphlab render SCENE.ini --out DIR: simulate headless and write a PNG every
 * K steps (and VTK files with --vtk), through EGL surfaceless or OSMesa. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cmd_common.h"
#include "commands.h"
#include "gpu.h"
#include "video.h"
#include "vtk.h"

static const app_cmd_spec spec = {
    .name = "render",
    .cmd = APP_CMD(render),
    .synopsis = "usage: sphlab render SCENE.ini --out DIR [--video FILE.mp4|FILE.gif] [options]\n"
                "Simulates the scene and writes DIR/frame_00000.png, one every K steps (the first\n"
                "is the initial state), and with --video the same frames as a video, without a\n"
                "display or a GPU. All frames share one colour range (--range). The same scene and\n"
                "options give the same bytes.\n",
    .footer = "Rendering is in software (llvmpipe) unless LIBGL_ALWAYS_SOFTWARE is set to 0.\n",
    .max_pos = 1,
    .extra_pos = "more than one scene file",
};

/* The frames' steps: the first at step 0, then every `every` steps until
 * `steps` (or the time `until` when >= 0), or the watchdog stops the run. */
static bool render_done(const sph_sim *sim, long steps, double until)
{
    return until >= 0 ? sph_sim_reached(sim, until) : (long)sim->step >= steps;
}

/* One colour range for the whole run: the scene is simulated once without
 * drawing, and the field's min and max over every frame's step are taken
 * (the frames are then drawn with it). False with the reason. */
static bool run_range(const sph_scene_def *def, int threads, sph_color_field f, long every, long steps, double until,
                      float range[2], char *err, size_t n)
{
    sph_sim *sim;
    sph_error serr;
    if (sph_sim_create_shared(def, threads, NULL, &sim, &serr) != SPH_ERR_OK) {
        snprintf(err, n, "%s", serr.msg);
        return false;
    }
    if (until >= 0) sph_sim_end_at(sim, until); /* the same steps as the drawn run */
    float *vals = malloc(((size_t)sim->n + 1) * sizeof *vals);
    if (!vals) {
        sph_sim_destroy(sim);
        snprintf(err, n, "out of memory");
        return false;
    }
    float lo = INFINITY, hi = -INFINITY;
    for (;;) {
        float a, b;
        sph_sim_sync(sim, SPH_SYNC_ALL);
        if (sph_color_field_values(sim, f, vals, &a, &b) && sim->n) {
            lo = fminf(lo, a);
            hi = fmaxf(hi, b);
        }
        if (render_done(sim, steps, until) || sim->alarm.raised) break;
        for (long k = 0; k < every && !render_done(sim, steps, until); k++) sph_sim_step(sim);
    }
    free(vals);
    sph_sim_destroy(sim);
    if (lo > hi) lo = hi = 0;
    range[0] = lo;
    range[1] = hi;
    return true;
}

int cmd_render(int argc, char **argv)
{
    app_opts opt;
    app_opts_init(&opt);
    opt.every = 10;
    int rc = app_opts_parse(&spec, argc, argv, &opt);
    if (rc >= 0) return rc;
    view_opts vo;
    view_opts_init(&vo, 800, 600);
    if (!view_opts_take(&vo, &opt, "render")) return 2;
    const char *out = opt.out, *vtk_dir = opt.vtk, *video_path = opt.video;
    const int fps = opt.fps > 0 ? (int)lround(opt.fps) : 25; /* [frames/s] */
    if (opt.fps > 0 && !video_path) /* accepted, but nothing plays the PNG frames at a rate */
        fprintf(stderr, "sphlab render: note: --fps %g is the video's frame rate: without --video it changes nothing\n",
                opt.fps);
    long every = opt.every, steps = opt.steps, threads = opt.threads;
    double until = opt.time;
    /* --gl: the GL context; --backend: where the passes run */
    sph_gl_backend backend = opt.gl && strcmp(opt.gl, "osmesa") == 0 ? SPH_GL_OSMESA : SPH_GL_EGL;
    bool quiet = opt.quiet;
    app_scene_opts so;
    if (!app_scene_from_opts(&so, &opt)) return 2; /* --backend after the --set options, so it wins */
    if (video_path && sph_video_format_of(video_path) == SPH_VIDEO_NONE) {
        fprintf(stderr, "sphlab render: --video '%s': unknown extension (accepted: %s)\n", video_path,
                sph_video_extensions);
        return 2;
    }
    if (!so.path || (!out && !video_path)) {
        app_opts_usage_error(&spec, so.path ? "--out DIR (or --video FILE) is needed" : "no scene file");
        return 2;
    }
    if (steps >= 0 && until >= 0) {
        fprintf(stderr, "sphlab render: give --steps or --time, not both\n");
        return 2;
    }
    sph_scene_def def;
    const int loaded = app_load_scene_status(&so, &def); /* 2: a bad --set */
    if (loaded) return loaded;
    if (steps < 0 && until < 0) {
        if (def.duration > 0)
            until = def.duration;
        else
            steps = def.steps;
    }
    char err[1024];
    if ((out && !sph_output_dir(out, err, sizeof err)) || (vtk_dir && !sph_output_dir(vtk_dir, err, sizeof err))) {
        fprintf(stderr, "sphlab render: %s\n", err);
        return 1;
    }
    /* the video file first: a path it cannot write is refused before the run */
    sph_video *video = NULL;
    if (video_path && !(sph_parent_dir(video_path, err, sizeof err) &&
                        (video = sph_video_open(video_path, vo.w, vo.h, fps, err, sizeof err)))) {
        fprintf(stderr, "sphlab render: %s\n", err);
        return 1;
    }
    /* software rasterising: the same pixels on every machine */
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
    /* The GL backend runs in the renderer's own context where it can (EGL,
     * OpenGL 4.3), and the frames are drawn from its buffers; otherwise it
     * makes a context of its own and each frame is copied through the host. */
    sph_renderer *r = NULL;
    if (def.backend == SPH_BACKEND_GL && backend == SPH_GL_EGL) {
        r = sph_renderer_create_gl43(backend, vo.w, vo.h, err, sizeof err);
        if (!r && !quiet)
            fprintf(stderr, "sphlab render: note: %s; the frames are copied from the GL backend through the host\n",
                    err);
    }
    sph_sim *sim;
    sph_error serr;
    sph_error_code made = sph_sim_create_shared(&def, (int)threads, r ? sph_renderer_context(r) : NULL, &sim, &serr);
    if (made != SPH_ERR_OK) {
        fprintf(stderr, "sphlab: %s\n", serr.msg);
        sph_renderer_destroy(r);
        sph_video_abort(video);
        return app_error_status(serr.code);
    }
    if (until >= 0) sph_sim_end_at(sim, until); /* the last step ends on it */
    sph_view view;
    if (!view_opts_apply(&vo, "render", sim, &view)) {
        sph_sim_destroy(sim);
        sph_renderer_destroy(r);
        sph_video_abort(video);
        return 2;
    }
    if (!r) r = sph_renderer_create(backend, vo.w, vo.h, err, sizeof err);
    if (!r) {
        fprintf(stderr, "sphlab render: no usable OpenGL: %s\n", err);
        sph_sim_destroy(sim);
        sph_video_abort(video);
        return 1;
    }
    /* one colour range for every frame: --range LO,HI, else the run's own
     * (not each frame's: a video's colours would mean another thing in each frame) */
    if (!vo.has_range && !vo.range_frame && !sph_color_field_categorical(view.field)) {
        if (!run_range(&def, (int)threads, view.field, every, steps, until, view.range, err, sizeof err)) {
            fprintf(stderr, "sphlab render: the colour range: %s\n", err);
            sph_sim_destroy(sim);
            sph_renderer_destroy(r);
            sph_video_abort(video);
            return 1;
        }
        view.fixed_range = true;
        if (!quiet)
            printf("colour range over the run: %s %.6g to %.6g %s\n", sph_color_field_names[view.field], view.range[0],
                   view.range[1], sph_color_field_unit(view.field, sim->dim));
    }

    uint8_t *rgb = malloc((size_t)vo.w * vo.h * 3);
    if (!rgb) {
        fprintf(stderr, "sphlab render: out of memory\n");
        sph_video_abort(video);
        sph_sim_destroy(sim); /* first: it may live in the renderer's context */
        sph_renderer_destroy(r);
        return 1;
    }
    bool progress = !quiet && isatty(STDERR_FILENO), ok = true, alarm = false;
    double t0 = sph_now_ms(), shown = t0;
    unsigned frame = 0;
    for (;;) {
        view.selected = sim_index_of_id(sim, vo.select_id); /* the reorder pass moves particles */
        view.device = sph_gpu_fields(sim);
        if (!sph_render(r, sim, &view, err, sizeof err)) {
            fprintf(stderr, "sphlab render: %s\n", err);
            ok = false;
            break;
        }
        sph_renderer_read_rgb(r, rgb);
        char path[1100];
        snprintf(path, sizeof path, "%s/frame_%05u.png", out, frame);
        if ((out && !sph_write_png(path, rgb, vo.w, vo.h, err, sizeof err)) ||
            (video && !sph_video_add(video, rgb, vo.w, vo.h, err, sizeof err)) || (vtk_dir && !sph_vtk_write_frame(sim, vtk_dir, frame, err, sizeof err))) {
            fprintf(stderr, "sphlab render: %s\n", err);
            ok = false;
            break;
        }
        frame++;
        if (render_done(sim, steps, until)) break;
        for (long k = 0; k < every && !render_done(sim, steps, until); k++) sph_sim_step(sim);
        if (sim->alarm.raised && !alarm) {
            char rep[1024];
            sph_sim_alarm_report(sim, rep, sizeof rep);
            fprintf(stderr, "%ssphlab render: the watchdog stopped the run:\n%s\n", progress ? "\n" : "", rep);
            /* the state it stopped at is drawn as the last frame */
            until = sim->t;
            steps = (long)sim->step;
            alarm = true;
        }
        double now = sph_now_ms();
        if (progress && now - shown > 200) {
            shown = now;
            double doneness = until >= 0 ? sim->t / until : (double)sim->step / (double)(steps ? steps : 1);
            fprintf(stderr, "\r  frame %u  step %llu  t = %.4f s  %3.0f%%   ", frame, (unsigned long long)sim->step, sim->t,
                    100 * doneness);
        }
    }
    if (progress) fprintf(stderr, "\r%60s\r", "");
    if (video) {
        char codec[128];
        snprintf(codec, sizeof codec, "%s", sph_video_codec(video));
        int vw, vh; /* the file's, which the summary reports (it gave 401x301 for a 400x300 MP4) */
        sph_video_size(video, &vw, &vh);
        if (!ok) {
            sph_video_abort(video);
        } else if (!sph_video_close(video, err, sizeof err)) {
            fprintf(stderr, "sphlab render: %s\n", err);
            ok = false;
        } else if (!quiet) {
            printf("video %s: %u frame%s (%dx%d) at %d frames/s, %s\n", video_path, frame, frame == 1 ? "" : "s",
                   vw, vh, fps, codec);
        }
    }
    if (!quiet && frame && out)
        printf("%u frame%s (%dx%d) in %s/%s%s%s, %.1f s; %s: %s%s\n", frame, frame == 1 ? "" : "s", vo.w, vo.h, out,
               vtk_dir ? " and VTK in " : "", vtk_dir ? vtk_dir : "", vtk_dir ? "/" : "", (sph_now_ms() - t0) / 1e3,
               sph_gl_backend_names[backend], sph_renderer_info(r),
               sph_renderer_drew_direct(r) ? "; particles drawn from the GL backend's buffers" : "");
    free(rgb);
    sph_sim_destroy(sim); /* first: it may live in the renderer's context */
    sph_renderer_destroy(r);
    return !ok ? 1 : alarm ? 4 : 0;
}
