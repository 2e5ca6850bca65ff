/* [compute] wide_density (ladder level L16): with packed_records = on, on a
 * CPU with AVX-512, the density pass reads 16 neighbours at a time from its
 * records instead of 8. The operations per pair are L15's; the 16 lanes are
 * summed in another order, so the state must stay within round-off of L15's
 * (the ladder's check: the same neighbour sets, positions within 1e-4 m),
 * the same to the bit on one thread and two, and the density must differ
 * from L15's by round-off only after one step. A 2D dam, a strip with wide
 * rows (32-bit indices, walked 8 at a time), and a switch from L15 to L16
 * and back in mid-run. No speed is asserted.
 *
 * Also: the volume walls' share of a particle's support answered early for a
 * particle beyond the reach of every wall (sph_wall_hidden_at): the same
 * bits as the full computation, at positions around that reach. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sph_compare.h"
#include "sph_levels.h"
#include "sph_walls.h"
#include "test_levels_util.h"
#include "test_util.h"

/* L15's keys, wide_density as asked (L16: on). */
#define L15_KEYS                                                                                                 \
    "[search]\nmethod = grid\nsort = counting\nreorder = on\nvector = on\nlists_in_place = on\nskin = 0.05\n"  \
    "compact_lists = on\nvector_avx2 = on\ncell_batch = on\n[compute]\nfuse_forces = on\npacked_records = on\n" \
    "uniform_mass = on\nwide_density = %s\n"

#define STRIP_2D TEST_LEVELS_STRIP_2D

static sph_sim *make(const char *scene, bool wide, int threads)
{
    char keys[512], ini[2048];
    snprintf(keys, sizeof keys, L15_KEYS, wide ? "on" : "off");
    snprintf(ini, sizeof ini, "%s%s", scene, keys);
    return test_sim(ini, threads);
}

/* The largest |rho_a - rho_b| / rho_a, particles matched by id. */
static double rho_gap(const sph_sim *a, const sph_sim *b)
{
    double gap = 0;
    for (uint32_t i = 0; i < a->n; i++)
        for (uint32_t j = 0; j < b->n; j++)
            if (b->P.id[j] == a->P.id[i]) {
                gap = fmax(gap, fabs((double)a->P.rho[i] - b->P.rho[j]) / a->P.rho[i]);
                break;
            }
    return gap;
}

/* L15 and L16 from the same start: after one step the density within
 * round-off of L15's (and, where the build has AVX-512, not the same bits:
 * the wide walk ran); after `steps` the ladder's check against L15. */
