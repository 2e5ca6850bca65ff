/* Neighbour search: every variant (hash with each sort and table size, grid,
 * brute force) on 1 and 2 threads finds exactly the pairs closer than h that
 * a plain double loop finds, with the same float predicate. Also the cell
 * coordinate (floor, saturation, NaN), the hash (unsigned wrap-around) and the
 * distinct hashes of the 3^dim stencil that the neighbours pass relies on. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "sph_search.h"
#include "test_util.h"

/* ---- cells and hashes ---------------------------------------------------- */

Test(search, cell_coord_is_floor_and_saturates)
{
    cr_assert_eq(sph_cell_coord(-0.5f, 1.0f), -1, "floor, not truncation toward 0");
    cr_assert_eq(sph_cell_coord(0.5f, 1.0f), 0);
    cr_assert_eq(sph_cell_coord(-1.0f, 1.0f), -1);
    cr_assert_eq(sph_cell_coord(1.0f, 1.0f), 1);
    cr_assert_eq(sph_cell_coord(0.0f, 1.0f), 0);
    cr_assert_eq(sph_cell_coord(-0.0f, 1.0f), 0);
    cr_assert_eq(sph_cell_coord(-1e-30f, 1.0f), -1);
    cr_assert_eq(sph_cell_coord(-0.3f, 4.0f), -2, "x = -0.3, h = 0.25: cell -2");
    cr_assert_eq(sph_cell_coord(0.3f, 4.0f), 1);
    cr_assert_eq(sph_cell_coord(-2.5f, 1.0f), -3);
    cr_assert_eq(sph_cell_coord(1e30f, 1.0f), SPH_CELL_LIMIT);
    cr_assert_eq(sph_cell_coord(-1e30f, 1.0f), -SPH_CELL_LIMIT);
    cr_assert_eq(sph_cell_coord(3e9f, 1.0f), SPH_CELL_LIMIT);
    cr_assert_eq(sph_cell_coord(-3e9f, 1.0f), -SPH_CELL_LIMIT);
    cr_assert_eq(sph_cell_coord(1e20f, 1e20f), SPH_CELL_LIMIT, "x / h overflows to +inf");
    cr_assert_eq(sph_cell_coord(INFINITY, 1.0f), SPH_CELL_LIMIT);
    cr_assert_eq(sph_cell_coord(-INFINITY, 1.0f), -SPH_CELL_LIMIT);
    cr_assert_eq(sph_cell_coord(NAN, 1.0f), 0);
    cr_assert_eq(sph_cell_coord(-NAN, 1.0f), 0);
    cr_assert_eq(sph_cell_coord(1.0f, NAN), 0);
    /* just inside the limit stays exact (1e9 is a float) */
    cr_assert_eq(sph_cell_coord(1e9f, 1.0f), 1000000000);
    cr_assert_eq(sph_cell_coord(-1e9f, 1.0f), -1000000000);
    /* every result lies within +-2^30, so c +- 1 never overflows int32 (x = +-2^30
     * itself gives +-2^30, one past SPH_CELL_LIMIT: (float)SPH_CELL_LIMIT rounds
     * to 2^30, so the saturation test lets it through; harmless, within 2^30) */
    const float xs[] = {1073741760.0f, 1073741824.0f, 1073741952.0f, -1073741760.0f, -1073741824.0f,
                        -1073741952.0f, 2147483648.0f, -2147483648.0f, 4e9f, -4e9f};
    for (int i = 0; i < 10; i++) {
        int32_t c = sph_cell_coord(xs[i], 1.0f);
        cr_assert(c >= -(SPH_CELL_LIMIT + 1) && c <= SPH_CELL_LIMIT + 1, "x = %.9g: cell %d beyond 2^30", xs[i], c);
    }
}

/* The hash in uint64_t, reduced mod 2^32: the unsigned wrap-around made explicit. */
static uint32_t hash_ref(int dim, int32_t cx, int32_t cy, int32_t cz)
{
    uint64_t m = 1ull << 32;
    uint64_t x = (uint64_t)((int64_t)cx + (int64_t)m) % m, y = (uint64_t)((int64_t)cy + (int64_t)m) % m,
             z = (uint64_t)((int64_t)cz + (int64_t)m) % m;
    uint64_t h = (x * SPH_HASH_P1) % m + (y * SPH_HASH_P2) % m;
    if (dim == 3) h += (z * SPH_HASH_P3) % m;
    return (uint32_t)(h % m);
}

static const int32_t probe_cells[] = {0, 1, -1, 2, -2, 7, -13, 1000, -1000, 123456, -654321, 271828182,
                                      -314159265, SPH_CELL_LIMIT, -SPH_CELL_LIMIT, SPH_CELL_LIMIT - 1,
                                      -SPH_CELL_LIMIT + 1, SPH_CELL_LIMIT + 1, -SPH_CELL_LIMIT - 1};
#define N_PROBES ((int)(sizeof probe_cells / sizeof probe_cells[0]))

