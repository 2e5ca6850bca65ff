/* Pass: density by summation, rho_i = sum_j m_j W(|x_i - x_j|, h), the
 * particle itself included (its W(0) term is most of the sum at low
 * neighbour counts). With walls of the volume model, rho0 times the share of
 * the kernel hidden behind the walls is added (sph_wall_hidden: the fluid's
 * lattice continued behind them): a particle at a wall is not missing half
 * its neighbours. With density_method = continuity a new run starts rho_c
 * from the lattice's m / spacing^dim (sph_sim.c), and the sum is made only
 * where continuity is switched on during a run (start_carrying); each step
 * rho_c += dt drho (drho from the density_rate pass just before) and rho = rho_c. */
#include "simd.h"
#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    return sph_scene_needs_density(def) ? NULL : "no effect of the scene needs density (the neighbour search)";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    if (def->density_method == SPH_DMETHOD_CONTINUITY) /* a new run starts from the lattice's, not a sum (sph_sim.c) */
        snprintf(out, (size_t)n,
                 "carried (continuity): rho_c + dt drho each step, from m / spacing^dim at the start; the %s "
                 "kernel's sum%s only where continuity is switched on during a run",
                 sph_kernel_names[def->kernel_density],
                 sph_scene_wall_volume(def) ? " (walls as the lattice continued)" : "");
    else
        snprintf(out, (size_t)n, "summation with the %s kernel%s", sph_kernel_names[def->kernel_density],
                 sph_scene_wall_volume(def) ? ", walls count as the lattice continued at rest" : "");
}

/* The sum for one particle; dim and dbl are constants (SPH_SPECIALISE). */
static inline void density_one(const sph_sim *sim, const sph_kernel *k, int i, const int dim, const bool dbl,
                               const bool periodic)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const float *per = sim->period, *iper = sim->inv_period;
    float xi[3];
    for (int d = 0; d < dim; d++) xi[d] = P->pred[d][i];
    float sf = P->mass[i] * sph_kernel_w(k, 0.0f);
    double sd = sf;
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        float r2 = 0;
        for (int d = 0; d < dim; d++) {
            float dx = xi[d] - P->pred[d][j];
            if (periodic) dx = sph_min_image(dx, per[d], iper[d]);
            r2 += dx * dx;
        }
        float w = P->mass[j] * sph_kernel_w(k, sqrtf(r2));
        if (dbl) sd += w;
        else sf += w;
    }
    float sum = dbl ? (float)sd : sf;
    if (sph_sim_wall_volume(sim)) sum += sim->def.rest_density * sph_wall_hidden(sim, k, i, NULL);
    P->rho[i] = sum;
    P->vol[i] = P->mass[i] / sum;
}

#if SPH_HAVE_AVX512
/* Poly6 needs no square root: W = sigma (h^2 - r^2)^3. */
static inline void density_one_avx512(const sph_sim *sim, const sph_kernel *k, int i, const int dim)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const __m512 h2 = _mm512_set1_ps(k->h2);
    __m512 xi[3], d3[3];
    sph_simd_centre(P, i, dim, xi);
    __m512 acc = _mm512_setzero_ps();
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    const uint32_t end = row.n;
    for (uint32_t e = 0; e < end; e += 16) {
        __mmask16 live = sph_simd_live(e, end);
        __m512i idx = sph_simd_nbr(&row, e, live);
        __m512 r2 = sph_simd_offsets(P, live, idx, xi, dim, d3);
        __m512 d = _mm512_max_ps(_mm512_sub_ps(h2, r2), _mm512_setzero_ps());
        __m512 w = _mm512_mul_ps(_mm512_mul_ps(d, d), d);
        acc = _mm512_mask3_fmadd_ps(w, sph_simd_gather(live, idx, P->mass), acc, live); /* dead lanes keep acc */
    }
    float sum = P->mass[i] * sph_kernel_w(k, 0.0f) + k->sigma * _mm512_reduce_add_ps(acc);
    if (sph_sim_wall_volume(sim)) sum += sim->def.rest_density * sph_wall_hidden(sim, k, i, NULL);
    P->rho[i] = sum;
    P->vol[i] = P->mass[i] / sum;
}
#endif

#if SPH_HAVE_AVX2
/* The loop above, 8 neighbours at a time ([search] vector_avx2 = on); with
 * rec (packed_records = on) each neighbour's x, y, z, m from its record
 * (sph_simd8_rec4) instead of 4 gathers: the same values, the same sums. */
