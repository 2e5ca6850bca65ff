/* Headless rendering, checked by its pixels: particles are drawn where they
 * are, wall particles dimmed, grid lines lie on cell borders, an overlay
 * switched off leaves no pixel, renders are reproducible to the byte, the two
 * GL backends agree, 3D wall particles leave the water in sight, and with no
 * usable GL the tool says so. Needs no GPU and no display. */
#define _GNU_SOURCE /* setenv, mkdtemp */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <stb_image.h>

#include "layout.h"
#include "render.h"
#include "sph_walls.h"
#include "test_util.h"

#define W 320
#define H 240

/* 100 particles in the lower-left corner of a 0.4 x 0.3 m box; the upper
 * right is empty, which is where background and grid lines are checked. */
static const char *scene_2d = "[scene]\nname=render test\neffects=gravity pressure viscosity walls\nsteps=4\n"
                              "[domain]\nmin=0 0\nmax=0.4 0.3\n[fluid a]\nmin=0 0\nmax=0.2 0.2\nspacing=0.02\n"
                              "[kernels]\nh=0.04\n[time]\ndt=0.0002\ncfl=0\n[search]\ntable_size=37\n";

static const uint32_t DOMAIN_BG = SPH_RGBA(42, 45, 54, 255);

static sph_renderer *renderer(sph_gl_backend b)
{
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
    char err[512];
    sph_renderer *r = sph_renderer_create(b, W, H, err, sizeof err);
    cr_assert_not_null(r, "no renderer: %s", err);
    return r;
}

static uint8_t *draw(sph_renderer *r, const sph_sim *sim, const sph_view *v)
{
    char err[512];
    cr_assert(sph_render(r, sim, v, err, sizeof err), "render failed: %s", err);
    uint8_t *rgb = malloc(W * H * 3);
    cr_assert_not_null(rgb);
    sph_renderer_read_rgb(r, rgb);
    return rgb;
}

static uint32_t pixel(const uint8_t *rgb, int x, int y)
{
    cr_assert(x >= 0 && x < W && y >= 0 && y < H, "pixel (%d, %d) outside", x, y);
    const uint8_t *p = rgb + 3 * ((size_t)y * W + x);
    return SPH_RGBA(p[0], p[1], p[2], 255);
}

static void world_px(sph_renderer *r, float x, float y, float px[2])
{
    float w[3] = {x, y, 0};
    cr_assert(sph_camera_project(sph_renderer_camera(r), w, px, NULL));
}

Test(render, particles_appear_where_they_are)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    for (int k = 0; k < 3; k++) sph_sim_step(sim);
    sph_renderer *r = renderer(SPH_GL_EGL);
    sph_view v = sph_view_default(sim);
    v.overlays = 0;
    uint8_t *img = draw(r, sim, &v);
    /* each particle's centre pixel has its own colour from the colour map */
    float *val = malloc(sim->n * sizeof *val), lo, hi;
    cr_assert(sph_color_field_values(sim, v.field, val, &lo, &hi));
    int checked = 0;
    for (uint32_t i = 0; i < sim->n; i += 7) {
        float px[2];
        world_px(r, sim->P.pos[0][i], sim->P.pos[1][i], px);
        uint32_t got = pixel(img, (int)px[0], (int)px[1]), want = sph_color_of(v.field, val[i], lo, hi);
        for (int c = 0; c < 3; c++)
            cr_expect_leq(abs((int)((got >> (8 * c)) & 255) - (int)((want >> (8 * c)) & 255)), 1,
                          "particle %u at (%g, %g) px: colour %06x, want %06x", i, px[0], px[1], got & 0xFFFFFF,
                          want & 0xFFFFFF);
        checked++;
    }
    cr_expect_gt(checked, 10);
    /* the empty part of the domain is background */
    float px[2];
    world_px(r, 0.33f, 0.25f, px);
    cr_expect_eq(pixel(img, (int)px[0], (int)px[1]), DOMAIN_BG);
    free(val);
    free(img);
    sph_renderer_destroy(r);
    sph_sim_destroy(sim);
}

/* With wall_model = particles the walls are layers of particles outside the
 * domain box; a tall tank fills the image's height, and its floor (where the
 * hydrostatic pressure is read) must be in the picture, not cut off below. */
Test(render, wall_particles_are_in_the_picture)
{
    sph_sim *sim = test_sim("[scene]\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.3 0.6\n"
                            "wall_model=particles\n[fluid a]\nmin=0 0\nmax=0.3 0.3\nspacing=0.02\n[kernels]\nh=0.04\n",
                            1);
    sph_renderer *r = renderer(SPH_GL_EGL);
    sph_view v = sph_view_default(sim);
    uint8_t *img = draw(r, sim, &v);
    int outside = 0, walls = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        if (!sph_is_wall(&sim->P, i)) continue;
        float px[2];
        world_px(r, sim->P.pos[0][i], sim->P.pos[1][i], px);
        walls++;
        if (!(px[0] >= 0 && px[0] < W && px[1] >= 0 && px[1] < H)) {
            if (!outside)
                cr_log_error("wall particle %u at (%g, %g) m is drawn at (%g, %g) px, outside %dx%d", i,
                             sim->P.pos[0][i], sim->P.pos[1][i], px[0], px[1], W, H);
            outside++;
        }
    }
    /* counts of particles and of pixels they land on (not timings): the tank has its wall layers, and
     * every one of them is inside the image */
    cr_expect_gt(walls, 100);
    cr_expect_eq(outside, 0, "%d of %d wall particles outside the picture", outside, walls);
    free(img);
    sph_renderer_destroy(r);
    sph_sim_destroy(sim);
}

