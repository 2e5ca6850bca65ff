/* The sort pass's three sorts and the offsets table: every sort gives qsort's
 * array bit for bit, ordered by (key, index), a permutation of its input; the
 * start table points at the first entry of each key's run. Sizes around
 * powers of two (the bitonic network pads to one), tables of one key (every
 * entry collides) and tables larger than n; and the seed's worked example. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "sph_search.h"
#include "test_util.h"

static uint64_t rng_state;
static uint32_t rnd(void) /* xorshift64*: reproducible inputs */
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (uint32_t)((rng_state * 0x2545F4914F6CDD1Dull) >> 32);
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

typedef enum pattern { RANDOM, SORTED, REVERSED, FEW_KEYS, ALL_EQUAL, PATTERN_COUNT } pattern;
static const char *const pattern_names[] = {"random", "sorted", "reversed", "few keys", "all equal"};

/* Entries as the hash pass writes them: index = position, key < table_size,
 * and a hash that varies independently of the key (so that a sort moving
 * keys without their hash shows). */
static void make_entries(sph_entry *e, uint32_t n, uint32_t table_size, pattern p)
{
    uint32_t *keys = malloc(((size_t)n + 1) * sizeof *keys);
    cr_assert_not_null(keys);
    const uint32_t few[3] = {0, table_size / 2, table_size - 1};
    for (uint32_t i = 0; i < n; i++) {
        switch (p) {
        case FEW_KEYS: keys[i] = few[rnd() % 3]; break;
        case ALL_EQUAL: keys[i] = table_size - 1; break;
        default: keys[i] = rnd() % table_size; break;
        }
    }
    if (p == SORTED || p == REVERSED) qsort(keys, n, sizeof *keys, cmp_u32);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t key = p == REVERSED ? keys[n - 1 - i] : keys[i];
        e[i] = (sph_entry){key, rnd(), i};
    }
    free(keys);
}

/* The checks every sorted array passes: equal to qsort's (memcmp), strictly
 * ordered by (key, index) (indices are distinct), a permutation of the input
 * (each index once, carrying its own entry). */
static void check_sorted(const char *what, const sph_entry *in, const sph_entry *out, const sph_entry *ref,
                         uint32_t n, uint32_t table_size)
{
    cr_assert(n == 0 || memcmp(out, ref, n * sizeof *out) == 0, "%s (n = %u, table %u): differs from qsort", what, n,
              table_size);
    for (uint32_t i = 1; i < n; i++)
        cr_assert(sph_entry_less(out[i - 1], out[i]), "%s (n = %u, table %u): entries %u, %u out of order", what, n,
                  table_size, i - 1, i);
    char *seen = calloc((size_t)n + 1, 1);
    cr_assert_not_null(seen);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t j = out[i].index;
        cr_assert(j < n && !seen[j], "%s (n = %u): index %u missing or repeated", what, n, j);
        seen[j] = 1;
        cr_assert(memcmp(&out[i], &in[j], sizeof in[j]) == 0, "%s (n = %u): entry of index %u altered", what, n, j);
    }
    free(seen);
}

/* The offsets table of a sorted array: start[k] is the first entry of key
 * k's run, SPH_EMPTY for a key no entry has. */
static void check_offsets(const char *what, const sph_entry *e, uint32_t n, uint32_t table_size)
{
    uint32_t *start = malloc((size_t)table_size * sizeof *start);
    char *present = calloc(table_size, 1);
    cr_assert(start && present);
    memset(start, 0x5a, (size_t)table_size * sizeof *start); /* garbage: the pass must overwrite every slot */
    sph_offsets_build(e, n, start, table_size);
    for (uint32_t i = 0; i < n; i++) present[e[i].key] = 1;
    for (uint32_t k = 0; k < table_size; k++) {
        uint32_t s = start[k];
        if (s == SPH_EMPTY) {
            cr_assert(!present[k], "%s (n = %u, table %u): key %u has entries but start is empty", what, n,
                      table_size, k);
            continue;
        }
        cr_assert(s < n, "%s (n = %u, table %u): start[%u] = %u out of range", what, n, table_size, k, s);
        cr_assert_eq(e[s].key, k, "%s: start[%u] = %u points at key %u", what, k, s, e[s].key);
        cr_assert(s == 0 || e[s - 1].key != k, "%s: start[%u] = %u is not the first of its run", what, k, s);
    }
    free(start);
    free(present);
}

