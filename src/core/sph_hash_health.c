/* Hash health (see sph_hash_health.h). The figures are recomputed from the
 * positions rather than read from the start table, so that they are the same
 * on every backend (the GL backend keeps the table on the device) and before
 * the first step (`sphlab check`); they use the hash pass's own cells, hash
 * and key, so they describe the table that pass builds. */
#include "sph_hash_health.h"

#include <math.h>
#include <stdlib.h>

#include "sph_search.h"

/* a % d without a division (Lemire, Kaser and Kurz 2019, "Faster remainder
 * by direct computation", section 3, 32-bit operands with a 64-bit M): the
 * walk takes 9 or 27 remainders per cell, and a division costs about as much
 * as the rest of the work. M = 2^64 / d rounded up; d = 1 gives M = 0 and a
 * remainder of 0, as it should. */
typedef struct health_mod {
    uint64_t m;
    uint32_t d;
} health_mod;

static inline uint32_t health_rem(health_mod f, uint32_t a)
{
    return (uint32_t)(((unsigned __int128)(f.m * a) * f.d) >> 64);
}

/* The positions the hash pass saw: the predicted ones once it has run. */
static float *const *health_positions(const sph_sim *sim)
{
    if (sim->P.pred[0] && sim->timing[SPH_PASS_HASH].calls > 0) return sim->P.pred;
    return sim->P.pos;
}

static void health_cell(const sph_cells *g, int dim, float *const x[3], uint32_t i, int32_t c[3])
{
    c[0] = c[1] = c[2] = 0;
    for (int d = 0; d < dim; d++) c[d] = sph_cells_coord(g, d, x[d][i]);
}

/* The hashes and keys of the 3^dim stencil's cells around c, without those
 * past the edge of a bounded axis, as the neighbours pass walks them. */
typedef struct stencil {
    int n;
    uint32_t key[27], hash[27];
} stencil;

static void health_stencil(const sph_cells *g, int dim, health_mod T, const int32_t c[3], stencil *s)
{
    const int zr = dim == 3 ? 1 : 0;
    int32_t cell[3] = {0, 0, 0};
    s->n = 0;
    for (int dz = -zr; dz <= zr; dz++) {
        if (dim == 3 && !sph_cells_step(g, 2, c[2], dz, &cell[2])) continue;
        for (int dy = -1; dy <= 1; dy++) {
            if (!sph_cells_step(g, 1, c[1], dy, &cell[1])) continue;
            for (int dx = -1; dx <= 1; dx++) {
                if (!sph_cells_step(g, 0, c[0], dx, &cell[0])) continue;
                uint32_t h = sph_cells_hash(g, cell);
                s->hash[s->n] = h;
                s->key[s->n++] = health_rem(T, h);
            }
        }
    }
}

/* the walk counts the true neighbours itself: it needs the particles by key */
static bool order_wanted(bool count_neighbours, bool lists)
{
    return count_neighbours && !lists;
}

static const char *health_no_table(const sph_sim *sim)
{
    if (!sim->in_pipeline[SPH_PASS_HASH]) {
        if (sim->def.search == SPH_SEARCH_BRUTE) return "no hash table (search = brute: all pairs)";
        return "no hash table (no effect needs neighbours)";
    }
    if (sim->S.cells.dense) return "no hash table (search = grid: a dense grid, one key per cell)";
    return NULL;
}