/* The colour a wall particle is drawn in: its field colour 55 % of the way
 * to mid grey (128), channel by channel (written out here, not taken from
 * the renderer, so that the test says what the picture must show). */
static uint32_t wall_dimmed(uint32_t c)
{
    uint32_t out = SPH_RGBA(0, 0, 0, 255);
    for (int k = 0; k < 3; k++) {
        float v = (float)((c >> (8 * k)) & 255);
        out |= (uint32_t)lroundf(v + 0.55f * (128.0f - v)) << (8 * k);
    }
    return out;
}

static bool near_colour(uint32_t a, uint32_t b, int tol)
{
    for (int c = 0; c < 3; c++)
        if (abs((int)((a >> (8 * c)) & 255) - (int)((b >> (8 * c)) & 255)) > tol) return false;
    return true;
}

/* Wall particles take their field's colour dimmed towards grey, so that the
 * water stands out of the walls while the walls' values stay readable: every
 * particle given the same speed, the fluid's discs are the colour map's
 * colour and the walls' the dimmed one. */
Test(render, wall_particles_are_dimmed_towards_grey)
{
    sph_sim *sim = test_sim("[scene]\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.3 0.6\n"
                            "wall_model=particles\n[fluid a]\nmin=0 0\nmax=0.3 0.3\nspacing=0.02\n[kernels]\nh=0.04\n",
                            1);
    for (uint32_t i = 0; i < sim->n; i++) sim->P.vel[0][i] = 0.5f; /* nothing steps: the render only reads it */
    sph_renderer *r = renderer(SPH_GL_EGL);
    sph_view v = sph_view_default(sim);
    v.overlays = 0;
    v.field = SPH_COLOR_SPEED;
    v.fixed_range = true;
    v.range[0] = 0;
    v.range[1] = 1;
    uint8_t *img = draw(r, sim, &v);
    const uint32_t fluid_c = sph_colormap_viridis(0.5f), wall_c = wall_dimmed(fluid_c);
    cr_expect(!near_colour(fluid_c, wall_c, 8), "the dimmed colour %06x is the fluid's %06x", wall_c & 0xFFFFFF,
              fluid_c & 0xFFFFFF);
    int walls = 0, fluid = 0, bad_walls = 0, bad_fluid = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        float px[2];
        world_px(r, sim->P.pos[0][i], sim->P.pos[1][i], px);
        const bool wall = sph_is_wall(&sim->P, i);
        uint32_t got = pixel(img, (int)px[0], (int)px[1]), want = wall ? wall_c : fluid_c;
        if (!near_colour(got, want, 1)) {
            if (!(bad_walls + bad_fluid))
                cr_log_error("%s particle %u at (%g, %g) px: colour %06x, want %06x", wall ? "wall" : "fluid", i,
                             px[0], px[1], got & 0xFFFFFF, want & 0xFFFFFF);
            wall ? bad_walls++ : bad_fluid++;
        }
        wall ? walls++ : fluid++;
    }
    cr_expect_gt(walls, 100);
    cr_expect_gt(fluid, 100);
    cr_expect_eq(bad_walls, 0, "%d of %d wall particles not dimmed", bad_walls, walls);
    cr_expect_eq(bad_fluid, 0, "%d of %d fluid particles not the colour map's", bad_fluid, fluid);
    free(img);
    sph_renderer_destroy(r);
    sph_sim_destroy(sim);
}

/* The column a 1-pixel line at x_px covers: [x - 0.5, x + 0.5) holds the
 * centre p + 0.5 of pixel p = ceil(x) - 1. */
static int line_column(float x)
{
    return (int)ceilf(x) - 1;
}

Test(render, grid_lines_lie_on_cell_borders)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_renderer *r = renderer(SPH_GL_EGL);
    sph_view v = sph_view_default(sim);
    v.overlays = SPH_OV_BIT(GRID);
    uint8_t *img = draw(r, sim, &v);
    const float h = sim->S.cells.size[0]; /* a hair above sim->def.h */
    float py[2];
    world_px(r, 0.3f, 6.5f * h, py); /* a row in the empty upper part, between horizontal lines */
    int y = (int)py[1];
    for (int k = 6; k <= 9; k++) {
        float on[2], mid[2];
        world_px(r, (float)k * h, 0.27f, on);
        world_px(r, ((float)k + 0.5f) * h, 0.27f, mid);
        cr_expect_neq(pixel(img, line_column(on[0]), y), DOMAIN_BG, "no line at x = %d h (column %d)", k,
                      line_column(on[0]));
        cr_expect_eq(pixel(img, (int)mid[0], y), DOMAIN_BG, "a mark between lines at x = %g h", k + 0.5);
    }
    free(img);
    sph_renderer_destroy(r);
    sph_sim_destroy(sim);
}