/* Sorts one input with all three sorts and checks each, and the offsets. */
static void check_all_sorts(uint32_t n, uint32_t table_size, pattern p)
{
#ifdef _OPENMP
    /* 2 threads from n = 1000 (the library goes parallel above
     * SPH_PARALLEL_MIN items); smaller inputs on 1, which keeps hundreds of
     * small parallel regions from costing seconds when the test processes
     * share the cores, should that threshold come down. */
    omp_set_num_threads(n >= 1000 ? 2 : 1);
#endif
    size_t bytes = ((size_t)n + 1) * sizeof(sph_entry); /* + 1: no zero-size allocations */
    sph_entry *in = malloc(bytes), *ref = malloc(bytes), *out = malloc(bytes), *scratch = malloc(bytes);
    uint32_t *count = malloc(((size_t)table_size + 1) * sizeof *count);
    cr_assert(in && ref && out && scratch && count);
    make_entries(in, n, table_size, p);
    char what[96];

    memcpy(ref, in, n * sizeof *in);
    sph_sort_qsort(ref, n);
    snprintf(what, sizeof what, "qsort, %s", pattern_names[p]);
    check_sorted(what, in, ref, ref, n, table_size);

    memcpy(out, in, n * sizeof *in);
    sph_sort_bitonic(out, n);
    snprintf(what, sizeof what, "bitonic, %s", pattern_names[p]);
    check_sorted(what, in, out, ref, n, table_size);

    memcpy(out, in, n * sizeof *in);
    memset(count, 0xa5, ((size_t)table_size + 1) * sizeof *count); /* garbage: the sort must clear it */
    sph_sort_counting(out, scratch, count, n, table_size);
    snprintf(what, sizeof what, "counting, %s", pattern_names[p]);
    check_sorted(what, in, out, ref, n, table_size);

    snprintf(what, sizeof what, "offsets, %s", pattern_names[p]);
    check_offsets(what, ref, n, table_size);
    free(in);
    free(ref);
    free(out);
    free(scratch);
    free(count);
}

static const uint32_t sizes[] = {0, 1, 2, 3, 4, 5, 7, 8, 9, 16, 17, 100, 1000, 1023, 1024, 1025, 4097};
#define N_SIZES (sizeof sizes / sizeof sizes[0])

Test(sort, all_sorts_match_qsort_table_size_n)
{
    rng_state = 0x9E3779B97F4A7C15ull;
    for (size_t s = 0; s < N_SIZES; s++)
        for (int p = 0; p < PATTERN_COUNT; p++) check_all_sorts(sizes[s], sizes[s] ? sizes[s] : 1, (pattern)p);
}

/* table_size = 1: every entry has key 0, the order is by index alone. */
Test(sort, all_sorts_match_qsort_one_key)
{
    rng_state = 12345;
    for (size_t s = 0; s < N_SIZES; s++)
        for (int p = 0; p < PATTERN_COUNT; p++) check_all_sorts(sizes[s], 1, (pattern)p);
}

/* Tables larger than n (most keys empty) and much smaller (long runs). */
Test(sort, all_sorts_match_qsort_other_table_sizes)
{
    rng_state = 777;
    for (size_t s = 0; s < N_SIZES; s++)
        for (int p = 0; p < PATTERN_COUNT; p++) {
            check_all_sorts(sizes[s], 4 * sizes[s] + 3, (pattern)p);
            check_all_sorts(sizes[s], 3, (pattern)p);
            check_all_sorts(sizes[s], 2, (pattern)p);
        }
}

/* Sizes where the bitonic network's steps (P/2 pairs, P = the power of two
 * >= n) exceed SPH_PARALLEL_MIN and run on 2 threads, a power of two plus one
 * and a ragged one; offsets likewise (n + table_size above it). Few inputs:
 * every step is a parallel region, over a hundred per sort, and on a loaded
 * machine each can wait for a descheduled thread. */
