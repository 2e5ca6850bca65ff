/* [search] vector_avx2 (ladder level L12): the pair passes' vector loops 8
 * neighbours at a time in AVX2 instead of AVX-512's 16 (or the scalar loops
 * on a CPU without AVX-512). The search is untouched, so the lists must be
 * L11's entry for entry; the sums run in another order, so the state must be
 * L11's within round-off (the ladder's own check, sph_sim_validate), and the
 * same to the bit on one thread and two. Every storage of the rows (plain,
 * compact, compact wide), the fused walk and the separate loops, both
 * pressure forms, 2D and 3D. No speed is asserted. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sph_compare.h"
#include "sph_levels.h"
#include "test_levels_util.h"
#include "test_util.h"

#if defined(__AVX2__) && defined(__FMA__)
#define HAVE_AVX2 1
#else
#define HAVE_AVX2 0
#endif

/* L11's keys (docs/performance.md), with fuse_forces and compact_lists as
 * asked (L11: both on); L12 adds vector_avx2 = on. */
#define L11_KEYS                                                                                                 \
    "[search]\nmethod = %s\nsort = counting\nreorder = on\nvector = on\nlists_in_place = on\nskin = 0.05\n"   \
    "compact_lists = %s\nvector_avx2 = %s\n[compute]\nfuse_forces = %s\n"

/* Variants of L11: the separate pressure_force and viscosity loops, plain 32-bit lists, the shared pressure form,
 * the hash instead of the dense grid (its runs hold cells of other keys: the scan filters them), the walls' push
 * as ghost particles ([domain] wall_force = ghost) instead of the energy's gradient. */
enum { FUSED = 0, APART = 1, PLAIN = 2, SHARED = 4, HASH = 8, GHOST = 16 };
#define DAM_3D TEST_LEVELS_DAM_3D
#define DAM_2D TEST_LEVELS_DAM_2D

#define STRIP_2D TEST_LEVELS_STRIP_2D /* many compact rows stored wide */

/* The scene with L11's keys in the variant asked, vector_avx2 on or off. */
static sph_sim *make(const char *scene, int variant, bool avx2, int threads)
{
    char keys[512], ini[2048];
    snprintf(keys, sizeof keys, L11_KEYS, variant & HASH ? "hash" : "grid", variant & PLAIN ? "off" : "on", avx2 ? "on" : "off",
             variant & APART ? "off" : "on");
    snprintf(ini, sizeof ini, "%s%s%s%s", scene, keys, variant & SHARED ? "[physics]\npressure_form = shared\n" : "",
             variant & GHOST ? "[domain]\nwall_force = ghost\n" : "");
    return test_sim(ini, threads);
}

/* Every row of b is a's, entry for entry. */
static void same_rows(const sph_sim *a, const sph_sim *b, const char *what)
{
    cr_assert_eq(a->n, b->n);
    for (uint32_t i = 0; i < a->n; i++) {
        cr_assert_eq(a->P.id[i], b->P.id[i], "%s: slot %u holds another particle", what, i);
        const sph_nbr_row ra = sph_nbr_row_of(&a->S, i), rb = sph_nbr_row_of(&b->S, i);
        cr_assert_eq(ra.n, rb.n, "%s: particle %u has %u neighbours, then %u", what, i, ra.n, rb.n);
        for (uint32_t k = 0; k < ra.n; k++)
            cr_assert_eq(sph_nbr_at(&ra, k), sph_nbr_at(&rb, k), "%s: particle %u's neighbour %u differs", what, i,
                         k);
    }
}

static bool same_state(const sph_sim *a, const sph_sim *b)
{
    bool same = a->n == b->n && memcmp(a->P.rho, b->P.rho, a->n * sizeof(float)) == 0;
    for (int d = 0; d < a->dim && same; d++)
        same = memcmp(a->P.pos[d], b->P.pos[d], a->n * sizeof(float)) == 0 &&
               memcmp(a->P.vel[d], b->P.vel[d], a->n * sizeof(float)) == 0;
    return same;
}