Test(render, an_overlay_switched_off_leaves_no_pixel)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_sim_step(sim);
    sph_renderer *r = renderer(SPH_GL_EGL);
    sph_view v = sph_view_default(sim);
    v.overlays = 0;
    uint8_t *plain = draw(r, sim, &v);
    const unsigned each[] = {SPH_OV_BIT(GRID), SPH_OV_BIT(KEYS), SPH_OV_BIT(COLLISIONS), SPH_OV_BIT(FORCES),
                             SPH_OV_BIT(HUD), SPH_OV_BIT(LEGEND)};
    for (size_t k = 0; k < sizeof each / sizeof *each; k++) {
        v.overlays = each[k];
        uint8_t *on = draw(r, sim, &v);
        size_t differ = 0;
        for (size_t i = 0; i < W * H * 3; i++) differ += on[i] != plain[i];
        cr_expect_gt(differ, 20u, "overlay %#x draws nothing", each[k]);
        free(on);
        v.overlays = 0;
        uint8_t *off = draw(r, sim, &v);
        cr_expect_eq(memcmp(off, plain, W * H * 3), 0, "overlay %#x left pixels after it was switched off", each[k]);
        free(off);
    }
    free(plain);
    sph_renderer_destroy(r);
    sph_sim_destroy(sim);
}

Test(render, the_same_state_renders_to_the_same_bytes)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_sim_step(sim);
    sph_renderer *r = renderer(SPH_GL_EGL);
    sph_view v = sph_view_default(sim);
    v.overlays = SPH_OV_BIT(GRID) | SPH_OV_BIT(KEYS) | SPH_OV_BIT(HUD) | SPH_OV_BIT(LEGEND) | SPH_OV_BIT(NEIGHBOURS);
    v.selected = 40;
    uint8_t *a = draw(r, sim, &v), *b = draw(r, sim, &v);
    cr_expect_eq(memcmp(a, b, W * H * 3), 0);
    free(a);
    free(b);
    sph_renderer_destroy(r);
    sph_sim_destroy(sim);
}

Test(render, a_3d_scene_draws_spheres_inside_the_view)
{
    sph_sim *sim = test_sim("[scene]\ndimension=3\neffects=gravity walls\n[domain]\nmax=0.4 0.3 0.2\n"
                            "[fluid a]\nmax=0.1 0.1 0.1\nspacing=0.02\n[physics]\ngravity=0 -9.81 0\n",
                            1);
    sph_renderer *r = renderer(SPH_GL_EGL);
    sph_view v = sph_view_default(sim);
    v.overlays = 0;
    uint8_t *img = draw(r, sim, &v);
    /* the default orbit shows the whole domain: every particle projects inside the view */
    const sph_camera *cam = sph_renderer_camera(r);
    int lit = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        float x[3] = {sim->P.pos[0][i], sim->P.pos[1][i], sim->P.pos[2][i]}, px[2];
        cr_assert(sph_camera_project(cam, x, px, NULL));
        cr_assert(px[0] >= cam->rect[0] && px[0] < cam->rect[0] + cam->rect[2] && px[1] >= cam->rect[1] &&
                  px[1] < cam->rect[1] + cam->rect[3]);
        uint32_t c = pixel(img, (int)px[0], (int)px[1]);
        lit += c != SPH_RGBA(30, 32, 38, 255);
    }
    cr_expect_eq(lit, (int)sim->n, "a particle's pixel is background");
    free(img);
    sph_renderer_destroy(r);
    sph_sim_destroy(sim);
}

/* A 3D tank of wall particles (wall_model = particles) holding a block of
 * water and a box obstacle: the walls' layers cover all six faces, so drawn
 * whole they hide the water from every side. */
static const char *scene_3d_walls =
    "[scene]\ndimension=3\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0 0\nmax=0.4 0.3 0.2\n"
    "wall_model=particles\n[fluid a]\nmin=0 0 0\nmax=0.16 0.16 0.2\nspacing=0.02\n"
    "[obstacle b]\nshape=box\nmin=0.26 0 0.06\nmax=0.32 0.08 0.14\n[kernels]\nh=0.04\n"
    "[physics]\ngravity=0 -9.81 0\n";

/* Colours the fluid yellow and every wall particle a dimmed purple: speed over a fixed
 * range [0, 1] m/s, the fluid given 1 m/s (nothing steps, the render only
 * reads it), the walls at rest. Counts the pixels of each colour. */
static void count_fluid_and_wall_pixels(const sph_sim *sim, sph_renderer *r, const sph_orbit *o, int *fluid,
                                        int *wall)
{
    sph_view v = sph_view_default(sim);
    v.overlays = 0; /* no legend: its bar has both colours */
    v.field = SPH_COLOR_SPEED;
    v.fixed_range = true;
    v.range[0] = 0;
    v.range[1] = 1;
    if (o) v.orbit = *o;
    uint8_t *img = draw(r, sim, &v);
    *fluid = *wall = 0;
    for (size_t k = 0; k < (size_t)W * H; k++) {
        int R = img[3 * k], G = img[3 * k + 1], B = img[3 * k + 2];
        *fluid += G > B + 60 && R > B + 60;   /* viridis(1), shaded: yellow */
        *wall += B > G + 15 && R > G + 10;    /* viridis(0) dimmed (wall_dimmed), shaded: greyish purple */
    }
    free(img);
}

