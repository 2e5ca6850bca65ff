/* Hash health (src/core/sph_hash_health.c): exact figures on hand-placed
 * particles with a forced collision, the load and occupied keys of a lattice,
 * candidates and true neighbours against a brute-force count, "no hash table"
 * for the dense grid, the HUD's rows and the ms-per-step window. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sph_hash_health.h"
#include "sph_overlay.h"
#include "sph_search.h"
#include "test_util.h"

/* Brute force: for every particle, the candidates of its 3^dim cell walk
 * (every particle whose key is a stencil cell's key, counted once per such
 * cell) and the true neighbours (same cell hash, not itself, r^2 < h^2). */
static void brute_counts(const sph_sim *sim, float *const x[3], uint64_t *cand, uint64_t *within)
{
    const sph_cells *g = &sim->S.cells;
    const uint32_t T = sim->S.table_size, n = sim->n;
    const int dim = sim->dim;
    const float h2 = sim->def.h * sim->def.h;
    *cand = *within = 0;
    for (uint32_t i = 0; i < n; i++) {
        int32_t ci[3] = {0, 0, 0};
        for (int d = 0; d < dim; d++) ci[d] = sph_cells_coord(g, d, x[d][i]);
        for (int dz = dim == 3 ? -1 : 0; dz <= (dim == 3 ? 1 : 0); dz++)
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int32_t c[3] = {ci[0] + dx, ci[1] + dy, ci[2] + dz}; /* unbounded axes: no edge */
                    uint32_t hc = sph_hash_cell(dim, c[0], c[1], c[2]);
                    for (uint32_t j = 0; j < n; j++) {
                        int32_t cj[3] = {0, 0, 0};
                        for (int d = 0; d < dim; d++) cj[d] = sph_cells_coord(g, d, x[d][j]);
                        uint32_t hj = sph_hash_cell(dim, cj[0], cj[1], cj[2]);
                        if (hj % T != hc % T) continue;
                        (*cand)++;
                        if (hj != hc || j == i) continue;
                        float r2 = 0;
                        for (int d = 0; d < dim; d++) r2 += (x[d][j] - x[d][i]) * (x[d][j] - x[d][i]);
                        *within += r2 < h2;
                    }
                }
    }
}

static void place(sph_sim *sim, uint32_t i, float x, float y)
{
    sim->P.pos[0][i] = x;
    sim->P.pos[1][i] = y;
    /* moved by hand: the index and the lists the start built are not the particles' any more */
    sim->fields_fresh &= ~(SPH_RES_ENTRIES | SPH_RES_START | SPH_RES_LISTS);
}

/* Four particles, h = 1: two in cell (0,0), one in (1,0), one in (5,5). With
 * table_size = 15823 (the first prime), hash(1,0) = 15823 has key 0, as
 * hash(0,0) = 0 does: one key holds two cells. */
Test(hash_health, forced_collision_gives_exact_figures)
{
    sph_sim *sim = test_sim("[scene]\ndimension=2\neffects=density\n[domain]\nmin=-10 -10\nmax=10 10\n"
                            "[fluid a]\nmin=0 0\nmax=2 2\nspacing=1\n[kernels]\nh=1\n"
                            "[search]\nmethod=hash\ntable_size=15823\n",
                            1);
    cr_assert_eq(sim->n, 4);
    cr_assert_eq(sim->S.table_size, 15823u);
    uint32_t k55 = sph_hash_cell(2, 5, 5, 0) % 15823u;
    cr_assert_neq(k55, 0u, "cell (5,5) must not share key 0 for this test");
    place(sim, 0, 0.2f, 0.3f);
    place(sim, 1, 0.7f, 0.6f);
    place(sim, 2, 1.5f, 0.5f);
    place(sim, 3, 5.5f, 5.5f);
    sph_hash_health hh;
    cr_assert(sph_sim_hash_health(sim, true, &hh));
    cr_assert(hh.has_table);
    cr_expect_eq(hh.table_size, 15823u);
    cr_expect_eq(hh.particles, 4u);
    cr_expect_eq(hh.load_factor, 4.0 / 15823.0);
    cr_expect_eq(hh.occupied, 2u, "keys 0 and key(5,5)");
    cr_expect_eq(hh.colliding, 1u, "key 0 holds cells (0,0) and (1,0)");
    cr_expect_eq(hh.longest_run, 3u);
    /* With T = P1 a cell's key moves with y only, except where the unsigned
     * hash wraps (x < 0): (0,0), (1,0), (2,0) all have key 0, (-1,0) not;
     * (4,5), (5,5), (6,5) share (5,5)'s key. Each stencil cell reads its
     * key's whole run. Particles 0, 1: (0,0) + (1,0) = 3 + 3; particle 2:
     * (0,0) + (1,0) + (2,0) = 9; particle 3: its row, 3 x 1. */
    uint64_t cand, within;
    brute_counts(sim, sim->P.pos, &cand, &within);
    cr_expect_eq(cand, 6u + 6u + 9u + 3u, "brute force: %llu candidates", (unsigned long long)cand);
    cr_expect_eq(hh.candidates, 24.0 / 4.0);
    /* true neighbours: 0-1 (r^2 = 0.34) twice; 2 is in another cell but within h of 1
     * (r^2 = 0.64 + 0.01): 1-2 twice; 0-2 r^2 = 1.69 + 0.04: no */
    cr_expect_eq(within, 4u);
    cr_expect_eq(hh.neighbours, 1.0);
    cr_expect_eq(hh.share, 4.0 / 24.0);
    sph_sim_destroy(sim);
}

