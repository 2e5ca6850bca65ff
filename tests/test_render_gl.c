/* The GL backend drawn straight from its buffers: a renderer with an OpenGL
 * 4.3 EGL context, a GL simulation created sharing it (sph_sim_create_shared
 * with sph_renderer_context), its buffers handed to the renderer in the view
 * (sph_view.device = sph_gpu_fields). Frames without host overlays download nothing from the device,
 * frames with the default ones a small constant (no field),
 * and they look like the CPU backend's frames of the same scene. Needs EGL
 * (Mesa's llvmpipe), no GPU and no display. */
#define _GNU_SOURCE /* setenv, dl_iterate_phdr */
#include <criterion/criterion.h>
#include <dlfcn.h>
#include <math.h>
#include <link.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_fields.h"
#include "gpu.h"
#include "render.h"
#include "sph_walls.h"
#include "test_util.h"

#define W 240
#define H 180

/* jittered, moving, with walls: particles reorder every step; time steps
 * small enough that the two backends stay within rounding of each other */
static const char *scene_2d =
    "[scene]\nname=direct 2d\ndimension=2\neffects=gravity pressure viscosity walls\njitter=0.2\n"
    "[domain]\nmin=-0.3 -0.2\nmax=0.3 0.4\nwall_damping=0.3\n[physics]\nviscosity=0.005\n"
    "[kernels]\nh=0.04\n[time]\ndt=0.0002\ncfl=0\n"
    "[fluid a]\nmin=-0.3 -0.2\nmax=0.0 0.1\nspacing=0.02\nvelocity=0.5 0\n";

static const char *scene_3d =
    "[scene]\nname=direct 3d\ndimension=3\neffects=gravity pressure viscosity walls\njitter=0.2\n"
    "[domain]\nmin=-0.2 -0.2 -0.2\nmax=0.2 0.2 0.2\nwall_damping=0.3\n[physics]\nviscosity=0.005\n"
    "[kernels]\nh=0.05\n[time]\ndt=0.0002\ncfl=0\n"
    "[fluid a]\nmin=-0.2 -0.2 -0.2\nmax=0.0 0.0 0.0\nspacing=0.025\nvelocity=0 0 0.3\n";

/* a tank of wall particles (wall_model = particles): the near faces' walls
 * are cut away (sph_renderer_shows) by the direct program as by the host's */
static const char *scene_3d_walls =
    "[scene]\nname=direct 3d walls\ndimension=3\neffects=gravity pressure viscosity walls\n"
    "[domain]\nmin=0 0 0\nmax=0.3 0.25 0.2\nwall_model=particles\n[physics]\nviscosity=0.005\n"
    "[kernels]\nh=0.05\n[time]\ndt=0.0002\ncfl=0\n"
    "[fluid a]\nmin=0 0 0\nmax=0.15 0.15 0.2\nspacing=0.025\n";

/* a 2D tank of wall particles: the walls' colours dimmed on both paths */
static const char *scene_2d_walls =
    "[scene]\nname=direct 2d walls\ndimension=2\neffects=gravity pressure viscosity walls\n"
    "[domain]\nmin=0 0\nmax=0.3 0.4\nwall_model=particles\n[physics]\nviscosity=0.005\n"
    "[kernels]\nh=0.04\n[time]\ndt=0.0002\ncfl=0\n"
    "[fluid a]\nmin=0 0\nmax=0.15 0.2\nspacing=0.02\n";

typedef struct pair {
    sph_renderer *r_gl, *r_cpu;
    sph_sim *gl, *cpu;
} pair;

/* Mesa unloads its driver when the last EGL display goes; what the driver
 * keeps until exit is then reported by LeakSanitizer from an "unknown
 * module" that no suppression can name. Pinning the loaded driver modules
 * keeps their names, so tests/lsan.supp's Mesa lines apply. */
