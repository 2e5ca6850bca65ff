/* [search] cell_batch (ladder level L15): with vector_avx2 = on, after a
 * reorder and with no periodic axis, the search tests the particles of one
 * cell together against each 8-candidate vector of the cell's stencil runs
 * and packs each row to 16-bit offsets 8 at a time. The rows must be L14's
 * entry for entry (the same words in the joined lists, the same row starts),
 * so the state is L14's to the bit after every step: a 3D and a 2D dam, a
 * block of 125 particles, blocks whose edges cut cells, cells of more
 * particles than one batch holds, plain 32-bit lists, wide compact rows, the
 * hash search, a periodic axis (where the key falls back to L14's scan), one
 * thread and two, and a switch from L14 to L15 and back in mid-run.
 * [search] wide_batch (L17, with AVX-512) tests 16 candidates at a time
 * instead of 8: the same cases, the same rows, the same state to the bit. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "sph_compare.h"
#include "sph_levels.h"
#include "test_levels_util.h"
#include "test_util.h"

/* L14's keys with method, compact_lists and cell_batch as asked (L15: grid, on, on). */
#define L14_KEYS                                                                                                 \
    "[search]\nmethod = %s\nsort = counting\nreorder = on\nvector = on\nlists_in_place = on\nskin = 0.05\n"    \
    "compact_lists = %s\nvector_avx2 = on\ncell_batch = %s\nwide_batch = %s\n[compute]\nfuse_forces = on\n"       \
    "packed_records = on\nuniform_mass = on\n"

enum { GRID = 0, HASH = 1, PLAIN = 2, WIDE = 4 }; /* WIDE: the batch with wide_batch = on (L17's search) */
#define DAM_3D TEST_LEVELS_DAM_3D
#define DAM_2D TEST_LEVELS_DAM_2D

/* 125 particles (5 x 5 x 5), h = 2 spacings: few, thin cells. */
#define BLOCK_SMALL                                                                                              \
    "[scene]\ndimension = 3\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0 0\nmax = 0.3 0.3 0.3\n" \
    "[fluid block]\nmin = 0.05 0.05 0\nmax = 0.15 0.15 0.1\nspacing = 0.02\n[physics]\nstiffness = 1000\n"      \
    "viscosity = 0.002\n[kernels]\nh = 0.04\n[time]\ndt = 0.0005\ncfl = 0\n"

/* Edges that cut cells (0.31 and 0.27 are no multiple of the cell's 0.042),
 * a second block apart, in 3D. */
#define BLOCKS_PARTIAL                                                                                           \
    "[scene]\ndimension = 3\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0 0\nmax = 0.8 0.4 0.4\n" \
    "[fluid column]\nmin = 0.013 0 0\nmax = 0.31 0.27 0.23\nspacing = 0.02\n"                                    \
    "[fluid drop]\nmin = 0.5 0.1 0.25\nmax = 0.61 0.19 0.33\nspacing = 0.02\n[physics]\nstiffness = 1000\n"     \
    "viscosity = 0.002\n[kernels]\nh = 0.04\n[time]\ndt = 0.0005\ncfl = 0\n"

/* h = 4 spacings: cells of about 70 particles in 3D, more than one batch of 32. */
#define FULL_CELLS_3D                                                                                            \
    "[scene]\ndimension = 3\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0 0\nmax = 0.5 0.3 0.3\n" \
    "[fluid column]\nmin = 0 0 0\nmax = 0.2 0.2 0.2\nspacing = 0.02\n[physics]\nstiffness = 1000\n"            \
    "viscosity = 0.002\n[kernels]\nh = 0.08\n[time]\ndt = 0.0005\ncfl = 0\n"

/* 2D, h = 7 spacings: cells of about 50 particles. */
#define FULL_CELLS_2D                                                                                            \
    "[scene]\ndimension = 2\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0\nmax = 1.2 0.6\n" \
    "[fluid column]\nmin = 0 0\nmax = 0.4 0.4\nspacing = 0.01\n[physics]\nstiffness = 1000\n"                 \
    "viscosity = 0.002\n[kernels]\nh = 0.07\n[time]\ndt = 0.0002\ncfl = 0\n"

#define STRIP_2D TEST_LEVELS_STRIP_2D

