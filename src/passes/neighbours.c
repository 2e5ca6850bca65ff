/* Pass: neighbour search. For each particle, the other particles closer than
 * h (r^2 < h^2) at the predicted positions, stored as compressed rows so the
 * density, pressure and viscosity passes reuse them instead of searching three
 * times as the seed's shaders do. With Verlet lists ([search] skin > 0) the
 * reach is h (1 + skin) and the lists are kept over several steps
 * (src/core/sph_skin.c).
 *   hash:  visit the 3^dim cells around the particle's cell; for each, look up
 *          its key's run in the sorted entries through the offsets table and
 *          keep entries whose hash is the cell's (other cells share the key).
 *   grid:  the same walk over the dense grid's cells (no collisions).
 *   brute: every pair, O(N^2): the reference the others are tested against.
 * The stencil's cells have distinct hashes (tests/test_search.c checks the
 * primes), so no entry is visited twice. Every variant gives the same sets.
 * With [search] cell_batch (AVX2, after a reorder) the particles of a cell are
 * tested together against each vector of candidates (rows_batched). */
#define _DEFAULT_SOURCE /* madvise */
#include "sph_memory.h"
#include "sph_search.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif
#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif

static const char *skip_reason(const sph_scene_def *def)
{
    return sph_scene_needs_neighbours(def) ? NULL : "no effect of the scene needs neighbours (density and the forces from it)";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    static const char *const about[SPH_SEARCH_COUNT] = {
        "hash: 3^d cells through keys and offsets", "grid: 3^d cells of a dense grid", "brute force, all pairs O(N^2)"};
    if (def->backend == SPH_BACKEND_GL) /* `check` said the lists were built there */
        snprintf(out, (size_t)n, "no lists on the GL backend: its pair passes walk the cells (%s) themselves",
                 def->search == SPH_SEARCH_BRUTE ? "all pairs" : def->search == SPH_SEARCH_GRID ? "a dense grid" : "hash");
    else
        snprintf(out, (size_t)n, "%s", about[def->search]);
}

/* Why lists can outgrow the estimate that validation checked. */
#define SPH_LISTS_WHY "more neighbours than on the lattice, which the estimate of `sphlab check` assumes"

typedef struct list {
    uint32_t *buf;
    size_t len, cap;
} list;

static void list_grow(list *l, size_t need)
{
    size_t cap = l->cap ? l->cap : 4096;
    while (cap < need) cap *= 2;
    uint32_t *b = realloc(l->buf, cap * sizeof *b);
    if (!b) {
        char size[32];
        sph_memory_fail("a thread's neighbour list could not grow to %s (%s)",
                        sph_memory_text((double)cap * sizeof *b, size, sizeof size), SPH_LISTS_WHY);
    }
    l->buf = b;
    l->cap = cap;
}

static inline void list_reserve(list *l, size_t more)
{
    if (l->len + more > l->cap) list_grow(l, l->len + more);
}

/* [search] compact_lists: a thread's rows as 16-bit words (sph_sim.h). */
typedef struct words {
    uint16_t *buf;
    size_t len, cap; /* words; cap even, so that a buffer holds whole 32-bit words */
} words;

static inline void words_reserve(words *c, size_t more)
{
    if (c->len + more <= c->cap) return;
    size_t cap = c->cap ? c->cap : 8192;
    while (cap < c->len + more) cap *= 2;
    uint16_t *b = realloc(c->buf, cap * sizeof *b);
    if (!b) {
        char size[32];
        sph_memory_fail("a thread's neighbour list could not grow to %s (%s)",
                        sph_memory_text((double)cap * sizeof *b, size, sizeof size), SPH_LISTS_WHY);
    }
    c->buf = b;
    c->cap = cap;
}

/* Appends row i (its m neighbours j[]) to c: the offsets j - i if all lie
 * within +-SPH_NBR_NEAR, else the marker and the 32-bit indices. In cell
 * order the neighbours of i lie within a few layers of cells of i, so rows
 * are narrow unless a layer holds more than about 32,000 particles. */
static inline void words_row(words *c, const uint32_t *j, size_t m, uint32_t i)
{
    bool near = true;
    for (size_t k = 0; k < m; k++) near &= j[k] - i + (uint32_t)SPH_NBR_NEAR <= 2u * SPH_NBR_NEAR;
    if (near) {
        words_reserve(c, m);
        for (size_t k = 0; k < m; k++) c->buf[c->len + k] = (uint16_t)(j[k] - i); /* read back as int16 */
        c->len += m;
        return;
    }
    words_reserve(c, 1 + 2 * m);
    c->buf[c->len++] = SPH_NBR_WIDE;
    for (size_t k = 0; k < m; k++, c->len += 2) memcpy(c->buf + c->len, j + k, sizeof *j);
}

/* The end of row i, just built in l: plain lists keep it where it is;
 * compact ones move it into c and empty l for the next row. */
static inline uint32_t row_done(list *l, words *c, uint32_t i)
{
    if (!c) return (uint32_t)l->len;
    words_row(c, l->buf, l->len, i);
    l->len = 0;
    return (uint32_t)c->len;
}

/* Appends the neighbours of i found in the run of one cell's key. The run is
 * scanned without branches on the distance test (each candidate is written,
 * and kept by advancing the length only if it passes), as that test is a coin
 * flip the branch predictor cannot learn. Positions come from spos, the
 * positions gathered in sorted order, so a run is read contiguously. */
