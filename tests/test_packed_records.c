/* [compute] packed_records (ladder level L13): with vector_avx2 = on the
 * density and pressure_force passes read each neighbour's fields from one
 * record per particle (8 loads and a transpose) instead of one gather per
 * field. The values and the operations are L12's, so the lists must be L12's
 * entry for entry and the state the same to the bit after many steps (and so
 * within the ladder's tolerance of L12: sph_simd8_rec4/rec8's transposes put
 * every field in its lane, or the states would part at the first step), and
 * the same on one thread and two. The fused walk and the separate loops, both
 * pressure forms, 2D and 3D, and a switch from L12 to L13 in mid-run (the
 * window's level keys). No speed is asserted. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
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

/* L12's keys, with fuse_forces as asked (L12: on), and packed_records on or off (L13: on). */
#define L12_KEYS                                                                                                 \
    "[search]\nmethod = grid\nsort = counting\nreorder = on\nvector = on\nlists_in_place = on\nskin = 0.05\n"  \
    "compact_lists = on\nvector_avx2 = on\n[compute]\nfuse_forces = %s\npacked_records = %s\n"

enum { FUSED = 0, APART = 1, SHARED = 2 };
#define DAM_3D TEST_LEVELS_DAM_3D
#define DAM_2D TEST_LEVELS_DAM_2D

static sph_sim *make(const char *scene, int variant, bool packed, int threads)
{
    char keys[512], ini[2048];
    snprintf(keys, sizeof keys, L12_KEYS, variant & APART ? "off" : "on", packed ? "on" : "off");
    snprintf(ini, sizeof ini, "%s%s%s", scene, keys, variant & SHARED ? "[physics]\npressure_form = shared\n" : "");
    return test_sim(ini, threads);
}

static void same_rows(const sph_sim *a, const sph_sim *b, const char *what)
{
    cr_assert_eq(a->n, b->n);
    for (uint32_t i = 0; i < a->n; i++) {
        const sph_nbr_row ra = sph_nbr_row_of(&a->S, i), rb = sph_nbr_row_of(&b->S, i);
        cr_assert_eq(ra.n, rb.n, "%s: particle %u has %u neighbours, then %u", what, i, ra.n, rb.n);
        for (uint32_t k = 0; k < ra.n; k++)
            cr_assert_eq(sph_nbr_at(&ra, k), sph_nbr_at(&rb, k), "%s: particle %u's neighbour %u differs", what, i,
                         k);
    }
}

/* L12 and L13 from the same start: the same lists, the same state to the bit
 * after every one of `steps` steps, and the ladder's check of L13 against L12. */
static void as_l12(const char *scene, int variant, int steps, int threads, const char *what)
{
    sph_sim *a = make(scene, variant, false, threads), *b = make(scene, variant, true, threads);
    for (int s = 0; s < steps; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
        const char *diff = test_levels_first_difference(a, b);
        cr_assert_null(diff, "%s: %s differs from L12's after step %d", what, diff, s + 1);
    }
    same_rows(a, b, what);
    cr_assert(!a->alarm.raised && !b->alarm.raised, "%s: the watchdog stopped a run", what);
    /* the key changed the loops: the records were made (on a CPU with AVX2) */
    cr_expect_eq(b->S.rec != NULL, HAVE_AVX2, "%s: records %s", what, b->S.rec ? "made" : "never made");
    cr_expect_null(a->S.rec, "%s: L12 made records", what);
    sph_compare_result r;
    sph_error err;
    cr_assert_eq(sph_sim_validate(b, &sph_levels[sph_level_find("L12")], 4, &r, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_eq(r.sets_differ, 0, "%s: %u neighbour sets differ from L12's", what, r.sets_differ);
    cr_expect(r.dx == 0, "%s: positions differ from L12's by %g m after 4 more steps", what, r.dx);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

static void same_on_threads(const char *scene, int variant, int steps, const char *what)
{
    sph_sim *a = make(scene, variant, true, 1), *b = make(scene, variant, true, 2);
    test_levels_same_after(a, b, steps, what);
}

Test(packed_records, same_as_l12_to_the_bit_3d) { as_l12(DAM_3D, FUSED, 40, 2, "3D dam"); }

/* The separate pressure_force and viscosity loops, and the shared pressure form (records hold p, not p/rho^2). */
Test(packed_records, same_as_l12_unfused_2d) { as_l12(DAM_2D, APART, 30, 2, "2D dam, unfused"); }
Test(packed_records, same_as_l12_shared_form_2d) { as_l12(DAM_2D, SHARED, 30, 1, "2D dam, shared form"); }
Test(packed_records, same_as_l12_shared_form_unfused_3d) { as_l12(DAM_3D, APART | SHARED, 20, 2, "3D, apart, shared"); }

Test(packed_records, same_on_one_and_two_threads_3d) { same_on_threads(DAM_3D, FUSED, 30, "3D dam"); }

/* Two blocks of different spacings: unequal masses, which the symmetric form's walk gathers by index (uniform_mass
 * off). With a compact row the records are read by offset and no index vector is made; the mass was gathered with
 * that empty vector, so every neighbour weighed as particle 0 (18 % less kinetic energy after 200 steps). */
#define TWO_MASSES_2D                                                                                            \
    "[scene]\ndimension = 2\neffects = gravity pressure viscosity walls\njitter = 0.1\n[domain]\nmin = 0 0\n"  \
    "max = 1.6 1.0\n[fluid a]\nmin = 0 0\nmax = 0.4 0.6\nspacing = 0.01\n[fluid b]\nmin = 0.8 0\n"            \
    "max = 1.2 0.4\nspacing = 0.0125\n[physics]\nstiffness = 1000\nviscosity = 0.002\n[kernels]\nh = 0.025\n"  \
    "[time]\ndt = 0.0005\ncfl = 0\n"

Test(packed_records, unequal_masses_same_as_l12_2d)
{
    as_l12(TWO_MASSES_2D, FUSED, 20, 2, "two masses, fused");
    as_l12(TWO_MASSES_2D, APART, 20, 1, "two masses, unfused");
}

/* L12 switched to L13 in mid-run (sph_sim_reconfigure, as the window does) and
 * back: the run goes on as L12's would, to the bit. */
static bool packed_on(const sph_scene_def *def) { return def->packed_records == SPH_ON; }

Test(packed_records, switched_live_from_l12)
{
    sph_sim *a = make(DAM_3D, FUSED, false, 2), *b = make(DAM_3D, FUSED, false, 2);
    test_levels_switch_live(a, b, "L12", "L13", packed_on);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}
