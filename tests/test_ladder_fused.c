/* The ladder's levels past L7 (docs/performance.md, "Past L7"): each must
 * give L7's neighbour sets and L7's state, within the bench's tolerances
 * (positions 1e-4 m, velocities 1e-3 m/s, densities 1e-3 relative), after
 * some steps of a 2D and a 3D dam break with walls. No speed is asserted. */
#define _DEFAULT_SOURCE /* mincore */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "test_util.h"

/* L7's keys; each level past it adds its own. */
#define L7_KEYS "[search]\nmethod = grid\nsort = counting\nreorder = on\nvector = on\n"

#define DAM_2D                                                                                                   \
    "[scene]\ndimension = 2\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0\nmax = 3 1.5\n"     \
    "[fluid column]\nmin = 0 0\nmax = 1.2 1\nspacing = 0.01\n[physics]\nstiffness = 1000\n"                       \
    "viscosity = 0.002\n[kernels]\nh = 0.02\n[time]\ndt = 0.0002\ncfl = 0\n"
#define DAM_3D                                                                                                   \
    "[scene]\ndimension = 3\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0 0\n"                \
    "max = 0.8 0.4 0.4\n[fluid column]\nmin = 0 0 0\nmax = 0.3 0.3 0.4\nspacing = 0.02\n[physics]\n"           \
    "stiffness = 1000\nviscosity = 0.002\n[kernels]\nh = 0.04\n[time]\ndt = 0.0005\ncfl = 0\n"

static sph_sim *make(const char *dam, const char *extra)
{
    char ini[2048];
    snprintf(ini, sizeof ini, "%s%s%s", dam, L7_KEYS, extra);
    return test_sim(ini, 2);
}