static inline void density_one_avx2(const sph_sim *sim, const sph_kernel *k, int i, const int dim, const float *rec)
{
    const sph_particles *P = &sim->P;
    const __m256 h2 = _mm256_set1_ps(k->h2), zero = _mm256_setzero_ps();
    __m256 xi[3], d3[3];
    sph_simd8_centre(P, i, dim, xi);
    __m256 acc = zero;
    const sph_nbr_row row = sph_nbr_row_of(&sim->S, (uint32_t)i);
    const uint32_t end = row.n;
    /* records and a compact row (the common case): the records' addresses straight from the offsets, no index
     * vector (as the force walk, pressure_force.c); the last block's dead lanes get offset 0, the particle's own
     * record, whose w the mask zeroes: the same sums to the bit */
    const bool by_offset = rec && row.o;
    const float *const rec_i = rec ? rec + 4 * (size_t)i : NULL;
    for (uint32_t e = 0; e < end; e += 8) {
        const __m256i live = sph_simd8_live(e, end);
        const __m256i idx = by_offset ? _mm256_setzero_si256() : sph_simd8_nbr(&row, e, end, live);
        __m256 r2, mj, f[4];
        if (rec) { /* sph_simd8_offsets' sums on the records' positions */
            if (by_offset) {
                int16_t last[8];
                sph_simd8_rec4_off_per(rec_i, 4, sph_simd8_block_offsets(row.o, e, end, last), 0, f);
            } else {
                uint32_t j[8];
                sph_simd8_indices(idx, j);
                sph_simd8_rec4(rec, 4, j, f);
            }
            for (int d = 0; d < 3; d++) d3[d] = d < dim ? _mm256_sub_ps(xi[d], f[d]) : zero;
            r2 = _mm256_add_ps(_mm256_mul_ps(d3[0], d3[0]), _mm256_mul_ps(d3[1], d3[1]));
            if (dim == 3) r2 = _mm256_add_ps(r2, _mm256_mul_ps(d3[2], d3[2]));
            mj = f[3];
        } else {
            r2 = sph_simd8_offsets(P, live, idx, xi, dim, d3);
            mj = sph_simd8_gather(live, idx, P->mass);
        }
        __m256 d = _mm256_max_ps(_mm256_sub_ps(h2, r2), zero);
        __m256 w = sph_simd8_keep(live, _mm256_mul_ps(_mm256_mul_ps(d, d), d));
        acc = _mm256_fmadd_ps(w, mj, acc); /* dead lanes add 0 (w = 0, mj a real mass) */
    }
    float sum = P->mass[i] * sph_kernel_w(k, 0.0f) + k->sigma * sph_simd8_sum(acc);
    if (sph_sim_wall_volume(sim)) sum += sim->def.rest_density * sph_wall_hidden(sim, k, i, NULL);
    P->rho[i] = sum;
    P->vol[i] = P->mass[i] / sum;
}
#endif

#if SPH_HAVE_WIDE_RECORDS
/* density_one_avx2 with records and a compact row, 16 neighbours at a time
 * ([compute] wide_density = on): the same operations per pair; the 16 lanes
 * are summed in another order than the 8, so the sum differs by round-off. */
static inline void density_one_wide(const sph_sim *sim, const sph_kernel *k, int i, const int dim, const float *rec,
                                    const sph_nbr_row row)
{
    const sph_particles *P = &sim->P;
    const __m512 h2 = _mm512_set1_ps(k->h2), zero = _mm512_setzero_ps();
    __m512 xi[3];
    sph_simd_centre(P, i, dim, xi);
    __m512 acc = zero;
    const uint32_t end = row.n;
    const float *const rec_i = rec + 4 * (size_t)i;
    for (uint32_t e = 0; e < end; e += 16) {
        int16_t last[16];
        __m512 f[4];
        sph_simd16_rec4_off(rec_i, 4, sph_simd16_block_offsets(row.o, e, end, last), 0, f);
        const __m512 dx = _mm512_sub_ps(xi[0], f[0]), dy = _mm512_sub_ps(xi[1], f[1]);
        __m512 r2 = _mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy));
        if (dim == 3) {
            const __m512 dz = _mm512_sub_ps(xi[2], f[2]);
            r2 = _mm512_add_ps(r2, _mm512_mul_ps(dz, dz));
        }
        const __m512 d = _mm512_max_ps(_mm512_sub_ps(h2, r2), zero);
        const __m512 w = _mm512_maskz_mul_ps(sph_simd_live(e, end), _mm512_mul_ps(d, d), d); /* dead lanes: 0 */
        acc = _mm512_fmadd_ps(w, f[3], acc);
    }
    float sum = P->mass[i] * sph_kernel_w(k, 0.0f) + k->sigma * _mm512_reduce_add_ps(acc);
    if (sph_sim_wall_volume(sim)) sum += sim->def.rest_density * sph_wall_hidden(sim, k, i, NULL);
    P->rho[i] = sum;
    P->vol[i] = P->mass[i] / sum;
}
#endif