static int pin_module(struct dl_phdr_info *info, size_t size, void *data)
{
    (void)size, (void)data;
    if (info->dlpi_name && (strstr(info->dlpi_name, "/dri/") || strstr(info->dlpi_name, "gallium")))
        dlopen(info->dlpi_name, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
    return 0;
}

/* The GL simulation in the first renderer's context; the CPU one drawn by a
 * second renderer, through the host as always. */
static pair make_pair(const char *ini)
{
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
    sph_gpu_register();
    char dev[512];
    if (!sph_gpu_probe(dev, sizeof dev)) cr_skip_test("no OpenGL 4.3 here: %s", dev);
    pair p;
    char err[512];
    p.r_gl = sph_renderer_create_gl43(SPH_GL_EGL, W, H, err, sizeof err);
    cr_assert_not_null(p.r_gl, "no 4.3 renderer: %s", err);
    dl_iterate_phdr(pin_module, NULL);
    sph_scene_def def = test_scene(ini);
    def.backend = SPH_BACKEND_GL;
    sph_error e;
    sph_error_code c = sph_sim_create_shared(&def, 1, sph_renderer_context(p.r_gl), &p.gl, &e);
    cr_assert_eq(c, SPH_ERR_OK, "%s", e.msg);
    cr_assert_not_null(sph_gpu_fields(p.gl));
    cr_assert(sph_gpu_fields(p.gl)->ctx == (const void *)sph_renderer_context(p.r_gl), "runs in the renderer's context");
    p.r_cpu = sph_renderer_create(SPH_GL_EGL, W, H, err, sizeof err);
    cr_assert_not_null(p.r_cpu, "%s", err);
    def.backend = SPH_BACKEND_CPU;
    cr_assert_eq(sph_sim_create(&def, 1, &p.cpu, &e), SPH_ERR_OK, "%s", e.msg);
    return p;
}

static void free_pair(pair *p)
{
    sph_sim_destroy(p->cpu);
    sph_renderer_destroy(p->r_cpu);
    sph_sim_destroy(p->gl); /* before its context */
    sph_renderer_destroy(p->r_gl);
}

/* Draws v with the simulation's device buffers handed over, as the commands do. */
static void frame(sph_renderer *r, const sph_sim *sim, const sph_view *v, uint8_t *rgb)
{
    char err[512];
    sph_view with = *v;
    with.device = sph_gpu_fields(sim);
    cr_assert(sph_render(r, sim, &with, err, sizeof err), "%s", err);
    sph_renderer_read_rgb(r, rgb);
}

/* Channel values more than 8 apart, and pixels that are not the background
 * or the domain's (so a frame with no particle cannot pass). */
static size_t differing(const uint8_t *a, const uint8_t *b)
{
    size_t k = 0;
    for (size_t i = 0; i < (size_t)W * H * 3; i++) k += abs((int)a[i] - (int)b[i]) > 8;
    return k;
}

static size_t particle_pixels(const uint8_t *a)
{
    size_t k = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        const uint8_t *p = a + 3 * i;
        bool bg = (p[0] == 30 && p[1] == 32 && p[2] == 38) || (p[0] == 42 && p[1] == 45 && p[2] == 54);
        k += !bg;
    }
    return k;
}

static void check_scene(const char *ini, sph_color_field f, unsigned overlays)
{
    pair p = make_pair(ini);
    sph_view v = sph_view_default(p.gl);
    v.field = f;
    v.overlays = overlays;
    uint8_t *a = malloc(W * H * 3), *b = malloc(W * H * 3);
    cr_assert(a && b);
    /* the first step reads the energy reference (sph_sim_stats) once */
    sph_sim_step(p.gl);
    sph_sim_step(p.cpu);
    for (int k = 0; k < 4; k++) {
        uint64_t before = sph_gpu_downloaded_bytes(p.gl);
        for (int s = 0; s < 3; s++) {
            sph_sim_step(p.gl);
            sph_sim_step(p.cpu);
        }
        frame(p.r_gl, p.gl, &v, a);
        cr_expect(sph_renderer_drew_direct(p.r_gl), "frame %d was copied through the host", k);
        cr_expect_eq(sph_gpu_downloaded_bytes(p.gl) - before, 0, "frame %d: %llu bytes downloaded", k,
                     (unsigned long long)(sph_gpu_downloaded_bytes(p.gl) - before));
        frame(p.r_cpu, p.cpu, &v, b);
        cr_expect(!sph_renderer_drew_direct(p.r_cpu));
        size_t drawn = particle_pixels(b);
        cr_expect_gt(drawn, (size_t)W * H / 50, "frame %d: only %zu particle pixels", k, drawn);
        size_t off = differing(a, b);
        cr_expect_leq(off, (size_t)W * H * 3 / 200, "frame %d: %zu channel values differ from the CPU's", k, off);
    }
    free(a);
    free(b);
    free_pair(&p);
}

