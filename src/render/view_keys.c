/* The live window's keys (sphlab view, cmd_view.c): the table of bindings
 * and what each key does. The parameter panel's changes take the same
 * actions (viewer_apply_change, viewer_go_level, ...), so a key and the
 * panel change a running simulation one way. */
#include <SDL.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io.h"
#include "sph_walls.h"
#include "view_window.h"

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
    X("l / shift+l", "next / previous level of the ladder (L0..L18, G0..G3)")  \
    X("e", "switch the reorder by cell on / off")                             \
    X("u", "switch the vector loops on / off")                                \
    X("t", "threads: 1 / one per core")                                       \
    X("b", "backend: cpu / gl (GL 4.3 compute)")                              \
    X("a / shift+a", "validate: run L0 (shift: L2) alongside, show the differences") \
    X("] / [", "about twice / half as many particles (filled again)")       \
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

const char *const viewer_key_names[] = {
#define VIEW_KEY_NAME(k, about) k,
    VIEW_KEYS(VIEW_KEY_NAME)
#undef VIEW_KEY_NAME
};
const char *const viewer_key_about[] = {
#define VIEW_KEY_ABOUT(k, about) about,
    VIEW_KEYS(VIEW_KEY_ABOUT)
#undef VIEW_KEY_ABOUT
};
const int viewer_key_count = (int)(sizeof viewer_key_names / sizeof *viewer_key_names);

void viewer_keys_print(FILE *f)
{
    for (int k = 0; k < viewer_key_count; k++) fprintf(f, "  %-18s %s\n", viewer_key_names[k], viewer_key_about[k]);
}

void viewer_say(viewer *w, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void viewer_say(viewer *w, const char *fmt, ...)
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
        viewer_say(w, "%s: %s", what, err.msg);
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
    if (restart(w, &w->def, "reset")) viewer_say(w, "reset to t = 0");
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
/* A chosen pass (keys n, d) that a new pipeline lacks is chosen no more: d then named a pass that was not
 * there, and the timings list marked none. */
static void forget_missing_pass(viewer *w)
{
    if (w->pass_cursor >= 0 && !w->sim->in_pipeline[w->pass_cursor]) w->pass_cursor = -1;
}

void viewer_apply_change(viewer *w, const char *assignment)
{
    sph_scene_def next = w->def;
    sph_error err;
    if (sph_scene_set(&next, assignment, &err) != SPH_ERR_OK || sph_scene_validate(&next, &err) != SPH_ERR_OK) {
        viewer_say(w, "%s", err.msg);
        return;
    }
    bool refill = key_refills(assignment);
    if (!refill) {
        if (sph_sim_reconfigure(w->sim, &next, &err) == SPH_ERR_OK) {
            w->def = next;
            if (sph_color_field_missing(w->sim, w->v.field)) w->v.field = sph_color_field_default(w->sim);
            forget_missing_pass(w);
            viewer_say(w, "%s", assignment);
            return;
        }
        refill = err.code == SPH_ERR_SCENE; /* it makes other particles (e.g. wall particles): a new scene */
        if (!refill) {
            viewer_say(w, "%s: %s", assignment, err.msg);
            return;
        }
    }
    if (restart(w, &next, assignment)) {
        forget_missing_pass(w);
        viewer_say(w, "%s: the scene starts again from t = 0", assignment);
    }
}

/* The keys k, o and m: the same path as the panel's changes. */
static void set_variant(viewer *w, const char *assignment)
{
    viewer_apply_change(w, assignment);
}

void viewer_save_scene(viewer *w, const char *path)
{
    char err[1200];
    if (sph_io_save_scene(path, &w->def, err, sizeof err))
        viewer_say(w, "scene saved as %s", path);
    else
        viewer_say(w, "save: %s", err);
}

/* Zooms by factor towards the world point at (camera.c). */
void viewer_zoom_at(viewer *w, float factor, const float at[3])
{
    float lo[3], hi[3]; /* the box the renderer fits: the domain and its wall particles */
    sph_wall_particles_bounds(&w->sim->def, lo, hi);
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
    viewer_say(w, "colour: %s", sph_color_field_names[f]);
}

static void cycle_kernel(viewer *w, bool pressure)
{
    char a[64];
    int k = ((int)(pressure ? w->def.kernel_pressure : w->def.kernel_density) + 1) % SPH_KERNEL_COUNT;
    snprintf(a, sizeof a, "kernels.%s=%s", pressure ? "pressure" : "density", sph_kernel_names[k]);
    set_variant(w, a);
}

void viewer_screenshot(viewer *w, const char *path)
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
        viewer_say(w, "screenshot: out of memory");
        return;
    }
    sph_renderer_read_rgb(w->r, rgb);
    if (sph_write_png(path, rgb, width, height, err, sizeof err))
        viewer_say(w, "saved %s (%dx%d)", path, width, height);
    else
        viewer_say(w, "screenshot: %s", err);
    free(rgb);
}

