/* Small experiments the lessons compute in this process, with the core's own
 * functions: the seed's worked example of the hash (the hash pass run on the
 * lesson's scene), and the bitonic network step by step (the index formula of
 * sph_sort_bitonic in src/passes/sort.c, with a snapshot after each step). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lesson.h"
#include "sph_search.h"
#include "sph_sim.h"

static int cmp_pair(const void *a, const void *b)
{
    const uint64_t *x = a, *y = b;
    return *x < *y ? -1 : *x > *y;
}

int lx_hash_example(const char *scene, const char **sets, int nsets, lx_hash_row *rows, int cap, int *cells,
                    int *colliding_cells, uint32_t *table_size)
{
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    sph_sim *sim = NULL;
    if (sph_scene_load(scene, &def, &err) != SPH_ERR_OK) goto fail;
    for (int i = 0; i < nsets; i++)
        if (sph_scene_set(&def, sets[i], &err) != SPH_ERR_OK) goto fail;
    if (sph_scene_validate(&def, &err) != SPH_ERR_OK || sph_sim_create(&def, 1, &sim, &err) != SPH_ERR_OK) goto fail;
    if (!sim->in_pipeline[SPH_PASS_HASH]) {
        fprintf(stderr, "sphlab lesson: %s: the scene has no hash pass\n", scene);
        sph_sim_destroy(sim);
        return -1;
    }
    for (int k = 0; k < SPH_PASS_COUNT; k++)
        if (sph_sim_step_pass(sim) == SPH_PASS_HASH) break;
    const sph_search_data *S = &sim->S;
    int n = (int)sim->n < cap ? (int)sim->n : cap;
    for (uint32_t e = 0; e < sim->n; e++) {
        uint32_t i = S->entries[e].index, id = sim->P.id[i];
        if ((int)id >= n) continue;
        lx_hash_row *r = &rows[id];
        r->id = id;
        r->x = sim->P.pred[0][i];
        r->y = sim->P.pred[1][i];
        r->cx = sph_cells_coord(&S->cells, 0, r->x);
        r->cy = sph_cells_coord(&S->cells, 1, r->y);
        r->hash = S->entries[e].hash;
        r->key = S->entries[e].key;
    }
    /* occupied cells (distinct hashes) and those sharing their key with another */
    uint64_t *kh = malloc((size_t)sim->n * sizeof *kh);
    *cells = *colliding_cells = 0;
    if (kh) {
        for (uint32_t e = 0; e < sim->n; e++) kh[e] = (uint64_t)S->entries[e].key << 32 | S->entries[e].hash;
        qsort(kh, sim->n, sizeof *kh, cmp_pair);
        size_t m = 0;
        for (uint32_t e = 0; e < sim->n; e++)
            if (e == 0 || kh[e] != kh[e - 1]) kh[m++] = kh[e]; /* distinct (key, hash) = cells */
        *cells = (int)m;
        for (size_t a = 0; a < m;) {
            size_t b = a;
            while (b < m && kh[b] >> 32 == kh[a] >> 32) b++;
            if (b - a > 1) *colliding_cells += (int)(b - a);
            a = b;
        }
        free(kh);
    }
    *table_size = S->table_size;
    sph_sim_destroy(sim);
    return n;
fail:
    fprintf(stderr, "sphlab lesson: %s\n", err.msg);
    sph_sim_destroy(sim);
    return -1;
}

/* The loops of sph_sort_bitonic (src/passes/sort.c), one step at a time. */
int lx_bitonic_steps(const uint32_t *keys, uint32_t n, lx_bitonic_cb cb, void *ctx)
{
    if (n < 2 || n > 1024) return 0;
    sph_entry e[1024];
    uint32_t k[1024], idx[1024];
    for (uint32_t i = 0; i < n; i++) e[i] = (sph_entry){keys[i], keys[i], i};
    uint32_t P = 1;
    while (P < n) P <<= 1;
    int steps = 0, stage = 0;
    for (uint32_t w0 = 1; w0 < P; w0 <<= 1, stage++) {
        int step = 0;
        for (uint32_t w = w0; w >= 1; w >>= 1, step++) {
            const int flip = w == w0;
            int swaps = 0;
            for (uint32_t i = 0; i < P / 2; i++) {
                uint32_t h = i & (w - 1);
                uint32_t left = h + 2 * w * (i / w);
                uint32_t right = flip ? left + (2 * w - 1) - 2 * h : left + w;
                if (right >= n) continue;
                if (sph_entry_less(e[right], e[left])) {
                    sph_entry t = e[left];
                    e[left] = e[right];
                    e[right] = t;
                    swaps++;
                }
            }
            for (uint32_t i = 0; i < n; i++) {
                k[i] = e[i].key;
                idx[i] = e[i].index;
            }
            if (cb) cb(ctx, stage, step, w, flip, k, idx, n, swaps);
            steps++;
        }
    }
    return steps;
}
