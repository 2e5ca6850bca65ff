/* Every CPU level of the ladder honours the scene's physics options: the
 * vector walks are specialised for the common case (one mass, the energy
 * form of the walls' push, the symmetric pressure form), and two of them once
 * fell back on it in silence (the 8-lane walk ignored wall_force = ghost, and
 * read every neighbour's mass at index 0 with packed records and compact
 * lists). So each level's keys are applied to scenes that leave the common
 * case, and its state after some steps must be the scalar loops' (search.vector
 * = off) within the ladder's tolerance, particles matched by id. A level that
 * refuses a scene (a key it cannot combine with) is skipped, and counted; the
 * GL levels are left to tests/test_gl_*.c. No speed is asserted. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sph_levels.h"
#include "sph_sim.h"
#include "test_util.h"

/* Two blocks of different spacings (unequal masses), the walls' push as ghost particles. */
#define TWO_MASSES_GHOST_2D                                                                                      \
    "[scene]\ndimension = 2\neffects = gravity pressure viscosity walls\njitter = 0.1\n[domain]\nmin = 0 0\n"   \
    "max = 1.6 1.0\nwall_force = ghost\n[fluid a]\nmin = 0 0\nmax = 0.4 0.6\nspacing = 0.01\n[fluid b]\n"       \
    "min = 0.8 0\nmax = 1.2 0.4\nspacing = 0.0125\n[physics]\nstiffness = 1000\nviscosity = 0.002\n"           \
    "[kernels]\nh = 0.025\n[time]\ndt = 0.0005\ncfl = 0\n"

/* 3D: two blocks, the walls' push as ghost particles, the Tait equation. */
#define TWO_MASSES_GHOST_3D                                                                                      \
    "[scene]\ndimension = 3\neffects = gravity pressure viscosity walls\njitter = 0.1\n[domain]\nmin = 0 0 0\n" \
    "max = 0.6 0.4 0.4\nwall_force = ghost\n[fluid a]\nmin = 0 0 0\nmax = 0.2 0.2 0.3\nspacing = 0.02\n"      \
    "[fluid b]\nmin = 0.36 0 0\nmax = 0.56 0.2 0.2\nspacing = 0.025\n[physics]\nstiffness = 1000\n"            \
    "viscosity = 0.002\neos = tait\n[kernels]\nh = 0.05\n[time]\ndt = 0.0005\ncfl = 0\n"

#define STEPS 30

static sph_sim *make(const char *ini, const sph_level *L, sph_error *err)
{
    sph_scene_def def = test_scene(ini);
    if (L && sph_level_apply(L, &def, err) != SPH_ERR_OK) return NULL;
    if (!L && sph_scene_set(&def, "search.vector=off", err) != SPH_ERR_OK) return NULL;
    sph_sim *sim = NULL;
    return sph_sim_create(&def, L && L->threads == 1 ? 1 : 2, &sim, err) == SPH_ERR_OK ? sim : NULL;
}

/* The largest |x_a - x_b| [m] over the particles, matched by id. */
static double gap_by_id(const sph_sim *a, const sph_sim *b)
{
    cr_assert_eq(a->n, b->n);
    uint32_t *at = malloc(b->n * sizeof *at);
    cr_assert_not_null(at);
    for (uint32_t j = 0; j < b->n; j++) at[b->P.id[j]] = j;
    double gap = 0;
    for (uint32_t i = 0; i < a->n; i++)
        for (int d = 0; d < a->dim; d++)
            gap = fmax(gap, fabs((double)a->P.pos[d][i] - b->P.pos[d][at[a->P.id[i]]]));
    free(at);
    return gap;
}

static void every_level(const char *ini, const char *what)
{
    sph_error err;
    sph_sim *ref = make(ini, NULL, &err);
    cr_assert_not_null(ref, "%s: %s", what, err.msg);
    cr_assert(ref->n > 1000);
    for (int s = 0; s < STEPS; s++) sph_sim_step(ref);
    int ran = 0, refused = 0;
    for (int l = 0; l < sph_level_count; l++) {
        const sph_level *L = &sph_levels[l];
        if (sph_level_gl(L)) continue;
        sph_sim *sim = make(ini, L, &err);
        if (!sim) {
            refused++;
            continue;
        }
        for (int s = 0; s < STEPS; s++) sph_sim_step(sim);
        cr_expect(!sim->alarm.raised, "%s, %s: the watchdog stopped the run", what, L->name);
        const double gap = gap_by_id(ref, sim);
        cr_expect(gap < 1e-5, "%s, %s: positions %g m from the scalar loops' after %d steps", what, L->name, gap,
                  STEPS);
        ran++;
        sph_sim_destroy(sim);
    }
    /* L0 is the brute force on the scalar loops, and every level from L6 on runs this scene's options */
    cr_expect(ran >= 10, "%s: only %d levels ran (%d refused the scene)", what, ran, refused);
    sph_sim_destroy(ref);
}

Test(levels_options, every_cpu_level_two_masses_ghost_walls_2d) { every_level(TWO_MASSES_GHOST_2D, "2D"); }

Test(levels_options, every_cpu_level_two_masses_ghost_walls_tait_3d) { every_level(TWO_MASSES_GHOST_3D, "3D"); }

/* The shared pressure form reads volumes, not masses: its walks' other path. */
Test(levels_options, every_cpu_level_two_masses_shared_form_2d)
{
    every_level(TWO_MASSES_GHOST_2D "[physics]\npressure_form = shared\n", "2D, shared form");
}