static inline void scan_cell(const sph_sim *sim, const float *spos, list *out, uint32_t i, uint32_t hash,
                             const float xi[3], float h2)
{
    const float *per = sim->period, *iper = sim->inv_period;
    const sph_search_data *S = &sim->S;
    const uint32_t key = hash % S->table_size;
    uint32_t e = S->start[key];
    if (e == SPH_EMPTY) return;
    if (S->next) { /* unsorted: walk the key's chain, particle by particle */
        const int dim = sim->dim;
        for (uint32_t j = e; j != SPH_EMPTY; j = S->next[j]) {
            if (S->entries[j].hash != hash || j == i) continue;
            float r2 = 0;
            for (int d = 0; d < dim; d++) {
                float dx = sph_min_image(sim->P.pred[d][j] - xi[d], per[d], iper[d]);
                r2 += dx * dx;
            }
            if (r2 < h2) {
                list_reserve(out, 1);
                out->buf[out->len++] = j;
            }
        }
        return;
    }
    const sph_entry *en = S->entries;
    uint32_t end = e;
    while (end < sim->n && en[end].key == key) end++;
    list_reserve(out, end - e);
    uint32_t *buf = out->buf;
    size_t len = out->len;
    if (!spos) { /* no sorted copy (a level that reorders, before its first reorder): read by index */
        const float *px = sim->P.pred[0], *py = sim->P.pred[1], *pz = sim->dim == 3 ? sim->P.pred[2] : NULL;
        for (; e < end; e++) {
            uint32_t j = en[e].index;
            float dx = sph_min_image(px[j] - xi[0], per[0], iper[0]);
            float dy = sph_min_image(py[j] - xi[1], per[1], iper[1]);
            float dz = pz ? sph_min_image(pz[j] - xi[2], per[2], iper[2]) : 0.0f;
            float r2 = dx * dx + dy * dy + dz * dz;
            buf[len] = j;
            len += (en[e].hash == hash) & (j != i) & (r2 < h2);
        }
        out->len = len;
        return;
    }
    for (; e < end; e++) {
        const float *xj = spos + 4 * (size_t)e;
        float dx = sph_min_image(xj[0] - xi[0], per[0], iper[0]);
        float dy = sph_min_image(xj[1] - xi[1], per[1], iper[1]);
        float dz = sph_min_image(xj[2] - xi[2], per[2], iper[2]);
        float r2 = dx * dx + dy * dy + dz * dz;
        uint32_t j = en[e].index;
        buf[len] = j;
        len += (en[e].hash == hash) & (j != i) & (r2 < h2);
    }
    out->len = len;
}

static void neighbours_of(const sph_sim *sim, const float *spos, list *out, uint32_t i)
{
    const sph_particles *P = &sim->P;
    const int dim = sim->dim;
    const float reach = sph_skin_radius(sim), h2 = reach * reach; /* h, or h (1 + skin) */
    float xi[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) xi[d] = P->pred[d][i];
    if (sim->def.search == SPH_SEARCH_BRUTE) {
        list_reserve(out, sim->n);
        for (uint32_t j = 0; j < sim->n; j++) {
            float r2 = 0;
            for (int d = 0; d < dim; d++) {
                float dx = sph_min_image(P->pred[d][j] - xi[d], sim->period[d], sim->inv_period[d]);
                r2 += dx * dx;
            }
            out->buf[out->len] = j;
            out->len += (j != i) & (r2 < h2);
        }
        return;
    }
    /* The 3^dim cells around the particle's cell (fewer at the edge of a
     * bounded grid; wrapped on periodic axes). */
    const sph_cells *g = &sim->S.cells;
    int32_t c[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) c[d] = sph_cells_coord(g, d, xi[d]);
    const int zr = dim == 3 ? 1 : 0;
    int32_t cell[3] = {0, 0, 0};
    for (int dz = -zr; dz <= zr; dz++) {
        if (dim == 3 && !sph_cells_step(g, 2, c[2], dz, &cell[2])) continue;
        for (int dy = -1; dy <= 1; dy++) {
            if (!sph_cells_step(g, 1, c[1], dy, &cell[1])) continue;
            for (int dx = -1; dx <= 1; dx++) {
                if (!sph_cells_step(g, 0, c[0], dx, &cell[0])) continue;
                scan_cell(sim, spos, out, i, sph_cells_hash(g, cell), xi, h2);
            }
        }
    }
}

/* ---- after a reorder: cell by cell, over contiguous arrays -------------- */

/* One run of candidates: sorted entries [start, end). With `exact` every entry
 * belongs to a stencil cell; otherwise only those whose cell hash is `hash`
 * (a hash key is shared by other cells). */
typedef struct run_range {
    uint32_t start, end, hash;
    bool exact;
} run_range;

/* The first entry past the run of keys [.., last] that starts at s. */
static inline uint32_t run_end(const sph_sim *sim, uint32_t s, uint32_t last)
{
    const sph_entry *en = sim->S.entries;
    while (s < sim->n && en[s].key <= last) s++;
    return s;
}

/* The dense grid numbers cells x fastest, so the (up to) three cells of a
 * stencil row along x hold one contiguous stretch of the sorted entries: one
 * run instead of three, about 3 * 8 candidates at h = 2 spacings, so a
 * 16-lane loop works on full vectors instead of half-empty ones. Not on a
 * periodic x axis, where the row wraps around. */
static int stencil_rows(const sph_sim *sim, const int32_t c[3], run_range *runs, const bool by_offsets)
{
    const sph_search_data *S = &sim->S;
    const sph_cells *g = &S->cells;
    const int dim = sim->dim, zr = dim == 3 ? 1 : 0;
    const int32_t x0 = c[0] > 0 ? c[0] - 1 : 0, x1 = c[0] + 1 < g->count[0] ? c[0] + 1 : g->count[0] - 1;
    int k = 0;
    int32_t cell[3] = {0, 0, 0};
    for (int dz = -zr; dz <= zr; dz++) {
        if (dim == 3 && !sph_cells_step(g, 2, c[2], dz, &cell[2])) continue;
        for (int dy = -1; dy <= 1; dy++) {
            if (!sph_cells_step(g, 1, c[1], dy, &cell[1])) continue;
            cell[0] = x1;
            const uint32_t last = sph_cells_hash(g, cell);
            uint32_t s = SPH_EMPTY;
            for (uint32_t key = last - (uint32_t)(x1 - x0); key <= last && s == SPH_EMPTY; key++) s = S->start[key];
            if (s == SPH_EMPTY) continue;
            /* by_offsets (cell_batch): the next key's start, where it has entries, ends the run */
            const uint32_t next = by_offsets && last + 1 < S->table_size ? S->start[last + 1] : SPH_EMPTY;
            runs[k++] = (run_range){s, next != SPH_EMPTY ? next : run_end(sim, s, last), 0, true};
        }
    }
    return k;
}