Test(search, hash_wraps_mod_2_32)
{
    for (int a = 0; a < N_PROBES; a++)
        for (int b = 0; b < N_PROBES; b++)
            for (int c = 0; c < N_PROBES; c++) {
                int32_t x = probe_cells[a], y = probe_cells[b], z = probe_cells[c];
                cr_assert_eq(sph_hash_cell(2, x, y, z), hash_ref(2, x, y, 0), "2D (%d, %d)", x, y);
                cr_assert_eq(sph_hash_cell(3, x, y, z), hash_ref(3, x, y, z), "3D (%d, %d, %d)", x, y, z);
            }
    /* the seed's primes, by value */
    cr_assert_eq(sph_hash_cell(3, 1, 0, 0), 15823u);
    cr_assert_eq(sph_hash_cell(3, 0, 1, 0), 9737333u);
    cr_assert_eq(sph_hash_cell(3, 0, 0, 1), 440817757u);
    cr_assert_eq(sph_hash_cell(3, -1, 0, 0), (uint32_t)(4294967296ull - 15823u));
    cr_assert_eq(sph_hash_cell(2, 5, 5, 99), 5u * 15823u + 5u * 9737333u, "2D ignores z");
}

/* The 3^dim cells around any cell have pairwise distinct hashes. */
Test(search, stencil_hashes_are_distinct)
{
    for (int dim = 2; dim <= 3; dim++) {
        const int zr = dim == 3 ? 1 : 0;
        for (int a = 0; a < N_PROBES; a++)
            for (int b = 0; b < N_PROBES; b++)
                for (int c = 0; c < (dim == 3 ? N_PROBES : 1); c++) {
                    int32_t cx = probe_cells[a], cy = probe_cells[b], cz = dim == 3 ? probe_cells[c] : 0;
                    /* sph_cell_coord keeps cells within +-2^30: c +- 1 is a valid int32 */
                    uint32_t h[27];
                    int n = 0;
                    for (int dz = -zr; dz <= zr; dz++)
                        for (int dy = -1; dy <= 1; dy++)
                            for (int dx = -1; dx <= 1; dx++) h[n++] = sph_hash_cell(dim, cx + dx, cy + dy, cz + dz);
                    for (int i = 0; i < n; i++)
                        for (int j = i + 1; j < n; j++)
                            cr_assert_neq(h[i], h[j], "%dD cell (%d, %d, %d): stencil cells %d and %d share hash %u",
                                          dim, cx, cy, cz, i, j, h[i]);
                }
    }
}

/* ---- neighbour lists ----------------------------------------------------- */

/* A geometry (dimension, h, domain, particle count) and positions in it. */
typedef struct setup {
    int dim;
    float h;
    float lo[3], hi[3]; /* the domain: only the grid variant and the particle block use it */
    uint32_t n;
    float *x[3];        /* positions written into pred */
} setup;

static uint64_t rng_state;
static double rnd(void) /* uniform in [0, 1), reproducible */
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (double)((rng_state * 0x2545F4914F6CDD1Dull) >> 11) * (1.0 / 9007199254740992.0);
}

static void setup_init(setup *s, int dim, float h, float lo, float hi, uint32_t n, uint64_t seed)
{
    memset(s, 0, sizeof *s);
    s->dim = dim;
    s->h = h;
    s->n = n;
    for (int d = 0; d < 3; d++) {
        s->lo[d] = lo;
        s->hi[d] = hi;
        s->x[d] = calloc(n, sizeof(float));
        cr_assert_not_null(s->x[d]);
    }
    rng_state = seed ? seed : 1;
}

static void setup_free(setup *s)
{
    for (int d = 0; d < 3; d++) free(s->x[d]);
}

