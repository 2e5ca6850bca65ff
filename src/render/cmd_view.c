/* sphlab view SCENE.ini: an SDL2 window with an OpenGL 3.3 core context (4.3
 * on the GL backend, whose simulation then runs in it: see cmd_view below)
 * (GL through libepoxy), running the scene live. The same renderer as
 * `sphlab render` draws into an offscreen framebuffer, which is copied to
 * the window; a screenshot reads that framebuffer, so it holds exactly what
 * is on screen, overlays and HUD included.
 *
 * Scripted mode (--frames N [--screenshot FILE] [--keys KEYS]) draws N
 * frames, pressing one key of KEYS before each, saves the last and exits:
 * the tests run the window path that way through SDL's offscreen driver.
 * This file opens the window and runs its loop; the keys and the actions
 * they take are in view_keys.c. */
#include <SDL.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd_common.h"
#include "font.h"
#include "commands.h"
#include "gl_context.h"
#include "gpu.h"
#include "io.h"
#include "layout.h"
#include "view_window.h"

static const app_cmd_spec spec = {
    .name = "view",
    .cmd = APP_CMD(view),
    .synopsis = "usage: sphlab view SCENE.ini [options]\n"
                "Opens a window and runs the scene live.\n",
    .footer = "Needs a display (X11 or Wayland). Without one, SDL_VIDEODRIVER=offscreen runs the\n"
              "scripted mode headless.\n\nkeys:\n",
    .more = viewer_keys_print,
    .max_pos = 1,
    .extra_pos = "more than one scene file",
};

/* The panel's ladder section: the levels, and the passes of the pipeline in check's order. */
static void fill_panel_ladder(viewer *w, sph_panel_ladder *pl)
{
    memset(pl, 0, sizeof *pl);
    pl->level = view_ladder_level(w->sim);
    for (int l = 0; l < sph_level_count && pl->n_levels < SPH_PANEL_ROWS; l++, pl->n_levels++) {
        pl->level_name[l] = sph_levels[l].name;
        pl->level_about[l] = sph_levels[l].about;
    }
    for (int p = 0; p < SPH_PASS_COUNT && pl->n_passes < SPH_PANEL_ROWS; p++)
        if (w->sim->in_pipeline[p]) {
            pl->pass_name[pl->n_passes] = sph_passes[p]->name;
            pl->pass_on[pl->n_passes++] = w->sim->enabled[p];
        }
    pl->particles = w->sim->n;
}

static void mouse_world(viewer *w, float x, float y, float out[3])
{
    float px[2] = {x, y}, on[3];
    /* the camera works in the simulation's frame (sim->origin) */
    for (int d = 0; d < 3; d++) on[d] = 0.5f * ((float)w->sim->def.domain_min[d] + (float)w->sim->def.domain_max[d]);
    if (w->sim->dim == 3) on[2] = w->v.slice_z;
    sph_camera_unproject(sph_renderer_camera(w->r), px, on, out);
}

static void start_interaction(viewer *w, float sign)
{
    if (!(w->def.effects & SPH_EFFECT(INTERACTION))) {
        /* as the panel would: scene.effects with interaction added */
        sph_scene_def next = w->def;
        next.effects |= SPH_EFFECT(INTERACTION);
        for (int i = 0; i < sph_scene_key_count; i++) {
            const sph_key *k = &sph_scene_keys[i];
            if (strcmp(k->section, "scene") != 0 || strcmp(k->name, "effects") != 0) continue;
            char value[256], a[320];
            sph_scene_value_text(k, &next, value, sizeof value);
            snprintf(a, sizeof a, "scene.effects=%s", value);
            viewer_apply_change(w, a);
        }
        if (!(w->def.effects & SPH_EFFECT(INTERACTION))) return;
        viewer_say(w, "added the interaction effect (mouse push/pull)");
    }
    w->sim->interaction_active = true;
    w->sim->interaction_sign = sign;
}