/* The runs of the 3^dim cells around cell c (at most 27). */
static int stencil_runs(const sph_sim *sim, const int32_t c[3], run_range *runs, const bool by_offsets)
{
    const sph_search_data *S = &sim->S;
    const sph_cells *g = &S->cells;
    const sph_entry *en = S->entries;
    const int dim = sim->dim, zr = dim == 3 ? 1 : 0;
    if (g->dense && !g->wrap[0]) /* table_size = cell count: no shared keys */
        return stencil_rows(sim, c, runs, by_offsets);
    int k = 0;
    int32_t cell[3] = {0, 0, 0};
    for (int dz = -zr; dz <= zr; dz++) {
        if (dim == 3 && !sph_cells_step(g, 2, c[2], dz, &cell[2])) continue;
        for (int dy = -1; dy <= 1; dy++) {
            if (!sph_cells_step(g, 1, c[1], dy, &cell[1])) continue;
            for (int dx = -1; dx <= 1; dx++) {
                if (!sph_cells_step(g, 0, c[0], dx, &cell[0])) continue;
                uint32_t hash = sph_cells_hash(g, cell), key = hash % S->table_size;
                uint32_t s = S->start[key];
                if (s == SPH_EMPTY) continue;
                uint32_t end = s;
                while (end < sim->n && en[end].key == key) end++;
                runs[k++] = (run_range){s, end, hash, false};
            }
        }
    }
    return k;
}

#ifdef __AVX2__
/* AVX2 has no compress: entry m lists the set lanes of the 8-bit mask m, one
 * lane number per 4 bits from the lowest, for a lane permutation. */
static const uint32_t compress8[256] = {
    0x00000000, 0x00000000, 0x00000001, 0x00000010, 0x00000002, 0x00000020, 0x00000021, 0x00000210,
    0x00000003, 0x00000030, 0x00000031, 0x00000310, 0x00000032, 0x00000320, 0x00000321, 0x00003210,
    0x00000004, 0x00000040, 0x00000041, 0x00000410, 0x00000042, 0x00000420, 0x00000421, 0x00004210,
    0x00000043, 0x00000430, 0x00000431, 0x00004310, 0x00000432, 0x00004320, 0x00004321, 0x00043210,
    0x00000005, 0x00000050, 0x00000051, 0x00000510, 0x00000052, 0x00000520, 0x00000521, 0x00005210,
    0x00000053, 0x00000530, 0x00000531, 0x00005310, 0x00000532, 0x00005320, 0x00005321, 0x00053210,
    0x00000054, 0x00000540, 0x00000541, 0x00005410, 0x00000542, 0x00005420, 0x00005421, 0x00054210,
    0x00000543, 0x00005430, 0x00005431, 0x00054310, 0x00005432, 0x00054320, 0x00054321, 0x00543210,
    0x00000006, 0x00000060, 0x00000061, 0x00000610, 0x00000062, 0x00000620, 0x00000621, 0x00006210,
    0x00000063, 0x00000630, 0x00000631, 0x00006310, 0x00000632, 0x00006320, 0x00006321, 0x00063210,
    0x00000064, 0x00000640, 0x00000641, 0x00006410, 0x00000642, 0x00006420, 0x00006421, 0x00064210,
    0x00000643, 0x00006430, 0x00006431, 0x00064310, 0x00006432, 0x00064320, 0x00064321, 0x00643210,
    0x00000065, 0x00000650, 0x00000651, 0x00006510, 0x00000652, 0x00006520, 0x00006521, 0x00065210,
    0x00000653, 0x00006530, 0x00006531, 0x00065310, 0x00006532, 0x00065320, 0x00065321, 0x00653210,
    0x00000654, 0x00006540, 0x00006541, 0x00065410, 0x00006542, 0x00065420, 0x00065421, 0x00654210,
    0x00006543, 0x00065430, 0x00065431, 0x00654310, 0x00065432, 0x00654320, 0x00654321, 0x06543210,
    0x00000007, 0x00000070, 0x00000071, 0x00000710, 0x00000072, 0x00000720, 0x00000721, 0x00007210,
    0x00000073, 0x00000730, 0x00000731, 0x00007310, 0x00000732, 0x00007320, 0x00007321, 0x00073210,
    0x00000074, 0x00000740, 0x00000741, 0x00007410, 0x00000742, 0x00007420, 0x00007421, 0x00074210,
    0x00000743, 0x00007430, 0x00007431, 0x00074310, 0x00007432, 0x00074320, 0x00074321, 0x00743210,
    0x00000075, 0x00000750, 0x00000751, 0x00007510, 0x00000752, 0x00007520, 0x00007521, 0x00075210,
    0x00000753, 0x00007530, 0x00007531, 0x00075310, 0x00007532, 0x00075320, 0x00075321, 0x00753210,
    0x00000754, 0x00007540, 0x00007541, 0x00075410, 0x00007542, 0x00075420, 0x00075421, 0x00754210,
    0x00007543, 0x00075430, 0x00075431, 0x00754310, 0x00075432, 0x00754320, 0x00754321, 0x07543210,
    0x00000076, 0x00000760, 0x00000761, 0x00007610, 0x00000762, 0x00007620, 0x00007621, 0x00076210,
    0x00000763, 0x00007630, 0x00007631, 0x00076310, 0x00007632, 0x00076320, 0x00076321, 0x00763210,
    0x00000764, 0x00007640, 0x00007641, 0x00076410, 0x00007642, 0x00076420, 0x00076421, 0x00764210,
    0x00007643, 0x00076430, 0x00076431, 0x00764310, 0x00076432, 0x00764320, 0x00764321, 0x07643210,
    0x00000765, 0x00007650, 0x00007651, 0x00076510, 0x00007652, 0x00076520, 0x00076521, 0x00765210,
    0x00007653, 0x00076530, 0x00076531, 0x00765310, 0x00076532, 0x00765320, 0x00765321, 0x07653210,
    0x00007654, 0x00076540, 0x00076541, 0x00765410, 0x00076542, 0x00765420, 0x00765421, 0x07654210,
    0x00076543, 0x00765430, 0x00765431, 0x07654310, 0x00765432, 0x07654320, 0x07654321, 0x76543210,
};
#endif

