/* Pass: spatial hash. Each particle gets the seed's (index, hash, key) entry
 * for the cell of its predicted position: cell = floor(x / size) with size a
 * hair above h (see sph_cells), hash from the seed's primes in unsigned
 * arithmetic, key = hash % table_size. The grid variant numbers the cells of
 * a dense grid over the domain instead (no collisions, but memory grows with
 * the domain, not with the fluid). Periodic axes have their own cell count. */
#include "sph_search.h"

#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    if (!sph_scene_needs_neighbours(def)) return "no effect of the scene needs neighbours (density and the forces from it)";
    if (def->search == SPH_SEARCH_BRUTE) return "search = brute compares all pairs, without an index";
    return NULL;
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    if (def->search == SPH_SEARCH_GRID)
        snprintf(out, (size_t)n, "grid: key = dense cell number over the domain");
    else if (def->table_size)
        snprintf(out, (size_t)n, "hash: seed primes, key = hash %% %u", def->table_size);
    else
        snprintf(out, (size_t)n, "hash: seed primes, key = hash %% N (particle count)");
}

static void run(sph_sim *sim)
{
    const sph_particles *P = &sim->P;
    sph_search_data *S = &sim->S;
    const sph_cells *g = &S->cells;
    const int n = (int)sim->n, dim = sim->dim;
    const uint32_t T = S->table_size;
    sph_entry *restrict e = S->entries;
    if (sph_skin_keep(sim)) return; /* Verlet lists kept: the cells of their build stay */
    S->reordered = false; /* until this step's reorder pass, if any */
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        int32_t c[3] = {0, 0, 0};
        for (int d = 0; d < dim; d++) c[d] = sph_cells_coord(g, d, P->pred[d][i]);
        uint32_t hash = sph_cells_hash(g, c);
        e[i] = (sph_entry){hash % T, hash, (uint32_t)i};
    }
}

const sph_pass sph_pass_hash = {
    .name = "hash",
    .summary = "cell, hash and key of each particle",
    .reads = SPH_BIT(PRED),
    .writes = SPH_RES_ENTRIES,
    .group = SPH_GROUP_SEARCH,
    .highlight = "key",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