void viewer_record_toggle(viewer *w)
{
    char m[1200];
    view_rec_toggle(&w->rec, w->r, m, sizeof m);
    viewer_say(w, "%s", m);
}

void viewer_toggle_pass(viewer *w, int p)
{
    if (p < 0 || p >= SPH_PASS_COUNT) {
        viewer_say(w, "no such pass in this scene's pipeline (`sphlab check` lists them)");
        return;
    }
    if (!w->sim->in_pipeline[p]) {
        viewer_say(w, "pass %s is not in this scene's pipeline", sph_passes[p]->name);
        return;
    }
    w->sim->enabled[p] = !w->sim->enabled[p];
    /* the ms-per-step window starts again: its steps ran the other pipeline, and their median was filed as the
     * level's live time once all passes were on again */
    w->sim->step_ms_count = 0;
    viewer_say(w, "pass %d %s %s", view_pass_number(w->sim, p), sph_passes[p]->name, w->sim->enabled[p] ? "on" : "off");
}

static void step_pass(viewer *w)
{
    sph_pass_id p = sph_sim_step_pass(w->sim);
    if (p >= SPH_PASS_COUNT) {
        viewer_say(w, "no pass ran (all off, or the watchdog stopped the run)");
        return;
    }
    w->last_pass = (int)p;
    w->paused = true;
    int f = sph_color_field_of_pass(w->sim, p);
    if (f >= 0) w->v.field = (sph_color_field)f;
    /* the index passes write the arrays the strip shows */
    bool strip = (p == SPH_PASS_HASH || p == SPH_PASS_SORT || p == SPH_PASS_OFFSETS) && !(w->v.overlays & SPH_OV_BIT(INDEX));
    if (strip) w->v.overlays |= SPH_OV_BIT(INDEX);
    /* what it wrote is the HUD's "ran pass" row; with the HUD off, said here (both: one list twice, two ways) */
    char wrote[256] = "";
    if (!(w->v.overlays & SPH_OV_BIT(HUD)))
        sph_mask_names(sph_sim_mask_present(w->sim, sph_passes[p]->writes), wrote, (int)sizeof wrote);
    if (!*wrote && f < 0 && !strip) { /* the HUD's row says it all; a script's log still gets the line */
        w->msg[0] = '\0'; /* and the last pass's message goes: it read as this one's */
        w->msg_until = 0;
        if (w->scripted) fprintf(stderr, "sphlab view: pass %s ran\n", sph_passes[p]->name);
        return;
    }
    viewer_say(w, "pass %s %s%s%s%s%s", sph_passes[p]->name, *wrote ? "wrote " : "ran", wrote,
               f >= 0 ? "; colour: " : "", f >= 0 ? sph_color_field_names[f] : "", strip ? "; index strip on" : "");
}

/* ---- the ladder, validate mode and N (keys l e u t b a ] [) ---- */

/* After a switch (view_ladder.c): the colour field, and the message said. */
static void switched(viewer *w, bool ok, const char *msg)
{
    if (ok && sph_color_field_missing(w->sim, w->v.field)) w->v.field = sph_color_field_default(w->sim);
    if (ok) forget_missing_pass(w);
    viewer_say(w, "%s", msg);
}

static void switch_sim(viewer *w, const sph_scene_def *def, int threads, const char *what)
{
    char msg[200];
    bool ok = view_switch(&w->sim, &w->def, &w->threads, def, threads, what, msg, sizeof msg);
    switched(w, ok, msg);
}

void viewer_go_level(viewer *w, int l)
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

void viewer_validate(viewer *w, const char *ref)
{
    char msg[300];
    if (view_validate(&w->ladder, w->sim, ref, msg, sizeof msg)) w->v.overlays |= SPH_OV_BIT(HUD) | SPH_OV_BIT(TIMINGS);
    viewer_say(w, "%s", msg);
}