/* The box's wall particles on the faces turned towards the camera are not
 * drawn (a cut-away box), so the water is seen from any orbit; the far faces'
 * walls still are. 2D is not concerned. */
Test(render, water_is_seen_through_the_walls_in_3d)
{
    sph_sim *sim = test_sim(scene_3d_walls, 1);
    cr_assert_not_null(sim->P.fixed);
    int n_fluid = 0;
    for (uint32_t i = 0; i < sim->n; i++)
        if (!sph_is_wall(&sim->P, i)) {
            sim->P.vel[0][i] = 1.0f;
            n_fluid++;
        }
    cr_assert_gt(n_fluid, 100);
    sph_renderer *r = renderer(SPH_GL_EGL);
    const sph_orbit orbits[4] = {sph_orbit_default(),
                                 {.yaw = -140, .pitch = -30, .zoom = 1},
                                 {.yaw = 200, .pitch = 60, .zoom = 1},
                                 {.yaw = 0, .pitch = 0, .zoom = 1}};
    for (int k = 0; k < 4; k++) {
        int fluid, wall;
        count_fluid_and_wall_pixels(sim, r, &orbits[k], &fluid, &wall);
        cr_log_info("orbit yaw %g pitch %g: %d pixels of water, %d of walls", orbits[k].yaw, orbits[k].pitch, fluid,
                    wall);
        /* counts of pixels (not timings): the water covers a good part of the view (320 x 240 px), and walls
         * (the far faces) are still drawn */
        cr_expect_gt(fluid, 2000, "orbit yaw %g pitch %g: %d pixels of water, %d of walls", orbits[k].yaw,
                     orbits[k].pitch, fluid, wall);
        cr_expect_gt(wall, 2000, "orbit yaw %g pitch %g: %d pixels of walls", orbits[k].yaw, orbits[k].pitch, wall);
    }
    sph_renderer_destroy(r);
    sph_sim_destroy(sim);
}

/* The rule itself (sph_renderer_shows, which picking uses too): the default
 * orbit's eye is past the domain's x, y and z maxima, so the box's wall
 * particles beyond those faces are left out; the water, the obstacle and the
 * far walls are drawn; in 2D every particle is. */
Test(render, only_the_near_walls_are_left_out_in_3d)
{
    sph_sim *sim = test_sim(scene_3d_walls, 1);
    sph_renderer *r = renderer(SPH_GL_EGL);
    sph_view v = sph_view_default(sim);
    free(draw(r, sim, &v));
    const float hi[3] = {0.4f, 0.3f, 0.2f}; /* [m] the domain's maxima (scene_3d_walls) */
    int hidden_inner = 0, near = 0, near_shown = 0, far = 0, far_shown = 0, obstacle = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        float x[3] = {sim->P.pos[0][i], sim->P.pos[1][i], sim->P.pos[2][i]};
        bool shown = sph_renderer_shows(r, x), beyond = x[0] > hi[0] || x[1] > hi[1] || x[2] > hi[2];
        bool inside = x[0] > 0 && x[1] > 0 && x[2] > 0 && !beyond;
        if (sim->P.obstacle[i] != 0.0f) obstacle++;
        if (inside) hidden_inner += !shown; /* the water and the obstacle */
        else if (beyond) near++, near_shown += shown;
        else far++, far_shown += shown;
    }
    cr_expect_gt(obstacle, 10);
    cr_expect_eq(hidden_inner, 0, "%d particles inside the domain left out", hidden_inner);
    cr_expect_gt(near, 100);
    cr_expect_eq(near_shown, 0, "%d of %d wall particles past the near faces drawn", near_shown, near);
    cr_expect_gt(far, 100);
    cr_expect_eq(far_shown, far, "%d of %d wall particles of the far faces drawn", far_shown, far);
    /* the same scene in 2D: nothing is cut away */
    sph_sim *flat = test_sim("[scene]\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.3 0.6\n"
                             "wall_model=particles\n[fluid a]\nmin=0 0\nmax=0.3 0.3\nspacing=0.02\n[kernels]\nh=0.04\n",
                             1);
    sph_view vf = sph_view_default(flat);
    free(draw(r, flat, &vf));
    int flat_hidden = 0;
    for (uint32_t i = 0; i < flat->n; i++) {
        float x[3] = {flat->P.pos[0][i], flat->P.pos[1][i], 0};
        flat_hidden += !sph_renderer_shows(r, x);
    }
    cr_expect_eq(flat_hidden, 0, "2D: %d particles left out", flat_hidden);
    sph_sim_destroy(flat);
    sph_renderer_destroy(r);
    sph_sim_destroy(sim);
}

/* ---- through the command line -------------------------------------------- */

static unsigned char *read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *b = malloc((size_t)n + 1);
    *len = fread(b, 1, (size_t)n, f);
    fclose(f);
    return b;
}

