/* Shared by the GL backend's tests: whether an OpenGL 4.3 context can be had,
 * and making, copying and comparing CPU and GL simulations. */
#ifndef TEST_GL_UTIL_H
#define TEST_GL_UTIL_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu.h"
#include "sph_sim.h"
#include "test_util.h"

/* No GL at all (no EGL display) is a reason to skip; a display without
 * OpenGL 4.3 is a failure: CI has Mesa, whose llvmpipe gives 4.5. Forced
 * onto software rendering, as CI has no GPU (setenv: _GNU_SOURCE before
 * the first include). */
static inline void need_gl(void)
{
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
    sph_gpu_register();
    char dev[512];
    if (sph_gpu_probe(dev, sizeof dev)) return;
    if (strstr(dev, "eglGetPlatformDisplay") || strstr(dev, "EGL_MESA_platform_surfaceless") ||
        strstr(dev, "eglInitialize"))
        cr_skip_test("no EGL display on this machine: %s", dev);
    cr_assert_fail("an EGL display but no OpenGL 4.3 context: %s", dev);
}

/* A simulation of the scene text with --set lines applied, on the CPU or
 * on the GL backend (which must then exist). */
static inline sph_sim *test_gl_make(const char *ini, const char *const *sets, int n_sets, bool gl)
{
    sph_scene_def def = test_scene(ini);
    sph_error err;
    for (int i = 0; i < n_sets; i++)
        cr_assert_eq(sph_scene_set(&def, sets[i], &err), SPH_ERR_OK, "--set %s: %s", sets[i], err.msg);
    def.backend = gl ? SPH_BACKEND_GL : SPH_BACKEND_CPU;
    sph_sim *sim;
    cr_assert_eq(sph_sim_create(&def, 2, &sim, &err), SPH_ERR_OK, "%s", err.msg);
    cr_assert(!gl || sim->backend, "the GL simulation has no backend");
    return sim;
}

/* g takes c's particles (every field of the registry both have), time step,
 * time (the start-up ramps depend on it), maxima and the carried density's
 * flag (density_method = continuity), and sends them to the device. */
static inline void test_gl_copy_state(sph_sim *g, const sph_sim *c)
{
    const uint32_t n = c->n;
    memcpy(g->P.id, c->P.id, (size_t)n * sizeof *g->P.id);
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        for (int d = 0; d < 3; d++)
            if (g->P.field[f][d] && c->P.field[f][d]) memcpy(g->P.field[f][d], c->P.field[f][d], n * sizeof(float));
    g->dt = c->dt;
    g->t = c->t;
    g->max_speed = c->max_speed;
    g->max_acc = c->max_acc;
    g->rho_carried = c->rho_carried;
    sph_sim_upload(g);
}

/* Largest |gl - cpu| of a field over particles and components (NaN counts
 * as infinite), and in *scale the largest |cpu|, the scale tolerances are
 * fractions of. The pressure is the density through the equation of state,
 * whose (rho/rho0)^gamma - 1 cancels near rest: its rounding is a few ulps
 * of k rho0 whatever p is, so that is its least scale (a quiet start keeps
 * |p| far below it). */
static inline double test_gl_field_error(const sph_sim *c, const sph_sim *g, sph_field_id f, double *scale)
{
    sph_field fc, fg;
    cr_assert(sph_sim_field(c, f, &fc) && sph_sim_field(g, f, &fg), "field %d missing", (int)f);
    double err = 0, big = 0;
    for (int k = 0; k < fc.ncomp; k++)
        for (uint32_t i = 0; i < c->n; i++) {
            double e = fabs((double)fg.c[k][i] - fc.c[k][i]);
            err = fmax(err, e == e ? e : INFINITY);
            big = fmax(big, fabs((double)fc.c[k][i]));
        }
    const double k_rho0 = (double)c->def.stiffness * c->def.rest_density;
    if (f == SPH_FIELD_P) big = fmax(big, k_rho0);
    if (f == SPH_FIELD_PRHO2) big = fmax(big, k_rho0 / ((double)c->def.rest_density * c->def.rest_density));
    *scale = big;
    return err;
}

