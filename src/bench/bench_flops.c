/* sphlab bench: counted floating-point operations per pass, so that the
 * ladder can say how far each level is from the machine's measured float
 * peak (docs/performance.md, "The machine's limits").
 *
 * The counts are the formulas' operations, counted by hand once, the same
 * for every level: a level that shares a distance between two passes, or
 * computes a lane it then masks, does more or fewer instructions than this,
 * but the same useful work. A square root and a division count one each
 * (they cost more cycles; the convention of LINPACK-style counts). */
#include <math.h>
#include <stdlib.h>

#include "bench.h"
#include "../passes/simd.h"

/* Flops per neighbour-list entry (i->j), counted by hand from the scalar
 * pair loops of src/passes/density.c, pressure_force.c and viscosity.c
 * (docs/performance.md, "The machine's limits"): density 13 (the distance
 * r^2 = 8, poly6's (h^2 - r^2)^3 and m_j times it); pressure force 25 plus a
 * square root and a division: 27; viscosity 25 plus a square root: 26.
 * The fused walk ([compute] fuse_forces) does both in the pressure force's
 * pass: 27 + 26 counted there (the same work, though it shares r and the
 * root), 0 in the viscosity pass that only keeps its place. */
#define BENCH_FLOPS_DENSITY 13
#define BENCH_FLOPS_PRESSURE 27
#define BENCH_FLOPS_VISCOSITY 26
/* Per candidate of the search, the particle itself included: dx (3 sub),
 * r^2 (3 mul, 2 add), the comparison with h^2 not counted: 8. */
#define BENCH_FLOPS_CANDIDATE 8

double bench_flops_per_entry(int pass, bool fused)
{
    switch (pass) {
    case SPH_PASS_DENSITY: return BENCH_FLOPS_DENSITY;
    case SPH_PASS_PRESSURE_FORCE: return fused ? BENCH_FLOPS_PRESSURE + BENCH_FLOPS_VISCOSITY : BENCH_FLOPS_PRESSURE;
    case SPH_PASS_VISCOSITY: return fused ? 0 : BENCH_FLOPS_VISCOSITY;
    default: return 0;
    }
}

double bench_flops_per_candidate(void) { return BENCH_FLOPS_CANDIDATE; }

/* The distance tests of one build of the lists: brute force tests every
 * other particle (n (n - 1)); a cell search tests every particle of the
 * 3^dim cells around a particle's cell, with the sim's own cells (size
 * h (1 + 2^-10), or h (1 + skin) with Verlet lists). The hash levels also
 * read the particles of another cell that shares a key (a collision): a few
 * more, not counted. Counted on the predicted positions with a dense count
 * grid over their bounding box: O(n + cells). NaN if unknown (a GL level,
 * no search, out of memory). */
static double cell_candidates(const sph_sim *sim)
{
    const uint32_t n = sim->n;
    const int dim = sim->def.dim;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    int32_t nc[3] = {1, 1, 1};
    for (int a = 0; a < dim; a++) {
        const float *x = sim->P.pred[a];
        lo[a] = hi[a] = x[0];
        for (uint32_t i = 1; i < n; i++) lo[a] = fmin(lo[a], x[i]), hi[a] = fmax(hi[a], x[i]);
        double size = sim->S.cells.size[a];
        if (!(size > 0)) return NAN;
        double cells = floor((hi[a] - lo[a]) / size) + 1;
        if (cells > 4096) return NAN; /* the bench's block is a few hundred cells wide at most */
        nc[a] = (int32_t)cells;
    }
    size_t total = (size_t)nc[0] * (size_t)nc[1] * (size_t)nc[2];
    uint32_t *count = calloc(total, sizeof *count);
    if (!count) return NAN;
    for (uint32_t i = 0; i < n; i++) {
        size_t c = 0;
        for (int a = dim - 1; a >= 0; a--) {
            int32_t k = (int32_t)floor((sim->P.pred[a][i] - lo[a]) / sim->S.cells.size[a]);
            if (k >= nc[a]) k = nc[a] - 1;
            c = c * (size_t)nc[a] + (size_t)(k < 0 ? 0 : k);
        }
        count[c]++;
    }
    double sum = 0;
    const int zr = dim == 3 ? 1 : 0;
    for (int32_t z = 0; z < nc[2]; z++)
        for (int32_t y = 0; y < nc[1]; y++)
            for (int32_t x = 0; x < nc[0]; x++) {
                uint32_t here = count[((size_t)z * nc[1] + y) * nc[0] + x];
                if (!here) continue;
                double around = 0;
                for (int dz = -zr; dz <= zr; dz++)
                    for (int dy = -1; dy <= 1; dy++)
                        for (int dx = -1; dx <= 1; dx++) {
                            int32_t X = x + dx, Y = y + dy, Z = z + dz;
                            if (X < 0 || Y < 0 || Z < 0 || X >= nc[0] || Y >= nc[1] || Z >= nc[2]) continue;
                            around += count[((size_t)Z * nc[1] + Y) * nc[0] + X];
                        }
                sum += here * around;
            }
    free(count);
    return sum;
}

void bench_flops_of(const sph_sim *sim, bench_meas *m)
{
    m->fused = sph_forces_fused(sim);
    m->skin = sim->def.skin;
    m->candidates = NAN;
    if (sim->backend || !sim->in_pipeline[SPH_PASS_NEIGHBOURS] || sim->n == 0) return;
    if (sim->def.search == SPH_SEARCH_BRUTE)
        m->candidates = (double)sim->n * (double)(sim->n - 1);
    else
        m->candidates = cell_candidates(sim);
}

void bench_pass_flops(const bench_meas *m, double flops[SPH_PASS_COUNT])
{
    for (int p = 0; p < SPH_PASS_COUNT; p++) flops[p] = NAN;
    if (!(m->pairs > 0)) return; /* a GL level: no lists, no count */
    for (int p = 0; p < SPH_PASS_COUNT; p++) {
        if (!isfinite(m->pass_ms[p])) continue;
        double per = bench_flops_per_entry(p, m->fused);
        if (per > 0 || p == SPH_PASS_VISCOSITY) flops[p] = m->pairs * per;
    }
    /* Verlet lists (skin > 0) are built on some steps only: the median step's
     * search time and one build's tests do not match, so no count */
    if (isfinite(m->pass_ms[SPH_PASS_NEIGHBOURS]) && m->skin == 0)
        flops[SPH_PASS_NEIGHBOURS] = m->candidates * BENCH_FLOPS_CANDIDATE;
}