/* The slot of each id (data are stored in cell order). */
static uint32_t *slots_by_id(const sph_sim *sim)
{
    uint32_t *at = malloc(sim->n * sizeof *at);
    cr_assert_not_null(at);
    for (uint32_t i = 0; i < sim->n; i++) at[sim->P.id[i]] = i;
    return at;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* The neighbours within h of the particle with this id, as ids, sorted;
 * returns the count. Verlet lists (L10) hold more entries, out to
 * h (1 + skin): only those within h, by the search's own float test, count. */
static uint32_t set_of(const sph_sim *sim, const uint32_t *at, uint32_t id, uint32_t *out, uint32_t cap)
{
    uint32_t i = at[id], n = 0;
    const float h2 = sim->def.h * sim->def.h;
    for (uint32_t e = sim->S.nbr_start[i]; e < sim->S.nbr_start[i + 1] && n < cap; e++) {
        const uint32_t j = sim->S.nbr[e];
        float r2 = 0.0f;
        for (int d = 0; d < sim->dim; d++) {
            const float dx = sim->P.pred[d][j] - sim->P.pred[d][i];
            r2 += dx * dx;
        }
        if (r2 < h2) out[n++] = sim->P.id[j];
    }
    qsort(out, n, sizeof *out, cmp_u32);
    return n;
}

/* Steps both simulations and compares them: neighbour sets after the first
 * step (and after every fourth step where `every`: the steps that keep
 * Verlet lists are the ones to check), the state after all. */
static void compare_sets(sph_sim *a, sph_sim *b, int steps, bool every, const char *what)
{
    cr_assert_eq(a->n, b->n);
    const int dim = a->dim;
    uint32_t sa[512], sb[512];
    for (int s = 0; s < steps; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
        if (s > 0 && (!every || s % 4 != 3)) continue;
        uint32_t *ata = slots_by_id(a), *atb = slots_by_id(b);
        for (uint32_t id = 0; id < a->n; id++) {
            uint32_t na = set_of(a, ata, id, sa, 512), nb = set_of(b, atb, id, sb, 512);
            if (s == 0) { /* from the same state: the same sets */
                cr_assert_eq(na, nb, "%s: particle %u has %u neighbours on L7, %u here", what, id, na, nb);
                cr_assert(memcmp(sa, sb, na * sizeof *sa) == 0, "%s: particle %u's neighbour set differs", what, id);
                continue;
            }
            /* later, the states differ by rounding (about 1e-7 m after a few
             * steps): a pair within 1e-4 h of r = h, where the dam's lattice
             * puts many, is rounding's call */
            uint32_t x = 0, y = 0;
            while (x < na || y < nb) {
                uint32_t other;
                if (y >= nb || (x < na && sa[x] < sb[y])) other = sa[x++];
                else if (x >= na || sb[y] < sa[x]) other = sb[y++];
                else {
                    x++, y++;
                    continue;
                }
                double r2 = 0;
                for (int d = 0; d < dim; d++) {
                    double dd = (double)a->P.pred[d][ata[id]] - a->P.pred[d][ata[other]];
                    r2 += dd * dd;
                }
                cr_assert(fabs(sqrt(r2) - a->def.h) <= 1e-4 * a->def.h,
                          "%s, step %d: particle %u and %u are neighbours in one run only, %g h apart", what, s + 1,
                          id, other, sqrt(r2) / a->def.h);
            }
        }
        free(ata);
        free(atb);
    }
    uint32_t *ata = slots_by_id(a), *atb = slots_by_id(b);
    double dx = 0, dv = 0, drho = 0;
    for (uint32_t id = 0; id < a->n; id++) {
        uint32_t i = ata[id], j = atb[id];
        for (int d = 0; d < dim; d++) {
            dx = fmax(dx, fabs((double)a->P.pos[d][i] - b->P.pos[d][j]));
            dv = fmax(dv, fabs((double)a->P.vel[d][i] - b->P.vel[d][j]));
        }
        drho = fmax(drho, fabs((double)a->P.rho[i] - b->P.rho[j]) / a->def.rest_density);
    }
    free(ata);
    free(atb);
    cr_assert(dx <= 1e-4, "%s: positions differ by %g m", what, dx);
    cr_assert(dv <= 1e-3, "%s: velocities differ by %g m/s", what, dv);
    cr_assert(drho <= 1e-3, "%s: densities differ by %g (relative)", what, drho);
    /* the dam has moved: the comparison is not of two states at rest */
    double vmax = 0;
    for (uint32_t i = 0; i < a->n; i++)
        for (int d = 0; d < dim; d++) vmax = fmax(vmax, fabs((double)a->P.vel[d][i]));
    cr_assert(vmax > 0.05, "%s: fastest particle %g m/s after %d steps", what, vmax, steps);
}

static void compare(sph_sim *a, sph_sim *b, int steps, const char *what) { compare_sets(a, b, steps, false, what); }

/* L8: the pressure force and viscosity in one walk of the lists. */
#define L8_KEYS "[compute]\nfuse_forces = on\n"

Test(ladder_fused, same_as_l7_2d)
{
    sph_sim *a = make(DAM_2D, ""), *b = make(DAM_2D, L8_KEYS);
    compare(a, b, 40, "2D dam, L8");
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

Test(ladder_fused, same_as_l7_3d)
{
    sph_sim *a = make(DAM_3D, ""), *b = make(DAM_3D, L8_KEYS);
    compare(a, b, 40, "3D dam, L8");
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* L9: L8 with the first thread's lists built in place. */
#define L9_KEYS "[compute]\nfuse_forces = on\n[search]\nlists_in_place = on\n"

Test(ladder_fused, l9_same_as_l7_2d)
{
    sph_sim *a = make(DAM_2D, ""), *b = make(DAM_2D, L9_KEYS);
    compare(a, b, 40, "2D dam, L9");
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

Test(ladder_fused, l9_same_as_l7_3d)
{
    sph_sim *a = make(DAM_3D, ""), *b = make(DAM_3D, L9_KEYS);
    compare(a, b, 40, "3D dam, L9");
    /* the first thread kept no buffer of its own: its rows were written in place */
    cr_assert_null(b->S.tbuf[0], "thread 0 built its lists in a buffer of its own");
    cr_assert_not_null(a->S.tbuf[0]);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* L18's key: with lists_in_place and two threads, lists_resident = on keeps
 * the pages of the second thread's buffer after it is copied into the joined
 * lists (off hands them back): the same state to the bit, and mincore(2)
 * finds the buffer's pages resident after a build with the key, not without. */
#define L18_KEYS L9_KEYS "lists_resident = on\n"

static size_t resident_pages(const void *p, size_t bytes)
{
    const size_t page = (size_t)sysconf(_SC_PAGESIZE);
    const uintptr_t a = ((uintptr_t)p + page - 1) & ~(uintptr_t)(page - 1), b = ((uintptr_t)p + bytes) & ~(uintptr_t)(page - 1);
    if (b <= a) return 0;
    const size_t n = (b - a) / page;
    unsigned char *v = calloc(n, 1);
    cr_assert_not_null(v);
    cr_assert_eq(mincore((void *)a, b - a, v), 0, "mincore");
    size_t in = 0;
    for (size_t k = 0; k < n; k++) in += v[k] & 1;
    free(v);
    return in;
}

Test(ladder_fused, l18_keeps_the_copied_pages_same_state_3d)
{
    sph_sim *a = make(DAM_3D, L9_KEYS), *b = make(DAM_3D, L18_KEYS);
    cr_assert_gt(a->n, 4096, "one thread only below SPH_PARALLEL_MIN");
    for (int s = 0; s < 3; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
    }
    cr_assert_eq(a->S.n_threads, 2);
    const size_t bytes_a = a->S.tcap[1] * sizeof(uint32_t), bytes_b = b->S.tcap[1] * sizeof(uint32_t);
    const size_t in_a = resident_pages(a->S.tbuf[1], bytes_a), in_b = resident_pages(b->S.tbuf[1], bytes_b);
    const size_t page = (size_t)sysconf(_SC_PAGESIZE);
    cr_expect_gt(bytes_b / page, 8, "a buffer of %zu bytes: too small to tell", bytes_b);
    cr_expect_lt(in_a, bytes_a / page / 4, "off: %zu of %zu pages of the copied buffer still resident", in_a,
                 bytes_a / page);
    cr_expect_gt(in_b, bytes_b / page / 2, "on: %zu of %zu pages of the copied buffer resident", in_b,
                 bytes_b / page);
    compare(a, b, 30, "3D dam, L18's pages kept");
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* Wall particles: the viscosity reads their mirrored velocities (vel_visc). */
Test(ladder_fused, same_as_l7_wall_particles)
{
    const char *walls = "[domain]\nwall_model = particles\n";
    char ka[256], kb[256];
    snprintf(ka, sizeof ka, "%s", walls);
    snprintf(kb, sizeof kb, "%s%s", walls, L8_KEYS);
    sph_sim *a = make(DAM_2D, ka), *b = make(DAM_2D, kb);
    compare(a, b, 40, "2D dam with wall particles, L8");
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* With the key on, the pressure_force pass writes acc_v itself (else the
 * comparisons above would pass on two unfused runs): acc_v is poisoned
 * before a step and must be whole once pressure_force has run. */
Test(ladder_fused, pressure_force_writes_viscosity)
{
    sph_sim *b = make(DAM_3D, L8_KEYS);
    for (int s = 0; s < 5; s++) sph_sim_step(b);
#if !defined(__AVX512F__)
    cr_skip_test("built without AVX-512: the fused loop does not exist, the passes run apart");
#endif
    for (int d = 0; d < 3; d++)
        for (uint32_t i = 0; i < b->n; i++) b->P.acc_v[d][i] = NAN;
    sph_pass_id p;
    do p = sph_sim_step_pass(b);
    while (p != SPH_PASS_PRESSURE_FORCE && p != SPH_PASS_COUNT);
    cr_assert_eq(p, SPH_PASS_PRESSURE_FORCE);
    uint32_t moving = 0;
    for (uint32_t i = 0; i < b->n; i++)
        for (int d = 0; d < 3; d++) {
            cr_assert(isfinite(b->P.acc_v[d][i]), "acc_v[%d] of %u not written by pressure_force", d, i);
            moving += b->P.acc_v[d][i] != 0.0f;
        }
    cr_assert_gt(moving, b->n / 2, "the viscous acceleration is 0 almost everywhere");
    sph_sim_destroy(b);
}

/* L10: L9 with Verlet lists, built out to h (1 + skin) and kept while no
 * particle has moved skin h / 2. The sets within h must be L7's at every
 * step, kept or built, and the lists must really be kept on most steps (else
 * the comparison would pass on lists rebuilt every step) and rebuilt once the
 * dam has moved (a small skin: 0.02 h, so 0.4 mm in 3D). */
#define L10_KEYS(skin) "[compute]\nfuse_forces = on\n[search]\nlists_in_place = on\nskin = " skin "\n"

Test(ladder_fused, l10_same_as_l7_2d)
{
    sph_sim *a = make(DAM_2D, ""), *b = make(DAM_2D, L10_KEYS("0.1"));
    compare_sets(a, b, 40, true, "2D dam, L10");
    cr_expect_lt(b->S.builds, 10, "the lists were built %llu times in 40 steps", (unsigned long long)b->S.builds);
    cr_expect_geq(a->S.builds, 40, "without a skin the lists are built every step");
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

Test(ladder_fused, l10_same_as_l7_3d)
{
    sph_sim *a = make(DAM_3D, ""), *b = make(DAM_3D, L10_KEYS("0.02"));
    compare_sets(a, b, 40, true, "3D dam, L10 (skin 0.02 h)");
    const unsigned long long built = b->S.builds;
    cr_expect(built > 1 && built < 30, "the lists were built %llu times in 40 steps (kept, and rebuilt)", built);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* A kept step moves no particle in memory: the ids stay where they were. */
Test(ladder_fused, l10_kept_step_leaves_the_order)
{
    sph_sim *b = make(DAM_3D, L10_KEYS("0.5"));
    sph_sim_step(b);
    uint32_t *before = malloc(b->n * sizeof *before);
    cr_assert_not_null(before);
    memcpy(before, b->P.id, b->n * sizeof *before);
    const uint64_t built = b->S.builds;
    sph_sim_step(b);
    cr_expect(b->S.lists_kept, "a skin of h / 2 keeps the lists on the second step");
    cr_expect_eq(b->S.builds, built, "built again on the second step");
    cr_expect(memcmp(before, b->P.id, b->n * sizeof *before) == 0, "a kept step reordered the particles");
    free(before);
    sph_sim_destroy(b);
}

/* A pass that walks the lists without skipping pairs beyond h is refused
 * with a skin (XSPH would average over the margin's pairs), naming the key,
 * its line and the pass; without a skin the same scene loads. */
Test(ladder_fused, l10_refuses_a_pass_that_counts_the_margin)
{
    char ini[2048];
    snprintf(ini, sizeof ini, "%s%s[physics]\nxsph = 0.5\n[search]\nskin = 0.05\n", DAM_2D, L7_KEYS);
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    cr_assert_eq(sph_scene_load_string(ini, "skin.ini", &def, &err), SPH_ERR_OK, "%s", err.msg);
    cr_assert_eq(sph_scene_validate(&def, &err), SPH_ERR_SCENE);
    cr_expect(strstr(err.msg, "skin.ini:") && strstr(err.msg, "skin = 0.05") && strstr(err.msg, "xsph"), "%s",
              err.msg);
    def.skin = 0.0f;
    cr_expect_eq(sph_scene_validate(&def, &err), SPH_ERR_OK, "%s", err.msg);
}