/* A lattice at h/2 spacing over 10 x 10 cells: 4 particles a cell. */
Test(hash_health, lattice_load_and_occupied_keys)
{
    const char *base = "[scene]\ndimension=2\neffects=density\n[domain]\nmin=0 0\nmax=10 10\n"
                       "[fluid a]\nmin=0 0\nmax=10 10\nspacing=0.5\n[kernels]\nh=1\n";
    char ini[512];
    snprintf(ini, sizeof ini, "%s[search]\nmethod=hash\ntable_size=100003\n", base);
    sph_sim *sim = test_sim(ini, 1);
    cr_assert_eq(sim->n, 400u);
    sph_hash_health hh;
    cr_assert(sph_sim_hash_health(sim, false, &hh));
    cr_expect_eq(hh.occupied, 100u, "one key per cell: %u", hh.occupied);
    cr_expect_eq(hh.colliding, 0u);
    cr_expect_eq(hh.longest_run, 4u);
    cr_expect_eq(hh.load_factor, 400.0 / 100003.0);
    /* the start's measurement built the lists (every particle has 8 neighbours within h inside the lattice,
     * fewer at its edges): counted from them, against the candidates */
    cr_expect(hh.share > 0 && hh.share <= 1 && hh.neighbours > 4 && hh.neighbours <= 8, "share %g, neighbours %g",
              hh.share, hh.neighbours);
    sph_sim_destroy(sim);
    /* the default table: one key per particle, load 1; keys now shared */
    snprintf(ini, sizeof ini, "%s[search]\nmethod=hash\n", base);
    sim = test_sim(ini, 1);
    cr_assert(sph_sim_hash_health(sim, false, &hh));
    cr_expect_eq(hh.table_size, 400u);
    cr_expect_eq(hh.load_factor, 1.0);
    /* the keys of the 100 cells, each cell counted once: a key of two or more cells collides */
    uint32_t cells_of[400] = {0};
    for (int cx = 0; cx < 10; cx++)
        for (int cy = 0; cy < 10; cy++) cells_of[sph_hash_cell(2, cx, cy, 0) % 400u]++;
    uint32_t occupied = 0, colliding = 0, longest = 0;
    for (int k = 0; k < 400; k++) {
        occupied += cells_of[k] > 0;
        colliding += cells_of[k] > 1;
        if (4 * cells_of[k] > longest) longest = 4 * cells_of[k];
    }
    cr_expect_eq(hh.occupied, occupied);
    cr_expect_eq(hh.colliding, colliding);
    cr_expect_gt(colliding, 0u, "the test wants a shared key");
    cr_expect_eq(hh.longest_run, longest);
    sph_sim_destroy(sim);
}

/* A column after some steps of a dam break (scattered, not a lattice): the
 * candidates and the share of true neighbours match the brute force, with a
 * small table (many collisions), the default one, in 2D and 3D, counted by
 * the walk and read from the neighbour lists. */
static void versus_brute(int dim, const char *search)
{
    char ini[768];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=%d\neffects=gravity pressure walls\n[domain]\nmin=0 0%s\nmax=0.6 0.4%s\n"
             "[fluid a]\nmin=0 0%s\nmax=0.2 0.2%s\nspacing=0.02\n[kernels]\nh=0.04\n%s",
             dim, dim == 3 ? " 0" : "", dim == 3 ? " 0.2" : "", dim == 3 ? " 0" : "", dim == 3 ? " 0.1" : "", search);
    sph_sim *sim = test_sim(ini, 1);
    for (int s = 0; s < 20; s++) sph_sim_step(sim);
    cr_assert(!sim->alarm.raised);
    uint64_t cand, within;
    brute_counts(sim, sim->P.pred, &cand, &within);
    sph_hash_health walk, lists;
    cr_assert(sph_sim_hash_health(sim, false, &lists));
    cr_expect_eq(lists.candidates, (double)cand / sim->n, "%dD %s: %g vs brute %g", dim, search, lists.candidates,
                 (double)cand / sim->n);
    cr_expect_eq(lists.share, (double)within / (double)cand, "%dD %s: share %g vs brute %g", dim, search,
                 lists.share, (double)within / (double)cand);
    /* the walk's own count, without the lists */
    sim->timing[SPH_PASS_NEIGHBOURS].calls = 0;
    cr_assert(sph_sim_hash_health(sim, true, &walk));
    cr_expect_eq(walk.share, lists.share);
    cr_expect_eq(walk.neighbours, (double)within / sim->n);
    cr_expect_gt(walk.share, 0.0);
    cr_expect_lt(walk.share, 1.0);
    sph_sim_destroy(sim);
}