Test(sort, all_sorts_match_qsort_parallel_sizes)
{
    rng_state = 4242;
    check_all_sorts(2 * SPH_PARALLEL_MIN + 1, 2 * SPH_PARALLEL_MIN + 1, RANDOM);
    check_all_sorts(2 * SPH_PARALLEL_MIN + 1, 3, FEW_KEYS);
    check_all_sorts(3 * SPH_PARALLEL_MIN + 7, 1000, RANDOM);
}

/* Bitonic sort of keys 0..n-1 given in every order of a small n: all 5040
 * permutations of 7 (a non-power of two, where the padding matters) and all
 * 40320 of 8 sort correctly. On one thread: the network's pattern does not
 * depend on the thread count (the other tests run it on several), and 45000
 * sorts on a team of threads would spend seconds starting parallel regions. */
static void check_every_permutation(uint32_t n)
{
    uint32_t perm[8];
    for (uint32_t i = 0; i < n; i++) perm[i] = i;
    uint32_t c[8] = {0};
    uint32_t i = 0, count = 0;
    sph_entry e[8];
    for (;;) {
        for (uint32_t j = 0; j < n; j++) e[j] = (sph_entry){perm[j], perm[j] * 7u, j};
        sph_sort_bitonic(e, n);
        for (uint32_t j = 0; j < n; j++)
            cr_assert(e[j].key == j && e[j].hash == j * 7u, "n = %u, permutation %u: slot %u has key %u", n, count,
                      j, e[j].key);
        count++;
        /* Heap's algorithm, iterative */
        while (i < n && c[i] >= i) c[i++] = 0;
        if (i >= n) break;
        uint32_t a = i % 2 ? c[i] : 0, t = perm[a];
        perm[a] = perm[i];
        perm[i] = t;
        c[i]++;
        i = 0;
    }
    uint32_t want = 1;
    for (uint32_t k = 2; k <= n; k++) want *= k;
    cr_assert_eq(count, want);
}

Test(sort, bitonic_every_permutation_of_7_and_8)
{
#ifdef _OPENMP
    omp_set_num_threads(1);
#endif
    check_every_permutation(7);
    check_every_permutation(8);
}

/* The seed's worked example: 10 particles, particle i in the cell of key
 * keys[i], table size 10. The seed's slide writes the start table with
 * "+inf" for the keys no particle has; here that is SPH_EMPTY. */
Test(sort, seed_worked_example)
{
    const uint32_t keys[10] = {9, 0, 6, 7, 1, 1, 4, 2, 2, 2};
    const uint32_t want_keys[10] = {0, 1, 1, 2, 2, 2, 4, 6, 7, 9};
    const uint32_t want_index[10] = {1, 4, 5, 7, 8, 9, 6, 2, 3, 0};
    const uint32_t want_start[10] = {0, 1, 3, SPH_EMPTY, 6, SPH_EMPTY, 7, 8, SPH_EMPTY, 9};
    for (int variant = 0; variant < 3; variant++) {
        sph_entry e[10], scratch[10];
        uint32_t count[11], start[10];
        for (uint32_t i = 0; i < 10; i++) e[i] = (sph_entry){keys[i], 1000 + keys[i], i};
        if (variant == 0) sph_sort_bitonic(e, 10);
        if (variant == 1) sph_sort_counting(e, scratch, count, 10, 10);
        if (variant == 2) sph_sort_qsort(e, 10);
        for (int i = 0; i < 10; i++) {
            cr_assert_eq(e[i].key, want_keys[i], "sort %d, slot %d", variant, i);
            cr_assert_eq(e[i].index, want_index[i], "sort %d, slot %d", variant, i);
            cr_assert_eq(e[i].hash, 1000 + want_keys[i], "sort %d, slot %d", variant, i);
        }
        sph_offsets_build(e, 10, start, 10);
        for (int k = 0; k < 10; k++) cr_assert_eq(start[k], want_start[k], "sort %d: start[%d] = %u", variant, k, start[k]);
    }
}

/* Offsets of an empty array: every key empty. */
Test(sort, offsets_of_nothing_are_all_empty)
{
    uint32_t start[5] = {1, 2, 3, 4, 5};
    sph_entry none[1] = {{0, 0, 0}};
    sph_offsets_build(none, 0, start, 5);
    for (int k = 0; k < 5; k++) cr_assert_eq(start[k], SPH_EMPTY);
}
