/* Pass: sort the (index, hash, key) entries by key, so that the entries of a
 * key sit together and the offsets table can point at the first of them.
 * Three variants: the seed's bitonic network (what a GPU runs: a fixed
 * pattern of compare-exchanges, O(N log^2 N)), a counting sort (O(N + keys),
 * the fastest here) and the C library's qsort (the reference). All three
 * order by (key, index), so they give the same array. */
#include "sph_memory.h"
#include "sph_search.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *skip_reason(const sph_scene_def *def)
{
    const char *why = sph_pass_hash.skip_reason(def);
    if (why) return why;
    return def->sort == SPH_SORT_NONE ? "search.sort = none: each key chains its particles instead" : NULL;
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    static const char *const about[SPH_SORT_COUNT] = {
        "bitonic network (the seed), O(N log^2 N)", "counting sort, O(N + keys)", "C library qsort (reference)",
        "none"};
    snprintf(out, (size_t)n, "%s", about[def->sort]);
}

static uint32_t next_pow2(uint32_t x)
{
    uint32_t p = 1;
    while (p < x) p <<= 1;
    return p;
}

/* The seed's network: log2(P) stages of 1..stage+1 steps over P = next power
 * of two >= n. Step 0 of a stage compares each element with its mirror in a
 * block of 2w ("flip"), later steps with the element w further ("disperse").
 * Pairs reaching past n are skipped: as if the array were padded with +inf,
 * which never moves. Pairs within one step are disjoint, so a step is parallel. */
void sph_sort_bitonic(sph_entry *e, uint32_t n)
{
    if (n < 2) return;
    uint32_t P = next_pow2(n);
    for (uint32_t w0 = 1; w0 < P; w0 <<= 1) {        /* stage: sorted runs of w0 become runs of 2 w0 */
        for (uint32_t w = w0; w >= 1; w >>= 1) {     /* step: compare distance class w */
            const int64_t pairs = P / 2;
            const int flip = w == w0;
#pragma omp parallel for schedule(static) if (pairs > SPH_PARALLEL_MIN)
            for (int64_t i = 0; i < pairs; i++) {
                uint32_t h = (uint32_t)i & (w - 1);
                uint32_t left = h + 2 * w * ((uint32_t)i / w);
                uint32_t right = flip ? left + (2 * w - 1) - 2 * h : left + w;
                if (right >= n) continue;
                if (sph_entry_less(e[right], e[left])) {
                    sph_entry t = e[left];
                    e[left] = e[right];
                    e[right] = t;
                }
            }
        }
    }
}

void sph_sort_counting(sph_entry *e, sph_entry *scratch, uint32_t *count, uint32_t n, uint32_t table_size)
{
    memset(count, 0, ((size_t)table_size + 1) * sizeof *count);
    for (uint32_t i = 0; i < n; i++) count[e[i].key + 1]++;
    for (uint32_t k = 0; k < table_size; k++) count[k + 1] += count[k]; /* count[k]: first slot of key k */
    for (uint32_t i = 0; i < n; i++) scratch[count[e[i].key]++] = e[i]; /* in input order: stable */
    memcpy(e, scratch, (size_t)n * sizeof *e);
}

static int entry_cmp(const void *a, const void *b)
{
    const sph_entry *x = a, *y = b;
    return sph_entry_less(*x, *y) ? -1 : sph_entry_less(*y, *x) ? 1 : 0;
}

void sph_sort_qsort(sph_entry *e, uint32_t n)
{
    qsort(e, n, sizeof *e, entry_cmp);
}

/* The counting sort's scratch (12 bytes a particle) and histogram. When the
 * neighbour lists are rebuilt after this sort (every step, or a Verlet
 * rebuild), their buffer is dead from here to the neighbours pass (the
 * reorder moves the particles they index), so the sort borrows it: a step's
 * peak then holds the lists or the scratch, not both (12-16 bytes a particle
 * less at 1,000,000). The rows are emptied first, so that nothing in between
 * (the watchdog's report, the window) reads the borrowed words as indices. */
static void counting_buffers(sph_sim *sim, sph_entry **scratch, uint32_t **count)
{
    sph_search_data *S = &sim->S;
    const size_t keys = (size_t)S->table_size + 1, need = 3 * (size_t)sim->n + keys; /* uint32 words */
    char size[32];
    if (sim->in_pipeline[SPH_PASS_NEIGHBOURS] && sim->enabled[SPH_PASS_NEIGHBOURS] && S->nbr_start) {
        if (S->nbr_cap < need) { /* nothing in it to keep */
            free(S->nbr);
            S->nbr = malloc(need * sizeof *S->nbr);
            S->nbr_cap = S->nbr ? need : 0;
            if (!S->nbr)
                sph_memory_fail("the counting sort's scratch could not be made (%s)",
                                sph_memory_text((double)need * sizeof *S->nbr, size, sizeof size));
        }
        memset(S->nbr_start, 0, ((size_t)sim->n + 1) * sizeof *S->nbr_start);
        S->lists_built = false;
        sim->fields_fresh &= ~SPH_RES_LISTS; /* until the neighbours pass writes them again */
        *count = S->nbr;
        *scratch = (sph_entry *)(void *)(S->nbr + keys);
        return;
    }
    if (!S->scratch) S->scratch = malloc((sim->n ? sim->n : 1) * sizeof *S->scratch);
    if (!S->count) S->count = malloc(keys * sizeof *S->count);
    if (!S->scratch || !S->count)
        sph_memory_fail("the counting sort's scratch could not be made (%s)",
                        sph_memory_text((double)need * sizeof(uint32_t), size, sizeof size));
    *scratch = S->scratch;
    *count = S->count;
}

static void run(sph_sim *sim)
{
    if (sph_skin_keep(sim)) return; /* Verlet lists kept: no new cells */
    sph_search_data *S = &sim->S;
    switch (sim->def.sort) {
    case SPH_SORT_BITONIC: sph_sort_bitonic(S->entries, sim->n); break;
    case SPH_SORT_COUNTING: {
        sph_entry *scratch;
        uint32_t *count;
        counting_buffers(sim, &scratch, &count);
        sph_sort_counting(S->entries, scratch, count, sim->n, S->table_size);
        break;
    }
    default: sph_sort_qsort(S->entries, sim->n); break;
    }
}

const sph_pass sph_pass_sort = {
    .name = "sort",
    .summary = "sort the entries by key",
    .reads = SPH_RES_ENTRIES,
    .writes = SPH_RES_ENTRIES,
    .group = SPH_GROUP_SEARCH,
    .highlight = "key",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