Test(hash_health, candidates_and_share_match_brute_force_2d)
{
    versus_brute(2, "[search]\nmethod=hash\n");
    versus_brute(2, "[search]\nmethod=hash\ntable_size=7\nsort=qsort\n");
    versus_brute(2, "[search]\nmethod=hash\nreorder=on\n");
}

Test(hash_health, candidates_and_share_match_brute_force_3d)
{
    versus_brute(3, "[search]\nmethod=hash\n");
    versus_brute(3, "[search]\nmethod=hash\ntable_size=13\nsort=none\n");
}

Test(hash_health, dense_grid_and_brute_have_no_table)
{
    const char *kinds[] = {"grid", "brute"};
    for (int k = 0; k < 2; k++) {
        char ini[512];
        snprintf(ini, sizeof ini,
                 "[scene]\ndimension=2\neffects=density\n[domain]\nmin=0 0\nmax=4 4\n"
                 "[fluid a]\nmin=0 0\nmax=2 2\nspacing=0.5\n[kernels]\nh=1\n[search]\nmethod=%s\n",
                 kinds[k]);
        sph_sim *sim = test_sim(ini, 1);
        sph_hash_health hh;
        cr_assert(sph_sim_hash_health(sim, true, &hh));
        cr_expect(!hh.has_table);
        cr_expect(hh.why && strstr(hh.why, "no hash table") && strstr(hh.why, kinds[k]), "%s: %s", kinds[k], hh.why);
        char lines[12][128];
        sph_hud_info info = {.steps_per_s = -1, .last_pass = -1};
        int n = sph_hud_lines(sim, &info, lines, 12);
        bool said = false;
        for (int i = 0; i < n; i++) said |= strstr(lines[i], "no hash table") != NULL;
        cr_expect(said, "%s: the HUD says there is no hash table", kinds[k]);
        sph_sim_destroy(sim);
    }
}

/* The HUD: the hash rows always; ms per step (the window's mean), steps/s
 * and frames/s with the timings. */
Test(hash_health, hud_rows_and_step_window)
{
    sph_sim *sim = test_sim("[scene]\ndimension=2\neffects=density\n[domain]\nmin=0 0\nmax=10 10\n"
                            "[fluid a]\nmin=0 0\nmax=10 10\nspacing=0.5\n[kernels]\nh=1\n",
                            1);
    /* the step window's bookkeeping (no step: no mean; one step: its passes'
     * sum), whatever the times are; nothing here depends on speed */
    int window = -1;
    cr_expect(isnan(sph_sim_step_ms(sim, &window)));
    cr_expect_eq(window, 0);
    sph_sim_step(sim);
    double sum = 0;
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (sim->in_pipeline[p]) sum += sim->timing[p].last_ms;
    cr_expect_eq(sph_sim_step_ms(sim, &window), sum, "one step: the sum of its passes");
    cr_expect_eq(window, 1);
    for (int s = 0; s < 70; s++) sph_sim_step(sim);
    double ms = sph_sim_step_ms(sim, &window);
    cr_expect_eq(window, SPH_STEP_WINDOW);
    cr_expect(ms > 0);
    char lines[12][128];
    sph_hud_info info = {.steps_per_s = 123, .last_pass = -1, .frames_per_s = 59.6};
    int n = sph_hud_lines(sim, &info, lines, 12);
    bool hash = false, search = false, timing = false;
    for (int i = 0; i < n; i++) {
        hash |= strncmp(lines[i], "hash: 400 keys, load 1.00, ", 27) == 0;
        search |= strncmp(lines[i], "search: ", 8) == 0 && strstr(lines[i], "candidates per particle") &&
                  strstr(lines[i], "% within h");
        timing |= strstr(lines[i], "ms/step (median of 60)") && strstr(lines[i], "123 steps/s") &&
                  strstr(lines[i], "60 frames/s");
    }
    cr_expect(hash && search && timing, "HUD rows missing (%d lines, first hash row wanted)", n);
    sph_sim_reset_timings(sim);
    cr_expect(isnan(sph_sim_step_ms(sim, NULL)));
    sph_sim_destroy(sim);
}

/* The window's ms per step is the median of its window, not the mean: one stalled step among 60 does not move
 * it. Arithmetic on values written into the window by hand; no step is run and nothing is timed. */
Test(hash_health, step_window_reports_the_median)
{
    sph_sim *sim = test_sim("[scene]\ndimension=2\neffects=density\n[domain]\nmin=0 0\nmax=1 1\n"
                            "[fluid a]\nmin=0 0\nmax=1 1\nspacing=0.25\n[kernels]\nh=0.5\n",
                            1);
    for (int s = 0; s < SPH_STEP_WINDOW; s++) sim->step_ms[s] = s == 7 ? 100.0 : 1.0 + 0.001 * s;
    sim->step_ms_count = SPH_STEP_WINDOW;
    const double median = sph_sim_step_ms(sim, NULL); /* of 59 values 1.000..1.059 without 1.007, and 100 */
    cr_expect_float_eq(median, 1.0305, 1e-12, "%g (the mean would be %g)", median, (59 * 1.0 + 0.001 * 1763 + 100) / 60);
    sph_sim_destroy(sim);
}