/* L11 and L12 from the same start: the same lists after the first step (the
 * search is the same code on the same positions), then states apart by
 * round-off only after `steps`, and the ladder's check (sph_sim_validate
 * against L11: the same neighbour sets, positions within 1e-5 m). */
static void as_l11(const char *scene, int variant, int steps, const char *what)
{
    sph_sim *a = make(scene, variant, false, 2), *b = make(scene, variant, true, 2);
    sph_sim_step(a);
    sph_sim_step(b);
    same_rows(a, b, what);
    for (int s = 1; s < steps; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
    }
    cr_assert(!a->alarm.raised && !b->alarm.raised, "%s: the watchdog stopped a run", what);
    double dx = 0;
    for (int d = 0; d < a->dim; d++)
        for (uint32_t i = 0; i < a->n; i++) {
            cr_assert_eq(a->P.id[i], b->P.id[i], "%s: slot %u holds another particle", what, i);
            dx = fmax(dx, fabs((double)a->P.pos[d][i] - b->P.pos[d][i]));
        }
    cr_expect(dx < 1e-5, "%s: positions differ from L11's by %g m after %d steps", what, dx, steps);
    /* the key changed the loops: sums in another order round otherwise somewhere */
    if (HAVE_AVX2) cr_expect(!same_state(a, b), "%s: the same state to the bit: were the AVX2 loops run?", what);
    sph_compare_result r;
    sph_error err;
    cr_assert_eq(sph_sim_validate(b, &sph_levels[sph_level_find("L11")], 4, &r, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_eq(r.sets_differ, 0, "%s: %u neighbour sets differ from L11's", what, r.sets_differ);
    cr_expect(r.dx < 1e-5, "%s: positions differ from L11's by %g m after 4 more steps", what, r.dx);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* L12 on one thread and on two: the same state to the bit after `steps`. */
static void same_on_threads(const char *scene, int variant, int steps, const char *what)
{
    sph_sim *a = make(scene, variant, true, 1), *b = make(scene, variant, true, 2);
    for (int s = 0; s < steps; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
    }
    cr_expect(same_state(a, b), "%s: one thread and two differ after %d steps", what, steps);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

Test(vector_avx2, same_lists_and_state_as_l11_3d) { as_l11(DAM_3D, FUSED, 40, "3D dam"); }

/* The separate pressure_force and viscosity loops, the shared pressure form, plain 32-bit lists. */
Test(vector_avx2, same_as_l11_unfused_shared_form_plain_lists_2d)
{
    as_l11(DAM_2D, APART | PLAIN | SHARED, 40, "2D dam, unfused, shared form, plain lists");
}

Test(vector_avx2, same_on_one_and_two_threads_3d) { same_on_threads(DAM_3D, FUSED, 30, "3D dam"); }

Test(vector_avx2, same_on_one_and_two_threads_unfused_2d)
{
    same_on_threads(DAM_2D, APART | SHARED, 30, "2D dam, unfused");
}

/* Wide compact rows (32-bit indices behind the marker) read by the 8-lane loops. */
Test(vector_avx2, wide_rows_same_on_one_and_two_threads)
{
    same_on_threads(STRIP_2D, FUSED, 3, "strip with wide rows");
    as_l11(STRIP_2D, FUSED, 3, "strip with wide rows");
}

/* The walls' push as ghost particles: the 8-lane walk (fused and apart) adds the same push as the 16-lane one (it
 * added the energy's gradient whatever wall_force said: 0.61 J/m of kinetic energy instead of 0.89 in a tank). */
Test(vector_avx2, ghost_walls_same_as_l11_2d)
{
    as_l11(DAM_2D, GHOST, 40, "2D dam, ghost walls");
    as_l11(DAM_2D, GHOST | APART, 40, "2D dam, ghost walls, unfused");
}

/* The hash's scan (runs shared by several cells) in 8 lanes: the same lists as L11's. */
Test(vector_avx2, hash_search_same_as_l11_3d) { as_l11(DAM_3D, HASH, 10, "3D dam, hash"); }
