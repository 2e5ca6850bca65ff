/* Pass: spatial hash. Each particle gets the seed's (index, hash, key) entry
 * for the cell of its predicted position: cell = floor(x / h), hash from the
 * seed's primes in unsigned arithmetic, key = hash % table_size. The grid
 * variant numbers the cells of a dense grid over the domain instead (no
 * collisions, but memory grows with the domain, not with the fluid). */
#include "sph_search.h"

#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    if (!sph_scene_needs_neighbours(def)) return "no effect needs neighbours (density, pressure, viscosity)";
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
    const int n = (int)sim->n, dim = sim->dim;
    const float inv_h = 1.0f / sim->def.h;
    const uint32_t T = S->table_size;
    sph_entry *restrict e = S->entries;
    if (sim->def.search == SPH_SEARCH_GRID) {
        const int32_t *g = S->grid_dims;
        const float *lo = sim->def.domain_min;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++) {
            uint32_t cell = 0;
            for (int d = dim - 1; d >= 0; d--)
                cell = cell * (uint32_t)g[d] + (uint32_t)sph_grid_coord(P->pred[d][i], lo[d], inv_h, g[d]);
            e[i] = (sph_entry){cell, cell, (uint32_t)i};
        }
        return;
    }
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        int32_t cz = dim == 3 ? sph_cell_coord(P->pred[2][i], inv_h) : 0;
        uint32_t hash = sph_hash_cell(dim, sph_cell_coord(P->pred[0][i], inv_h),
                                      sph_cell_coord(P->pred[1][i], inv_h), cz);
        e[i] = (sph_entry){hash % T, hash, (uint32_t)i};
    }
}

const sph_pass sph_pass_hash = {
    "hash", "cell, hash and key of each particle", "pred", "entries", skip_reason, describe, run,
};