static void handle_event(viewer *w, const SDL_Event *e, float scale)
{
    switch (e->type) {
    case SDL_QUIT: w->quit = true; break;
    case SDL_KEYDOWN: viewer_key_down(w, e->key.keysym.sym, e->key.keysym.mod); break;
    case SDL_MOUSEBUTTONDOWN: {
        int b = e->button.button == SDL_BUTTON_LEFT ? 0 : e->button.button == SDL_BUTTON_RIGHT ? 1 : 2;
        w->down[b] = true;
        w->press[0] = (float)e->button.x * scale;
        w->press[1] = (float)e->button.y * scale;
        w->dragging = false;
        break;
    }
    case SDL_MOUSEBUTTONUP: {
        int b = e->button.button == SDL_BUTTON_LEFT ? 0 : e->button.button == SDL_BUTTON_RIGHT ? 1 : 2;
        w->down[b] = false;
        if (!w->dragging && b < 2) {
            float px[2] = {(float)e->button.x * scale, (float)e->button.y * scale};
            int32_t i = b == 0 ? sph_renderer_pick(w->r, w->sim, px, 12.0f * scale) : -1;
            w->sel_id = i >= 0 ? (long)w->sim->P.id[i] : -1;
            if (i >= 0) {
                w->v.overlays |= SPH_OV_BIT(NEIGHBOURS);
                viewer_say(w, "picked particle %u", w->sim->P.id[i]);
            }
        }
        w->sim->interaction_active = false;
        w->dragging = false;
        break;
    }
    case SDL_MOUSEMOTION: {
        float x = (float)e->motion.x * scale, y = (float)e->motion.y * scale;
        w->cursor[0] = x;
        w->cursor[1] = y;
        if (!(w->down[0] || w->down[1] || w->down[2])) break;
        if (!w->dragging && fabsf(x - w->press[0]) + fabsf(y - w->press[1]) > 4) {
            w->dragging = true;
            if (w->down[0] || w->down[1]) start_interaction(w, w->down[0] ? 1.0f : -1.0f);
        }
        if (!w->dragging) break;
        if (w->down[2] && w->sim->dim == 3) {
            w->v.orbit.yaw += 0.4f * (float)e->motion.xrel;
            w->v.orbit.pitch = fmaxf(-89.0f, fminf(89.0f, w->v.orbit.pitch + 0.4f * (float)e->motion.yrel));
        } else if (w->sim->interaction_active) {
            mouse_world(w, x, y, w->sim->interaction_point);
        }
        break;
    }
    case SDL_MOUSEWHEEL: { /* towards the point under the cursor */
        int mx, my;
        SDL_GetMouseState(&mx, &my);
        float at[3];
        mouse_world(w, (float)mx * scale, (float)my * scale, at);
        if (e->wheel.y > 0) viewer_zoom_at(w, 1.1f, at);
        if (e->wheel.y < 0) viewer_zoom_at(w, 1.0f / 1.1f, at);
        break;
    }
    case SDL_WINDOWEVENT:
        if (e->window.event == SDL_WINDOWEVENT_LEAVE) w->cursor[0] = w->cursor[1] = -1;
        break;
    default: break;
    }
}

static void fill_panel(viewer *w)
{
    w->v.panel = NULL;
    w->v.panel_lines = 0;
    int n = 0;
    if (w->help) {
        snprintf(w->panel[n++], 128, "keys");
        for (int k = 0; k < viewer_key_count && n < 24; k++) snprintf(w->panel[n++], 128, "%-14s %s", viewer_key_names[k], viewer_key_about[k]);
    } else if (w->v.selected >= 0 && (uint32_t)w->v.selected < w->sim->n) {
        sph_sim_sync(w->sim, SPH_SYNC_ALL); /* the inspector reads the host copy */
        n = sph_inspect_lines(w->sim, (uint32_t)w->v.selected, w->panel, 24);
    } else {
        return;
    }
    w->v.panel = (const char(*)[128])w->panel;
    w->v.panel_lines = n;
}

/* SDL picks its offscreen driver by itself when there is no display; a
 * window nobody sees is only wanted when asked for (the scripted tests). */
static bool display_check(char *err, size_t n)
{
    const char *drv = getenv("SDL_VIDEODRIVER");
    if (drv && *drv) return true;
    const char *x = getenv("DISPLAY"), *wl = getenv("WAYLAND_DISPLAY");
    if ((x && *x) || (wl && *wl)) return true;
    snprintf(err, n, "no display: DISPLAY and WAYLAND_DISPLAY are not set (sphlab view needs X11 or Wayland; "
                     "`sphlab render` works without one, and SDL_VIDEODRIVER=offscreen runs `view --frames N` headless)");
    return false;
}