/* Scans one run for particle i, appending the neighbours to buf from len;
 * returns the new length. Positions are the particle arrays themselves.
 * r^2 is summed in the same order as the other variants (no fused
 * multiply-add) so every variant decides the borderline pairs alike. */
static inline size_t scan_run(const sph_sim *sim, const run_range *r, uint32_t i, const float xi[3], float h2,
                              uint32_t *buf, size_t len, const int dim, const bool periodic)
{
    const float *px = sim->P.pred[0], *py = sim->P.pred[1], *pz = dim == 3 ? sim->P.pred[2] : NULL;
    const uint32_t *chash = sim->S.cell_hash;
    uint32_t j = r->start;
#ifdef __AVX2__
    if (!periodic && sim->def.vector == SPH_ON && sim->def.vector_avx2 == SPH_ON) { /* 8 lanes, the same sums */
        const __m256 vx = _mm256_set1_ps(xi[0]), vy = _mm256_set1_ps(xi[1]), vz = _mm256_set1_ps(xi[2]);
        const __m256 vh2 = _mm256_set1_ps(h2);
        const __m256i vhash = _mm256_set1_epi32((int)r->hash), vi = _mm256_set1_epi32((int)i);
        const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
        const __m256i nibble = _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28), fifteen = _mm256_set1_epi32(15);
        for (; j < r->end; j += 8) {
            const uint32_t left = r->end - j;
            const __m256i live = _mm256_cmpgt_epi32(_mm256_set1_epi32(left >= 8 ? 8 : (int)left), lane);
            __m256 dx = _mm256_sub_ps(_mm256_maskload_ps(px + j, live), vx);
            __m256 dy = _mm256_sub_ps(_mm256_maskload_ps(py + j, live), vy);
            __m256 r2 = _mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy));
            if (dim == 3) {
                __m256 dz = _mm256_sub_ps(_mm256_maskload_ps(pz + j, live), vz);
                r2 = _mm256_add_ps(r2, _mm256_mul_ps(dz, dz));
            }
            const __m256i idx = _mm256_add_epi32(_mm256_set1_epi32((int)j), lane);
            __m256i m = _mm256_and_si256(live, _mm256_castps_si256(_mm256_cmp_ps(r2, vh2, _CMP_LT_OQ)));
            if (!r->exact) {
                const __m256i hj = _mm256_maskload_epi32((const int *)(const void *)(chash + j), live);
                m = _mm256_and_si256(m, _mm256_cmpeq_epi32(hj, vhash));
            }
            m = _mm256_andnot_si256(_mm256_cmpeq_epi32(idx, vi), m);
            const unsigned bits = (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(m));
            const __m256i perm =
                _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32((int)compress8[bits]), nibble), fifteen);
            _mm256_storeu_si256((__m256i *)(void *)(buf + len), _mm256_permutevar8x32_epi32(idx, perm));
            len += (size_t)__builtin_popcount(bits);
        }
        return len;
    }
#endif
#ifdef __AVX512F__
    if (!periodic && sim->def.vector == SPH_ON) {
        const __m512 vx = _mm512_set1_ps(xi[0]), vy = _mm512_set1_ps(xi[1]), vz = _mm512_set1_ps(xi[2]);
        const __m512 vh2 = _mm512_set1_ps(h2);
        const __m512i vhash = _mm512_set1_epi32((int)r->hash), vi = _mm512_set1_epi32((int)i);
        const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
        for (; j < r->end; j += 16) {
            uint32_t left = r->end - j;
            __mmask16 live = left >= 16 ? (__mmask16)0xFFFF : (__mmask16)((1u << left) - 1);
            __m512 dx = _mm512_sub_ps(_mm512_maskz_loadu_ps(live, px + j), vx);
            __m512 dy = _mm512_sub_ps(_mm512_maskz_loadu_ps(live, py + j), vy);
            __m512 r2 = _mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy));
            if (dim == 3) {
                __m512 dz = _mm512_sub_ps(_mm512_maskz_loadu_ps(live, pz + j), vz);
                r2 = _mm512_add_ps(r2, _mm512_mul_ps(dz, dz));
            }
            __m512i idx = _mm512_add_epi32(_mm512_set1_epi32((int)j), lane);
            __mmask16 m = _mm512_mask_cmp_ps_mask(live, r2, vh2, _CMP_LT_OQ);
            if (!r->exact) m = _mm512_mask_cmpeq_epi32_mask(m, _mm512_maskz_loadu_epi32(live, chash + j), vhash);
            m = _mm512_mask_cmpneq_epi32_mask(m, idx, vi);
            /* compress in a register, then store all 16 lanes: on some CPUs
             * (AMD Zen 4) a compress straight to memory is microcoded and slow */
            _mm512_storeu_si512((void *)(buf + len), _mm512_maskz_compress_epi32(m, idx));
            len += (size_t)__builtin_popcount((unsigned)m);
        }
        return len;
    }
#endif
    for (; j < r->end; j++) {
        float dx = px[j] - xi[0], dy = py[j] - xi[1], dz = dim == 3 ? pz[j] - xi[2] : 0.0f;
        if (periodic) {
            dx = sph_min_image(dx, sim->period[0], sim->inv_period[0]);
            dy = sph_min_image(dy, sim->period[1], sim->inv_period[1]);
            dz = sph_min_image(dz, sim->period[2], sim->inv_period[2]);
        }
        float r2 = dx * dx + dy * dy;
        if (dim == 3) r2 += dz * dz;
        buf[len] = j;
        len += (r2 < h2) & (r->exact || chash[j] == r->hash) & (j != i);
    }
    return len;
}