Test(render, cli_frames_are_byte_identical_run_to_run)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d1 = test_temp_dir("render"), *d2 = test_temp_dir("render");
    char args[1024], out[4096];
    const char *opts = "--steps 4 --every 2 --size 200x150 --overlay grid,keys,index,forces --select 30 --quiet";
    snprintf(args, sizeof args, "render %s --out %s %s", scene, d1, opts);
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    snprintf(args, sizeof args, "render %s --out %s %s --threads 2", scene, d2, opts);
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    for (int f = 0; f < 3; f++) {
        char p1[128], p2[128];
        snprintf(p1, sizeof p1, "%s/frame_%05d.png", d1, f);
        snprintf(p2, sizeof p2, "%s/frame_%05d.png", d2, f);
        size_t n1 = 0, n2 = 0;
        unsigned char *a = read_all(p1, &n1), *b = read_all(p2, &n2);
        cr_assert(a && b, "frame %d missing", f);
        cr_expect(n1 == n2 && memcmp(a, b, n1) == 0, "frame %d differs between runs", f);
        free(a);
        free(b);
    }
    char p3[128];
    snprintf(p3, sizeof p3, "%s/frame_00003.png", d1);
    cr_expect(access(p3, F_OK) != 0, "4 steps every 2: frames 0, 1, 2 only");
    test_remove_dir(d1);
    test_remove_dir(d2);
    remove(scene);
}

Test(render, egl_and_osmesa_render_the_same_picture)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d[2] = {test_temp_dir("render"), test_temp_dir("render")};
    const char *gl[2] = {"egl", "osmesa"};
    unsigned char *img[2];
    int w = 0, h = 0;
    for (int k = 0; k < 2; k++) {
        char args[1024], out[4096];
        snprintf(args, sizeof args,
                 "render %s --out %s --gl %s --steps 2 --every 2 --size 240x180 --overlay grid,keys,collisions,hud,legend --quiet",
                 scene, d[k], gl[k]);
        cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s: %s", gl[k], out);
        char p[128];
        snprintf(p, sizeof p, "%s/frame_00001.png", d[k]);
        int n;
        img[k] = stbi_load(p, &w, &h, &n, 3);
        cr_assert_not_null(img[k], "%s: cannot read %s", gl[k], p);
        cr_assert(w == 240 && h == 180);
    }
    size_t off = 0;
    int worst = 0;
    for (size_t i = 0; i < (size_t)w * h * 3; i++) {
        int dd = abs((int)img[0][i] - (int)img[1][i]);
        if (dd > worst) worst = dd;
        off += dd > 8;
    }
    cr_expect_leq(off, (size_t)w * h * 3 / 200, "%zu of %d channel values differ by more than 8 (worst %d)", off,
                  w * h * 3, worst);
    stbi_image_free(img[0]);
    stbi_image_free(img[1]);
    test_remove_dir(d[0]);
    test_remove_dir(d[1]);
    remove(scene);
}

Test(render, without_usable_gl_it_says_so_and_exits_non_zero)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d = test_temp_dir("render");
    char args[1024], out[4096];
    /* an EGL with no vendor library: what a machine without Mesa's EGL looks like */
    snprintf(args, sizeof args, "render %s --out %s --steps 0 --quiet", scene, d);
    int rc = test_sphlab_env("__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json", args, out, sizeof out);
    cr_expect_eq(rc, 1, "exit %d: %s", rc, out);
    cr_expect(strstr(out, "no usable OpenGL") && strstr(out, "EGL"), "message: %s", out);
    test_remove_dir(d);
    remove(scene);
}

Test(render, an_unwritable_output_directory_is_a_clear_error)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    char args[1024], out[4096];
    snprintf(args, sizeof args, "render %s --out /proc/sphlab-no/frames --steps 0 --quiet", scene);
    int rc = test_sphlab(args, out, sizeof out);
    cr_expect_eq(rc, 1, "exit %d: %s", rc, out);
    cr_expect(strstr(out, "/proc/sphlab-no") && strstr(out, "cannot create"), "message: %s", out);
    remove(scene);
}

/* ---- the window, through SDL's offscreen video driver --------------------- */

static unsigned char *load_png(const char *path, int *w, int *h)
{
    int n;
    unsigned char *img = stbi_load(path, w, h, &n, 3);
    cr_assert_not_null(img, "cannot read %s", path);
    return img;
}

Test(render, window_screenshot_is_what_render_draws)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d = test_temp_dir("render");
    char args[1024], out[4096];
    const char *draw_opts = "--size 240x180 --overlay none --overlay grid,keys,legend";
    snprintf(args, sizeof args, "view %s --frames 3 --steps-per-frame 2 --screenshot %s/shot.png %s", scene, d,
             draw_opts);
    int rc = test_sphlab_env("SDL_VIDEODRIVER=offscreen", args, out, sizeof out);
    cr_assert_eq(rc, 0, "view exit %d: %s", rc, out);
    /* the window colours each frame by its own range: so does this render */
    snprintf(args, sizeof args, "render %s --out %s --steps 6 --every 6 --range frame --quiet %s", scene, d, draw_opts);
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    char p1[128], p2[128];
    snprintf(p1, sizeof p1, "%s/shot.png", d);
    snprintf(p2, sizeof p2, "%s/frame_00001.png", d);
    int w1, h1, w2, h2;
    unsigned char *a = load_png(p1, &w1, &h1), *b = load_png(p2, &w2, &h2);
    cr_assert(w1 == 240 && h1 == 180 && w2 == 240 && h2 == 180);
    /* 3 frames of 2 steps in the window = the render's frame at step 6 */
    size_t off = 0;
    for (size_t i = 0; i < (size_t)w1 * h1 * 3; i++) off += abs((int)a[i] - (int)b[i]) > 8;
    cr_expect_leq(off, (size_t)w1 * h1 * 3 / 200, "%zu channel values differ", off);
    stbi_image_free(a);
    stbi_image_free(b);
    test_remove_dir(d);
    remove(scene);
}