/* Periodic along x: the key falls back to L14's scan. */
#define PERIODIC_2D                                                                                              \
    "[scene]\ndimension = 2\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0\nmax = 0.6 0.4\n" \
    "periodic = x\n[fluid layer]\nmin = 0 0\nmax = 0.6 0.2\nspacing = 0.01\n[physics]\nstiffness = 1000\n"    \
    "viscosity = 0.002\n[kernels]\nh = 0.02\n[time]\ndt = 0.0002\ncfl = 0\n"

static sph_sim *make(const char *scene, int variant, bool batch, int threads)
{
    char keys[512], ini[2048];
    snprintf(keys, sizeof keys, L14_KEYS, variant & HASH ? "hash" : "grid", variant & PLAIN ? "off" : "on",
             batch ? "on" : "off", batch && (variant & WIDE) ? "on" : "off");
    snprintf(ini, sizeof ini, "%s%s", scene, keys);
    return test_sim(ini, threads);
}

/* The joined lists of b are a's to the word, and so are the row starts. */
static void same_lists(const sph_sim *a, const sph_sim *b, const char *what, int step)
{
    cr_assert_eq(a->n, b->n);
    cr_assert_eq(a->S.compact, b->S.compact);
    cr_assert(memcmp(a->S.nbr_start, b->S.nbr_start, (a->n + 1) * sizeof *a->S.nbr_start) == 0,
              "%s: the row starts differ from L14's after step %d", what, step);
    const size_t bytes = a->S.nbr_start[a->n] * (a->S.compact ? sizeof(uint16_t) : sizeof(uint32_t));
    cr_assert(memcmp(a->S.nbr, b->S.nbr, bytes) == 0, "%s: the lists differ from L14's after step %d", what, step);
}

/* L14 and L15 from the same start: the same lists and the same state to the
 * bit after every one of `steps` steps, and the ladder's check of L15
 * against L14. */