void viewer_rescale(viewer *w, bool more)
{
    const float f = powf(2.0f, (more ? -1.0f : 1.0f) / (float)w->def.dim);
    sph_scene_def next;
    char why[512];
    if (!view_scene_rescaled(&w->def, f, &next, why, sizeof why)) {
        viewer_say(w, "%s particles: %s", more ? "more" : "fewer", why);
        return;
    }
    const int threads = w->threads;
    w->ladder.validated = false; /* for other particles */
    if (restart(w, &next, more ? "more particles" : "fewer particles"))
        viewer_say(w, "%u particles: spacing and h x %.3f, the scene starts again from t = 0 (%d thread%s kept)", w->sim->n,
            (double)f, threads <= 0 ? w->sim->threads : threads, w->sim->threads == 1 ? "" : "s");
}

void viewer_key_down(viewer *w, SDL_Keycode k, Uint16 mod)
{
    const bool shift = mod & KMOD_SHIFT;
    const float h = w->def.h;
    sph_orbit *o = &w->v.orbit;
    if (k >= SDLK_1 && k <= SDLK_9) {
        int ov = (int)(k - SDLK_1);
        if (ov < SPH_OV_COUNT) {
            w->v.overlays ^= 1u << ov;
            viewer_say(w, "overlay %s %s", sph_overlay_names[ov], (w->v.overlays >> ov) & 1 ? "on" : "off");
        }
        return;
    }
    if (k >= SDLK_F1 && k <= SDLK_F12) {
        viewer_toggle_pass(w, view_pass_of_number(w->sim, (int)(k - SDLK_F1) + 1));
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
            viewer_say(w, "parameter panel %s", w->params_open ? "open" : "hidden");
        } else {
            viewer_say(w, "no parameter panel (Dear ImGui could not start; see the terminal)");
        }
        break;
    case SDLK_w: viewer_save_scene(w, w->save_path); break;
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
    case SDLK_a: viewer_validate(w, shift ? "L2" : "L0"); break;
    case SDLK_RIGHTBRACKET:
    case SDLK_LEFTBRACKET: viewer_rescale(w, k == SDLK_RIGHTBRACKET); break;
    case SDLK_n:
        w->pass_cursor = view_pass_next(w->sim, w->pass_cursor, shift ? -1 : 1);
        if (w->pass_cursor >= 0)
            viewer_say(w, "pass %d %s chosen (d switches it)", view_pass_number(w->sim, w->pass_cursor),
                sph_passes[w->pass_cursor]->name);
        w->v.overlays |= SPH_OV_BIT(TIMINGS); /* the numbered list */
        break;
    case SDLK_d:
        if (w->pass_cursor < 0)
            viewer_say(w, "no pass chosen: n chooses one (shift+n backwards), then d switches it");
        else
            viewer_toggle_pass(w, w->pass_cursor);
        break;
    case SDLK_c: cycle_field(w, shift ? -1 : 1); break;
    case SDLK_z:
    case SDLK_x:
        if (w->sim->dim != 3) { /* a 2D scene has no slice: the keys moved a plane nothing draws */
            viewer_say(w, "a 2D scene has no slice: z and x move the 3D views' plane");
            break;
        }
        w->v.slice_z += k == SDLK_z ? -h : h;
        viewer_say(w, "slice z = %.4g m", w->v.slice_z);
        break;
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
        viewer_zoom_at(w, k == SDLK_MINUS || k == SDLK_KP_MINUS ? 1.0f / 1.25f : 1.25f, at);
        break;
    }
    case SDLK_p: viewer_screenshot(w, NULL); break;
    case SDLK_v: viewer_record_toggle(w); break;
    case SDLK_h: w->help = !w->help; break;
    default: break;
    }
}

/* Scripted keys: one character each ('.', ' ', digits, letters; '\n' is enter, '\t' tab). */
void viewer_key_char(viewer *w, char c)
{
    SDL_Keycode k = c == '\n'   ? SDLK_RETURN
                    : c == '\t' ? SDLK_TAB
                                : (SDL_Keycode)(unsigned char)(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    viewer_key_down(w, k, (c >= 'A' && c <= 'Z') ? KMOD_SHIFT : 0);
}