/* Rows of particles [lo, hi) of a reordered index; row ends (local) in nbr_start[i + 1]. */
static inline void rows_reordered(const sph_sim *sim, list *l, words *cw, uint32_t lo, uint32_t hi, const int dim,
                                  const bool periodic)
{
    const sph_cells *g = &sim->S.cells;
    const float reach = sph_skin_radius(sim), h2 = reach * reach; /* h, or h (1 + skin) */
    run_range runs[27];
    int nruns = 0;
    int32_t cur[3] = {0, 0, 0};
    bool have = false;
    for (uint32_t i = lo; i < hi; i++) {
        float xi[3] = {0, 0, 0};
        int32_t c[3] = {0, 0, 0};
        for (int d = 0; d < dim; d++) {
            xi[d] = sim->P.pred[d][i];
            c[d] = sph_cells_coord(g, d, xi[d]);
        }
        if (!have || c[0] != cur[0] || c[1] != cur[1] || c[2] != cur[2]) { /* a new cell: look its stencil up */
            nruns = stencil_runs(sim, c, runs, false);
            cur[0] = c[0], cur[1] = c[1], cur[2] = c[2];
            have = true;
        }
        for (int k = 0; k < nruns; k++) {
            list_reserve(l, runs[k].end - runs[k].start + 16); /* + a vector's slack */
            l->len = scan_run(sim, &runs[k], i, xi, h2, l->buf, l->len, dim, periodic);
        }
        sim->S.nbr_start[i + 1] = row_done(l, cw, i);
    }
}

#ifdef __AVX2__
/* [search] cell_batch = on (L15): the particles of one cell share its
 * stencil's runs, so each 8-candidate vector of a run is loaded once and
 * tested against every particle of the cell in turn (x_i broadcast), instead
 * of once per particle; and the loops end once per vector and cell, not once
 * per vector and particle. Each particle's survivors go to its own row in
 * scratch, in the order scan_run appends them (runs in order, candidates in
 * order), with the same sums, so the rows are scan_run's to the entry. */
#define SPH_BATCH_MAX 32 /* particles tested together; a fuller cell is taken in several batches */

/* A batch of the cell batch searches: i0 and the particles after it in the
 * same cell, up to SPH_BATCH_MAX and hi; c[] receives the cell. The end. */
static inline uint32_t batch_end(const sph_sim *sim, uint32_t i0, uint32_t hi, const int dim, int32_t c[3])
{
    const sph_cells *g = &sim->S.cells;
    for (int d = 0; d < dim; d++) c[d] = sph_cells_coord(g, d, sim->P.pred[d][i0]);
    uint32_t i1 = i0 + 1;
    while (i1 < hi && i1 - i0 < SPH_BATCH_MAX) {
        bool same = true;
        for (int d = 0; d < dim; d++) same &= sph_cells_coord(g, d, sim->P.pred[d][i1]) == c[d];
        if (!same) break;
        i1++;
    }
    return i1;
}

/* The batch's scratch: nb rows of `stride` entries each (every candidate of
 * the runs and `slack` for a vector's store past the last), grown as needed. */
static inline size_t batch_rows(uint32_t **rows, size_t *cap, uint32_t nb, const run_range *runs, int nruns,
                                size_t slack)
{
    size_t stride = slack;
    for (int k = 0; k < nruns; k++) stride += runs[k].end - runs[k].start;
    if (nb * stride > *cap) {
        *cap = 2 * nb * stride;
        free(*rows);
        *rows = malloc(*cap * sizeof **rows);
        if (!*rows) sph_memory_fail("a thread's rows of one cell could not be held (%s)", SPH_LISTS_WHY);
    }
    return stride;
}

/* The batch's rows in order i0 .. i0 + nb - 1, as rows_reordered emits them:
 * packed into cw (words_row8, defined below), or appended to l. */
static inline void words_row8(words *c, const uint32_t *j, size_t m, uint32_t i);
static inline void batch_emit(const sph_sim *sim, list *l, words *cw, const uint32_t *rows, size_t stride,
                              const uint32_t *len, uint32_t i0, uint32_t nb)
{
    for (uint32_t b = 0; b < nb; b++) {
        const uint32_t *row = rows + b * stride;
        if (cw) {
            words_row8(cw, row, len[b], i0 + b);
            sim->S.nbr_start[i0 + b + 1] = (uint32_t)cw->len;
        } else {
            list_reserve(l, len[b]);
            memcpy(l->buf + l->len, row, len[b] * sizeof *row);
            l->len += len[b];
            sim->S.nbr_start[i0 + b + 1] = (uint32_t)l->len;
        }
    }
}

/* Row i (m neighbours j[], with 8 entries of slack readable past m) as in
 * words_row, 8 at a time: the offsets j - i packed to 16 bits in registers
 * and stored while checked within +-SPH_NBR_NEAR; a row that is not is
 * written again wide over them. */