Test(render_gl, direct_2d_density_downloads_nothing_and_matches_the_cpu)
{
    check_scene(scene_2d, SPH_COLOR_DENSITY, 0);
}

Test(render_gl, direct_2d_speed_downloads_nothing_and_matches_the_cpu)
{
    check_scene(scene_2d, SPH_COLOR_SPEED, 0);
}

Test(render_gl, direct_3d_pressure_acc_downloads_nothing_and_matches_the_cpu)
{
    check_scene(scene_3d, SPH_COLOR_ACC_P, SPH_OV_BIT(GRID));
}

Test(render_gl, direct_3d_wall_particles_cut_away_as_on_the_cpu)
{
    check_scene(scene_3d_walls, SPH_COLOR_DENSITY, 0);
}

Test(render_gl, direct_2d_wall_particles_dimmed_as_on_the_cpu)
{
    check_scene(scene_2d_walls, SPH_COLOR_DENSITY, 0);
}

/* The direct program dims the wall particles itself, from the backend's
 * FIXED buffer: at rest, speed over [0, 1] m/s colours every particle
 * viridis(0); the fluid's disc centres are that colour, the walls' that
 * colour 55 % of the way to mid grey (128), as the host path draws them
 * (test_render.c: render/wall_particles_are_dimmed_towards_grey). */
Test(render_gl, direct_wall_particles_are_dimmed_towards_grey)
{
    pair p = make_pair(scene_2d_walls);
    sph_view v = sph_view_default(p.gl);
    v.overlays = 0;
    v.field = SPH_COLOR_SPEED;
    v.fixed_range = true;
    v.range[0] = 0;
    v.range[1] = 1;
    uint8_t *a = malloc((size_t)W * H * 3);
    cr_assert_not_null(a);
    frame(p.r_gl, p.gl, &v, a);
    cr_expect(sph_renderer_drew_direct(p.r_gl));
    const uint32_t c0 = sph_colormap_viridis(0.0f);
    int want[2][3], walls = 0, fluid = 0, bad = 0;
    for (int k = 0; k < 3; k++) {
        float c = (float)((c0 >> (8 * k)) & 255);
        want[0][k] = (int)c;
        want[1][k] = (int)lroundf(c + 0.55f * (128.0f - c));
    }
    /* nothing stepped: the host's positions are the device's, in the same order */
    for (uint32_t i = 0; i < p.gl->n; i++) {
        float x[3] = {p.gl->P.pos[0][i], p.gl->P.pos[1][i], 0}, px[2];
        cr_assert(sph_camera_project(sph_renderer_camera(p.r_gl), x, px, NULL));
        const int wall = sph_is_wall(&p.gl->P, i);
        cr_assert(px[0] >= 0 && px[0] < W && px[1] >= 0 && px[1] < H);
        const uint8_t *got = a + 3 * ((size_t)px[1] * W + (size_t)px[0]);
        bool ok = true;
        for (int k = 0; k < 3; k++) ok &= abs((int)got[k] - want[wall][k]) <= 1;
        if (!ok && !bad++)
            cr_log_error("%s particle %u: colour %d %d %d, want %d %d %d", wall ? "wall" : "fluid", i, got[0], got[1],
                         got[2], want[wall][0], want[wall][1], want[wall][2]);
        wall ? walls++ : fluid++;
    }
    cr_expect_gt(walls, 50);
    cr_expect_gt(fluid, 50);
    cr_expect_eq(bad, 0, "%d of %u particles not in their colour (walls dimmed)", bad, p.gl->n);
    free(a);
    free_pair(&p);
}