static void as_l15(const char *scene, int steps, int threads, const char *what)
{
    sph_sim *a = make(scene, false, threads), *b = make(scene, true, threads);
    cr_assert(a->n > 100);
    sph_sim_step(a);
    sph_sim_step(b);
    const double gap = rho_gap(a, b);
    cr_expect(gap < 1e-5, "%s: the density differs from L15's by %g (relative) after one step", what, gap);
#if defined(__AVX512F__) && defined(__AVX2__) && defined(__FMA__)
    cr_expect(memcmp(a->P.rho, b->P.rho, a->n * sizeof *a->P.rho) != 0,
              "%s: the density is L15's to the bit: the 16-lane walk did not run", what);
#endif
    for (int s = 1; s < steps; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
    }
    cr_assert(!a->alarm.raised && !b->alarm.raised, "%s: the watchdog stopped a run", what);
    sph_compare_result r;
    sph_error err;
    cr_assert_eq(sph_sim_validate(b, &sph_levels[sph_level_find("L15")], 4, &r, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_eq(r.sets_differ, 0, "%s: %u neighbour sets differ from L15's", what, r.sets_differ);
    cr_expect(r.dx < 1e-4, "%s: positions differ from L15's by %g m after 4 more steps", what, r.dx);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

Test(wide_density, within_round_off_of_l15_3d) { as_l15(TEST_LEVELS_DAM_3D, 40, 2, "3D dam"); }
Test(wide_density, within_round_off_of_l15_2d) { as_l15(TEST_LEVELS_DAM_2D, 30, 2, "2D dam"); }

/* Rows stored wide are walked 8 at a time: still within round-off (a wide row read as offsets would not be). */
Test(wide_density, wide_rows_2d)
{
    sph_sim *a = make(STRIP_2D, false, 2), *b = make(STRIP_2D, true, 2);
    for (int s = 0; s < 3; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
    }
    const double gap = rho_gap(a, b);
    cr_expect(gap < 1e-5, "strip: the density differs from L15's by %g (relative)", gap);
    cr_expect(!b->alarm.raised, "strip: the watchdog stopped the run");
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

Test(wide_density, same_on_one_and_two_threads_3d)
{
    test_levels_same_after(make(TEST_LEVELS_DAM_3D, true, 1), make(TEST_LEVELS_DAM_3D, true, 2), 30,
                           "one thread against two");
}

/* L15 switched to L16 in mid-run (sph_sim_reconfigure, as the window does)
 * and back: the key follows the level, and the run stays within round-off of
 * one left at L15 all along. */
Test(wide_density, switched_live_from_l15)
{
    sph_sim *a = make(TEST_LEVELS_DAM_3D, false, 2), *b = make(TEST_LEVELS_DAM_3D, false, 2);
    sph_error err;
    for (int s = 0; s < 30; s++) {
        if (s == 10 || s == 20) {
            sph_scene_def next = b->def;
            cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find(s == 10 ? "L16" : "L15")], &next, &err),
                         SPH_ERR_OK, "%s", err.msg);
            cr_assert_eq(next.wide_density == SPH_ON, s == 10, "wide_density after the switch at step %d", s);
            cr_assert_eq(sph_sim_reconfigure(b, &next, &err), SPH_ERR_OK, "%s", err.msg);
            next = a->def;
            cr_assert_eq(sph_sim_reconfigure(a, &next, &err), SPH_ERR_OK, "%s", err.msg);
        }
        sph_sim_step(a);
        sph_sim_step(b);
    }
    const double gap = rho_gap(a, b);
    cr_expect(gap < 1e-4, "the density differs from L15's run by %g (relative) after 30 steps", gap);
    cr_expect_eq(sph_level_of(&b->def, 2, 2), sph_level_find("L15"), "the level after the switch back");
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* sph_wall_hidden_at's early answer for a particle beyond every wall's reach
 * against the full computation (sph_wall_hidden_near), bit for bit, share and
 * gradient, at positions stepping across the reach h of each wall in 2D and
 * 3D (the float steps just below, at and above h included). */
static void wall_far_same(const char *scene)
{
    sph_sim *s = test_sim(scene, 1);
    const sph_kernel *k = &s->k_density;
    const int dim = s->dim;
    int checked = 0, far = 0;
    for (int axis = 0; axis < dim; axis++)
        for (int side = 0; side < 2; side++)
            for (int step = -400; step <= 400; step++) {
                float pos[3];
                for (int d = 0; d < 3; d++)
                    pos[d] = d < dim ? 0.5f * (float)(s->def.domain_min[d] + s->def.domain_max[d]) : 0.0f;
                const float wall = (float)(side ? s->def.domain_max[axis] : s->def.domain_min[axis]);
                float d = k->h + (float)step * k->h / 256.0f;
                if (step >= -3 && step <= 3) d = nextafterf(k->h, step < 0 ? 0.0f : 1.0f) + (float)step * 1e-9f;
                pos[axis] = side ? wall - d : wall + d;
                float g1[3] = {9, 9, 9}, g2[3] = {9, 9, 9};
                const float h1 = sph_wall_hidden_at(s, k, pos, g1), h2 = sph_wall_hidden_near(s, k, pos, g2);
                cr_assert(memcmp(&h1, &h2, sizeof h1) == 0, "axis %d side %d d = %.9g: share %.9g, in full %.9g", axis,
                          side, (double)d, (double)h1, (double)h2);
                cr_assert(memcmp(g1, g2, (size_t)dim * sizeof *g1) == 0,
                          "axis %d side %d d = %.9g: gradient differs from the full computation", axis, side,
                          (double)d);
                cr_assert(sph_wall_hidden_at(s, k, pos, NULL) == h1);
                far += h1 == 0.0f && g1[axis] == 0.0f;
                checked++;
            }
    cr_expect(far > checked / 4 && far < checked, "%d of %d positions beyond reach: the steps miss the edge", far,
              checked);
    sph_sim_destroy(s);
}

Test(wide_density, walls_far_answer_is_the_full_ones_3d) { wall_far_same(TEST_LEVELS_DAM_3D); }
Test(wide_density, walls_far_answer_is_the_full_ones_2d) { wall_far_same(TEST_LEVELS_DAM_2D); }
