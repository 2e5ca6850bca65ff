/* Validate mode (as Fluids v3 has): the same state run at two settings for a
 * few steps, side by side, and what differs: the neighbour sets of the first
 * step and the positions at the end. A correct optimisation finds the same
 * neighbour sets as the reference level (brute force, L0) and positions that
 * differ only by float rounding (sums in another order); a wrong one shows
 * at once. The window's validate key and the tests call it. */
#ifndef SPH_COMPARE_H
#define SPH_COMPARE_H

#include <stdbool.h>
#include <stdint.h>

#include "sph_levels.h"
#include "sph_sim.h"

/* A neighbour-set difference at a pair this close to the support's edge,
 * |r - h| <= SPH_COMPARE_EDGE h, is float rounding's call (a sum in another
 * order, a fused multiply-add), not a wrong answer: it is counted apart (as
 * the bench's checks do, BENCH_EDGE). */
#define SPH_COMPARE_EDGE 1e-5

typedef struct sph_compare_result {
    uint32_t n;             /* particles compared (both runs have the same ids) */
    int steps;              /* steps run from the common state */
    uint32_t sets_differ;   /* particles whose first-step neighbour set differs beyond the edge band */
    uint32_t pairs_differ;  /* ordered pairs in one run's sets only, beyond the edge band */
    uint32_t edge_pairs;    /* ordered pairs in one run's sets only, at the support's edge */
    uint32_t worst_id;      /* id of the particle with the most differing pairs (UINT32_MAX: none) */
    double pairs_a, pairs_b; /* [1] ordered neighbour pairs of the first step, each run */
    double dx;              /* [m] largest position difference after `steps` steps */
    double dv;              /* [m/s] largest velocity difference after `steps` steps */
    uint32_t dx_id;         /* id of the particle with the largest dx */
    bool stopped;           /* the watchdog stopped one of the runs: the figures are up to there */
} sph_compare_result;

/* Runs copies of a and b (each left as it was; they must hold the same
 * particles, by id) for `steps` steps (at least 1) and compares them. */
sph_error_code sph_sim_compare(const sph_sim *a, const sph_sim *b, int steps, sph_compare_result *out,
                               sph_error *err);
/* Compares sim with the same state run at the reference level `ref` (its
 * keys applied to sim's scene, on its thread count). */
sph_error_code sph_sim_validate(const sph_sim *sim, const sph_level *ref, int steps, sph_compare_result *out,
                                sph_error *err);
/* The result in one line of at most n characters, for the HUD and messages. */
void sph_compare_text(const sph_compare_result *r, const char *ref, char *out, size_t n);

#endif