/* The legend's numbers cost the range's 8 bytes; the HUD syncs what it
 * shows; a colour the device does not hold (keys) goes through the host. */
Test(render_gl, overlays_read_back_only_what_they_show)
{
    pair p = make_pair(scene_2d);
    sph_view v = sph_view_default(p.gl);
    v.overlays = SPH_OV_BIT(LEGEND);
    uint8_t *a = malloc(W * H * 3);
    cr_assert_not_null(a);
    sph_sim_step(p.gl);
    sph_sim_step(p.gl);
    uint64_t before = sph_gpu_downloaded_bytes(p.gl);
    frame(p.r_gl, p.gl, &v, a);
    cr_expect_eq(sph_gpu_downloaded_bytes(p.gl) - before, 8);
    cr_expect(sph_renderer_drew_direct(p.r_gl));
    sph_sim_step(p.gl);
    v.overlays = SPH_OV_BIT(HUD);
    before = sph_gpu_downloaded_bytes(p.gl);
    frame(p.r_gl, p.gl, &v, a);
    /* the density error and energies reduced on the device (48 bytes, once
     * while nothing ran), the hash health too (20 bytes): no field */
    const uint64_t hud = sph_gpu_downloaded_bytes(p.gl) - before;
    cr_expect_eq(hud, 48 + 20, "the HUD's frame downloaded %llu bytes", (unsigned long long)hud);
    v.overlays = 0;
    v.field = SPH_COLOR_KEY;
    sph_sim_step(p.gl);
    frame(p.r_gl, p.gl, &v, a);
    cr_expect(!sph_renderer_drew_direct(p.r_gl), "keys are not on the device: the host copy draws them");
    free(a);
    free_pair(&p);
}

/* The default overlays (the HUD and the legend) read back a few numbers a
 * frame, whatever the particle count: the statistics, the hash health and
 * the colour scale's range, reduced on the device. */
Test(render_gl, default_overlays_read_back_a_small_constant)
{
    const char *scenes[] = {scene_2d, scene_3d};
    for (int k = 0; k < 2; k++) {
        pair p = make_pair(scenes[k]);
        sph_view v = sph_view_default(p.gl);
        cr_assert(v.overlays & SPH_OV_BIT(HUD), "the HUD is a default overlay");
        uint8_t *a = malloc(W * H * 3);
        cr_assert_not_null(a);
        sph_sim_step(p.gl); /* the energy reference, read once */
        for (int f = 0; f < 3; f++) {
            for (int s = 0; s < 3; s++) sph_sim_step(p.gl);
            uint64_t before = sph_gpu_downloaded_bytes(p.gl);
            frame(p.r_gl, p.gl, &v, a);
            uint64_t bytes = sph_gpu_downloaded_bytes(p.gl) - before;
            cr_expect_leq(bytes, 128, "%dD frame %d read back %llu bytes (a particle's position is %zu)", p.gl->dim,
                          f, (unsigned long long)bytes, p.gl->dim * sizeof(float));
            cr_expect(sph_renderer_drew_direct(p.r_gl));
        }
        free(a);
        free_pair(&p);
    }
}

/* The reorder pass swaps buffers: the names change from step to step. */
Test(render_gl, field_buffers_are_swapped_by_the_reorder_pass)
{
    pair p = make_pair(scene_2d);
    unsigned a = 0, b = 0;
    cr_assert(sph_gpu_field_buffer(p.gl, SPH_FIELD_POS, &a));
    sph_sim_step(p.gl);
    cr_assert(sph_gpu_field_buffer(p.gl, SPH_FIELD_POS, &b));
    cr_expect_neq(a, b, "the reorder pass gathers into the spare buffer and swaps");
    cr_expect(!sph_gpu_field_buffer(p.cpu, SPH_FIELD_POS, &a), "a CPU simulation has no buffer");
    cr_expect_eq(sph_gpu_downloaded_bytes(p.cpu), 0);
    free_pair(&p);
}