/* b to the GL backend and b back (or l through the G levels and back, or r after them): the GL simulation, in
 * its own context, is destroyed while that context is current, and every later frame drew into nothing (stripes
 * or black) until the window's context was made current again. Paused, the state is the same: so is the drawing
 * of the domain (the left part of the window; the HUD on the right says what was switched). Without an OpenGL
 * 4.3 device b is refused and the frames are trivially alike. */
Test(render, window_after_the_gl_backend_draws_again, .timeout = 120)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d = test_temp_dir("render");
    char args[1024], out[8192];
    const char *keys[2] = {"", "bb"};
    for (int k = 0; k < 2; k++) {
        snprintf(args, sizeof args, "view %s --paused --frames 4 --keys '%s' --size 320x240 --screenshot %s/s%d.png",
                 scene, keys[k], d, k);
        int rc = test_sphlab_env("SDL_VIDEODRIVER=offscreen", args, out, sizeof out);
        cr_assert_eq(rc, 0, "view exit %d: %s", rc, out);
    }
    char p0[128], p1[128];
    snprintf(p0, sizeof p0, "%s/s0.png", d);
    snprintf(p1, sizeof p1, "%s/s1.png", d);
    int w0, h0, w1, h1;
    unsigned char *a = load_png(p0, &w0, &h0), *b = load_png(p1, &w1, &h1);
    cr_assert(w0 == w1 && h0 == h1);
    size_t off = 0, all = 0;
    for (int y = 0; y < h0; y++)
        for (int x = 0; x < w0 / 2; x++, all++) {
            const size_t i = 3 * ((size_t)y * (size_t)w0 + (size_t)x);
            off += abs((int)a[i] - (int)b[i]) + abs((int)a[i + 1] - (int)b[i + 1]) + abs((int)a[i + 2] - (int)b[i + 2]) >
                   24;
        }
    cr_expect_leq(off, all / 50, "%zu of %zu pixels of the domain differ after b b", off, all);
    stbi_image_free(a);
    stbi_image_free(b);
    test_remove_dir(d);
    remove(scene);
}

Test(render, window_keys_step_pass_by_pass_and_switch_overlays)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d = test_temp_dir("render");
    char args[1024], out[8192];
    /* paused; one pass at a time: the first two of the pipeline (external, hash),
     * overlay 1 (grid), the next pass */
    snprintf(args, sizeof args, "view %s --paused --frames 5 --keys '..1.' --size 240x180 --screenshot %s/k.png", scene,
             d);
    int rc = test_sphlab_env("SDL_VIDEODRIVER=offscreen", args, out, sizeof out);
    cr_assert_eq(rc, 0, "view exit %d: %s", rc, out);
    /* what a pass wrote is the HUD's "ran pass" row (on by default); the message says the rest */
    const char *want[] = {"pass external ran; colour: speed", "pass hash ran; colour: key; index strip on",
                          "overlay grid on", "pass ", "saved"};
    const char *at = out;
    for (size_t k = 0; k < sizeof want / sizeof *want; k++) {
        const char *p = strstr(at, want[k]);
        cr_expect_not_null(p, "no '%s' (in order) in: %s", want[k], out);
        if (p) at = p;
    }
    char p1[128];
    snprintf(p1, sizeof p1, "%s/k.png", d);
    cr_expect_eq(access(p1, F_OK), 0);
    test_remove_dir(d);
    remove(scene);
}

/* A pass chosen with n that a switch takes out of the pipeline (pressure_force, once s chose pcisph) is chosen no
 * more: d said "pass pressure_force is not in this scene's pipeline" and the timings marked none. */
/* The window on scene_2d through SDL's offscreen driver with opts (frames, keys, overlays), which must exit 0;
 * its messages in out. */
static void scripted_view(const char *opts, char *out, size_t n)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    char args[1024];
    snprintf(args, sizeof args, "view %s --paused --size 240x180 %s", scene, opts);
    int rc = test_sphlab_env("SDL_VIDEODRIVER=offscreen", args, out, n);
    remove(scene);
    cr_assert_eq(rc, 0, "view exit %d: %s", rc, out);
}

Test(render, window_forgets_a_chosen_pass_a_switch_removes)
{
    char out[8192];
    scripted_view("--frames 13 --keys 'nnnnnnnnnsd'", out, sizeof out);
    const char *chose = strstr(out, "pass 9 pressure_force chosen");
    cr_assert_not_null(chose, "%s", out);
    cr_expect_not_null(strstr(chose, "no pass chosen: n chooses one"), "%s", out);
    cr_expect_null(strstr(chose, "is not in this scene's pipeline"), "%s", out);
}

