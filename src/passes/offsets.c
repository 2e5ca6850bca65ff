/* Pass: the start-offset table (the seed's "liste des departs"): for each
 * key, where its run begins in the sorted entries; SPH_EMPTY if no particle
 * has that key. */
#include "sph_search.h"

#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    return sph_pass_hash.skip_reason(def);
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    if (def->sort == SPH_SORT_NONE)
        snprintf(out, (size_t)n, "unsorted: a linked list per key (head of each key, next of each particle)");
    else
        snprintf(out, (size_t)n, "first sorted entry of each key, empty keys marked");
}

/* The unsorted hash: start[k] is the last particle with key k and next[i]
 * the particle before i with the same key, SPH_EMPTY ending the chain. O(N)
 * with no sort, but a chain jumps across memory at every step. */
static void build_chains(const sph_entry *e, uint32_t n, uint32_t *head, uint32_t *next, uint32_t table_size)
{
    for (uint32_t k = 0; k < table_size; k++) head[k] = SPH_EMPTY;
    for (uint32_t i = 0; i < n; i++) {
        next[i] = head[e[i].key];
        head[e[i].key] = i;
    }
}

void sph_offsets_build(const sph_entry *e, uint32_t n, uint32_t *start, uint32_t table_size)
{
#pragma omp parallel if (n > SPH_PARALLEL_MIN)
    {
#pragma omp for schedule(static)
        for (int64_t k = 0; k < (int64_t)table_size; k++) start[k] = SPH_EMPTY;
        /* Each entry that begins a run writes its own slot: no two entries
         * write the same key, so the loop needs no ordering. */
#pragma omp for schedule(static)
        for (int64_t i = 0; i < (int64_t)n; i++)
            if (i == 0 || e[i].key != e[i - 1].key) start[e[i].key] = (uint32_t)i;
    }
}

static void run(sph_sim *sim)
{
    if (sph_skin_keep(sim)) return; /* Verlet lists kept: no new cells */
    if (sim->def.sort == SPH_SORT_NONE)
        build_chains(sim->S.entries, sim->n, sim->S.start, sim->S.next, sim->S.table_size);
    else
        sph_offsets_build(sim->S.entries, sim->n, sim->S.start, sim->S.table_size);
}

const sph_pass sph_pass_offsets = {
    .name = "offsets",
    .summary = "start of each key in the sorted entries",
    .reads = SPH_RES_ENTRIES,
    .writes = SPH_RES_START,
    .group = SPH_GROUP_SEARCH,
    .highlight = "key",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
