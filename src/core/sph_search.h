/* The spatial index shared by the hash, sort, offsets and neighbours passes:
 * cells, the seed's hash, the sorts and the start-offset table. */
#ifndef SPH_SEARCH_H
#define SPH_SEARCH_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#include "sph_sim.h"

/* Cells stay within +-2^30 so that a neighbour cell (c +- 1) never overflows int32. */
#define SPH_CELL_LIMIT 1073741823

/* Cell index along one axis: floor(x * inv_size). floor, not truncation:
 * truncation (the seed's int(x / h)) sends everything in (-h, h) to cell 0,
 * a cell twice as wide as the others, and numbers every negative cell one
 * off from floor. The search still finds every pair (cells stay adjacent),
 * but cell 0 holds twice the candidates and the cell numbers no longer say
 * where a particle is. Saturates at +-SPH_CELL_LIMIT and maps NaN to 0, so
 * the float-to-int conversion is always defined. */
static inline int32_t sph_cell_coord(float x, float inv_h)
{
    float q = floorf(x * inv_h);
    /* (float)SPH_CELL_LIMIT rounds to 2^30, so compare with 2^30 itself */
    if (!(q > -1073741824.0f)) return q != q ? 0 : -SPH_CELL_LIMIT;
    if (q >= 1073741824.0f) return SPH_CELL_LIMIT;
    return (int32_t)q;
}

/* The seed's hash of a cell, in unsigned arithmetic (wraps mod 2^32). */
static inline uint32_t sph_hash_cell(int dim, int32_t cx, int32_t cy, int32_t cz)
{
    uint32_t h = (uint32_t)cx * SPH_HASH_P1 + (uint32_t)cy * SPH_HASH_P2;
    if (dim == 3) h += (uint32_t)cz * SPH_HASH_P3;
    return h;
}

/* Order of the sorted index: by key, then by particle index, so that every
 * sort gives the same array and the simulation does not depend on which. */
static inline int sph_entry_less(sph_entry a, sph_entry b)
{
    return a.key < b.key || (a.key == b.key && a.index < b.index);
}

/* The sorts of the sort pass, each leaving e[0..n) ordered by sph_entry_less. */
void sph_sort_bitonic(sph_entry *e, uint32_t n);
/* Stable counting sort by key: input must be in index order (as the hash pass
 * writes it). Uses scratch[n] and count[table_size + 1]; the result is in e. */
void sph_sort_counting(sph_entry *e, sph_entry *scratch, uint32_t *count, uint32_t n, uint32_t table_size);
void sph_sort_qsort(sph_entry *e, uint32_t n);

/* start[k] = position of the first entry with key k in the sorted e, or
 * SPH_EMPTY where no particle has key k (the seed's "liste des departs"). */
void sph_offsets_build(const sph_entry *e, uint32_t n, uint32_t *start, uint32_t table_size);

/* Verlet lists (sph_skin.c, [search] skin): the lists' reach, h (1 + skin);
 * whether this step keeps the lists (decided once per step, by the first
 * search pass that asks; false without a skin); and the mark a build leaves. */
float sph_skin_radius(const sph_sim *sim);
bool sph_skin_keep(sph_sim *sim);
void sph_skin_mark(sph_sim *sim);

/* Grid variant: cell index along one axis within the domain grid, clamped to
 * [0, dims). Clamping never moves two cells further apart, so particles
 * within h of each other stay in neighbouring cells even outside the domain. */
static inline int32_t sph_grid_coord(float x, float lo, float inv_h, int32_t dims)
{
    int32_t c = sph_cell_coord(x - lo, inv_h);
    return c < 0 ? 0 : c >= dims ? dims - 1 : c;
}

/* Cell of coordinate x along axis d: bounded axes clamp (a periodic axis's
 * positions are already wrapped; the clamp only absorbs rounding). */
static inline int32_t sph_cells_coord(const sph_cells *g, int d, float x)
{
    int32_t c = sph_cell_coord(x - g->origin[d], g->inv_size[d]);
    if (g->count[d]) c = c < 0 ? 0 : c >= g->count[d] ? g->count[d] - 1 : c;
    return c;
}

/* The neighbouring cell c + delta along axis d; false if there is none
 * (past the edge of a bounded, non-periodic grid). */
static inline bool sph_cells_step(const sph_cells *g, int d, int32_t c, int delta, int32_t *out)
{
    int32_t n = c + delta;
    if (g->count[d] && (n < 0 || n >= g->count[d])) {
        if (!g->wrap[d]) return false;
        n = n < 0 ? n + g->count[d] : n - g->count[d];
    }
    *out = n;
    return true;
}

/* The hash of a cell: the seed's primes, or the cell's number in a dense grid. */
static inline uint32_t sph_cells_hash(const sph_cells *g, const int32_t c[3])
{
    if (g->dense)
        return (uint32_t)c[0] + (uint32_t)g->count[0] * ((uint32_t)c[1] + (uint32_t)g->count[1] * (uint32_t)c[2]);
    return sph_hash_cell(g->dim, c[0], c[1], c[2]);
}

/* Shortest displacement along an axis with period p (inv_p = 1/p; both 0 if
 * not periodic, which leaves dx as it is). */
static inline float sph_min_image(float dx, float p, float inv_p)
{
    return dx - p * rintf(dx * inv_p);
}

/* A coordinate brought back into [lo, lo + p). */
static inline float sph_wrap(float x, float lo, float p, float inv_p)
{
    float w = x - p * floorf((x - lo) * inv_p);
    return w >= lo + p ? lo : w < lo ? lo : w;
}

#endif
