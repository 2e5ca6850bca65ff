/* The GL backend's two sorts against the CPU's (src/gpu/gpu_passes.c): the
 * counting sort with its prefix sum (the default, [search] sort = counting)
 * and the bitonic network with its short steps in shared memory
 * (shaders/gpu_bitonic_local.comp), at sizes that are and are not powers of
 * two, with several long stages (N up to 10,000: P = 16,384, 2 WG = 256), and
 * with few keys (long runs of equal keys, where the order is the index's).
 * The entries the device's hash pass wrote are read back before its sort and
 * sorted on the CPU: the device's order must be that order exactly. */
#define _GNU_SOURCE /* setenv */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu.h"
#include "sph_search.h"
#include "test_gl_util.h"
#include "test_util.h"


/* A 2D block of side particles a side (jittered, so cells fill unevenly). */
static void check_sort(int side, const char *sort, const char *table)
{
    char ini[1024];
    double spacing = 1.0 / side;
    snprintf(ini, sizeof ini,
             "[scene]\nname=gl sort\ndimension=2\neffects=gravity pressure walls\njitter=0.3\n"
             "[domain]\nmin=0 0\nmax=1.2 1.2\n[kernels]\nh=%.9g\n[time]\ndt=0.0001\n"
             "[search]\nsort=%s\ntable_size=%s\n"
             "[fluid a]\nmin=0 0\nmax=1 1\nspacing=%.9g\n",
             2 * spacing, sort, table, spacing);
    sph_scene_def def = test_scene(ini);
    def.backend = SPH_BACKEND_GL;
    sph_sim *sim;
    sph_error err;
    cr_assert_eq(sph_sim_create(&def, 1, &sim, &err), SPH_ERR_OK, "%s", err.msg);
    cr_assert(sim->in_pipeline[SPH_PASS_SORT]);
    const uint32_t n = sim->n;
    sph_pass_id p;
    do p = sph_sim_step_pass(sim);
    while (p != SPH_PASS_HASH && p != SPH_PASS_COUNT);
    cr_assert_eq(p, SPH_PASS_HASH);
    sph_sim_sync(sim, SPH_SYNC_INDEX);
    sph_entry *ref = malloc(n * sizeof *ref);
    cr_assert(ref);
    memcpy(ref, sim->S.entries, n * sizeof *ref);
    sph_sort_qsort(ref, n);
    cr_assert_eq(sph_sim_step_pass(sim), SPH_PASS_SORT);
    sph_sim_sync(sim, SPH_SYNC_INDEX);
    uint32_t keys = sim->S.table_size, runs = 0;
    for (uint32_t i = 0; i < n; i++) {
        const sph_entry a = sim->S.entries[i], b = ref[i];
        cr_assert(a.key == b.key && a.hash == b.hash && a.index == b.index,
                  "%s sort, %u particles, %u keys: entry %u is (%u, %u, %u), the CPU's (%u, %u, %u)", sort, n, keys,
                  i, a.key, a.hash, a.index, b.key, b.hash, b.index);
        runs += i > 0 && a.key == ref[i - 1].key;
    }
    cr_assert(runs > 0, "some keys repeat, so the order within a run is tested");
    free(ref);
    sph_sim_destroy(sim);
}

Test(gl_sort, both_sorts_give_the_cpu_order, .timeout = 300)
{
    need_gl();
    /* 8 x 8 = 64 (one padded block), 16 x 16 = 256 (exactly one block),
     * 37 x 37 = 1369, 100 x 100 = 10,000 (several long stages) */
    const int sides[] = {8, 16, 37, 100};
    const char *sorts[] = {"counting", "bitonic"};
    const char *tables[] = {"7", "0"};
    for (size_t s = 0; s < sizeof sides / sizeof *sides; s++)
        for (int k = 0; k < 2; k++)
            for (int t = 0; t < 2; t++) check_sort(sides[s], sorts[k], tables[t]);
}

Test(gl_sort, counting_is_the_default)
{
    sph_scene_def def = test_scene("[scene]\nname=d\ndimension=2\n[fluid a]\nmin=0 0\nmax=0.1 0.1\nspacing=0.05\n");
    cr_assert_eq(def.sort, SPH_SORT_COUNTING);
}
