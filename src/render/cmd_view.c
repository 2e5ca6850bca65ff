/* sphlab view SCENE.ini: an SDL2 window with an OpenGL 3.3 core context (4.3
 * on the GL backend, whose simulation then runs in it: see cmd_view below)
 * (GL through libepoxy), running the scene live. The same renderer as
 * `sphlab render` draws into an offscreen framebuffer, which is copied to
 * the window; a screenshot reads that framebuffer, so it holds exactly what
 * is on screen, overlays and HUD included.
 *
 * Scripted mode (--frames N [--screenshot FILE] [--keys KEYS]) draws N
 * frames, pressing one key of KEYS before each, saves the last and exits:
 * the tests run the window path that way through SDL's offscreen driver. */
#include <SDL.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd_common.h"
#include "commands.h"
#include "gl_context.h"
#include "gpu.h"
#include "io.h"
#include "layout.h"
#include "panel.h"
#include "view_ladder.h"
#include "view_record.h"

/* The key bindings, written once: the help panel, `--help` and
 * docs/rendering.md list them from here. */
#define VIEW_KEYS(X)                                                          \
    X("space", "pause / run")                                                 \
    X(".", "advance one pass (colours by what it wrote)")                     \
    X("enter", "advance one whole step")                                      \
    X("r", "reset: the scene from its start (and fit it to the view)")       \
    X("tab", "parameter panel: show / hide")                                  \
    X("w", "write the scene (as the panel's Save scene as)")                  \
    X("f", "fit the domain to the view")                                      \
    X("F1..F12", "switch pass 1..12 on or off (numbered as `sphlab check`)") \
    X("k / shift+k", "cycle the density / pressure kernel")                   \
    X("o", "cycle the sort: bitonic, counting, qsort, none")                  \
    X("m", "cycle the search: hash, grid, brute")                             \
    X("s", "cycle the pressure solver: eos, pcisph, dfsph")                   \
    /* the ladder, validate mode, N and the pass list (view_ladder.c) */      \
    X("l / shift+l", "next / previous level of the ladder (L0..L7, G0..G3)")  \
    X("e", "switch the reorder by cell on / off")                             \
    X("u", "switch the vector loops on / off")                                \
    X("t", "threads: 1 / one per core")                                       \
    X("b", "backend: cpu / gl (GL 4.3 compute)")                              \
    X("a / shift+a", "validate: run L0 (shift: L2) alongside, show the differences") \
    X("] / [", "twice / half as many particles (the scene filled again)")     \
    X("n / shift+n", "choose the next / previous pass (numbers as `sphlab check`)") \
    X("d", "switch the chosen pass on / off")                                 \
    X("1..9", "overlays: grid keys collisions neighbours forces index hud timings legend") \
    X("c / shift+c", "next / previous colour field")                          \
    X("z / x", "3D: slice down / up by h")                                    \
    X("arrows", "3D: orbit; 2D: pan")                                         \
    X("+ / -", "zoom towards the picked particle (or the centre)")            \
    X("wheel", "zoom towards the cursor")                                     \
    X("left click", "pick a particle (inspector, neighbours)")                \
    X("left / right drag", "pull / push the fluid")                           \
    X("middle drag", "3D: orbit")                                             \
    X("p", "screenshot PNG (what is on screen)")                              \
    X("v", "record a video: start / stop (--video FILE; sphlab-NNNN.mp4)")   \
    X("h", "this list")                                                       \
    X("esc / q", "quit")

static const char *const key_names[] = {
#define VIEW_KEY_NAME(k, about) k,
    VIEW_KEYS(VIEW_KEY_NAME)
#undef VIEW_KEY_NAME
};
static const char *const key_about[] = {
#define VIEW_KEY_ABOUT(k, about) about,
    VIEW_KEYS(VIEW_KEY_ABOUT)
#undef VIEW_KEY_ABOUT
};
#define N_KEYS ((int)(sizeof key_names / sizeof *key_names))

static void print_keys(FILE *f)
{
    for (int k = 0; k < N_KEYS; k++) fprintf(f, "  %-18s %s\n", key_names[k], key_about[k]);
}

static const app_cmd_spec spec = {
    .name = "view",
    .cmd = APP_CMD(view),
    .synopsis = "usage: sphlab view SCENE.ini [options]\n"
                "Opens a window and runs the scene live.\n",
    .footer = "Needs a display (X11 or Wayland). Without one, SDL_VIDEODRIVER=offscreen runs the\n"
              "scripted mode headless.\n\nkeys:\n",
    .more = print_keys,
    .max_pos = 1,
    .extra_pos = "more than one scene file",
};