/* The direct path needs both halves of the handle: the buffers handed over
 * in the view, and the simulation running in the renderer's very context. */
Test(render_gl, direct_drawing_needs_the_buffers_and_the_same_context)
{
    pair p = make_pair(scene_2d);
    sph_sim_step(p.gl);
    uint8_t *a = malloc((size_t)W * H * 3);
    cr_assert_not_null(a);
    sph_view v = sph_view_default(p.gl);
    v.overlays = 0;
    char err[512];
    cr_assert(sph_render(p.r_gl, p.gl, &v, err, sizeof err), "%s", err);
    cr_expect(!sph_renderer_drew_direct(p.r_gl), "no buffers handed over: the host copy is drawn");
    frame(p.r_gl, p.gl, &v, a);
    cr_expect(sph_renderer_drew_direct(p.r_gl), "buffers in the renderer's context: drawn from them");
    /* a GL simulation with a context of its own is drawn through the host */
    sph_scene_def def = test_scene(scene_2d);
    def.backend = SPH_BACKEND_GL;
    sph_error e;
    sph_sim *own;
    cr_assert_eq(sph_sim_create(&def, 1, &own, &e), SPH_ERR_OK, "%s", e.msg);
    cr_assert_not_null(sph_gpu_fields(own));
    cr_expect(sph_gpu_fields(own)->ctx != (const void *)sph_renderer_context(p.r_gl));
    frame(p.r_gl, own, &v, a);
    cr_expect(!sph_renderer_drew_direct(p.r_gl), "buffers of another context: the host copy is drawn");
    sph_sim_destroy(own);
    free(a);
    free_pair(&p);
}

/* Storage buffer bindings belong to the context: a second simulation made in
 * the same shared context (the window's reset or variant switch) rebinds
 * them, and deleting its buffers unbinds them. The first must still compute
 * on its own buffers afterwards: it matches the CPU as if nothing happened. */
Test(render_gl, a_second_simulation_in_the_context_leaves_the_first_intact)
{
    pair p = make_pair(scene_2d);
    for (int s = 0; s < 5; s++) {
        sph_sim_step(p.gl);
        sph_sim_step(p.cpu);
    }
    sph_scene_def def = test_scene(scene_3d);
    def.backend = SPH_BACKEND_GL;
    sph_error e;
    sph_sim *other;
    sph_error_code c = sph_sim_create_shared(&def, 1, sph_renderer_context(p.r_gl), &other, &e);
    cr_assert_eq(c, SPH_ERR_OK, "%s", e.msg);
    sph_sim_step(other);
    sph_sim_destroy(other);
    for (int s = 0; s < 20; s++) {
        sph_sim_step(p.gl);
        sph_sim_step(p.cpu);
    }
    cr_assert(!p.gl->alarm.raised && !p.cpu->alarm.raised);
    sph_sim_sync(p.gl, SPH_SYNC_ALL);
    uint32_t *at = malloc(p.cpu->n * sizeof *at); /* CPU index of each id */
    cr_assert_not_null(at);
    for (uint32_t i = 0; i < p.cpu->n; i++) at[p.cpu->P.id[i]] = i;
    double worst = 0;
    for (uint32_t i = 0; i < p.gl->n; i++) {
        cr_assert_lt(p.gl->P.id[i], p.cpu->n, "id %u out of range: the buffers were mixed up", p.gl->P.id[i]);
        uint32_t j = at[p.gl->P.id[i]];
        for (int d = 0; d < 2; d++) {
            double dx = (double)p.gl->P.pos[d][i] - p.cpu->P.pos[d][j];
            worst = dx > worst ? dx : -dx > worst ? -dx : worst;
        }
    }
    cr_expect(worst <= 1e-4, "positions differ from the CPU's by %g m after the other simulation", worst);
    free(at);
    free_pair(&p);
}