/* 2D, 225 particles in a box reaching below zero on both axes (negative
 * cells), jittered so that no two distances tie. */
#define TEST_GL_SCENE_2D \
    "[scene]\nname=gl 2d\ndimension=2\neffects=gravity pressure viscosity walls\njitter=0.2\n" \
    "[domain]\nmin=-0.3 -0.2\nmax=0.3 0.4\nwall_damping=0.3\n" \
    "[physics]\nnegative_pressure=clamp\nviscosity=0.005\n" \
    "[kernels]\nh=0.04\n[time]\ndt=0.001\ncfl=0.4\n" \
    "[fluid a]\nmin=-0.3 -0.2\nmax=0.0 0.1\nspacing=0.02\nvelocity=0.5 0\n"

/* 3D, 512 particles, also across zero. */
#define TEST_GL_SCENE_3D \
    "[scene]\nname=gl 3d\ndimension=3\neffects=gravity pressure viscosity walls\njitter=0.2\n" \
    "[domain]\nmin=-0.2 -0.2 -0.2\nmax=0.2 0.2 0.2\nwall_damping=0.3\n" \
    "[physics]\nnegative_pressure=clamp\nviscosity=0.005\ngravity=0 -9.81 0\n" \
    "[kernels]\nh=0.05\n[time]\ndt=0.001\ncfl=0.4\n" \
    "[fluid a]\nmin=-0.2 -0.2 -0.2\nmax=0.0 0.0 0.0\nspacing=0.025\nvelocity=0 0 0.3\n"

#define TEST_GL_TOL_POS_RUN 1e-4 /* [m] positions after a whole run of separate simulations */

/* The largest gap [m] between the CPU's and GL's positions of the same particles, matched by id (both
 * reorder the same way, but the comparison does not rely on it); g synchronised by the caller. */
static inline double test_gl_position_gap(const sph_sim *c, const sph_sim *g)
{
    uint32_t *where = malloc(c->n * sizeof *where);
    cr_assert_not_null(where);
    for (uint32_t i = 0; i < g->n; i++) where[g->P.id[i]] = i;
    double err = 0;
    for (uint32_t i = 0; i < c->n; i++)
        for (int d = 0; d < c->dim; d++) err = fmax(err, fabs((double)g->P.pos[d][where[c->P.id[i]]] - c->P.pos[d][i]));
    free(where);
    return err;
}

/* Separate simulations on the CPU and on GL, 40 steps each: positions stay within TEST_GL_TOL_POS_RUN and
 * the kinetic energies within 1e-3. */
static inline void test_gl_whole_run(const char *ini, const char *const *sets, int n_sets)
{
    need_gl();
    sph_sim *c = test_gl_make(ini, sets, n_sets, false), *g = test_gl_make(ini, sets, n_sets, true);
    for (int s = 0; s < 40; s++) {
        sph_sim_step(c);
        sph_sim_step(g);
    }
    cr_assert(!g->alarm.raised && !c->alarm.raised, "the watchdog stopped a run");
    cr_expect(fabs(g->t - c->t) <= 1e-6 * c->t, "simulated time %g on GL, %g on the CPU", g->t, c->t);
    sph_sim_sync(g, SPH_SYNC_ALL);
    double err = test_gl_position_gap(c, g);
    if (getenv("SPH_TEST_VERBOSE"))
        fprintf(stderr, "whole run (%dD, 40 steps): positions differ by %.3g m\n", c->dim, err);
    cr_expect(err <= TEST_GL_TOL_POS_RUN, "positions after 40 steps differ by %.3g m (tolerance %g m)", err,
              TEST_GL_TOL_POS_RUN);
    sph_stats sc, sg;
    sph_sim_stats(c, &sc);
    sph_sim_stats(g, &sg);
    cr_expect(fabs(sg.ekin - sc.ekin) <= 1e-3 * sc.ekin, "kinetic energy %g on GL, %g on the CPU", sg.ekin, sc.ekin);
    sph_sim_destroy(g);
    sph_sim_destroy(c);
}

#endif