typedef struct viewer {
    sph_scene_def def;   /* current definition: variants switched here */
    sph_scene_def start; /* as loaded, for messages */
    sph_sim *sim;
    sph_renderer *r;
    sph_view v;
    int threads;
    bool paused, help, quit;
    sph_color_field user_field; /* the field chosen by the user, restored after pass stepping */
    long sel_id;         /* the selected particle's id (its index changes when particles are reordered), or -1 */
    int last_pass;
    char msg[200];
    double msg_until;
    double sps;          /* steps per second, smoothed */
    /* mouse */
    bool down[3];
    float press[2];
    bool dragging;
    int shots;
    char panel[24][128];
    bool scripted;
    /* the parameter panel (src/panel/) beside the view */
    sph_panel *params;
    bool params_open;
    char save_path[1024]; /* where Save scene as and the key w write */
    float cursor[2];      /* [px] the mouse in the frame, or -1 when outside the window */
    /* the ladder (view_ladder.h): live speed per level, validate, the chosen pass */
    view_ladder ladder;
    int pass_cursor;      /* the pass the keys n and d act on, or -1 */
    char ladder_lines[8][128];
    view_rec rec; /* the record key: a video of what is on screen */
} viewer;

static void say(viewer *w, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void say(viewer *w, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(w->msg, sizeof w->msg, fmt, ap);
    va_end(ap);
    w->msg_until = sph_now_ms() + 4000;
    if (w->scripted) fprintf(stderr, "sphlab view: %s\n", w->msg);
}

/* The camera shows the whole domain again: zoom 1, no pan (3D keeps its orbit's angles). */
static void fit(viewer *w)
{
    w->v.orbit.zoom = 1.0f;
    memset(w->v.orbit.pan, 0, sizeof w->v.orbit.pan);
}

/* A new simulation of def from t = 0, fitted to the view; false (and the
 * reason said) if it cannot be made, the running one left as it was. */
static bool restart(viewer *w, const sph_scene_def *def, const char *what)
{
    sph_sim *fresh;
    sph_error err;
    /* in the context the simulation it replaces ran in (the window's, if shared) */
    if (sph_sim_create_shared(def, w->threads, w->sim->backend_share, &fresh, &err) != SPH_ERR_OK) {
        say(w, "%s: %s", what, err.msg);
        return false;
    }
    memcpy(fresh->enabled, w->sim->enabled, sizeof fresh->enabled);
    sph_sim_destroy(w->sim);
    w->sim = fresh;
    w->def = *def;
    w->last_pass = -1;
    if (sph_color_field_missing(w->sim, w->v.field)) w->v.field = sph_color_field_default(w->sim);
    fit(w);
    return true;
}

static void reset(viewer *w)
{
    if (restart(w, &w->def, "reset")) say(w, "reset to t = 0");
}

/* Keys that make other particles or place them at the start (the blocks,
 * the dimension, the jitter, the box): their change starts the scene again
 * from t = 0. Every other key changes the running simulation, its particles
 * kept (sph_sim_reconfigure), as the keys k, o and m do. */
static bool key_refills(const char *assignment)
{
    static const char *const refill[] = {"fluid", "scene.dimension=", "scene.jitter=", "scene.seed=",
                                         "domain.min=", "domain.max=", "domain.periodic="};
    for (size_t k = 0; k < sizeof refill / sizeof *refill; k++)
        if (strncmp(assignment, refill[k], strlen(refill[k])) == 0) return true;
    return false;
}

/* A change from the parameter panel: parsed and checked as a --set option,
 * then applied to the running simulation, or as a new scene where it must. */
static void apply_change(viewer *w, const char *assignment)
{
    sph_scene_def next = w->def;
    sph_error err;
    if (sph_scene_set(&next, assignment, &err) != SPH_ERR_OK || sph_scene_validate(&next, &err) != SPH_ERR_OK) {
        say(w, "%s", err.msg);
        return;
    }
    bool refill = key_refills(assignment);
    if (!refill) {
        if (sph_sim_reconfigure(w->sim, &next, &err) == SPH_ERR_OK) {
            w->def = next;
            if (sph_color_field_missing(w->sim, w->v.field)) w->v.field = sph_color_field_default(w->sim);
            say(w, "%s", assignment);
            return;
        }
        refill = err.code == SPH_ERR_SCENE; /* it makes other particles (e.g. wall particles): a new scene */
        if (!refill) {
            say(w, "%s: %s", assignment, err.msg);
            return;
        }
    }
    if (restart(w, &next, assignment)) say(w, "%s: the scene starts again from t = 0", assignment);
}

/* The keys k, o and m: the same path as the panel's changes. */
static void set_variant(viewer *w, const char *assignment)
{
    apply_change(w, assignment);
}

static void save_scene(viewer *w, const char *path)
{
    char err[1200];
    if (sph_io_save_scene(path, &w->def, err, sizeof err))
        say(w, "scene saved as %s", path);
    else
        say(w, "save: %s", err);
}

/* Zooms by factor towards the world point at (camera.c). */
static void zoom_at(viewer *w, float factor, const float at[3])
{
    float lo[3], hi[3]; /* the domain in the simulation's frame, as the renderer fits it */
    for (int d = 0; d < 3; d++) lo[d] = (float)w->sim->def.domain_min[d], hi[d] = (float)w->sim->def.domain_max[d];
    sph_orbit_zoom_at(&w->v.orbit, lo, hi, at, factor);
}

static void cycle_field(viewer *w, int dir)
{
    int f = (int)w->v.field;
    for (int k = 0; k < SPH_COLOR_COUNT; k++) {
        f = (f + dir + SPH_COLOR_COUNT) % SPH_COLOR_COUNT;
        if (!sph_color_field_missing(w->sim, (sph_color_field)f)) break; /* also skips fields without a colour */
    }
    w->v.field = w->user_field = (sph_color_field)f;
    say(w, "colour: %s", sph_color_field_names[f]);
}

static void cycle_kernel(viewer *w, bool pressure)
{
    char a[64];
    int k = ((int)(pressure ? w->def.kernel_pressure : w->def.kernel_density) + 1) % SPH_KERNEL_COUNT;
    snprintf(a, sizeof a, "kernels.%s=%s", pressure ? "pressure" : "density", sph_kernel_names[k]);
    set_variant(w, a);
}

static void screenshot(viewer *w, const char *path)
{
    int width, height;
    sph_renderer_size(w->r, &width, &height);
    uint8_t *rgb = malloc((size_t)width * height * 3);
    char name[64], err[1024];
    if (!path) {
        snprintf(name, sizeof name, "sphlab-%04d.png", w->shots++);
        path = name;
    }
    if (!rgb) {
        say(w, "screenshot: out of memory");
        return;
    }
    sph_renderer_read_rgb(w->r, rgb);
    if (sph_write_png(path, rgb, width, height, err, sizeof err))
        say(w, "saved %s (%dx%d)", path, width, height);
    else
        say(w, "screenshot: %s", err);
    free(rgb);
}

static void record_toggle(viewer *w)
{
    char m[1200];
    view_rec_toggle(&w->rec, w->r, m, sizeof m);
    say(w, "%s", m);
}

static void toggle_pass(viewer *w, int p)
{
    if (p < 0 || p >= SPH_PASS_COUNT) {
        say(w, "no such pass in this scene's pipeline (`sphlab check` lists them)");
        return;
    }
    if (!w->sim->in_pipeline[p]) {
        say(w, "pass %s is not in this scene's pipeline", sph_passes[p]->name);
        return;
    }
    w->sim->enabled[p] = !w->sim->enabled[p];
    say(w, "pass %d %s %s", view_pass_number(w->sim, p), sph_passes[p]->name, w->sim->enabled[p] ? "on" : "off");
}

static void step_pass(viewer *w)
{
    sph_pass_id p = sph_sim_step_pass(w->sim);
    if (p >= SPH_PASS_COUNT) {
        say(w, "no pass ran (all off, or the watchdog stopped the run)");
        return;
    }
    w->last_pass = (int)p;
    w->paused = true;
    int f = sph_color_field_of_pass(w->sim, p);
    if (f >= 0) w->v.field = (sph_color_field)f;
    /* the index passes write the arrays the strip shows */
    bool strip = (p == SPH_PASS_HASH || p == SPH_PASS_SORT || p == SPH_PASS_OFFSETS) && !(w->v.overlays & SPH_OV_BIT(INDEX));
    if (strip) w->v.overlays |= SPH_OV_BIT(INDEX);
    char wrote[160];
    sph_mask_names(sph_passes[p]->writes, wrote, (int)sizeof wrote);
    say(w, "pass %s wrote %s%s%s%s", sph_passes[p]->name, wrote, f >= 0 ? "; colour: " : "",
        f >= 0 ? sph_color_field_names[f] : "", strip ? "; index strip on" : "");
}

/* ---- the ladder, validate mode and N (keys l e u t b a ] [) ---- */

/* After a switch (view_ladder.c): the colour field, and the message said. */
static void switched(viewer *w, bool ok, const char *msg)
{
    if (ok && sph_color_field_missing(w->sim, w->v.field)) w->v.field = sph_color_field_default(w->sim);
    say(w, "%s", msg);
}

static void switch_sim(viewer *w, const sph_scene_def *def, int threads, const char *what)
{
    char msg[200];
    bool ok = view_switch(&w->sim, &w->def, &w->threads, def, threads, what, msg, sizeof msg);
    switched(w, ok, msg);
}

static void go_level(viewer *w, int l)
{
    char msg[200];
    bool ok = view_go_level(&w->sim, &w->def, &w->threads, l, msg, sizeof msg);
    switched(w, ok, msg);
}

static void next_level(viewer *w, int dir)
{
    char msg[200];
    bool ok = view_next_level(&w->sim, &w->def, &w->threads, dir, msg, sizeof msg);
    switched(w, ok, msg);
}

static void validate(viewer *w, const char *ref)
{
    char msg[300];
    if (view_validate(&w->ladder, w->sim, ref, msg, sizeof msg)) w->v.overlays |= SPH_OV_BIT(HUD) | SPH_OV_BIT(TIMINGS);
    say(w, "%s", msg);
}

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

static void rescale(viewer *w, bool more)
{
    const float f = powf(2.0f, (more ? -1.0f : 1.0f) / (float)w->def.dim);
    sph_scene_def next;
    char why[512];
    if (!view_scene_rescaled(&w->def, f, &next, why, sizeof why)) {
        say(w, "%s particles: %s", more ? "more" : "fewer", why);
        return;
    }
    const int threads = w->threads;
    w->ladder.validated = false; /* for other particles */
    if (restart(w, &next, more ? "more particles" : "fewer particles"))
        say(w, "%u particles: spacing and h x %.3f, the scene starts again from t = 0 (%d thread%s kept)", w->sim->n,
            (double)f, threads <= 0 ? w->sim->threads : threads, w->sim->threads == 1 ? "" : "s");
}

static void handle_key(viewer *w, SDL_Keycode k, Uint16 mod)
{
    const bool shift = mod & KMOD_SHIFT;
    const float h = w->def.h;
    sph_orbit *o = &w->v.orbit;
    if (k >= SDLK_1 && k <= SDLK_9) {
        int ov = (int)(k - SDLK_1);
        if (ov < SPH_OV_COUNT) {
            w->v.overlays ^= 1u << ov;
            say(w, "overlay %s %s", sph_overlay_names[ov], (w->v.overlays >> ov) & 1 ? "on" : "off");
        }
        return;
    }
    if (k >= SDLK_F1 && k <= SDLK_F12) {
        toggle_pass(w, view_pass_of_number(w->sim, (int)(k - SDLK_F1) + 1));
        return;
    }
    switch (k) {
    case SDLK_ESCAPE:
    case SDLK_q: w->quit = true; break;
    case SDLK_SPACE:
        w->paused = !w->paused;
        if (!w->paused) {
            w->last_pass = -1;
            w->v.field = w->user_field;
        }
        break;
    case SDLK_PERIOD: step_pass(w); break;
    case SDLK_RETURN:
    case SDLK_KP_ENTER:
        sph_sim_step(w->sim);
        w->last_pass = -1;
        w->paused = true;
        w->v.field = w->user_field;
        break;
    case SDLK_r: reset(w); break;
    case SDLK_f: fit(w); break;
    case SDLK_TAB:
        if (w->params) {
            w->params_open = !w->params_open;
            say(w, "parameter panel %s", w->params_open ? "open" : "hidden");
        } else {
            say(w, "no parameter panel (Dear ImGui could not start; see the terminal)");
        }
        break;
    case SDLK_w: save_scene(w, w->save_path); break;
    case SDLK_k: cycle_kernel(w, shift); break;
    case SDLK_o: {
        char a[64];
        snprintf(a, sizeof a, "search.sort=%s", sph_sort_names[(w->def.sort + 1) % SPH_SORT_COUNT]);
        set_variant(w, a);
        break;
    }
    case SDLK_m: {
        char a[64];
        snprintf(a, sizeof a, "search.method=%s", sph_search_names[(w->def.search + 1) % SPH_SEARCH_COUNT]);
        set_variant(w, a);
        break;
    }
    case SDLK_s: {
        char a[64];
        snprintf(a, sizeof a, "physics.pressure_solver=%s",
                 sph_pressure_solver_names[(w->def.pressure_solver + 1) % SPH_PSOLVER_COUNT]);
        set_variant(w, a);
        break;
    }
    case SDLK_l: next_level(w, shift ? -1 : 1); break;
    case SDLK_e: set_variant(w, w->def.reorder == SPH_ON ? "search.reorder=off" : "search.reorder=on"); break;
    case SDLK_u: set_variant(w, w->def.vector == SPH_ON ? "search.vector=off" : "search.vector=on"); break;
    case SDLK_t: {
        sph_scene_def def = w->def;
        switch_sim(w, &def, w->sim->threads == 1 ? 0 : 1, "threads");
        break;
    }
    case SDLK_b: {
        sph_scene_def def = w->def;
        def.backend = def.backend == SPH_BACKEND_GL ? SPH_BACKEND_CPU : SPH_BACKEND_GL;
        switch_sim(w, &def, w->sim->threads, "backend");
        break;
    }
    case SDLK_a: validate(w, shift ? "L2" : "L0"); break;
    case SDLK_RIGHTBRACKET:
    case SDLK_LEFTBRACKET: rescale(w, k == SDLK_RIGHTBRACKET); break;
    case SDLK_n:
        w->pass_cursor = view_pass_next(w->sim, w->pass_cursor, shift ? -1 : 1);
        if (w->pass_cursor >= 0)
            say(w, "pass %d %s chosen (d switches it)", view_pass_number(w->sim, w->pass_cursor),
                sph_passes[w->pass_cursor]->name);
        w->v.overlays |= SPH_OV_BIT(TIMINGS); /* the numbered list */
        break;
    case SDLK_d: toggle_pass(w, w->pass_cursor); break;
    case SDLK_c: cycle_field(w, shift ? -1 : 1); break;
    case SDLK_z: w->v.slice_z -= h; say(w, "slice z = %.4g m", w->v.slice_z); break;
    case SDLK_x: w->v.slice_z += h; say(w, "slice z = %.4g m", w->v.slice_z); break;
    case SDLK_LEFT:
    case SDLK_RIGHT:
    case SDLK_UP:
    case SDLK_DOWN: {
        float dx = k == SDLK_LEFT ? -1.0f : k == SDLK_RIGHT ? 1.0f : 0.0f, dy = k == SDLK_DOWN ? -1.0f : k == SDLK_UP ? 1.0f : 0.0f;
        if (w->sim->dim == 3) {
            o->yaw += 10.0f * dx;
            o->pitch = fmaxf(-89.0f, fminf(89.0f, o->pitch + 10.0f * dy));
        } else {
            float span = (float)(w->def.domain_max[0] - w->def.domain_min[0]) / o->zoom;
            o->pan[0] += 0.1f * span * dx;
            o->pan[1] += 0.1f * span * dy;
        }
        break;
    }
    case SDLK_PLUS:
    case SDLK_EQUALS:
    case SDLK_KP_PLUS:
    case SDLK_MINUS:
    case SDLK_KP_MINUS: { /* towards the picked particle, else the view's centre */
        float at[3];
        sph_sim_sync(w->sim, SPH_SYNC_ALL); /* the positions below are read from the host copy */
        int32_t i = sim_index_of_id(w->sim, w->sel_id);
        for (int d = 0; d < 3; d++)
            at[d] = i >= 0 && d < w->sim->dim ? w->sim->P.pos[d][i]
                                              : 0.5f * (float)(w->sim->def.domain_min[d] + w->sim->def.domain_max[d]) + o->pan[d];
        zoom_at(w, k == SDLK_MINUS || k == SDLK_KP_MINUS ? 1.0f / 1.25f : 1.25f, at);
        break;
    }
    case SDLK_p: screenshot(w, NULL); break;
    case SDLK_v: record_toggle(w); break;
    case SDLK_h: w->help = !w->help; break;
    default: break;
    }
}

/* Scripted keys: one character each ('.', ' ', digits, letters; '\n' is enter, '\t' tab). */
static void press_char(viewer *w, char c)
{
    SDL_Keycode k = c == '\n'   ? SDLK_RETURN
                    : c == '\t' ? SDLK_TAB
                                : (SDL_Keycode)(unsigned char)(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    handle_key(w, k, (c >= 'A' && c <= 'Z') ? KMOD_SHIFT : 0);
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
            apply_change(w, a);
        }
        if (!(w->def.effects & SPH_EFFECT(INTERACTION))) return;
        say(w, "added the interaction effect (mouse push/pull)");
    }
    w->sim->interaction_active = true;
    w->sim->interaction_sign = sign;
}