/* A click names the particle under the cursor by id, also after steps that
 * reordered the particles on the device: the pick brings back positions
 * and ids together. Each target's screen position comes from the CPU twin
 * (the same run within rounding), and the GL simulation's pick must name
 * the same id. */
Test(render_gl, picking_names_the_particle_under_the_cursor)
{
    pair p = make_pair(scene_2d);
    for (int s = 0; s < 5; s++) {
        sph_sim_step(p.gl);
        sph_sim_step(p.cpu);
    }
    sph_view v = sph_view_default(p.gl);
    v.device = sph_gpu_fields(p.gl);
    char err[256];
    cr_assert(sph_render(p.r_gl, p.gl, &v, err, sizeof err), "%s", err); /* sets the camera */
    cr_assert(sph_renderer_drew_direct(p.r_gl), "drawn from the buffers: the host copy is stale before the pick");
    const sph_camera *cam = sph_renderer_camera(p.r_gl);
    int hits = 0;
    for (uint32_t target = 10; target < p.cpu->n; target += 37) {
        uint32_t j = 0;
        while (p.cpu->P.id[j] != target) j++;
        float x[3] = {p.cpu->P.pos[0][j], p.cpu->P.pos[1][j], 0}, px[2], depth;
        cr_assert(sph_camera_project(cam, x, px, &depth));
        int32_t i = sph_renderer_pick(p.r_gl, p.gl, px, 12.0f);
        cr_assert(i >= 0, "nothing picked at particle %u", target);
        cr_expect_eq(p.gl->P.id[i], target, "the click on particle %u named particle %u", target, p.gl->P.id[i]);
        hits++;
    }
    cr_assert_gt(hits, 3);
    free_pair(&p);
}

/* The window's reset (r) replaces the GL simulation by a new one in the same
 * context, with new buffers (here of another scene: other N and dimension),
 * and destroys the old one: the very next frame draws the new buffers (the
 * direct draw's vertex array is pointed at them every frame), as the CPU
 * twin of the new scene is drawn. */
Test(render_gl, a_reset_draws_the_new_buffers_at_once)
{
    pair p = make_pair(scene_2d);
    sph_view v = sph_view_default(p.gl);
    v.field = SPH_COLOR_SPEED;
    v.overlays = 0;
    uint8_t *a = malloc(W * H * 3), *b = malloc(W * H * 3);
    cr_assert(a && b);
    for (int s = 0; s < 3; s++) sph_sim_step(p.gl);
    frame(p.r_gl, p.gl, &v, a);
    cr_expect(sph_renderer_drew_direct(p.r_gl));
    /* the reset: the new simulation first, in the same context, then the old one goes */
    sph_scene_def def = test_scene(scene_3d);
    def.backend = SPH_BACKEND_GL;
    sph_error e;
    sph_sim *fresh;
    cr_assert_eq(sph_sim_create_shared(&def, 1, sph_renderer_context(p.r_gl), &fresh, &e), SPH_ERR_OK, "%s", e.msg);
    sph_sim_destroy(p.gl);
    p.gl = fresh;
    def.backend = SPH_BACKEND_CPU;
    sph_sim_destroy(p.cpu);
    cr_assert_eq(sph_sim_create(&def, 1, &p.cpu, &e), SPH_ERR_OK, "%s", e.msg);
    for (int s = 0; s < 2; s++) {
        sph_sim_step(p.gl);
        sph_sim_step(p.cpu);
    }
    v = sph_view_default(p.gl);
    v.field = SPH_COLOR_SPEED;
    v.overlays = 0;
    frame(p.r_gl, p.gl, &v, a);
    cr_expect(sph_renderer_drew_direct(p.r_gl), "the new simulation is drawn from its buffers");
    frame(p.r_cpu, p.cpu, &v, b);
    size_t drawn = particle_pixels(b), off = differing(a, b);
    cr_expect_gt(drawn, (size_t)W * H / 50, "only %zu particle pixels", drawn);
    cr_expect_leq(off, (size_t)W * H * 3 / 200, "the frame after the reset: %zu channel values differ from the CPU's",
                  off);
    free(a);
    free(b);
    free_pair(&p);
}