static inline void words_row8(words *c, const uint32_t *j, size_t m, uint32_t i)
{
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), vi = _mm256_set1_epi32((int)i);
    const __m256i shift = _mm256_set1_epi32(SPH_NBR_NEAR), lim = _mm256_set1_epi32(2 * SPH_NBR_NEAR);
    __m256i far = _mm256_setzero_si256();
    words_reserve(c, m + 8); /* each store writes 8 words */
    uint16_t *o = c->buf + c->len;
    for (size_t k = 0; k < m; k += 8) {
        const __m256i live = _mm256_cmpgt_epi32(_mm256_set1_epi32(m - k >= 8 ? 8 : (int)(m - k)), lane);
        const __m256i d = _mm256_sub_epi32(_mm256_loadu_si256((const void *)(j + k)), vi);
        /* near: unsigned d + NEAR <= 2 NEAR, i.e. max(d + NEAR, 2 NEAR) == 2 NEAR */
        const __m256i u = _mm256_add_epi32(d, shift);
        far = _mm256_or_si256(far, _mm256_andnot_si256(_mm256_cmpeq_epi32(_mm256_max_epu32(u, lim), lim), live));
        const __m256i p = _mm256_permute4x64_epi64(_mm256_packs_epi32(d, d), 0x08); /* d0..d3, d4..d7 low */
        _mm_storeu_si128((__m128i *)(void *)(o + k), _mm256_castsi256_si128(p));
    }
    if (_mm256_testz_si256(far, far))
        c->len += m;
    else
        words_row(c, j, m, i); /* wide */
}

/* rows_reordered for AVX2, no periodic axis, a cell's particles at a time;
 * inlined so that each dim gets its own copy, without its tests in the loop. */
__attribute__((always_inline)) static inline void rows_batched(const sph_sim *sim, list *l, words *cw, uint32_t lo,
                                                              uint32_t hi, const int dim)
{
    const float *px = sim->P.pred[0], *py = sim->P.pred[1], *pz = dim == 3 ? sim->P.pred[2] : NULL;
    const uint32_t *chash = sim->S.cell_hash, n = sim->n;
    const float reach = sph_skin_radius(sim), h2 = reach * reach; /* h, or h (1 + skin) */
    const __m256 vh2 = _mm256_set1_ps(h2);
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    /* compress8 unpacked: lane numbers of the set bits, added to the first
     * index for the survivors' indices (one load, no shifts or permutation) */
    uint32_t lanes[256][8];
    for (unsigned m = 0; m < 256; m++)
        for (unsigned k = 0; k < 8; k++) lanes[m][k] = compress8[m] >> (4 * k) & 15u;
    run_range runs[27];
    uint32_t *rows = NULL, len[SPH_BATCH_MAX];
    size_t rows_cap = 0;
    for (uint32_t i0 = lo; i0 < hi;) {
        int32_t c[3] = {0, 0, 0};
        const uint32_t i1 = batch_end(sim, i0, hi, dim, c), nb = i1 - i0;
        const int nruns = stencil_runs(sim, c, runs, true);
        const size_t stride = batch_rows(&rows, &rows_cap, nb, runs, nruns, 8); /* every candidate, a vector's slack */
        for (uint32_t b = 0; b < nb; b++) len[b] = 0;
        for (int k = 0; k < nruns; k++) {
            const run_range *r = &runs[k];
            const __m256i vhash = _mm256_set1_epi32((int)r->hash);
            for (uint32_t j = r->start; j < r->end; j += 8) {
                const uint32_t left = r->end - j;
                const __m256i live = _mm256_cmpgt_epi32(_mm256_set1_epi32(left >= 8 ? 8 : (int)left), lane);
                __m256 xj, yj, zj = _mm256_setzero_ps();
                if (j + 8 <= n) { /* plain loads (the lanes past the run are masked off below) */
                    xj = _mm256_loadu_ps(px + j), yj = _mm256_loadu_ps(py + j);
                    if (dim == 3) zj = _mm256_loadu_ps(pz + j);
                } else {
                    xj = _mm256_maskload_ps(px + j, live), yj = _mm256_maskload_ps(py + j, live);
                    if (dim == 3) zj = _mm256_maskload_ps(pz + j, live);
                }
                const __m256i vj = _mm256_set1_epi32((int)j), idx = _mm256_add_epi32(vj, lane);
                __m256i base = live;
                if (!r->exact) {
                    const __m256i hj = _mm256_maskload_epi32((const int *)(const void *)(chash + j), live);
                    base = _mm256_and_si256(base, _mm256_cmpeq_epi32(hj, vhash));
                }
                const bool self = j < i1 && i0 < j + 8; /* the batch's own particles among these 8 */
                for (uint32_t b = 0; b < nb; b++) { /* scan_run's sums and tests, for i0 + b */
                    const uint32_t i = i0 + b;
                    const __m256 dx = _mm256_sub_ps(xj, _mm256_set1_ps(px[i]));
                    const __m256 dy = _mm256_sub_ps(yj, _mm256_set1_ps(py[i]));
                    __m256 r2 = _mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy));
                    if (dim == 3) {
                        const __m256 dz = _mm256_sub_ps(zj, _mm256_set1_ps(pz[i]));
                        r2 = _mm256_add_ps(r2, _mm256_mul_ps(dz, dz));
                    }
                    __m256i m = _mm256_and_si256(base, _mm256_castps_si256(_mm256_cmp_ps(r2, vh2, _CMP_LT_OQ)));
                    if (self) m = _mm256_andnot_si256(_mm256_cmpeq_epi32(idx, _mm256_set1_epi32((int)i)), m);
                    const unsigned bits = (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(m));
                    const __m256i at = _mm256_loadu_si256((const void *)lanes[bits]);
                    _mm256_storeu_si256((__m256i *)(void *)(rows + b * stride + len[b]), _mm256_add_epi32(vj, at));
                    len[b] += (uint32_t)__builtin_popcount(bits);
                }
            }
        }
        batch_emit(sim, l, cw, rows, stride, len, i0, nb);
        i0 = i1;
    }
    free(rows);
}
#endif

static uintptr_t page_size(void)
{
    const long ps = sysconf(_SC_PAGESIZE);
    return ps > 0 ? (uintptr_t)ps : 4096;
}

/* Hands the pages wholly inside [p, p + bytes) back to the system: their
 * contents are not needed again (a released page reads as zeros). Only a
 * hint: if it fails, the pages stay. */
static void release_pages(void *p, size_t bytes)
{
    const uintptr_t page = page_size();
    const uintptr_t a = ((uintptr_t)p + page - 1) & ~(page - 1), b = ((uintptr_t)p + bytes) & ~(page - 1);
    if (b > a) (void)madvise((void *)a, b - a, MADV_DONTNEED);
}