static void handle_event(viewer *w, const SDL_Event *e, float scale)
{
    switch (e->type) {
    case SDL_QUIT: w->quit = true; break;
    case SDL_KEYDOWN: handle_key(w, e->key.keysym.sym, e->key.keysym.mod); break;
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
                say(w, "picked particle %u", w->sim->P.id[i]);
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
        if (e->wheel.y > 0) zoom_at(w, 1.1f, at);
        if (e->wheel.y < 0) zoom_at(w, 1.0f / 1.1f, at);
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
        for (int k = 0; k < N_KEYS && n < 24; k++) snprintf(w->panel[n++], 128, "%-14s %s", key_names[k], key_about[k]);
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
    if (!app_load_scene(&so, &w.def)) return 1;
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
            say(&w, "speed-ups of levels not visited here: from %s (the bench's scene and N)", csv);
    }
    w.cursor[0] = w.cursor[1] = -1;
    /* Save scene as: --save-scene, else NAME-saved.ini in the current directory (as the screenshots) */
    if (opt.save_scene) {
        snprintf(w.save_path, sizeof w.save_path, "%s", opt.save_scene);
    } else {
        const char *base = strrchr(so.path, '/') ? strrchr(so.path, '/') + 1 : so.path;
        size_t len = strlen(base);
        if (len > 4 && strcmp(base + len - 4, ".ini") == 0) len -= 4;
        snprintf(w.save_path, sizeof w.save_path, "%.*s-saved.ini", (int)(len < 1000 ? len : 1000), base);
    }
    w.params = sph_panel_create(win, ctx, w.save_path, err, sizeof err);
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
        if (w.scripted && frame < (long)strlen(keys)) press_char(&w, keys[frame]);
        if (w.quit) break;
        if (dw < 64 || dh < 64) { /* minimised: nothing to draw */
            SDL_Delay(20);
            continue;
        }
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
                say(&w, "the watchdog stopped the run (see the terminal); r resets");
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
        /* the push/pull reach at the cursor, over the view (2D: in the plane; 3D: on the slice) */
        w.v.ring_radius = 0;
        const sph_camera *cam = sph_renderer_camera(w.r);
        if (w.cursor[0] >= cam->rect[0] && w.cursor[0] < cam->rect[0] + cam->rect[2] && w.cursor[1] >= cam->rect[1] &&
            w.cursor[1] < cam->rect[1] + cam->rect[3] && cam->img_w == dw && cam->img_h == dh) {
            mouse_world(&w, w.cursor[0], w.cursor[1], w.v.ring_at);
            w.v.ring_radius = w.def.interaction_radius;
            w.v.ring_active = w.sim->interaction_active;
        }
        if (w.sim->backend && !w.sim->backend_share) {
            /* read the backend's buffers back now, while its context is the
             * current one (sph_render would otherwise switch to it) */
            sph_sim_sync(w.sim, SPH_SYNC_ALL);
            /* the GL backend's passes made their own context current; SDL
             * skips a make-current of the context it believes current, so
             * release it first */
            SDL_GL_MakeCurrent(win, NULL);
            SDL_GL_MakeCurrent(win, ctx);
            sph_glctx_forget_current();
        }
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
            if (po.set[0]) apply_change(&w, po.set);
            if (po.save[0]) save_scene(&w, po.save);
            /* the ladder section: one change a frame, as the keys make it */
            if (po.level >= 0) go_level(&w, po.level);
            if (po.pass >= 0) toggle_pass(&w, view_pass_of_number(w.sim, po.pass + 1));
            if (po.particles) rescale(&w, po.particles > 0);
            if (po.validate) validate(&w, po.validate == 2 ? "L2" : "L0");
        }
        if (w.rec.video && !view_rec_frame(&w.rec, w.r, err, sizeof err)) say(&w, "%s", err);
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
    if (w.rec.video) record_toggle(&w); /* quitting finishes the video */
    if (shot) {
        w.msg[0] = '\0';
        screenshot(&w, shot);
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
