/* [search] compact_lists (ladder level L11): the neighbour lists as 16-bit
 * offsets j - i, with wide rows (32-bit indices behind a marker) for
 * neighbours more than 32,767 places away. The lists must decode to the plain
 * lists' rows entry for entry (so the passes sum the same pairs in the same
 * order and the state is the same to the bit), on one thread or two, with
 * narrow and wide rows alike. No speed or memory size is asserted. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_levels_util.h"
#include "test_util.h"

/* L10's keys (docs/performance.md): L11 adds compact_lists = on. */
#define L10_KEYS                                                                                                 \
    "[search]\nmethod = grid\nsort = counting\nreorder = on\nvector = on\nlists_in_place = on\nskin = 0.05\n"   \
    "[compute]\nfuse_forces = on\n"

#define DAM_3D                                                                                                   \
    "[scene]\ndimension = 3\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0 0\n"                \
    "max = 0.8 0.4 0.4\n[fluid column]\nmin = 0 0 0\nmax = 0.3 0.3 0.4\nspacing = 0.02\n[physics]\n"           \
    "stiffness = 1000\nviscosity = 0.002\n[kernels]\nh = 0.04\n[time]\ndt = 0.0005\ncfl = 0\n"

#define STRIP_2D TEST_LEVELS_STRIP_2D

static sph_sim *make(const char *scene, bool compact, int threads)
{
    char ini[2048];
    snprintf(ini, sizeof ini, "%s%s%s", scene, L10_KEYS, compact ? "[search]\ncompact_lists = on\n" : "");
    return test_sim(ini, threads);
}

/* Every row of b decodes to a's row, entry for entry; returns b's wide rows. */
static uint32_t same_rows(const sph_sim *a, const sph_sim *b, const char *what)
{
    cr_assert_eq(a->n, b->n);
    cr_assert(!a->S.compact && b->S.compact, "%s: a plain and a compact simulation", what);
    uint32_t wide = 0;
    for (uint32_t i = 0; i < a->n; i++) {
        cr_assert_eq(a->P.id[i], b->P.id[i], "%s: slot %u holds another particle", what, i);
        const sph_nbr_row ra = sph_nbr_row_of(&a->S, i), rb = sph_nbr_row_of(&b->S, i);
        cr_assert_eq(ra.n, rb.n, "%s: particle %u has %u neighbours in plain lists, %u in compact ones", what, i,
                     ra.n, rb.n);
        for (uint32_t k = 0; k < ra.n; k++)
            cr_assert_eq(sph_nbr_at(&ra, k), sph_nbr_at(&rb, k), "%s: particle %u's neighbour %u differs", what, i,
                         k);
        wide += rb.x != NULL;
    }
    return wide;
}

static void same_state(const sph_sim *a, const sph_sim *b, const char *what)
{
    for (int d = 0; d < a->dim; d++) {
        cr_assert(memcmp(a->P.pos[d], b->P.pos[d], a->n * sizeof(float)) == 0, "%s: positions differ", what);
        cr_assert(memcmp(a->P.vel[d], b->P.vel[d], a->n * sizeof(float)) == 0, "%s: velocities differ", what);
    }
    cr_assert(memcmp(a->P.rho, b->P.rho, a->n * sizeof(float)) == 0, "%s: densities differ", what);
}

/* The 3D dam on two threads: the rows after every step (built and kept),
 * and the state to the bit after 30 steps; every row is narrow here. */
Test(compact_lists, same_rows_and_state_as_plain_lists_3d)
{
    sph_sim *a = make(DAM_3D, false, 2), *b = make(DAM_3D, true, 2);
    uint32_t wide = 0;
    for (int s = 0; s < 30; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
        wide += same_rows(a, b, "3D dam");
    }
    same_state(a, b, "3D dam after 30 steps");
    cr_expect_eq(wide, 0, "%u rows of the small dam were stored wide", wide);
    cr_expect_lt(b->S.builds, 30, "the Verlet lists were rebuilt every step");
    /* half the words of the plain lists' entries, as all rows are narrow */
    cr_expect_eq(b->S.nbr_start[b->n], a->S.nbr_start[a->n]);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* The long strip: some rows wide, most narrow, the same rows as the plain
 * lists, and the same on one thread as on two (thread 1's rows start at an
 * odd word when thread 0's share ends on one). */
Test(compact_lists, wide_rows_hold_far_neighbours)
{
    sph_sim *a = make(STRIP_2D, false, 2), *b = make(STRIP_2D, true, 2), *c = make(STRIP_2D, true, 1);
    cr_assert_gt(b->n, 70000u);
    for (int s = 0; s < 3; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
        sph_sim_step(c);
        const uint32_t wide = same_rows(a, b, "strip, two threads");
        cr_expect_eq(same_rows(a, c, "strip, one thread"), wide);
        cr_expect(wide > 1000 && wide < b->n, "step %d: %u of %u rows wide (some, not all)", s + 1, wide, b->n);
    }
    same_state(a, b, "strip, two threads");
    same_state(a, c, "strip, one thread");
    sph_sim_destroy(a);
    sph_sim_destroy(b);
    sph_sim_destroy(c);
}

/* A pass that walks the lists and was not measured with compact ones is
 * refused, naming the key's file and line and the pass. */
Test(compact_lists, refuses_an_untried_pass)
{
    char ini[2048];
    snprintf(ini, sizeof ini, "%s%s[physics]\nxsph = 0.5\n[search]\ncompact_lists = on\n", DAM_3D, L10_KEYS);
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    cr_assert_eq(sph_scene_load_string(ini, "compact.ini", &def, &err), SPH_ERR_OK, "%s", err.msg);
    def.skin = 0.0f; /* the skin's own refusal would come first */
    cr_assert_eq(sph_scene_validate(&def, &err), SPH_ERR_SCENE);
    cr_expect(strstr(err.msg, "compact.ini:") && strstr(err.msg, "compact_lists") && strstr(err.msg, "xsph"), "%s",
              err.msg);
    def.compact_lists = SPH_OFF;
    cr_expect_eq(sph_scene_validate(&def, &err), SPH_ERR_OK, "%s", err.msg);
}
