/* [compute] uniform_mass (ladder level L14): with packed_records = on and the
 * symmetric pressure form, the AVX2 force walk takes the neighbours' mass as
 * one constant when every particle's mass is the same, instead of gathering
 * it. The constant is the value the gather would have read, so the state must
 * be L13's to the bit after every step; with one mass changed the walk must
 * gather again (a walk that kept the constant would part from L13 at once).
 * Also: the same on one thread and two, a switch from L13 to L14 and back in
 * mid-run (the window's level keys), the shared pressure form (no mass in the
 * walk: the key changes nothing). No speed is asserted. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "sph_compare.h"
#include "sph_levels.h"
#include "test_levels_util.h"
#include "test_util.h"

/* L13's keys (fused walk, packed records), uniform_mass on or off (L14: on). */
#define L13_KEYS                                                                                                 \
    "[search]\nmethod = grid\nsort = counting\nreorder = on\nvector = on\nlists_in_place = on\nskin = 0.05\n"  \
    "compact_lists = on\nvector_avx2 = on\n[compute]\nfuse_forces = %s\npacked_records = on\n"                \
    "uniform_mass = %s\n"

enum { FUSED = 0, APART = 1, SHARED = 2 };
#define DAM_3D TEST_LEVELS_DAM_3D
#define DAM_2D TEST_LEVELS_DAM_2D

static sph_sim *make(const char *scene, int variant, bool uniform, int threads)
{
    char keys[512], ini[2048];
    snprintf(keys, sizeof keys, L13_KEYS, variant & APART ? "off" : "on", uniform ? "on" : "off");
    snprintf(ini, sizeof ini, "%s%s%s", scene, keys, variant & SHARED ? "[physics]\npressure_form = shared\n" : "");
    return test_sim(ini, threads);
}

/* One particle (by id, wherever the reorder put it) 1.5 times heavier in both runs. */
static void heavier(sph_sim *s, uint32_t id)
{
    for (uint32_t i = 0; i < s->n; i++)
        if (s->P.id[i] == id) s->P.mass[i] *= 1.5f;
}

/* L13 and L14 from the same start: the same state to the bit after every one
 * of `steps` steps, and the ladder's check of L14 against L13. */
static void as_l13(const char *scene, int variant, int steps, int threads, bool one_heavier, const char *what)
{
    sph_sim *a = make(scene, variant, false, threads), *b = make(scene, variant, true, threads);
    cr_assert(a->n > 100);
    if (one_heavier) {
        heavier(a, a->n / 2);
        heavier(b, a->n / 2);
    }
    for (int s = 0; s < steps; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
        const char *diff = test_levels_first_difference(a, b);
        cr_assert_null(diff, "%s: %s differs from L13's after step %d", what, diff, s + 1);
    }
    cr_assert(!a->alarm.raised && !b->alarm.raised, "%s: the watchdog stopped a run", what);
    sph_compare_result r;
    sph_error err;
    cr_assert_eq(sph_sim_validate(b, &sph_levels[sph_level_find("L13")], 4, &r, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_eq(r.sets_differ, 0, "%s: %u neighbour sets differ from L13's", what, r.sets_differ);
    cr_expect(r.dx == 0, "%s: positions differ from L13's by %g m after 4 more steps", what, r.dx);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

Test(uniform_mass, same_as_l13_to_the_bit_3d) { as_l13(DAM_3D, FUSED, 40, 2, false, "3D dam"); }
Test(uniform_mass, same_as_l13_unfused_2d) { as_l13(DAM_2D, APART, 30, 2, false, "2D dam, unfused"); }
Test(uniform_mass, same_as_l13_shared_form_3d) { as_l13(DAM_3D, SHARED, 20, 1, false, "3D dam, shared form"); }

/* One mass unlike the others: the walk gathers (the constant would be wrong for
 * that particle's neighbours), and the run is still L13's to the bit. */
Test(uniform_mass, unequal_masses_gathered_3d) { as_l13(DAM_3D, FUSED, 20, 2, true, "3D dam, one mass x1.5"); }
Test(uniform_mass, unequal_masses_gathered_2d) { as_l13(DAM_2D, APART, 20, 1, true, "2D dam, one mass x1.5"); }

/* That the heavier particle matters: without it the runs part (so the test above can fail). */
Test(uniform_mass, one_heavier_mass_changes_the_run)
{
    sph_sim *a = make(DAM_3D, FUSED, true, 1), *b = make(DAM_3D, FUSED, true, 1);
    heavier(b, b->n / 2);
    for (int s = 0; s < 5; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
    }
    cr_expect_not_null(test_levels_first_difference(a, b), "a 1.5 times heavier particle changed nothing in 5 steps");
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

Test(uniform_mass, same_on_one_and_two_threads_3d)
{
    sph_sim *a = make(DAM_3D, FUSED, true, 1), *b = make(DAM_3D, FUSED, true, 2);
    test_levels_same_after(a, b, 30, "one thread against two");
}

/* L13 switched to L14 in mid-run (sph_sim_reconfigure, as the window does) and
 * back: the run goes on as L13's would, to the bit. */
static bool uniform_on(const sph_scene_def *def) { return def->uniform_mass == SPH_ON; }

Test(uniform_mass, switched_live_from_l13)
{
    sph_sim *a = make(DAM_3D, FUSED, false, 2), *b = make(DAM_3D, FUSED, false, 2);
    test_levels_switch_live(a, b, "L13", "L14", uniform_on);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}