/* With the HUD off the message lists what the pass wrote, only the fields this scene has: the reorder pass
 * moves every field it may meet, and the list named obstacle, slip, p_pci and kappa in a scene with none. */
Test(render, window_step_says_only_the_fields_the_scene_has)
{
    char out[8192];
    scripted_view("--no-overlay hud --frames 5 --keys '....'", out, sizeof out);
    const char *r = strstr(out, "pass reorder wrote pos vel");
    cr_assert_not_null(r, "%s", out);
    const char *end = strchr(r, '\n');
    const size_t len = end ? (size_t)(end - r) : strlen(r);
    char line[512];
    snprintf(line, sizeof line, "%.*s", (int)len, r);
    cr_expect(!strstr(line, "kappa") && !strstr(line, "obstacle") && !strstr(line, "p_pci"), "%s", line);
}

/* The parameter panel open (--panel) in a scripted run: m switches the
 * search through the panel's path, w saves the scene as the panel's "Save
 * scene as" does; the saved file reproduces the change. The domain lies left
 * of the side column (HUD and panel), the panel is drawn in the column, and
 * tab hides it. */
Test(render, window_panel_changes_the_run_saves_the_scene_and_stays_beside_the_domain)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d = test_temp_dir("render");
    char args[1024], out[8192], saved[128], shot[128];
    snprintf(saved, sizeof saved, "%s/saved.ini", d);
    snprintf(shot, sizeof shot, "%s/p.png", d);
    snprintf(args, sizeof args, "view %s --panel --frames 4 --keys 'mfw' --size 640x400 --save-scene %s --screenshot %s",
             scene, saved, shot);
    int rc = test_sphlab_env("SDL_VIDEODRIVER=offscreen", args, out, sizeof out);
    cr_assert_eq(rc, 0, "view exit %d: %s", rc, out);
    cr_expect(!strstr(out, "no parameter panel"), "%s", out);
    cr_expect(strstr(out, "search.method=grid") && strstr(out, "scene saved as"), "%s", out);
    sph_scene_def def = sph_default_scene_def();
    sph_error err = {0};
    cr_assert_eq(sph_scene_load(saved, &def, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_eq(def.search, SPH_SEARCH_GRID, "the saved scene has the live change");
    cr_expect_eq(def.table_size, 37u);
    cr_expect_float_eq(def.h, 0.04f, 1e-9f);
    int w, h;
    unsigned char *img = load_png(shot, &w, &h);
    cr_assert(w == 640 && h == 400);
    sph_layout L;
    sph_layout_compute(w, h, sph_layout_side_width(w, h), true, false, &L);
    size_t bg_left = 0, bg_right = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const unsigned char *p = img + 3 * ((size_t)y * w + x);
            bool bg = SPH_RGBA(p[0], p[1], p[2], 255) == DOMAIN_BG;
            if (bg && x < L.side[0]) bg_left++;
            if (bg && x >= L.side[0]) bg_right++;
        }
    cr_expect_gt(bg_left, 1000, "the domain is drawn left of the column");
    cr_expect_eq(bg_right, 0, "%zu domain pixels under the column", bg_right);
    /* the panel's widgets: many colours in the column's lower half (an empty column has one) */
    uint32_t seen[64];
    int n_seen = 0;
    for (int y = h / 2; y < h && n_seen < 64; y++)
        for (int x = L.side[0]; x < w && n_seen < 64; x++) {
            const unsigned char *p = img + 3 * ((size_t)y * w + x);
            uint32_t c = SPH_RGBA(p[0], p[1], p[2], 255);
            bool known = false;
            for (int k = 0; k < n_seen && !known; k++) known = seen[k] == c;
            if (!known) seen[n_seen++] = c;
        }
    cr_expect_gt(n_seen, 8, "only %d colours in the column: no panel drawn", n_seen);
    stbi_image_free(img);
    /* tab hides it */
    snprintf(args, sizeof args, "view %s --panel --frames 2 --keys '\t' --size 320x240", scene);
    rc = test_sphlab_env("SDL_VIDEODRIVER=offscreen", args, out, sizeof out);
    cr_expect_eq(rc, 0, "view exit %d: %s", rc, out);
    cr_expect(strstr(out, "parameter panel hidden"), "%s", out);
    test_remove_dir(d);
    remove(scene);
}

Test(render, window_without_a_display_says_so_and_exits_non_zero)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    char args[1024], out[4096];
    snprintf(args, sizeof args, "view %s", scene);
    int rc = test_sphlab_env("-u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER", args, out, sizeof out);
    cr_expect_eq(rc, 1, "exit %d: %s", rc, out);
    cr_expect(strstr(out, "no display") != NULL, "message: %s", out);
    /* a display that is not there */
    rc = test_sphlab_env("SDL_VIDEODRIVER=x11 DISPLAY=:97", args, out, sizeof out);
    cr_expect_eq(rc, 1, "exit %d: %s", rc, out);
    cr_expect(strstr(out, "sphlab view: SDL") != NULL, "message: %s", out);
    remove(scene);
}

/* On the GL backend the window asks for OpenGL 4.3 and the simulation runs
 * in the window's context: the particles are drawn from its buffers. With
 * no overlay nothing is read back after the first frame (whose first step
 * reads the energy reference once), and the picture is the CPU backend's. */