/* The variants: [search] sections. The masks below pick them by index. */
static const char *const variants[] = {
    "[search]\nmethod=brute\n",                                 /* 0 */
    "[search]\nmethod=hash\nsort=counting\n",                   /* 1 */
    "[search]\nmethod=hash\nsort=bitonic\n",                    /* 2 */
    "[search]\nmethod=hash\nsort=qsort\n",                      /* 3 */
    "[search]\nmethod=hash\nsort=counting\ntable_size=1\n",     /* 4: every cell collides */
    "[search]\nmethod=hash\nsort=bitonic\ntable_size=3\n",      /* 5 */
    "[search]\nmethod=hash\nsort=qsort\ntable_size=3\n",        /* 6 */
    "[search]\nmethod=hash\nsort=counting\ntable_size=100003\n", /* 7: more keys than particles */
    "[search]\nmethod=grid\nsort=counting\n",                   /* 8 */
    "[search]\nmethod=grid\nsort=bitonic\n",                    /* 9 */
    /* R: the particle data reordered by cell, then searched cell by cell
     * (rows_reordered; on the dense grid, a stencil row is one run) */
    "[search]\nmethod=grid\nsort=counting\nreorder=on\n",                           /* 10 R */
    "[search]\nmethod=grid\nsort=bitonic\nreorder=on\nvector=off\n",               /* 11 R */
    "[search]\nmethod=hash\nsort=counting\nreorder=on\n",                           /* 12 R */
    "[search]\nmethod=hash\nsort=qsort\nreorder=on\ntable_size=3\nvector=off\n",    /* 13 R */
    /* periodic axes (not in ALL_VARIANTS: the inputs must lie in the domain) */
    "[search]\nmethod=brute\n[domain]\nperiodic=y\n",                               /* 14 */
    "[search]\nmethod=grid\nsort=counting\nreorder=on\n[domain]\nperiodic=y\n",     /* 15 R: rows, y wraps */
    "[search]\nmethod=brute\n[domain]\nperiodic=x z\n",                             /* 16 */
    "[search]\nmethod=grid\nsort=counting\nreorder=on\n[domain]\nperiodic=y z\n",   /* 17 R: rows, y z wrap */
    "[search]\nmethod=brute\n[domain]\nperiodic=y z\n",                             /* 18 */
    "[search]\nmethod=grid\nsort=counting\nreorder=on\n[domain]\nperiodic=x z\n",   /* 19 R: x wraps, cell by cell */
};
#define N_VARIANTS ((int)(sizeof variants / sizeof variants[0]))
#define ALL_VARIANTS ((1u << 14) - 1) /* 0 to 13 */
/* hash with counting sort and qsort and table size N, grid with counting sort */
#define LARGE_VARIANTS ((1u << 1) | (1u << 3) | (1u << 8) | (1u << 10) | (1u << 12))
/* brute force, hash with N keys and with 1, grid */
#define METHOD_VARIANTS ((1u << 0) | (1u << 1) | (1u << 4) | (1u << 8))

/* Describes a variant on one line: "method=hash sort=counting". */
static const char *variant_name(int v, char *buf, size_t cap)
{
    snprintf(buf, cap, "%s", variants[v] + strlen("[search]\n"));
    size_t len = strlen(buf);
    if (len && buf[len - 1] == '\n') buf[--len] = '\0';
    for (char *c = buf; *c; c++)
        if (*c == '\n') *c = ' ';
    return buf;
}

/* Simulations made in this test, by scene text and threads: making one costs
 * milliseconds (kernel tables), so each position set of a geometry reuses
 * them, as the pipeline reuses its buffers from step to step. */
#define CACHE_SIZE 32
static struct cached {
    char ini[1024];
    int threads;
    sph_sim *sim;
} cache[CACHE_SIZE];
static int n_cached;

static void cache_clear(void)
{
    for (int c = 0; c < n_cached; c++) sph_sim_destroy(cache[c].sim);
    n_cached = 0;
}

/* A simulation of variant v for s's geometry, whose pipeline has hash, sort,
 * offsets, neighbours and density (nothing moves; the fluid block is a row of
 * n nodes along x, floor((max - min) / spacing) = n, 1, 1), with s's positions
 * written into pred and the search passes run, as sph_sim_step_pass would. */
static sph_sim *run_search(const setup *s, int v, int threads)
{
    double ext = s->hi[0] - s->lo[0];
    for (int d = 1; d < s->dim; d++) ext = fmin(ext, (double)s->hi[d] - s->lo[d]);
    double sp = ext / (s->n + 1.0);
    char ini[1024];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=%d\neffects=density\n"
             "[domain]\nmin=%.9g %.9g %.9g\nmax=%.9g %.9g %.9g\n"
             "[fluid a]\nmin=%.9g %.9g %.9g\nmax=%.9g %.9g %.9g\nspacing=%.9g\n"
             "[kernels]\nh=%.9g\n%s",
             s->dim, s->lo[0], s->lo[1], s->lo[2], s->hi[0], s->hi[1], s->hi[2], s->lo[0], s->lo[1], s->lo[2],
             s->lo[0] + (s->n + 0.5) * sp, s->lo[1] + 1.5 * sp, s->lo[2] + 1.5 * sp, sp, s->h, variants[v]);
    sph_sim *sim = NULL;
    for (int c = 0; c < n_cached && !sim; c++)
        if (cache[c].threads == threads && strcmp(cache[c].ini, ini) == 0) sim = cache[c].sim;
    if (!sim) {
        cr_assert_lt(n_cached, CACHE_SIZE);
        sim = test_sim(ini, threads);
        cr_assert_eq(sim->n, s->n, "scene made %u particles, want %u", sim->n, s->n);
        cr_assert_eq(sim->def.h, s->h);
        cr_assert(sim->in_pipeline[SPH_PASS_NEIGHBOURS]);
        for (int p = SPH_PASS_HASH; p <= SPH_PASS_OFFSETS; p++) /* brute force alone needs no index */
            cr_assert_eq(sim->in_pipeline[p], sim->def.search != SPH_SEARCH_BRUTE, "%s: pass %s", variants[v],
                         sph_passes[p]->name);
        snprintf(cache[n_cached].ini, sizeof cache[n_cached].ini, "%s", ini);
        cache[n_cached].threads = threads;
        cache[n_cached++].sim = sim;
    }
    for (int d = 0; d < s->dim; d++) memcpy(sim->P.pred[d], s->x[d], s->n * sizeof(float));