/* Copies a thread's rows into the joined lists and hands the copied pages of
 * its buffer back to the system as it goes (their contents are not needed
 * again: the next build writes the buffer from its start, and a released page
 * reads as zeros), so that a step's peak holds the lists once, not once and a
 * half with two threads. */
static void copy_releasing(void *dst, void *src, size_t bytes)
{
    const size_t chunk = (size_t)1 << 20;
    const uintptr_t page = page_size();
    uintptr_t done = (uintptr_t)src; /* released up to here */
    for (size_t off = 0; off < bytes; off += chunk) {
        const size_t m = bytes - off < chunk ? bytes - off : chunk;
        memcpy((char *)dst + off, (char *)src + off, m);
        const uintptr_t end = (uintptr_t)src + off + m;
        release_pages((void *)done, end - done);
        if ((end & ~(page - 1)) > done) done = end & ~(page - 1);
    }
}

#ifdef __AVX512F__
/* [search] wide_batch = on: rows_batched with 16 candidates to a vector
 * (AVX-512): the same sums and tests per candidate, the survivors of each
 * vector compressed in a register in their order, so the rows are
 * rows_batched's (and scan_run's) entry for entry. */
__attribute__((always_inline)) static inline void rows_batched16(const sph_sim *sim, list *l, words *cw, uint32_t lo,
                                                                uint32_t hi, const int dim)
{
    const float *px = sim->P.pred[0], *py = sim->P.pred[1], *pz = dim == 3 ? sim->P.pred[2] : NULL;
    const uint32_t *chash = sim->S.cell_hash;
    const float reach = sph_skin_radius(sim), h2 = reach * reach; /* h, or h (1 + skin) */
    const __m512 vh2 = _mm512_set1_ps(h2);
    const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    run_range runs[27];
    uint32_t *rows = NULL, len[SPH_BATCH_MAX];
    size_t rows_cap = 0;
    for (uint32_t i0 = lo; i0 < hi;) {
        int32_t c[3] = {0, 0, 0};
        const uint32_t i1 = batch_end(sim, i0, hi, dim, c), nb = i1 - i0;
        const int nruns = stencil_runs(sim, c, runs, true);
        const size_t stride = batch_rows(&rows, &rows_cap, nb, runs, nruns, 16); /* every candidate, a vector's slack */
        for (uint32_t b = 0; b < nb; b++) len[b] = 0;
        for (int k = 0; k < nruns; k++) {
            const run_range *r = &runs[k];
            const __m512i vhash = _mm512_set1_epi32((int)r->hash);
            for (uint32_t j = r->start; j < r->end; j += 16) {
                const uint32_t left = r->end - j;
                const __mmask16 live = left >= 16 ? (__mmask16)0xFFFF : (__mmask16)((1u << left) - 1);
                const __m512 xj = _mm512_maskz_loadu_ps(live, px + j), yj = _mm512_maskz_loadu_ps(live, py + j);
                const __m512 zj = dim == 3 ? _mm512_maskz_loadu_ps(live, pz + j) : _mm512_setzero_ps();
                const __m512i idx = _mm512_add_epi32(_mm512_set1_epi32((int)j), lane);
                __mmask16 base = live;
                if (!r->exact) base = _mm512_mask_cmpeq_epi32_mask(base, _mm512_maskz_loadu_epi32(live, chash + j), vhash);
                const bool self = j < i1 && i0 < j + 16; /* the batch's own particles among these 16 */
                for (uint32_t b = 0; b < nb; b++) { /* scan_run's sums and tests, for i0 + b */
                    const uint32_t i = i0 + b;
                    const __m512 dx = _mm512_sub_ps(xj, _mm512_set1_ps(px[i]));
                    const __m512 dy = _mm512_sub_ps(yj, _mm512_set1_ps(py[i]));
                    __m512 r2 = _mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy));
                    if (dim == 3) {
                        const __m512 dz = _mm512_sub_ps(zj, _mm512_set1_ps(pz[i]));
                        r2 = _mm512_add_ps(r2, _mm512_mul_ps(dz, dz));
                    }
                    __mmask16 m = _mm512_mask_cmp_ps_mask(base, r2, vh2, _CMP_LT_OQ);
                    if (self) m = _mm512_mask_cmpneq_epi32_mask(m, idx, _mm512_set1_epi32((int)i));
                    /* compressed in a register, then stored whole (a compress to memory is slow on some CPUs) */
                    _mm512_storeu_si512((void *)(rows + b * stride + len[b]), _mm512_maskz_compress_epi32(m, idx));
                    len[b] += (uint32_t)__builtin_popcount((unsigned)m);
                }
            }
        }
        batch_emit(sim, l, cw, rows, stride, len, i0, nb);
        i0 = i1;
    }
    free(rows);
}
#endif

/* Each thread builds the lists of a contiguous range of particles in its own
 * buffer; the rows are then laid end to end. */
static void run(sph_sim *sim)
{
    sph_search_data *S = &sim->S;
    const uint32_t n = sim->n;
    const int T = S->n_threads;
    size_t base[SPH_MAX_THREADS + 1];
    float *spos = S->spos;
    if (sph_skin_keep(sim)) return; /* Verlet lists: the last build's still hold every pair within h */
    /* With thread 0 building in place and others copying in: the joined
     * lists past thread 0's rows are dead until the copies, so they are
     * released now and the other threads' buffers as they are copied; a
     * step's peak then holds the lists once (not once and a half with two
     * threads), for some page faults on the copied share at each build. */
    const bool release = sim->def.lists_in_place == SPH_ON && sim->def.lists_resident != SPH_ON && T > 1 &&
                         n > SPH_PARALLEL_MIN;
    if (release && S->nbr && S->nbr_first < S->nbr_cap * sizeof *S->nbr)
        release_pages((char *)S->nbr + S->nbr_first, S->nbr_cap * sizeof *S->nbr - S->nbr_first);
    if (spos && !S->reordered && !S->next) { /* positions in sorted order, padded to 4 floats (z = 0 in 2D) */
        const int dim = sim->dim;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int64_t e = 0; e < (int64_t)n; e++) {
            uint32_t j = S->entries[e].index;
            float *o = spos + 4 * e;
            o[0] = sim->P.pred[0][j];
            o[1] = sim->P.pred[1][j];
            o[2] = dim == 3 ? sim->P.pred[2][j] : 0.0f;
            o[3] = 0.0f;
        }
    }