static void as_l14(const char *scene, int variant, int steps, int threads, const char *what)
{
    sph_sim *a = make(scene, variant, false, threads), *b = make(scene, variant, true, threads);
    cr_assert(a->n >= 100, "%s: %u particles", what, a->n);
    for (int s = 0; s < steps; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
        same_lists(a, b, what, s + 1);
        const char *diff = test_levels_first_difference(a, b);
        cr_assert_null(diff, "%s: %s differs from L14's after step %d", what, diff, s + 1);
    }
    cr_assert(!a->alarm.raised && !b->alarm.raised, "%s: the watchdog stopped a run", what);
    sph_compare_result r;
    sph_error err;
    cr_assert_eq(sph_sim_validate(b, &sph_levels[sph_level_find("L14")], 4, &r, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_eq(r.sets_differ, 0, "%s: %u neighbour sets differ from L14's", what, r.sets_differ);
    cr_expect(r.dx == 0, "%s: positions differ from L14's by %g m after 4 more steps", what, r.dx);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

Test(cell_batch, same_lists_and_state_as_l14_3d) { as_l14(DAM_3D, GRID, 40, 2, "3D dam"); }
Test(cell_batch, same_lists_and_state_as_l14_2d) { as_l14(DAM_2D, GRID, 30, 2, "2D dam"); }
Test(cell_batch, small_block_3d) { as_l14(BLOCK_SMALL, GRID, 20, 1, "125 particles"); }
Test(cell_batch, blocks_with_partial_cells_3d) { as_l14(BLOCKS_PARTIAL, GRID, 20, 2, "blocks cutting cells"); }
Test(cell_batch, cells_fuller_than_a_batch_3d) { as_l14(FULL_CELLS_3D, GRID, 10, 2, "h = 4 spacings"); }
Test(cell_batch, cells_fuller_than_a_batch_2d) { as_l14(FULL_CELLS_2D, GRID, 10, 1, "2D, h = 7 spacings"); }
Test(cell_batch, plain_lists_3d) { as_l14(DAM_3D, GRID | PLAIN, 20, 2, "3D dam, 32-bit lists"); }
Test(cell_batch, wide_rows_2d) { as_l14(STRIP_2D, GRID, 3, 2, "strip with wide rows"); }
Test(cell_batch, hash_search_3d) { as_l14(DAM_3D, HASH, 10, 2, "3D dam, hash"); }
Test(cell_batch, periodic_axis_falls_back_2d) { as_l14(PERIODIC_2D, GRID, 20, 2, "2D, periodic x"); }

Test(cell_batch, wide_same_lists_and_state_as_l14_3d) { as_l14(DAM_3D, GRID | WIDE, 40, 2, "3D dam, 16 wide"); }
Test(cell_batch, wide_same_lists_and_state_as_l14_2d) { as_l14(DAM_2D, GRID | WIDE, 30, 2, "2D dam, 16 wide"); }
Test(cell_batch, wide_small_block_3d) { as_l14(BLOCK_SMALL, GRID | WIDE, 20, 1, "125 particles, 16 wide"); }
Test(cell_batch, wide_blocks_with_partial_cells_3d)
{
    as_l14(BLOCKS_PARTIAL, GRID | WIDE, 20, 2, "blocks cutting cells, 16 wide");
}
Test(cell_batch, wide_cells_fuller_than_a_batch_3d) { as_l14(FULL_CELLS_3D, GRID | WIDE, 10, 2, "h = 4 s, 16 wide"); }
Test(cell_batch, wide_cells_fuller_than_a_batch_2d) { as_l14(FULL_CELLS_2D, GRID | WIDE, 10, 1, "h = 7 s, 16 wide"); }
Test(cell_batch, wide_plain_lists_3d) { as_l14(DAM_3D, GRID | PLAIN | WIDE, 20, 2, "32-bit lists, 16 wide"); }
Test(cell_batch, wide_rows_of_a_strip_2d) { as_l14(STRIP_2D, GRID | WIDE, 3, 2, "strip with wide rows, 16 wide"); }
Test(cell_batch, wide_periodic_axis_falls_back_2d) { as_l14(PERIODIC_2D, GRID | WIDE, 20, 2, "periodic x, 16 wide"); }

/* The strip has wide rows indeed (else wide_rows_2d tests nothing of them). */
Test(cell_batch, strip_has_wide_rows)
{
    sph_sim *b = make(STRIP_2D, GRID, true, 1);
    sph_sim_step(b);
    uint32_t wide = 0;
    const uint16_t *w = (const uint16_t *)(const void *)b->S.nbr;
    for (uint32_t i = 0; i < b->n; i++)
        wide += b->S.nbr_start[i + 1] > b->S.nbr_start[i] && w[b->S.nbr_start[i]] == SPH_NBR_WIDE;
    cr_expect_gt(wide, 0, "no wide row in the strip");
    sph_sim_destroy(b);
}

Test(cell_batch, same_on_one_and_two_threads_3d)
{
    sph_sim *a = make(DAM_3D, GRID, true, 1), *b = make(DAM_3D, GRID, true, 2);
    test_levels_same_after(a, b, 30, "one thread against two");
}

/* L14 switched to L15 in mid-run (sph_sim_reconfigure, as the window does) and
 * back: the run goes on as L14's would, to the bit. */
static bool batch_on(const sph_scene_def *def) { return def->cell_batch == SPH_ON; }

Test(cell_batch, switched_live_from_l14)
{
    sph_sim *a = make(DAM_3D, GRID, false, 2), *b = make(DAM_3D, GRID, false, 2);
    test_levels_switch_live(a, b, "L14", "L15", batch_on);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* L16 switched to L17 (the search 16 wide) in mid-run and back: to the bit. */
static bool wide_on(const sph_scene_def *def) { return def->wide_batch == SPH_ON; }

Test(cell_batch, wide_switched_live_from_l16)
{
    char ini[2048];
    snprintf(ini, sizeof ini, "%s", DAM_3D);
    sph_sim *a = NULL, *b = NULL;
    sph_error err;
    for (int k = 0; k < 2; k++) {
        sph_scene_def def = test_scene(ini);
        cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L16")], &def, &err), SPH_ERR_OK, "%s", err.msg);
        sph_sim **s = k ? &b : &a;
        cr_assert_eq(sph_sim_create(&def, 2, s, &err), SPH_ERR_OK, "%s", err.msg);
    }
    test_levels_switch_live(a, b, "L16", "L17", wide_on);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}