#ifdef _OPENMP
    omp_set_num_threads(sim->threads); /* as sph_sim_step_pass does before a pass */
#endif
    const bool R = strstr(variants[v], "reorder=on") != NULL;
    if (R) /* ids = creation order, to map the reordered rows back */
        for (uint32_t i = 0; i < s->n; i++) sim->P.id[i] = i;
    const sph_pass_id passes[] = {SPH_PASS_HASH, SPH_PASS_SORT, SPH_PASS_REORDER, SPH_PASS_OFFSETS, SPH_PASS_NEIGHBOURS};
    for (int p = 0; p < 5; p++) {
        if (passes[p] == SPH_PASS_REORDER && !R) continue;
        if (sim->in_pipeline[passes[p]]) test_run_pass(sim, passes[p]);
    }
    if (R) {
        cr_assert(sim->S.reordered, "reorder did not run");
        /* the rows back in creation order, entries as creation indices (ids) */
        const uint32_t n = s->n, *id = sim->P.id;
        uint32_t *st = calloc(n + 1, 4), *nb = malloc(((size_t)sim->S.nbr_start[n] + 1) * 4), *at = malloc(n * 4);
        cr_assert(st && nb && at);
        for (uint32_t i = 0; i < n; i++) at[id[i]] = i;
        size_t len = 0;
        for (uint32_t o = 0; o < n; o++) {
            uint32_t i = at[o];
            for (uint32_t k = sim->S.nbr_start[i]; k < sim->S.nbr_start[i + 1]; k++) nb[len++] = id[sim->S.nbr[k]];
            st[o + 1] = (uint32_t)len;
        }
        memcpy(sim->S.nbr_start, st, (n + 1) * 4);
        memcpy(sim->S.nbr, nb, len * 4);
        free(st);
        free(nb);
        free(at);
    }
    return sim;
}

/* Neighbour lists as compressed rows. */
typedef struct lists {
    uint32_t n;
    uint32_t *start; /* [n + 1] */
    uint32_t *nbr;
} lists;

/* Reference lists: all j != i with r^2 < h^2, in float as neighbours.c
 * computes it (dx = x_j - x_i; r2 += dx * dx), in increasing j. */