#pragma omp parallel num_threads(T) if (n > SPH_PARALLEL_MIN)
    {
        int t = 0, nt = 1;
#ifdef _OPENMP
        t = omp_get_thread_num();
        nt = omp_get_num_threads();
#endif
        uint32_t lo = (uint32_t)((uint64_t)n * (uint64_t)t / (uint64_t)nt);
        uint32_t hi = (uint32_t)((uint64_t)n * (uint64_t)(t + 1) / (uint64_t)nt);
        /* in place: thread 0's rows start the joined array, so it builds there */
        const bool direct = sim->def.lists_in_place == SPH_ON && t == 0;
        /* compact: each row is built in l (32-bit, one row at a time), then stored in cw as words */
        const bool compact = S->compact;
        list l = {0};
        words c = {0}, *cw = NULL;
        if (compact) {
            c = direct ? (words){(uint16_t *)(void *)S->nbr, 0, 2 * S->nbr_cap}
                       : (words){(uint16_t *)(void *)S->tbuf[t], 0, S->tcap[t]};
            cw = &c;
        } else {
            l = direct ? (list){S->nbr, 0, S->nbr_cap} : (list){S->tbuf[t], 0, S->tcap[t]};
        }
        if (S->reordered) {
            const bool periodic = sim->period[0] > 0 || sim->period[1] > 0 || sim->period[2] > 0;
#ifdef __AVX2__
            const sph_scene_def *D = &sim->def;
            if (!periodic && D->vector == SPH_ON && D->vector_avx2 == SPH_ON && D->cell_batch == SPH_ON) {
#ifdef __AVX512F__
                if (D->wide_batch == SPH_ON)
                    sim->dim == 2 ? rows_batched16(sim, &l, cw, lo, hi, 2) : rows_batched16(sim, &l, cw, lo, hi, 3);
                else
#endif
                    sim->dim == 2 ? rows_batched(sim, &l, cw, lo, hi, 2) : rows_batched(sim, &l, cw, lo, hi, 3);
            } else
#endif
            if (sim->dim == 2)
                periodic ? rows_reordered(sim, &l, cw, lo, hi, 2, true) : rows_reordered(sim, &l, cw, lo, hi, 2, false);
            else
                periodic ? rows_reordered(sim, &l, cw, lo, hi, 3, true) : rows_reordered(sim, &l, cw, lo, hi, 3, false);
        } else {
            for (uint32_t i = lo; i < hi; i++) {
                neighbours_of(sim, spos, &l, i);
                S->nbr_start[i + 1] = row_done(&l, cw, i); /* local end of row i, made global below */
            }
        }
        size_t len = l.len; /* in the lists' unit: 32-bit indices, or words */
        if (compact) {
            free(l.buf);
            len = c.len;
            if (direct) {
                S->nbr = (uint32_t *)(void *)c.buf;
                S->nbr_cap = c.cap / 2;
            } else {
                S->tbuf[t] = (uint32_t *)(void *)c.buf;
                S->tcap[t] = c.cap;
            }
        } else if (direct) {
            S->nbr = l.buf;
            S->nbr_cap = l.cap;
        } else {
            S->tbuf[t] = l.buf;
            S->tcap[t] = l.cap;
        }
        base[t + 1] = len;
        if (direct) S->nbr_first = len * (compact ? sizeof *c.buf : sizeof *l.buf);
#pragma omp barrier
#pragma omp single
        {
            base[0] = 0;
            for (int k = 0; k < nt; k++) base[k + 1] += base[k];
            for (int k = nt + 1; k <= T; k++) base[k] = base[nt];
            if (base[nt] > UINT32_MAX) /* row offsets are 32-bit */
                sph_memory_fail("%.3g neighbour pairs, more than the lists' 2^32", (double)base[nt]);
            const size_t need = compact ? (base[nt] + 1) / 2 : base[nt]; /* 32-bit words */
            if (need > S->nbr_cap) {
                size_t cap = need + need / 4 + 1024;
                uint32_t *b = realloc(S->nbr, cap * sizeof *b); /* keeps thread 0's rows if built in place */
                if (!b) {
                    char size[32];
                    sph_memory_fail("the neighbour lists could not grow to %s (%s)",
                                    sph_memory_text((double)cap * sizeof *b, size, sizeof size), SPH_LISTS_WHY);
                }
                S->nbr = b;
                S->nbr_cap = cap;
            }
            S->nbr_start[0] = 0;
        }
        for (uint32_t i = lo; i < hi; i++) S->nbr_start[i + 1] += (uint32_t)base[t];
        if (len && !direct) {
            void *to = compact ? (void *)((uint16_t *)(void *)S->nbr + base[t]) : (void *)(S->nbr + base[t]);
            void *from = compact ? (void *)c.buf : (void *)l.buf;
            const size_t bytes = len * (compact ? sizeof *c.buf : sizeof *l.buf);
            if (release)
                copy_releasing(to, from, bytes);
            else
                memcpy(to, from, bytes);
        }
    }
    sph_skin_mark(sim);
}

const sph_pass sph_pass_neighbours = {
    .name = "neighbours",
    .summary = "neighbour lists within h",
    .reads = SPH_BIT(PRED) | SPH_RES_ENTRIES | SPH_RES_START,
    .writes = SPH_RES_LISTS,
    .group = SPH_GROUP_SEARCH,
    .highlight = "neighbours",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