Test(render, window_on_the_gl_backend_draws_from_its_buffers)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d = test_temp_dir("render");
    char args[1024], out[4096];
    const char *opts = "--frames 4 --steps-per-frame 2 --size 240x180 --overlay none";
    snprintf(args, sizeof args, "view %s --backend gl %s --screenshot %s/gl.png", scene, opts, d);
    int rc = test_sphlab_env("SDL_VIDEODRIVER=offscreen", args, out, sizeof out);
    cr_assert_eq(rc, 0, "view exit %d: %s", rc, out);
    const char *line = strstr(out, "particles drawn from its buffers; bytes read back from it per frame:");
    cr_assert_not_null(line, "no report of the direct path in: %s", out);
    unsigned long long bytes[4];
    int got = sscanf(strchr(line, ':') + 1, "%llu %llu %llu %llu", &bytes[0], &bytes[1], &bytes[2], &bytes[3]);
    cr_assert_eq(got, 4, "%s", line);
    for (int f = 1; f < 4; f++) cr_expect_eq(bytes[f], 0, "frame %d read back %llu bytes", f, bytes[f]);
    /* the default overlays (HUD, legend): their few numbers reduced on the
     * device, no field (the scene's positions and predicted ones: 1,600 bytes) */
    snprintf(args, sizeof args, "view %s --backend gl --frames 4 --steps-per-frame 2 --size 240x180", scene);
    rc = test_sphlab_env("SDL_VIDEODRIVER=offscreen", args, out, sizeof out);
    cr_assert_eq(rc, 0, "view exit %d: %s", rc, out);
    line = strstr(out, "bytes read back from it per frame:");
    cr_assert_not_null(line, "no report of the bytes read back in: %s", out);
    got = sscanf(strchr(line, ':') + 1, "%llu %llu %llu %llu", &bytes[0], &bytes[1], &bytes[2], &bytes[3]);
    cr_assert_eq(got, 4, "%s", line);
    for (int f = 1; f < 4; f++) cr_expect_leq(bytes[f], 128, "default overlays: frame %d read back %llu bytes", f, bytes[f]);
    snprintf(args, sizeof args, "view %s --backend cpu %s --screenshot %s/cpu.png", scene, opts, d);
    rc = test_sphlab_env("SDL_VIDEODRIVER=offscreen", args, out, sizeof out);
    cr_assert_eq(rc, 0, "view exit %d: %s", rc, out);
    char p1[128], p2[128];
    snprintf(p1, sizeof p1, "%s/gl.png", d);
    snprintf(p2, sizeof p2, "%s/cpu.png", d);
    int w1, h1, w2, h2;
    unsigned char *a = load_png(p1, &w1, &h1), *b = load_png(p2, &w2, &h2);
    cr_assert(w1 == 240 && h1 == 180 && w2 == 240 && h2 == 180);
    size_t off = 0, lit = 0;
    for (size_t i = 0; i < (size_t)w1 * h1 * 3; i++) off += abs((int)a[i] - (int)b[i]) > 8;
    for (size_t i = 0; i < (size_t)w1 * h1; i++) lit += a[3 * i + 1] > 100; /* viridis' greens and yellows */
    cr_expect_gt(lit, (size_t)50, "no particle drawn (%zu bright pixels)", lit);
    cr_expect_leq(off, (size_t)w1 * h1 * 3 / 200, "%zu channel values differ from the CPU backend's", off);
    stbi_image_free(a);
    stbi_image_free(b);
    test_remove_dir(d);
    remove(scene);
}

/* A field with one value everywhere (the speed at step 0) is labelled once in the legend, with "everywhere"
 * under it: it read "0", "0" and "0" at the bar's top, middle and bottom. Counted as runs of bright rows of
 * text right of the legend's bar (the legend ends at the image's right edge without the HUD), from an eighth of
 * the height down (below the field's name and unit): one label block in the middle (the old legend's middle and
 * bottom labels made two). */
Test(render, legend_of_a_constant_field_says_its_value_once)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    const char *d = test_temp_dir("render");
    char args[1024], out[4096], path[256];
    snprintf(args, sizeof args, "render %s --out %s --steps 0 --size 800x600 --overlay none --overlay legend "
                                "--color speed --quiet", scene, d);
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    snprintf(path, sizeof path, "%s/frame_00000.png", d);
    int w, h;
    unsigned char *img = load_png(path, &w, &h);
    int runs = 0, gap = 100; /* gap: rows since the last bright one; lines of one label are closer than 8 rows */
    for (int y = h / 8; y < h - 2; y++) {
        bool ink = false;
        for (int x = w - 60; x < w - 2 && !ink; x++) {
            const unsigned char *px = img + 3 * ((size_t)y * (size_t)w + (size_t)x);
            ink = px[0] + px[1] + px[2] > 450;
        }
        if (ink && gap > 8) runs++;
        gap = ink ? 0 : gap + 1;
    }
    stbi_image_free(img);
    cr_expect_eq(runs, 1, "%d separated labels right of the bar, want 1 (the value and 'everywhere')", runs);
    test_remove_dir(d);
    remove(scene);
}