bool sph_sim_hash_health(const sph_sim *sim, bool count_neighbours, sph_hash_health *out)
{
    *out = (sph_hash_health){.has_table = false, .neighbours = NAN, .share = NAN};
    out->why = health_no_table(sim);
    if (out->why) return true;
    const uint32_t n = sim->n, T = sim->S.table_size ? sim->S.table_size : 1;
    const int dim = sim->dim;
    const sph_cells *g = &sim->S.cells;
    /* the lists as the neighbours pass left them: not while the counting sort has borrowed their buffer, nor
     * after a reorder, until the pass has run again (sph_sim_step_pass keeps fields_fresh) */
    const bool lists = !sim->backend && sim->in_pipeline[SPH_PASS_NEIGHBOURS] && sim->S.nbr_start &&
                       (sim->fields_fresh & SPH_RES_LISTS) && (sim->fields_fresh & SPH_RES_ENTRIES);
    /* a backend counts on the device rather than download the positions;
     * a fresh host copy is counted here */
    sph_backend *b = sim->backend;
    if (!count_neighbours && b && b->hash_health && (b->stale & (SPH_BIT(POS) | SPH_BIT(PRED))) &&
        b->hash_health(b, sim, out))
        return true;
    sph_sim_sync(sim, SPH_BIT(POS) | SPH_BIT(PRED));
    float *const *x = health_positions(sim);
    out->has_table = true;
    out->table_size = T;
    out->particles = n;
    out->load_factor = (double)n / T;
    /* per key: its particle count, the hash of its first particle and
     * whether another hash joined it (one record, one cache line touched);
     * with count_neighbours, a counting sort of the particles by key, so
     * that a key's particles can be read */
    typedef struct key_rec {
        uint32_t count, first, mixed;
    } key_rec;
    const health_mod Tm = {UINT64_MAX / T + 1, T};
    key_rec *rec = calloc((size_t)T + 1, sizeof *rec);
    uint32_t *hash = order_wanted(count_neighbours, lists) ? malloc((size_t)(n ? n : 1) * sizeof *hash) : NULL;
    uint32_t *order = hash ? malloc((size_t)(n ? n : 1) * sizeof *order) : NULL;
    uint32_t *start = hash ? malloc(((size_t)T + 1) * sizeof *start) : NULL;
    if (!rec || (order_wanted(count_neighbours, lists) && !(hash && order && start))) {
        free(rec), free(hash), free(order), free(start);
        *out = (sph_hash_health){.why = "out of memory for the hash health", .neighbours = NAN, .share = NAN};
        return false;
    }
    for (uint32_t i = 0; i < n; i++) {
        int32_t c[3];
        health_cell(g, dim, x, i, c);
        uint32_t h = sph_cells_hash(g, c);
        key_rec *r = &rec[health_rem(Tm, h)];
        if (hash) hash[i] = h;
        if (!r->count++) r->first = h;
        else r->mixed |= h != r->first;
    }
    for (uint32_t k = 0; k < T; k++) {
        if (!rec[k].count) continue;
        out->occupied++;
        out->colliding += rec[k].mixed;
        if (rec[k].count > out->longest_run) out->longest_run = rec[k].count;
    }
    /* candidates depend only on the cell: consecutive particles of one cell
     * (the usual order: blocks are laid out row by row, and sorted after a
     * reorder) reuse the previous sum */
    uint64_t cand = 0, within = 0;
    uint64_t cell_cand = 0;
    int32_t prev[3] = {0, 0, 0};
    bool have = false;
    stencil s;
    if (order) { /* start[k]: the first of key k's particles in order[] */
        uint32_t sum = 0;
        for (uint32_t k = 0; k < T; k++) {
            start[k] = sum;
            sum += rec[k].count;
        }
        start[T] = sum;
        for (uint32_t i = 0; i < n; i++) order[start[health_rem(Tm, hash[i])]++] = i;
        for (uint32_t k = T; k > 0; k--) start[k] = start[k - 1]; /* each had advanced to the next key's start */
        start[0] = 0;
    }
    const float h2 = sim->def.h * sim->def.h;
    for (uint32_t i = 0; i < n; i++) {
        int32_t c[3];
        health_cell(g, dim, x, i, c);
        bool same = have && c[0] == prev[0] && c[1] == prev[1] && c[2] == prev[2];
        if (!same || order) health_stencil(g, dim, Tm, c, &s);
        if (!same) {
            cell_cand = 0;
            for (int k = 0; k < s.n; k++)
                cell_cand += rec[s.key[k]].count;
            prev[0] = c[0], prev[1] = c[1], prev[2] = c[2];
            have = true;
        }
        cand += cell_cand;
        if (!order) continue;
        /* the neighbours pass's test: same cell hash, not itself, r^2 < h^2
         * summed in the same order (x, y, then z) */
        for (int k = 0; k < s.n; k++)
            for (uint32_t e = start[s.key[k]]; e < start[s.key[k] + 1]; e++) {
                uint32_t j = order[e];
                if (hash[j] != s.hash[k] || j == i) continue;
                float r2 = 0;
                for (int d = 0; d < dim; d++) {
                    float dx = sph_min_image(x[d][j] - x[d][i], sim->period[d], sim->inv_period[d]);
                    r2 += dx * dx;
                }
                within += r2 < h2;
            }
    }
    if (lists) within = sim->S.nbr_start[n];
    out->candidates = n ? (double)cand / n : 0;
    if (lists || order) {
        out->neighbours = n ? (double)within / n : 0;
        out->share = cand ? (double)within / (double)cand : 0;
    }
    free(rec), free(hash), free(order), free(start);
    return true;
}
