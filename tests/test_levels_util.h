/* What the tests of the ladder's CPU levels share (test_vector_avx2.c,
 * test_packed_records.c, test_uniform_mass.c): two small dam breaks, the
 * first field where two runs part, and a switch from one level to the next
 * and back in mid-run, as the window's level keys make it. */
#ifndef TEST_LEVELS_UTIL_H
#define TEST_LEVELS_UTIL_H

#include <criterion/criterion.h>
#include <string.h>

#include "sph_levels.h"
#include "sph_sim.h"

/* 3D: 4,500 particles at 0.02 m, h = 2 spacings; 2D: 3,600 at 0.01 m. */
#define TEST_LEVELS_DAM_3D                                                                                       \
    "[scene]\ndimension = 3\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0 0\n"                \
    "max = 0.8 0.4 0.4\n[fluid column]\nmin = 0 0 0\nmax = 0.3 0.3 0.4\nspacing = 0.02\n[physics]\n"           \
    "stiffness = 1000\nviscosity = 0.002\n[kernels]\nh = 0.04\n[time]\ndt = 0.0005\ncfl = 0\n"

#define TEST_LEVELS_DAM_2D                                                                                       \
    "[scene]\ndimension = 2\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0\nmax = 1.6 0.8\n" \
    "[fluid column]\nmin = 0 0\nmax = 0.6 0.6\nspacing = 0.01\n[physics]\nstiffness = 1000\n"                 \
    "viscosity = 0.002\n[kernels]\nh = 0.02\n[time]\ndt = 0.0002\ncfl = 0\n"

/* A strip 200 m long and 4 spacings high (centred on 0, where floats are
 * finest): a row of cells holds about 40,000 particles, so a neighbour in the
 * next row of cells is that many places away, past the 16-bit offsets' reach:
 * those rows are stored wide. The drop above it has rows of cells of about
 * 100 particles: narrow rows. */
#define TEST_LEVELS_STRIP_2D                                                                                     \
    "[scene]\ndimension = 2\neffects = gravity pressure viscosity walls\n"                                        \
    "[domain]\nmin = -100.25 0\nmax = 100.25 0.5\n"                                                            \
    "[fluid strip]\nmin = -100 0\nmax = 100 0.04\nspacing = 0.01\n"                                              \
    "[fluid drop]\nmin = -0.5 0.3\nmax = 0.5 0.45\nspacing = 0.01\n[physics]\nstiffness = 1000\n"              \
    "viscosity = 0.002\n[kernels]\nh = 0.02\n[time]\ndt = 0.0002\ncfl = 0\n"

/* The first field where a and b differ to the bit (count, order, rho, pos, vel, acc_p, acc_v), or NULL. */
static inline const char *test_levels_first_difference(const sph_sim *a, const sph_sim *b)
{
    const size_t bytes = a->n * sizeof(float);
    if (a->n != b->n) return "particle count";
    if (memcmp(a->P.id, b->P.id, a->n * sizeof *a->P.id) != 0) return "order";
    if (memcmp(a->P.rho, b->P.rho, bytes) != 0) return "rho";
    for (int d = 0; d < a->dim; d++) {
        if (memcmp(a->P.pos[d], b->P.pos[d], bytes) != 0) return "pos";
        if (memcmp(a->P.vel[d], b->P.vel[d], bytes) != 0) return "vel";
        if (memcmp(a->P.acc_p[d], b->P.acc_p[d], bytes) != 0) return "acc_p";
        if (a->P.acc_v[d] && b->P.acc_v[d] && memcmp(a->P.acc_v[d], b->P.acc_v[d], bytes) != 0) return "acc_v";
    }
    return NULL;
}

/* a and b stepped in turn for `steps` steps must end alike to the bit (e.g. one thread against two); both are
 * destroyed. */
static inline void test_levels_same_after(sph_sim *a, sph_sim *b, int steps, const char *what)
{
    for (int s = 0; s < steps; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
    }
    const char *diff = test_levels_first_difference(a, b);
    cr_expect_null(diff, "%s: the two runs differ in %s after %d steps", what, diff, steps);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* a and b start alike at level `lower`; b is switched to `upper` before step
 * 11 and back before step 21 (sph_sim_reconfigure), a only reconfigured in
 * place (a reconfigure starts a new simulation with the carried state), and
 * the two must agree to the bit after each of 30 steps. key_on(def) says
 * whether the upper level's key is on in a def: checked after each switch. */
static inline void test_levels_switch_live(sph_sim *a, sph_sim *b, const char *lower, const char *upper,
                                           bool (*key_on)(const sph_scene_def *))
{
    sph_error err;
    for (int s = 0; s < 30; s++) {
        if (s == 10 || s == 20) {
            sph_scene_def next = b->def;
            cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find(s == 10 ? upper : lower)], &next, &err),
                         SPH_ERR_OK, "%s", err.msg);
            cr_assert_eq(key_on(&next), s == 10, "%s's key after the switch to %s", upper, s == 10 ? upper : lower);
            cr_assert_eq(sph_sim_reconfigure(b, &next, &err), SPH_ERR_OK, "%s", err.msg);
            next = a->def;
            cr_assert_eq(sph_sim_reconfigure(a, &next, &err), SPH_ERR_OK, "%s", err.msg);
        }
        sph_sim_step(a);
        sph_sim_step(b);
        const char *diff = test_levels_first_difference(a, b);
        cr_assert_null(diff, "%s differs from %s's after step %d (switched at 10, back at 20)", diff, lower, s + 1);
    }
}

#endif