static lists reference_lists(const setup *s)
{
    lists L = {s->n, calloc((size_t)s->n + 1, sizeof(uint32_t)), NULL};
    size_t cap = 1024, len = 0;
    L.nbr = malloc(cap * sizeof(uint32_t));
    cr_assert(L.start && L.nbr);
    const float h2 = s->h * s->h;
    for (uint32_t i = 0; i < s->n; i++) {
        float xi[3] = {0, 0, 0};
        for (int d = 0; d < s->dim; d++) xi[d] = s->x[d][i];
        for (uint32_t j = 0; j < s->n; j++) {
            if (j == i) continue;
            float r2 = 0;
            for (int d = 0; d < s->dim; d++) {
                float dx = s->x[d][j] - xi[d];
                r2 += dx * dx;
            }
            if (!(r2 < h2)) continue;
            if (len == cap) {
                cap *= 2;
                L.nbr = realloc(L.nbr, cap * sizeof(uint32_t));
                cr_assert_not_null(L.nbr);
            }
            L.nbr[len++] = j;
        }
        L.start[i + 1] = (uint32_t)len;
    }
    return L;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* The simulation's lists as sets: each row sorted. */
static lists sorted_lists(const sph_sim *sim)
{
    const sph_search_data *S = &sim->S;
    lists L = {sim->n, malloc(((size_t)sim->n + 1) * sizeof(uint32_t)), NULL};
    size_t len = S->nbr_start[sim->n];
    L.nbr = malloc((len + 1) * sizeof(uint32_t));
    cr_assert(L.start && L.nbr);
    memcpy(L.start, S->nbr_start, ((size_t)sim->n + 1) * sizeof(uint32_t));
    if (len) memcpy(L.nbr, S->nbr, len * sizeof(uint32_t));
    for (uint32_t i = 0; i < sim->n; i++) {
        cr_assert(L.start[i] <= L.start[i + 1], "row %u: start %u > end %u", i, L.start[i], L.start[i + 1]);
        qsort(L.nbr + L.start[i], L.start[i + 1] - L.start[i], sizeof(uint32_t), cmp_u32);
    }
    return L;
}

static void lists_free(lists *L)
{
    free(L->start);
    free(L->nbr);
}

/* Same sets row by row; names the first particle whose set differs and one
 * neighbour missing or extra (a repeated one shows as extra). */
static void check_same_sets(const setup *s, const lists *want, const lists *got, const char *what)
{
    cr_assert_eq(got->start[0], 0, "%s: first row does not start at 0", what);
    for (uint32_t i = 0; i < want->n; i++) {
        uint32_t nw = want->start[i + 1] - want->start[i], ng = got->start[i + 1] - got->start[i];
        const uint32_t *w = want->nbr + want->start[i], *g = got->nbr + got->start[i];
        if (nw == ng && (nw == 0 || memcmp(w, g, nw * sizeof *w) == 0)) continue;
        uint32_t a = 0, b = 0, missing = UINT32_MAX, extra = UINT32_MAX;
        while (a < nw || b < ng) {
            if (b >= ng || (a < nw && w[a] < g[b])) {
                missing = w[a];
                break;
            }
            if (a >= nw || g[b] < w[a]) {
                extra = g[b];
                break;
            }
            a++, b++;
        }
        uint32_t j = missing != UINT32_MAX ? missing : extra;
        cr_assert_fail("%dD h = %.9g, %s: particle %u at (%.9g, %.9g, %.9g) has %u neighbours, want %u; %s %u at "
                       "(%.9g, %.9g, %.9g)",
                       s->dim, s->h, what, i, s->x[0][i], s->x[1][i], s->dim == 3 ? s->x[2][i] : 0.0f, ng, nw,
                       missing != UINT32_MAX ? "missing" : "extra", j, j < s->n ? s->x[0][j] : 0.0f,
                       j < s->n ? s->x[1][j] : 0.0f, j < s->n && s->dim == 3 ? s->x[2][j] : 0.0f);
    }
}

/* Every variant of the mask against the reference sets, on 1 thread; and on
 * 2 if the input has more than SPH_PARALLEL_MIN particles (the passes run
 * smaller inputs on one thread whatever the setting): there the rows must be
 * identical, order included, to those on 1. `set` names the positions in
 * messages. Returns the number of neighbour pairs, for the callers to check
 * that the input is not trivial. */
static size_t check_variants(const setup *s, unsigned mask, const char *set)
{
    lists want = reference_lists(s);
    for (int v = 0; v < N_VARIANTS; v++) {
        if (!(mask & (1u << v))) continue;
        char name[96], what[192];
        variant_name(v, name, sizeof name);
        snprintf(what, sizeof what, "%s, %s, 1 thread", set, name);
        sph_sim *one = run_search(s, v, 1);
        lists got = sorted_lists(one);
        check_same_sets(s, &want, &got, what);
        lists_free(&got);
        if (s->n > SPH_PARALLEL_MIN) {
            sph_sim *two = run_search(s, v, 2);
            cr_assert(memcmp(one->S.nbr_start, two->S.nbr_start, ((size_t)s->n + 1) * sizeof(uint32_t)) == 0 &&
                          memcmp(one->S.nbr, two->S.nbr, (size_t)one->S.nbr_start[s->n] * sizeof(uint32_t)) == 0,
                      "%dD, %s, %s: lists on 2 threads differ from those on 1", s->dim, set, name);
        }
    }
    size_t pairs = want.start[s->n];
    lists_free(&want);
    return pairs;
}

/* Uniform random in [lo, hi)^dim for particles [from, to). */
static void fill_uniform(setup *s, uint32_t from, uint32_t to, double lo, double hi)
{
    for (uint32_t i = from; i < to; i++)
        for (int d = 0; d < s->dim; d++) s->x[d][i] = (float)(lo + (hi - lo) * rnd());
}

/* One geometry per dimension (domain [-1, 1]^dim, h = 0.1, 720 particles)
 * and eight position sets in it, every variant on each:
 *  - uniform in a box of ~30 neighbours per particle;
 *  - the same around the origin (cells -1 and 0: floor, not truncation);
 *  - entirely negative, inside the domain and far outside it (x in [-5, -4.2]
 *    in 2D, [-5, -4.5] in 3D);
 *  - clustered: four tight clumps (sums of uniforms, sd ~ h/3), long key runs;
 *  - all in one cell [0, h)^dim;
 *  - outside the domain: around both of its edges and in clumps at +-1000
 *    (the grid clamps them to its border cells; no pair may be lost);
 *  - coincident: groups of 10 at one point each (r = 0 < h: 9 neighbours each). */
static void scattered_inputs(int dim)
{
    setup s;
    const uint32_t n = 720;
    setup_init(&s, dim, 0.1f, -1.0f, 1.0f, n, 100 + dim);
    const double w = dim == 2 ? 0.8 : 0.5; /* box width for ~30 (2D) / ~23 (3D) neighbours */
    size_t pairs;

    fill_uniform(&s, 0, n, 0.0, w);
    pairs = check_variants(&s, ALL_VARIANTS, "uniform");
    cr_assert_gt(pairs, (size_t)n * 15, "%dD uniform: %zu pairs", dim, pairs);

    fill_uniform(&s, 0, n, -w / 2, w / 2);
    pairs = check_variants(&s, ALL_VARIANTS, "around the origin");
    cr_assert_gt(pairs, (size_t)n * 15, "%dD around the origin: %zu pairs", dim, pairs);

    fill_uniform(&s, 0, n, -0.95, -0.95 + w);
    pairs = check_variants(&s, ALL_VARIANTS, "negative");
    cr_assert_gt(pairs, (size_t)n * 15, "%dD negative: %zu pairs", dim, pairs);

    fill_uniform(&s, 0, n, -5.0, -5.0 + w);
    pairs = check_variants(&s, ALL_VARIANTS, "far negative");
    cr_assert_gt(pairs, (size_t)n * 15, "%dD far negative: %zu pairs", dim, pairs);

    const double centres[4][3] = {{0.2, 0.2, 0.2}, {0.7, -0.3, 0.5}, {-0.5, 0.8, -0.8}, {0.25, 0.22, 0.3}};
    for (uint32_t i = 0; i < n; i++)
        for (int d = 0; d < dim; d++) {
            double g = rnd() + rnd() + rnd() - 1.5; /* sd 0.5 */
            s.x[d][i] = (float)(centres[i % 4][d] + g * 0.066);
        }
    pairs = check_variants(&s, ALL_VARIANTS, "clustered");
    cr_assert_gt(pairs, (size_t)n * 30, "%dD clustered: %zu pairs", dim, pairs);

    fill_uniform(&s, 0, n, 0.001, 0.099);
    pairs = check_variants(&s, ALL_VARIANTS, "one cell");
    cr_assert_gt(pairs, (size_t)n * (n / 3), "%dD one cell: %zu pairs", dim, pairs);

    fill_uniform(&s, 0, n / 3, -1.25, -0.75);
    fill_uniform(&s, n / 3, 2 * n / 3, 0.75, 1.25);
    for (uint32_t i = 2 * n / 3; i < n; i++)
        for (int d = 0; d < dim; d++)
            s.x[d][i] = (float)((i % 2 ? 1000.0 : -1000.0) + (d == 0 ? 0 : i % 4 < 2 ? 3.0 : -7.0) + 0.2 * rnd());
    pairs = check_variants(&s, ALL_VARIANTS, "outside the domain");
    cr_assert_gt(pairs, (size_t)n * 5, "%dD outside the domain: %zu pairs", dim, pairs);

    for (uint32_t i = 0; i < n; i++)
        for (int d = 0; d < dim; d++) s.x[d][i] = -0.9f + (float)(i / 10) * 0.3f + 0.05f * (float)d;
    pairs = check_variants(&s, ALL_VARIANTS, "coincident");
    cr_assert_eq(pairs, (size_t)n * 9, "%dD coincident: %zu pairs, want 9 per particle", dim, pairs);

    setup_free(&s);
    cache_clear();
}

Test(search, scattered_inputs_2d) { scattered_inputs(2); }
Test(search, scattered_inputs_3d) { scattered_inputs(3); }

/* Above SPH_PARALLEL_MIN particles the passes run in parallel (smaller
 * inputs stay on one thread): 2 SPH_PARALLEL_MIN + 808 particles in 2D,
 * SPH_PARALLEL_MIN + 904 in 3D, with h giving ~30 neighbours. Three variants
 * (hash with counting sort and qsort, grid): brute force and tables of 1 and
 * 3 keys are O(N^2) here, and the bitonic sort, whose hundred steps are as
 * many parallel regions (slow when the test processes share the cores), gives
 * qsort's array bit for bit at these sizes on 2 threads (test_sort.c). */
Test(search, large_inputs_on_two_threads)
{
    for (int dim = 2; dim <= 3; dim++) {
        uint32_t n = dim == 2 ? 2 * SPH_PARALLEL_MIN + 808 : SPH_PARALLEL_MIN + 904;
        double box = dim == 2 ? 1.0 : 0.6;
        double h = dim == 2 ? sqrt(30.0 / (3.14159265 * n)) : cbrt(30.0 * box * box * box / (4.18879 * n));
        setup s;
        setup_init(&s, dim, (float)h, 0.0f, 1.0f, n, 91 + dim);
        fill_uniform(&s, 0, n, 0.0, box);
        size_t pairs = check_variants(&s, LARGE_VARIANTS, "uniform");
        cr_assert_gt(pairs, (size_t)s.n * 20, "%dD: %zu pairs", dim, pairs);
        setup_free(&s);
        cache_clear();
    }
}

/* Particles on the cell borders x = k h exactly, a few ulps either side of
 * them, and pairs at distance exactly h (not neighbours: r^2 < h^2 is strict)
 * and just under h (neighbours) along an axis, from particle `from` on. */
static void fill_borders(setup *s, uint32_t from, int kmin)
{
    const float h = s->h;
    uint32_t i = from;
    while (i < s->n) {
        int r = (int)(rnd() * 4);
        float p[3];
        for (int d = 0; d < s->dim; d++) {
            int k = kmin + (int)(rnd() * 8);
            p[d] = (float)k * h;
            int ulps = (int)(rnd() * 7) - 3;
            if (r == 1)
                for (int u = 0; u < abs(ulps); u++) p[d] = nextafterf(p[d], ulps > 0 ? INFINITY : -INFINITY);
        }
        for (int d = 0; d < s->dim; d++) s->x[d][i] = p[d];
        i++;
        if (i < s->n && r >= 2) { /* a partner along one axis: at h exactly (r = 2) or just under (r = 3) */
            int axis = (int)(rnd() * s->dim);
            for (int d = 0; d < s->dim; d++) s->x[d][i] = p[d];
            float q = p[axis] + h;
            if (r == 3) q = nextafterf(q, -INFINITY);
            s->x[axis][i] = q;
            i++;
        }
    }
}

/* The tightest pairs around the cells' real borders, origin[d] + k size[d]
 * (the cells are a hair larger than h, so that rounding cannot put a pair
 * closer than h two cells apart): particles a few ulps either side of a
 * border of the hash's cells or of the grid's, each with a partner along one
 * axis at the largest float distance still under h, above or below. */
static void fill_real_borders(setup *s, const sph_cells *hash, const sph_cells *grid)
{
    const float h2 = s->h * s->h;
    uint32_t i = 0;
    while (i < s->n) {
        const sph_cells *g = rnd() < 0.5 ? hash : grid;
        float p[3];
        for (int d = 0; d < s->dim; d++) {
            int k = 1 + (int)(rnd() * 6);
            p[d] = g->origin[d] + (float)k * g->size[d];
            int ulps = (int)(rnd() * 7) - 3;
            for (int u = 0; u < abs(ulps); u++) p[d] = nextafterf(p[d], ulps > 0 ? INFINITY : -INFINITY);
            s->x[d][i] = p[d];
        }
        i++;
        if (i == s->n) break;
        int axis = (int)(rnd() * s->dim);
        const float away = rnd() < 0.5 ? INFINITY : -INFINITY;
        float q = away > 0 ? p[axis] + s->h : p[axis] - s->h, dq = q - p[axis];
        for (int step = 0; step < 64 && !(dq * dq < h2); step++) { /* toward p until closer than h */
            q = nextafterf(q, p[axis]);
            dq = q - p[axis];
        }
        for (int step = 0; step < 64; step++) { /* away from p while still closer than h */
            float next = nextafterf(q, away), dn = next - p[axis];
            if (!(dn * dn < h2)) break;
            q = next;
        }
        for (int d = 0; d < s->dim; d++) s->x[d][i] = p[d];
        s->x[axis][i] = q;
        i++;
    }
}

/* Cell borders for h = 0.25 (exact in binary) and h = 0.1 (not); with
 * h = 0.25 also four particles, far from the rest, whose lists are checked
 * one by one: 0 and 1 at distance exactly h across the border x = 0.25 (not
 * neighbours), 2 and 3 at 0.25 - 2^-26 (the float below h) across x = 0
 * (neighbours). */
static void cell_borders(int dim)
{
    const float hs[2] = {0.25f, 0.1f};
    for (int t = 0; t < 2; t++) {
        setup s;
        setup_init(&s, dim, hs[t], -4.0f * hs[t], 6.0f * hs[t], 600, 51 + dim + 10 * t);
        const unsigned mask = ALL_VARIANTS;
        fill_borders(&s, 0, -3);
        size_t pairs = check_variants(&s, mask, "cell borders");
        cr_assert_gt(pairs, (size_t)s.n, "%dD h = %g: %zu pairs", dim, hs[t], pairs);
        const sph_cells hash_cells = run_search(&s, 1, 1)->S.cells, grid_cells = run_search(&s, 8, 1)->S.cells;
        fill_real_borders(&s, &hash_cells, &grid_cells);
        pairs = check_variants(&s, mask, "real cell borders");
        cr_assert_geq(pairs, (size_t)s.n, "%dD h = %g: %zu pairs", dim, hs[t], pairs);
        if (t == 1) {
            setup_free(&s);
            cache_clear();
            continue;
        }
        const float x[4] = {0.0f, 0.25f, -0x1p-26f, 0.25f - 0x1p-25f};
        const float y[4] = {3.0f, 3.0f, -3.0f, -3.0f}; /* the others are within [-0.75, 1.25] */
        for (int i = 0; i < 4; i++) {
            s.x[0][i] = x[i];
            s.x[1][i] = y[i];
            if (dim == 3) s.x[2][i] = 0.5f;
        }
        check_variants(&s, mask, "pairs at h");
        for (int v = 0; v < N_VARIANTS; v++) {
            if (!(mask & (1u << v))) continue;
            char name[96];
            variant_name(v, name, sizeof name);
            const sph_sim *sim = run_search(&s, v, 1);
            const uint32_t *st = sim->S.nbr_start, *nb = sim->S.nbr;
            cr_assert_eq(st[1] - st[0], 0, "%dD %s: distance exactly h is no neighbour", dim, name);
            cr_assert_eq(st[2] - st[1], 0, "%dD %s: distance exactly h is no neighbour", dim, name);
            cr_assert_eq(st[3] - st[2], 1, "%dD %s: distance just under h is a neighbour", dim, name);
            cr_assert_eq(nb[st[2]], 3);
            cr_assert_eq(st[4] - st[3], 1, "%dD %s: distance just under h is a neighbour", dim, name);
            cr_assert_eq(nb[st[3]], 2);
        }
        setup_free(&s);
        cache_clear();
    }
}

Test(search, cell_borders_and_pairs_at_h_2d) { cell_borders(2); }
Test(search, cell_borders_and_pairs_at_h_3d) { cell_borders(3); }

/* Two particles closer than h, p0 and p1 in 2D, domain [lo, hi]^2: brute
 * force, hash (table sizes N and 1) and grid list each as the other's
 * neighbour. */
static void check_pair(float h, float lo, float hi, const float p0[2], const float p1[2])
{
    setup s;
    setup_init(&s, 2, h, lo, hi, 2, 1);
    for (int d = 0; d < 2; d++) {
        s.x[d][0] = p0[d];
        s.x[d][1] = p1[d];
    }
    float dx = p1[0] - p0[0], dy = p1[1] - p0[1];
    cr_assert(dx * dx + dy * dy < h * h, "the pair must be closer than h in float");
    for (int v = 0; v < N_VARIANTS; v++) {
        if (!(METHOD_VARIANTS & (1u << v))) continue;
        char name[96];
        variant_name(v, name, sizeof name);
        const sph_sim *sim = run_search(&s, v, 1);
        const uint32_t *st = sim->S.nbr_start;
        cr_assert(st[1] - st[0] == 1 && st[2] - st[1] == 1,
                  "%s, h = %.9g: (%.9g, %.9g) and (%.9g, %.9g) at distance %.9g < h are not neighbours (%u and %u "
                  "neighbours)",
                  name, h, p0[0], p0[1], p1[0], p1[1], sqrtf(dx * dx + dy * dy), st[1] - st[0], st[2] - st[1]);
    }
    setup_free(&s);
    cache_clear();
}

/* With cells of exactly h, the grid cell floor(fl(fl(y - lo) * fl(1/h)))
 * rounded y = 0.49999997 (just under the border y = 0.5) with lo = -0.4,
 * h = 0.1 up to (0.9 * 10 =) 9.0: grid row 9, while y = 0.39999998 (just
 * under 0.4) stayed in row 7. The pair, 0.099999994 < h apart, was two rows
 * apart and the grid search missed it. */
Test(search, pair_under_h_across_a_rounded_grid_border)
{
    const float p0[2] = {-0.2f, 0x1.fffffep-2f}; /* (-0.2, nextafterf(0.5f, 0)) */
    const float p1[2] = {-0.2f, 0x1.999998p-2f}; /* (-0.2, nextafterf(0.4f, 0)) */
    check_pair(0.1f, -0.4f, 0.6f, p0, p1);
}

/* With cells of exactly h, fl(1/0.06f) = 16.666668 is rounded up, so
 * x = 0.0599999949 (the float under h = 0.06) got x * inv_h = 1.0: cell 1,
 * while x = -1e-9 is in cell -1. The pair, 0.0599999949 < h apart, was two
 * cells apart and the hash search missed it (any x in about (-4e-9, 0) did;
 * likewise h = 0.03). */
Test(search, pair_under_h_across_the_origin_with_h_rounded)
{
    const float p0[2] = {-1e-9f, 0.3f};
    const float p1[2] = {0x1.eb851cp-5f, 0.3f}; /* nextafterf(0.06f, 0) = 0.0599999949 */
    check_pair(0.06f, -1.0f, 1.0f, p0, p1);
}

/* Periodic axes against brute force with the minimum image: the grid's rows
 * when y (and z) wrap, cell by cell when x wraps; a third of the points
 * within 0.12 of a periodic boundary, so many pairs cross it. */
static void periodic_case(int dim, int ref, int v, const char *what)
{
    setup s;
    const uint32_t n = 700;
    setup_init(&s, dim, 0.1f, -1.0f, 1.0f, n, 7 + dim);
    for (uint32_t i = 0; i < n; i++)
        for (int d = 0; d < dim; d++) {
            double u = rnd();
            float x = (float)(-1.0 + 2.0 * u);
            if (i % 3 == 0) x = (float)(u < 0.5 ? -1.0 + 0.12 * rnd() : 1.0 - 0.12 * rnd());
            if (x >= 1.0f) x = nextafterf(1.0f, 0);
            s.x[d][i] = x;
        }
    sph_sim *a = run_search(&s, ref, 1);
    lists want = sorted_lists(a);
    sph_sim *b = run_search(&s, v, 1);
    lists got = sorted_lists(b);
    check_same_sets(&s, &want, &got, what);
    cr_assert_gt(want.start[n], (size_t)n, "%zu pairs", (size_t)want.start[n]);
    lists_free(&want);
    lists_free(&got);
    setup_free(&s);
    cache_clear();
}
Test(search, periodic_rows_and_cells_equal_brute_force)
{
    periodic_case(2, 14, 15, "2d periodic y");
    periodic_case(3, 18, 17, "3d periodic y z");
    periodic_case(3, 16, 19, "3d periodic x z");
}