int cmd_view(int argc, char **argv)
{
    app_opts opt;
    app_opts_init(&opt);
    int parsed = app_opts_parse(&spec, argc, argv, &opt);
    if (parsed >= 0) return parsed;
    view_opts vo;
    view_opts_init(&vo, 1024, 720);
    if (!view_opts_take(&vo, &opt, "view")) return 2;
    long threads = opt.threads, frames = opt.frames, spf = opt.steps_per_frame;
    const char *shot = opt.screenshot, *keys = opt.keys ? opt.keys : "";
    bool start_paused = opt.paused;
    app_scene_opts so;
    if (!app_scene_from_opts(&so, &opt)) return 2; /* --backend after the --set options, so it wins */
    if (!so.path) {
        app_opts_usage_error(&spec, "no scene file");
        return 2;
    }
    if ((shot || *keys) && frames < 0) {
        fprintf(stderr, "sphlab view: --screenshot and --keys go with --frames N\n");
        return 2;
    }
    viewer w;
    memset(&w, 0, sizeof w);
    w.threads = (int)threads;
    w.scripted = frames > 0;
    w.rec.path = opt.video;
    w.rec.fps = opt.fps > 0 ? (int)lround(opt.fps) : 25;
    if (opt.video && sph_video_format_of(opt.video) == SPH_VIDEO_NONE) {
        fprintf(stderr, "sphlab view: --video '%s': unknown extension (accepted: %s)\n", opt.video, sph_video_extensions);
        return 2;
    }
    w.last_pass = -1;
    w.pass_cursor = -1;
    w.paused = start_paused;
    const int loaded = app_load_scene_status(&so, &w.def); /* 2: a bad --set */
    if (loaded) return loaded;
    w.start = w.def;
    char err[1024];
    if (!display_check(err, sizeof err)) {
        fprintf(stderr, "sphlab view: %s\n", err);
        return 1;
    }
    sph_error serr;
    int rc = 1;
    SDL_Window *win = NULL;
    SDL_GLContext ctx = NULL;
    /* On the GL backend the window asks for OpenGL 4.3, and the simulation
     * shares the window's context: the particles are then drawn from its
     * buffers, with no copy through the host. */
    const bool want_gl43 = w.def.backend == SPH_BACKEND_GL;
    bool shared = false;
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        fprintf(stderr, "sphlab view: SDL cannot open the video subsystem: %s\n", SDL_GetError());
        goto out;
    }
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, want_gl43 ? 4 : 3);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 3);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_CORE);
    SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
    char title[128];
    snprintf(title, sizeof title, "sphlab: %s", w.def.name[0] ? w.def.name : so.path);
    win = SDL_CreateWindow(title, SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, vo.w, vo.h,
                           SDL_WINDOW_OPENGL | SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI);
    if (!win) {
        fprintf(stderr, "sphlab view: SDL (%s driver) cannot open a window: %s\n", SDL_GetCurrentVideoDriver(),
                SDL_GetError());
        goto out;
    }
    SDL_SetWindowMinimumSize(win, 160, 120);
    ctx = SDL_GL_CreateContext(win);
    shared = want_gl43 && ctx;
    if (want_gl43 && !ctx) {
        fprintf(stderr,
                "sphlab view: note: SDL (%s driver) cannot make an OpenGL 4.3 core context (%s); the GL backend "
                "runs in a context of its own and each frame is copied through the host\n",
                SDL_GetCurrentVideoDriver(), SDL_GetError());
        SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
        ctx = SDL_GL_CreateContext(win);
    }
    if (!ctx) {
        fprintf(stderr, "sphlab view: no usable OpenGL: SDL (%s driver) cannot make an OpenGL 3.3 core context: %s\n",
                SDL_GetCurrentVideoDriver(), SDL_GetError());
        goto out;
    }
    SDL_GL_SetSwapInterval(w.scripted ? 0 : 1);
    int dw, dh;
    SDL_GL_GetDrawableSize(win, &dw, &dh);
    w.r = sph_renderer_create(SPH_GL_CURRENT, dw, dh, err, sizeof err);
    if (!w.r) {
        fprintf(stderr, "sphlab view: no usable OpenGL: %s\n", err);
        goto out;
    }
    /* the renderer's handle on the window's context; a reset or a variant
     * makes its new backend in the same one (reset, sph_sim_reconfigure) */
    if (sph_sim_create_shared(&w.def, w.threads, shared ? sph_renderer_context(w.r) : NULL, &w.sim, &serr) !=
        SPH_ERR_OK) {
        fprintf(stderr, "sphlab: %s\n", serr.msg);
        goto out;
    }
    if (!view_opts_apply(&vo, "view", w.sim, &w.v)) {
        rc = 2;
        goto out;
    }
    /* the window shows everything by default, except what a script leaves out */
    bool chose = vo.ov_on || vo.ov_off || vo.ov_none;
    if (!chose) w.v.overlays |= SPH_OV_BIT(TIMINGS);
    w.user_field = w.v.field;
    w.sel_id = vo.select_id;
    /* the last `sphlab bench ladder` CSV (its own directory, or `make bench`'s), for levels not visited here */
    for (int k = 0; k < 2 && !w.ladder.csv_path[0]; k++) {
        char csv[64];
        snprintf(csv, sizeof csv, "%sladder-%dd.csv", k ? "build/bench/" : "", w.sim->dim);
        if (view_ladder_load_csv(&w.ladder, csv))
            viewer_say(&w, "speed-ups of levels not visited here: from %s (the bench's scene and N)", csv);
    }
    w.cursor[0] = w.cursor[1] = -1;
    /* Save scene as: --save-scene, else NAME-saved.ini in the current directory (as the screenshots) */
    if (opt.save_scene) {
        snprintf(w.save_path, sizeof w.save_path, "%s", opt.save_scene);
    } else {
        const char *base = strrchr(so.path, '/') ? strrchr(so.path, '/') + 1 : so.path;
        size_t len = strlen(base);
        if (len > 4 && strcmp(base + len - 4, ".ini") == 0) len -= 4;
        /* every lesson's scene is lesson.ini: its folder names it (07-full-simulation-lesson-saved.ini), so that
         * one lesson's save does not overwrite another's */
        const char *dir = so.path, *dir_end = base > so.path ? base - 1 : so.path;
        for (const char *c = so.path; c < dir_end; c++)
            if (*c == '/') dir = c + 1;
        if (dir_end > dir && *dir != '.' && len == 6 && strncmp(base, "lesson", 6) == 0) /* not ./ or ../ */
            snprintf(w.save_path, sizeof w.save_path, "%.*s-lesson-saved.ini", (int)(dir_end - dir < 200 ? dir_end - dir : 200),
                     dir);
        else
            snprintf(w.save_path, sizeof w.save_path, "%.*s-saved.ini", (int)(len < 1000 ? len : 1000), base);
    }
    w.params = sph_panel_create(win, ctx, w.save_path, sph_font_path(), err, sizeof err);
    if (!w.params) fprintf(stderr, "sphlab view: no parameter panel: %s\n", err);
    w.params_open = w.params && (opt.panel || !w.scripted);
    if (!w.scripted) {
        printf("sphlab view: %s%s; press h for the keys\n", sph_renderer_info(w.r),
               shared ? "; the GL backend runs in this context, drawn from its buffers" : "");
        fflush(stdout);
    }
    /* bytes read back from the GL backend, per frame, for a scripted run's report */
    char per_frame[256] = "";
    size_t used = 0;
    bool direct_all = true;
    double last = sph_now_ms();
    bool backend_context_was_current = false; /* the last frame's simulation ran in a GL context of its own */
    long drawn_frames = 0; /* a screenshot of a window that drew nothing is no picture (q as the first key) */
    for (long frame = 0; !w.quit && (frames < 0 || frame < frames); frame++) {
        /* a reset replaces the simulation and a variant switch its backend,
         * each with a count of its own */
        const void *counted = w.sim->backend;
        uint64_t bytes0 = sph_gpu_downloaded_bytes(w.sim);
        int ww, wh;
        SDL_GetWindowSize(win, &ww, &wh);
        SDL_GL_GetDrawableSize(win, &dw, &dh);
        float scale = ww > 0 ? (float)dw / (float)ww : 1.0f;
        SDL_Event e;
        while (SDL_PollEvent(&e)) {
            /* the panel first: what it takes (the mouse over it, typing) the view does not see */
            bool taken = w.params && sph_panel_event(w.params, &e) && w.params_open;
            if (!taken || e.type == SDL_QUIT) handle_event(&w, &e, scale);
        }
        if (w.scripted && frame < (long)strlen(keys)) viewer_key_char(&w, keys[frame]);
        if (w.quit) break;
        if (dw < 64 || dh < 64) { /* minimised: nothing to draw */
            SDL_Delay(20);
            continue;
        }
        drawn_frames++;
        if (!sph_renderer_resize(w.r, dw, dh, err, sizeof err)) {
            fprintf(stderr, "sphlab view: %s\n", err);
            goto out;
        }
        /* advance: a fixed number of steps, or as many as fit in 15 ms */
        double t0 = sph_now_ms();
        uint64_t s0 = w.sim->step;
        if (!w.paused && !w.sim->alarm.raised) {
            if (spf >= 0 || w.scripted) {
                for (long k = 0; k < (spf >= 0 ? spf : 1); k++) sph_sim_step(w.sim);
            } else {
                do sph_sim_step(w.sim);
                while (sph_now_ms() - t0 < 15.0 && !w.sim->alarm.raised);
            }
            if (w.sim->alarm.raised) {
                char rep[2048];
                sph_sim_alarm_report(w.sim, rep, sizeof rep);
                fprintf(stderr, "sphlab view: the watchdog stopped the run:\n%s\n", rep);
                viewer_say(&w, "the watchdog stopped the run (see the terminal); r resets");
                w.paused = true;
            }
        }
        double now = sph_now_ms();
        if (w.sim->step > s0 && now > last) {
            double sps = (double)(w.sim->step - s0) / ((now - last) / 1e3);
            w.sps = w.sps > 0 ? 0.9 * w.sps + 0.1 * sps : sps;
        }
        last = now;
        w.v.hud.steps_per_s = w.paused ? 0 : w.sps;
        w.v.hud.paused = w.paused;
        w.v.hud.last_pass = w.last_pass;
        w.v.hud.message = now < w.msg_until ? w.msg : NULL;
        view_ladder_record(&w.ladder, w.sim);
        w.v.hud.n_extra = view_ladder_lines(&w.ladder, w.sim, w.ladder_lines, 8);
        w.v.hud.extra = (const char(*)[128])w.ladder_lines;
        w.v.hud.pass_cursor = w.pass_cursor + 1;
        w.v.selected = sim_index_of_id(w.sim, w.sel_id);
        fill_panel(&w);
        /* the HUD, timings, text panel and parameter panel sit in a column beside the view */
        const bool column = w.params_open || (w.v.overlays & (SPH_OV_BIT(HUD) | SPH_OV_BIT(TIMINGS))) || w.v.panel_lines;
        w.v.side_px = column ? sph_layout_side_width(dw, dh) : 0;
        /* the parameter panel keeps its first rows below the HUD and the inspector (drawable pixels) */
        w.v.panel_keep_px =
            w.params && w.params_open ? (int)ceilf(sph_layout_panel_keep(SPH_PANEL_FONT_PX) * scale) : 0;
        /* the push/pull reach at the cursor, over the view (2D: in the plane; 3D: on the slice) */
        w.v.ring_radius = 0;
        const sph_camera *cam = sph_renderer_camera(w.r);
        if (w.cursor[0] >= cam->rect[0] && w.cursor[0] < cam->rect[0] + cam->rect[2] && w.cursor[1] >= cam->rect[1] &&
            w.cursor[1] < cam->rect[1] + cam->rect[3] && cam->img_w == dw && cam->img_h == dh) {
            mouse_world(&w, w.cursor[0], w.cursor[1], w.v.ring_at);
            w.v.ring_radius = w.def.interaction_radius;
            w.v.ring_active = w.sim->interaction_active;
        }
        const bool own_context = w.sim->backend && !w.sim->backend_share;
        if (own_context) {
            /* read the backend's buffers back now, while its context is the
             * current one (sph_render would otherwise switch to it) */
            sph_sim_sync(w.sim, SPH_SYNC_ALL);
        }
        if (own_context || backend_context_was_current) {
            /* the GL backend's passes made their own context current (and a
             * simulation switched away from GL, or reset, destroyed it while
             * current: every later frame drew into nothing); SDL skips a
             * make-current of the context it believes current, so release it
             * first */
            SDL_GL_MakeCurrent(win, NULL);
            SDL_GL_MakeCurrent(win, ctx);
            sph_glctx_forget_current();
        }
        backend_context_was_current = own_context;
        w.v.device = sph_gpu_fields(w.sim);
        if (!sph_render(w.r, w.sim, &w.v, err, sizeof err)) {
            fprintf(stderr, "sphlab view: %s\n", err);
            goto out;
        }
        /* the panel draws into the renderer's frame (still bound), so the window and a screenshot both show it */
        if (w.params && w.params_open) {
            int side[4];
            sph_renderer_side_free(w.r, side);
            for (int k = 0; k < 4; k++) side[k] = (int)((float)side[k] / scale); /* drawable pixels to window units */
            sph_panel_out po;
            sph_panel_ladder pl;
            fill_panel_ladder(&w, &pl);
            sph_panel_set_ladder(w.params, &pl);
            sph_panel_frame(w.params, &w.def, side, now < w.msg_until ? w.msg : "", &po);
            sph_panel_draw(w.params);
            sph_panel_set_ladder(w.params, NULL);
            if (po.set[0]) viewer_apply_change(&w, po.set);
            if (po.save[0]) viewer_save_scene(&w, po.save);
            /* the ladder section: one change a frame, as the keys make it */
            if (po.level >= 0) viewer_go_level(&w, po.level);
            if (po.pass >= 0) viewer_toggle_pass(&w, view_pass_of_number(w.sim, po.pass + 1));
            if (po.particles) viewer_rescale(&w, po.particles > 0);
            if (po.validate) viewer_validate(&w, po.validate == 2 ? "L2" : "L0");
        }
        if (w.rec.video && !view_rec_frame(&w.rec, w.r, err, sizeof err)) viewer_say(&w, "%s", err);
        sph_renderer_present(w.r, dw, dh);
        SDL_GL_SwapWindow(win);
        direct_all &= sph_renderer_drew_direct(w.r);
        if (w.scripted && w.sim->backend && used + 24 < sizeof per_frame)
            used += (size_t)snprintf(per_frame + used, sizeof per_frame - used, " %llu",
                                     (const void *)w.sim->backend == counted
                                         ? (unsigned long long)(sph_gpu_downloaded_bytes(w.sim) - bytes0)
                                                      : (unsigned long long)sph_gpu_downloaded_bytes(w.sim));
    }
    if (w.scripted && w.sim && w.sim->backend)
        fprintf(stderr, "sphlab view: GL backend %s; bytes read back from it per frame:%s\n",
                !shared ? "in a context of its own, frames copied through the host"
                : direct_all ? "in the window's context, particles drawn from its buffers"
                             : "in the window's context, some frames copied through the host (colour field or overlays)",
                per_frame);
    /* the last frame's inspector, for the scripted tests (a lesson's first frame) */
    if (w.scripted && !w.help)
        for (int k = 0; k < w.v.panel_lines; k++) fprintf(stderr, "sphlab view: inspector: %s\n", w.panel[k]);
    rc = 0;
    if (w.rec.video) viewer_record_toggle(&w); /* quitting finishes the video */
    if (shot && drawn_frames == 0) {
        fprintf(stderr, "sphlab view: --screenshot %s: no frame was drawn (the keys quit first): nothing saved\n",
                shot);
        rc = 1;
    } else if (shot) {
        w.msg[0] = '\0';
        viewer_screenshot(&w, shot);
        if (strncmp(w.msg, "saved", 5) != 0) rc = 1;
    }
out:
    sph_video_abort(w.rec.video); /* an error stopped the window: no half video */
    /* the simulation first: a shared context must still be there */
    sph_sim_destroy(w.sim);
    if (w.params) { /* its GL objects live in the window's context */
        SDL_GL_MakeCurrent(win, NULL);
        SDL_GL_MakeCurrent(win, ctx);
        sph_panel_destroy(w.params);
    }
    if (ctx) { /* a backend of its own may have taken the thread's GL */
        SDL_GL_MakeCurrent(win, NULL);
        SDL_GL_MakeCurrent(win, ctx);
    }
    sph_renderer_destroy(w.r);
    if (ctx) SDL_GL_DeleteContext(ctx);
    if (win) SDL_DestroyWindow(win);
    SDL_Quit();
    return rc;
}