/* density_method = continuity switched on by a reconfiguration (a new
 * simulation starts from the lattice's density, sph_sim.c): the carried
 * density starts from this sum. The start-up evaluation (dt = 0, sph_sim_create) sums at x,
 * not at the predicted x + v dt that every step's sum sees: only the first
 * step of some length hands its sum on, so its density is exactly the
 * summation's. */
static void start_carrying(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    if (!P->rho_c) return;
    const int n = (int)sim->n;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) P->rho_c[i] = P->rho[i];
    sim->rho_carried = sim->dt > 0.0f;
}

static void run(sph_sim *sim)
{
    const sph_kernel k = sim->k_density;
    const int n = (int)sim->n, dim = sim->dim;
    sph_particles *P = &sim->P;
    if (sim->rho_carried && P->rho_c) {
        /* density_method = continuity, after its start: the carried density
         * moves on by the rate just made (passes/density_rate.c), no sum */
        const float dt = sim->dt;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++) {
            const float rho = P->rho_c[i] + dt * P->drho[i];
            P->rho_c[i] = rho;
            P->rho[i] = rho;
            P->vol[i] = P->mass[i] / rho;
        }
        return;
    }
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
    const bool periodic = sph_sim_periodic(sim);
#if SPH_HAVE_AVX2
    if (sph_simd8_on(sim) && k.kind == SPH_KERNEL_POLY6) {
        float *rec = sph_simd8_packed(sim) ? sph_simd8_records(sim, 4) : NULL;
        if (rec) {
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
            for (int i = 0; i < n; i++) {
                for (int d = 0; d < 3; d++) rec[4 * (size_t)i + (size_t)d] = d < dim ? P->pred[d][i] : 0.0f;
                rec[4 * (size_t)i + 3] = P->mass[i];
            }
        }
#if SPH_HAVE_WIDE_RECORDS
        if (rec && sph_simd16_density(sim)) { /* 16 at a time; a wide row (32-bit indices) 8 at a time */
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
            for (int i = 0; i < n; i++) {
                const sph_nbr_row row = sph_nbr_row_of(&sim->S, (uint32_t)i); /* read once, walked here */
                if (dim == 3)
                    row.o ? density_one_wide(sim, &k, i, 3, rec, row) : density_one_avx2(sim, &k, i, 3, rec);
                else
                    row.o ? density_one_wide(sim, &k, i, 2, rec, row) : density_one_avx2(sim, &k, i, 2, rec);
            }
            start_carrying(sim);
            return;
        }
#endif
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++) {
            if (rec)
                dim == 3 ? density_one_avx2(sim, &k, i, 3, rec) : density_one_avx2(sim, &k, i, 2, rec);
            else
                dim == 3 ? density_one_avx2(sim, &k, i, 3, NULL) : density_one_avx2(sim, &k, i, 2, NULL);
        }
        start_carrying(sim);
        return;
    }
#endif
#if SPH_HAVE_AVX512
    if (sph_simd_on(sim) && k.kind == SPH_KERNEL_POLY6) {
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++) dim == 3 ? density_one_avx512(sim, &k, i, 3) : density_one_avx512(sim, &k, i, 2);
        start_carrying(sim);
        return;
    }
#endif
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) SPH_SPECIALISE_P(dim, dbl, periodic, density_one, sim, &k, i);
    start_carrying(sim);
}

const sph_pass sph_pass_density = {
    .name = "density",
    .summary = "density by kernel summation",
    .reads = SPH_BIT(PRED) | SPH_BIT(MASS) | SPH_RES_LISTS,
    /* and rho_c with density_method = continuity (not in reads: it exists
     * only in those scenes) */
    .writes = SPH_BIT(RHO) | SPH_BIT(VOL) | SPH_BIT(RHO_C),
    .group = SPH_GROUP_DENSITY,
    .highlight = "density",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
