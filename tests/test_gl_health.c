/* The hash health on the GL backend (shaders/gpu_health.comp,
 * src/gpu/gpu_health.c): the same figures as the CPU's sph_sim_hash_health
 * (src/core/sph_hash_health.c) on the same positions, exactly (they are
 * counts), read back as 20 bytes instead of the positions. On llvmpipe
 * through EGL surfaceless; skipped where there is no EGL display. */
#define _GNU_SOURCE /* setenv */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu.h"
#include "sph_hash_health.h"
#include "test_gl_util.h"
#include "test_util.h"

static const char *scene_2d =
    "[scene]\nname=gl health 2d\ndimension=2\neffects=gravity pressure viscosity walls\njitter=0.2\n"
    "[domain]\nmin=-0.3 -0.2\nmax=0.3 0.4\nwall_damping=0.3\n[physics]\nviscosity=0.005\n"
    "[kernels]\nh=0.04\n[time]\ndt=0.001\ncfl=0.4\n[search]\nmethod=hash\n"
    "[fluid a]\nmin=-0.3 -0.2\nmax=0.0 0.1\nspacing=0.02\nvelocity=0.5 0\n";

static const char *scene_3d =
    "[scene]\nname=gl health 3d\ndimension=3\neffects=gravity pressure viscosity walls\njitter=0.2\n"
    "[domain]\nmin=-0.2 -0.2 -0.2\nmax=0.2 0.2 0.2\nwall_damping=0.3\n[physics]\nviscosity=0.005\n"
    "[kernels]\nh=0.05\n[time]\ndt=0.001\ncfl=0.4\n[search]\nmethod=hash\n"
    "[fluid a]\nmin=-0.2 -0.2 -0.2\nmax=0.0 0.0 0.0\nspacing=0.025\nvelocity=0 0 0.3\n";

static sph_sim *make(const char *ini, const char *set, bool gl)
{
    sph_scene_def def = test_scene(ini);
    sph_error err;
    if (set) cr_assert_eq(sph_scene_set(&def, set, &err), SPH_ERR_OK, "--set %s: %s", set, err.msg);
    def.backend = gl ? SPH_BACKEND_GL : SPH_BACKEND_CPU;
    sph_sim *sim;
    cr_assert_eq(sph_sim_create(&def, 1, &sim, &err), SPH_ERR_OK, "%s", err.msg);
    return sim;
}

/* Every figure but the neighbour count, exactly. */
static void expect_same(const sph_hash_health *dev, const sph_hash_health *cpu, const char *what)
{
    cr_assert(dev->has_table && cpu->has_table, "%s: no table (%s)", what, cpu->why ? cpu->why : "");
    cr_expect_eq(dev->table_size, cpu->table_size, "%s: table size", what);
    cr_expect_eq(dev->particles, cpu->particles, "%s: particles", what);
    cr_expect(dev->load_factor == cpu->load_factor, "%s: load %g, CPU %g", what, dev->load_factor, cpu->load_factor);
    cr_expect_eq(dev->occupied, cpu->occupied, "%s: occupied %u, CPU %u", what, dev->occupied, cpu->occupied);
    cr_expect_eq(dev->colliding, cpu->colliding, "%s: colliding %u, CPU %u", what, dev->colliding, cpu->colliding);
    cr_expect_eq(dev->longest_run, cpu->longest_run, "%s: longest run %u, CPU %u", what, dev->longest_run,
                 cpu->longest_run);
    cr_expect(dev->candidates == cpu->candidates, "%s: candidates %.9g, CPU %.9g", what, dev->candidates,
              cpu->candidates);
    cr_expect(isnan(dev->neighbours) && isnan(dev->share), "%s: the device counts no neighbours", what);
    if (getenv("SPH_TEST_VERBOSE"))
        fprintf(stderr, "%-28s %u keys, %u occupied, %u colliding, run %u, %.3f candidates\n", what, dev->table_size,
                dev->occupied, dev->colliding, dev->longest_run, dev->candidates);
}

/* The GL and CPU simulations of one scene: before any step (the same
 * positions), then after three steps each, the CPU one given the GL one's
 * positions and predicted positions (the state the device counted). */
static void check(const char *ini, const char *set, const char *what, bool collide)
{
    need_gl();
    sph_sim *g = make(ini, set, true), *c = make(ini, set, false);
    sph_hash_health dev, cpu;
    cr_assert(sph_gpu_hash_health(g, &dev), "%s: no device hash health", what);
    cr_assert(sph_sim_hash_health(c, false, &cpu));
    expect_same(&dev, &cpu, what);
    for (int s = 0; s < 3; s++) {
        sph_sim_step(g);
        sph_sim_step(c);
    }
    /* on the stale host copy sph_sim_hash_health counts on the device */
    uint64_t before = sph_gpu_downloaded_bytes(g);
    cr_assert(sph_sim_hash_health(g, false, &dev));
    cr_expect_eq(sph_gpu_downloaded_bytes(g) - before, 20, "%s: %llu bytes read back, not 20", what,
                 (unsigned long long)(sph_gpu_downloaded_bytes(g) - before));
    sph_sim_sync(g, SPH_SYNC_ALL);
    for (int d = 0; d < c->dim; d++) {
        memcpy(c->P.pos[d], g->P.pos[d], c->n * sizeof(float));
        memcpy(c->P.pred[d], g->P.pred[d], c->n * sizeof(float));
    }
    cr_assert(sph_sim_hash_health(c, false, &cpu));
    expect_same(&dev, &cpu, what);
    if (collide) cr_expect(dev.colliding > 0 && dev.longest_run > 1, "%s: no collision to count", what);
    sph_sim_destroy(c);
    sph_sim_destroy(g);
}

Test(gl_health, same_as_cpu_2d)
{
    check(scene_2d, NULL, "2d", false);
    check(scene_2d, "search.table_size=61", "2d, 61 keys", true);
    check(scene_2d, "domain.periodic=x", "2d periodic x", false);
}

Test(gl_health, same_as_cpu_3d)
{
    check(scene_3d, NULL, "3d", false);
    check(scene_3d, "search.table_size=7", "3d, 7 keys", true);
}

/* A dense grid has no hash table: nothing computed, nothing read back. */
Test(gl_health, grid_has_no_table)
{
    need_gl();
    sph_sim *g = make(scene_2d, "search.method=grid", true);
    sph_sim_step(g);
    sph_hash_health hh;
    cr_expect(!sph_gpu_hash_health(g, &hh));
    uint64_t before = sph_gpu_downloaded_bytes(g);
    cr_assert(sph_sim_hash_health(g, false, &hh));
    cr_expect(!hh.has_table && hh.why);
    cr_expect_eq(sph_gpu_downloaded_bytes(g) - before, 0);
    sph_sim_destroy(g);
}
