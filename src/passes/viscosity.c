/* Pass: viscosity, as an acceleration approximating nu lap v.
 *   laplacian: a_i = (nu rho0 / rho_i) sum_j m_j (v_j - v_i) / rho_j lap W_ij
 *              (Mueller 2003 with mu = nu rho0; pairwise equal and opposite)
 *   smoothing: a_i = nu (2 dim / M2) sum_j (m_j / rho_j) (v_j - v_i) W_ij
 *              (the seed's velocity smoothing; a kernel average differs from
 *              the centre value by (M2 / 2 dim) lap v, M2 = int r^2 W dV, so
 *              the factor makes both forms mean the same nu)
 *   morris:    a_i = nu sum_j m_j (rho_i + rho_j) / (rho_i rho_j)
 *                    (x_ij . grad W_ij) / (r^2 + eta^2) (v_i - v_j)
 *              (Morris 1997, after Brookshaw: a Laplacian built from the
 *              kernel's first derivative, which a kernel gives accurately
 *              where its second derivative is noisy: on a 2D lattice at h = 2
 *              spacings, 2.4% off with the cubic spline where Mueller's
 *              lap W is 20% off, tests/test_physics.c. Pairwise equal and
 *              opposite.)
 *   artificial: a_i = -sum_j m_j Pi_ij grad W_ij, for approaching pairs
 *              (v_ij . x_ij < 0) Pi_ij = -alpha c h_s (v_ij . x_ij) /
 *              (rho_avg (r^2 + 0.01 h_s^2)), else 0; c = sqrt(k), h_s = h/2,
 *              rho_avg = (rho_i + rho_j)/2 (Monaghan 1992, "Smoothed particle
 *              hydrodynamics", Annu. Rev. Astron. Astrophys. 30:543, eq. 4.2
 *              without the beta term), with the pressure kernel's gradient:
 *              Monaghan adds Pi_ij to the pressure term, and the viscosity
 *              kernel's W' grows as 1/r^(dim-1) at r = 0, which the 0.01 h_s^2
 *              would not bound. It acts only along x_ij and only on
 *              approach, so it damps compression (shocks, splashes) but not
 *              rigid motion or separation; pairwise equal and opposite.
 *   morris-artificial: the sum of both, morris with the physical nu and
 *              artificial with alpha: Monaghan's term damps the pressure
 *              noise of a weakly compressible fluid, but being along x_ij it
 *              gives a particle sliding on a no-slip floor no friction;
 *              Morris's term, fed the walls' mirrored velocity, does.
 * It reads vel and writes acc_v only: the seed's shader added the result to
 * the velocities it was still reading for other particles, so its outcome
 * depended on the order threads ran in. With wall particles, the neighbours'
 * velocities are read from vel_visc (the wall_state pass: the fluid's own,
 * the walls' mirrored for no-slip), and walls get no acceleration; Monaghan's
 * term sees a wall particle at v_w + g dt, the frame of the fluid's velocity
 * just kicked by gravity (sph_wall_kick), as the continuity equation does:
 * else a column at rest reads as approaching the floor at g dt, and the
 * floor row was pushed off it (0.13 m/s^2 at alpha = 0.1, s = 0.01 m). */
#include "simd.h"
#include "sph_search.h"
#include "sph_start.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    return (def->effects & SPH_EFFECT(VISCOSITY)) ? NULL : "effects do not list viscosity";
}

/* The largest r / h (sampled in thousandths) where the viscosity kernel's Laplacian is below 0; 0 if nowhere. */
static double laplacian_negative_to(const sph_scene_def *def)
{
    if (!(def->h > 0)) return 0;
    const sph_kernel k = sph_kernel_make(def->kernel_viscosity, def->dim, def->h);
    double to = 0;
    for (int t = 1; t < 1000; t++)
        if (sph_kernel_lap(&k, def->h * (float)t / 1000.0f) < 0.0f) to = t / 1000.0;
    return to;
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    if (def->viscosity_form == SPH_VFORM_ARTIFICIAL)
        snprintf(out, (size_t)n, "artificial form (Monaghan), %s kernel's gradient, alpha %g, c %g m/s",
                 sph_kernel_names[def->kernel_pressure], def->alpha, sqrt(def->stiffness));
    else if (def->viscosity_form == SPH_VFORM_MORRIS_ARTIFICIAL)
        snprintf(out, (size_t)n,
                 "morris form, %s kernel, nu %g m^2/s, plus artificial (Monaghan), %s kernel's gradient, alpha %g, "
                 "c %g m/s",
                 sph_kernel_names[def->kernel_viscosity], def->viscosity, sph_kernel_names[def->kernel_pressure],
                 def->alpha, sqrt(def->stiffness));
    else {
        int used = snprintf(out, (size_t)n, "%s form, %s kernel, nu %g m^2/s",
                            sph_viscosity_form_names[def->viscosity_form], sph_kernel_names[def->kernel_viscosity],
                            def->viscosity);
        /* Mueller's form weighs each neighbour by lap W(r): every kernel but the viscosity kernel has a Laplacian
         * below 0 near r = 0 (cubic below h/2 in 3D), so neighbours that close push each other's velocities apart
         * and feed noise: a user's still 3D cube at h = 3 spacings with cubic reached 0.55 m/s in 400 steps, 0.008
         * m/s with the viscosity kernel. Said where a lattice neighbour falls there (h = 2 spacings: none) */
        const double negative_to = def->viscosity_form == SPH_VFORM_LAPLACIAN ? laplacian_negative_to(def) : 0;
        double s = INFINITY;
        for (int b = 0; b < def->n_blocks; b++) s = fmin(s, def->blocks[b].spacing);
        if (used > 0 && used < n && negative_to * def->h > 1.001 * s)
            snprintf(out + used, (size_t)(n - used),
                     "; this kernel's Laplacian is negative for r < %.2f h (%.2f spacings), so those neighbours push "
                     "each other's velocities apart and the noise can gain energy: the viscosity kernel's is positive "
                     "everywhere, or take viscosity_form = morris",
                     negative_to, negative_to * def->h / s);
    }
}

/* The viscous acceleration of one particle; dim and dbl are constants. */
static inline void viscosity_one(const sph_sim *sim, const sph_kernel *k, const float *kick, int i, const int dim,
                                 const bool dbl, const bool periodic)
{
    const sph_kernel *kp = &sim->k_pressure;
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const bool laplacian = sim->def.viscosity_form == SPH_VFORM_LAPLACIAN;
    const bool both = sim->def.viscosity_form == SPH_VFORM_MORRIS_ARTIFICIAL;
    const bool morris = sim->def.viscosity_form == SPH_VFORM_MORRIS || both;
    const bool artificial = sim->def.viscosity_form == SPH_VFORM_ARTIFICIAL || both;
    /* artificial: alpha c h_s, and the 0.01 h_s^2 that keeps close pairs finite */
    const float hs = 0.5f * k->h, ach = sim->def.alpha * sqrtf(sim->def.stiffness) * hs, eps2 = 0.01f * hs * hs;
    const float nu = sim->def.viscosity;
    const float *per = sim->period, *iper = sim->inv_period;
    /* eta = 0.01 h keeps the sum finite for coincident particles (the scene
     * allows only kernels with W'(0) = 0, so W'(r) / r is bounded anyway).
     * Morris's 0.1 h biases the nearest pairs (r = h/2) by 4%, and the whole
     * sum by 3-4% at h = 2 spacings. */
    const float eta2 = 1e-4f * k->h * k->h;
    const float rho_i = P->rho[i];
    float *const *vj = P->vel_visc[0] ? P->vel_visc : P->vel;
    float xi[3], vi[3], af[3] = {0, 0, 0}, avf[3] = {0, 0, 0}; /* avf, avd: the artificial part when both */
    double ad[3] = {0, 0, 0}, avd[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) {
        xi[d] = P->pred[d][i];
        vi[d] = P->vel[d][i];
    }
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        float r2 = 0, dx[3];
        for (int d = 0; d < dim; d++) {
            dx[d] = xi[d] - P->pred[d][j];
            if (periodic) dx[d] = sph_min_image(dx[d], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        float r = sqrtf(r2);
        float coef;
        if (artificial) { /* along x_ij, so not of the form coef (v_j - v_i) below */
            float vx = 0; /* a wall particle seen at v_w + g dt, the step's frame (sph_wall_kick) */
            const bool wall = sph_is_wall(P, j);
            for (int d = 0; d < dim; d++) vx += (vi[d] - P->vel[d][j] - (wall ? kick[d] : 0.0f)) * dx[d];
            if (vx < 0.0f && r > 0.0f) { /* receding, or coincident: no force */
                float pi_ij = -ach * vx / (0.5f * (rho_i + P->rho[j]) * (r2 + eps2));
                float f = -P->mass[j] * pi_ij * sph_kernel_dw(kp, r) / r; /* grad W_ij = W'(r) x_ij / r */
                for (int d = 0; d < dim; d++) {
                    if (dbl) (both ? avd : ad)[d] += f * dx[d];
                    else (both ? avf : af)[d] += f * dx[d];
                }
            }
            if (!both) continue;
        }
        if (morris) /* -(x_ij . grad W) = -r W'(r) >= 0 */
            coef = -P->mass[j] * (rho_i + P->rho[j]) / (rho_i * P->rho[j]) * r * sph_kernel_dw(k, r) / (r2 + eta2);
        else
            coef = P->vol[j] * (laplacian ? sph_kernel_lap(k, r) : sph_kernel_w(k, r));
        for (int d = 0; d < dim; d++) {
            float t = coef * (vj[d][j] - vi[d]);
            if (dbl) ad[d] += t;
            else af[d] += t;
        }
    }
    float s = both        ? nu
              : artificial ? 1.0f
              : morris    ? nu
              : laplacian ? nu * sim->def.rest_density / rho_i
                          : nu * 2.0f * (float)dim / k->m2;
    if (both)
        for (int d = 0; d < dim; d++) P->acc_v[d][i] = s * (dbl ? (float)ad[d] : af[d]) + (dbl ? (float)avd[d] : avf[d]);
    else
        for (int d = 0; d < dim; d++) P->acc_v[d][i] = s * (dbl ? (float)ad[d] : af[d]);
}

#if SPH_HAVE_AVX512
/* The viscosity kernel's Laplacian is linear: c (1 - r/h), c = 6 sigma/h^2
 * in 3D, sigma/h^2 in 2D (see sph_kernel_lap). */
static inline void viscosity_one_avx512(const sph_sim *sim, const sph_kernel *k, int i, const int dim)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    __m512 xi[3], d3[3];
    sph_simd_centre(P, i, dim, xi);
    const __m512 vxi = _mm512_set1_ps(P->vel[0][i]), vyi = _mm512_set1_ps(P->vel[1][i]);
    const __m512 vzi = _mm512_set1_ps(dim == 3 ? P->vel[2][i] : 0.0f);
    float *const *vj = P->vel_visc[0] ? P->vel_visc : P->vel;
    const __m512 inv_h = _mm512_set1_ps(k->inv_h), one = _mm512_set1_ps(1.0f), zero = _mm512_setzero_ps();
    const __m512 h2 = _mm512_set1_ps(sim->def.h * sim->def.h);
    __m512 ax = zero, ay = zero, az = zero;
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    const uint32_t end = row.n;
    for (uint32_t e = 0; e < end; e += 16) {
        __mmask16 live = sph_simd_live(e, end);
        __m512i idx = sph_simd_nbr(&row, e, live);
        __m512 r2 = sph_simd_offsets(P, live, idx, xi, dim, d3);
        /* pairs within h only, as the search decides them: Verlet lists ([search] skin) hold more, where
         * 1 - r/h can round to a hair above 0 */
        const __mmask16 in = _mm512_mask_cmp_ps_mask(live, r2, h2, _CMP_LT_OQ);
        __m512 lap = _mm512_max_ps(_mm512_fnmadd_ps(_mm512_sqrt_ps(r2), inv_h, one), zero); /* 1 - r/h */
        __m512 coef = _mm512_mul_ps(sph_simd_gather(live, idx, P->vol), lap);
        ax = _mm512_mask3_fmadd_ps(coef, _mm512_sub_ps(sph_simd_gather(live, idx, vj[0]), vxi), ax, in);
        ay = _mm512_mask3_fmadd_ps(coef, _mm512_sub_ps(sph_simd_gather(live, idx, vj[1]), vyi), ay, in);
        if (dim == 3)
            az = _mm512_mask3_fmadd_ps(coef, _mm512_sub_ps(sph_simd_gather(live, idx, vj[2]), vzi), az, in);
    }
    const float c = k->sigma * k->inv_h * k->inv_h * (dim == 3 ? 6.0f : 1.0f);
    const float s = c * sim->def.viscosity * sim->def.rest_density / P->rho[i];
    P->acc_v[0][i] = s * _mm512_reduce_add_ps(ax);
    P->acc_v[1][i] = s * _mm512_reduce_add_ps(ay);
    if (dim == 3) P->acc_v[2][i] = s * _mm512_reduce_add_ps(az);
}
#endif

#if SPH_HAVE_AVX2
/* The loop above, 8 neighbours at a time ([search] vector_avx2 = on). */
static inline void viscosity_one_avx2(const sph_sim *sim, const sph_kernel *k, int i, const int dim)
{
    const sph_particles *P = &sim->P;
    __m256 xi[3], d3[3];
    sph_simd8_centre(P, i, dim, xi);
    const __m256 vxi = _mm256_set1_ps(P->vel[0][i]), vyi = _mm256_set1_ps(P->vel[1][i]);
    const __m256 vzi = _mm256_set1_ps(dim == 3 ? P->vel[2][i] : 0.0f);
    float *const *vj = P->vel_visc[0] ? P->vel_visc : P->vel;
    const __m256 inv_h = _mm256_set1_ps(k->inv_h), one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
    const __m256 h2 = _mm256_set1_ps(sim->def.h * sim->def.h);
    __m256 ax = zero, ay = zero, az = zero;
    const sph_nbr_row row = sph_nbr_row_of(&sim->S, (uint32_t)i);
    const uint32_t end = row.n;
    for (uint32_t e = 0; e < end; e += 8) {
        const __m256i live = sph_simd8_live(e, end), idx = sph_simd8_nbr(&row, e, end, live);
        __m256 r2 = sph_simd8_offsets(P, live, idx, xi, dim, d3);
        /* pairs within h only, as in viscosity_one_avx512 */
        const __m256i in = _mm256_and_si256(live, _mm256_castps_si256(_mm256_cmp_ps(r2, h2, _CMP_LT_OQ)));
        __m256 lap = _mm256_max_ps(_mm256_fnmadd_ps(_mm256_sqrt_ps(r2), inv_h, one), zero); /* 1 - r/h */
        __m256 coef = sph_simd8_keep(in, _mm256_mul_ps(sph_simd8_gather(live, idx, P->vol), lap));
        ax = _mm256_fmadd_ps(coef, _mm256_sub_ps(sph_simd8_gather(live, idx, vj[0]), vxi), ax);
        ay = _mm256_fmadd_ps(coef, _mm256_sub_ps(sph_simd8_gather(live, idx, vj[1]), vyi), ay);
        if (dim == 3) az = _mm256_fmadd_ps(coef, _mm256_sub_ps(sph_simd8_gather(live, idx, vj[2]), vzi), az);
    }
    const float c = k->sigma * k->inv_h * k->inv_h * (dim == 3 ? 6.0f : 1.0f);
    const float s = c * sim->def.viscosity * sim->def.rest_density / P->rho[i];
    P->acc_v[0][i] = s * sph_simd8_sum(ax);
    P->acc_v[1][i] = s * sph_simd8_sum(ay);
    if (dim == 3) P->acc_v[2][i] = s * sph_simd8_sum(az);
}
#endif

/* Wall particles get no acceleration: they never move. */
static inline bool wall_still(sph_sim *sim, int i)
{
    if (!sph_is_wall(&sim->P, i)) return false;
    for (int d = 0; d < sim->dim; d++) sim->P.acc_v[d][i] = 0.0f;
    return true;
}

static void run(sph_sim *sim)
{
    const sph_kernel k = sim->k_viscosity;
    const int n = (int)sim->n, dim = sim->dim;
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
    const bool periodic = sph_sim_periodic(sim);
    if (sph_forces_fused(sim)) return; /* the pressure_force pass wrote acc_v in its walk */
    float kick[3];
    sph_wall_kick(sim, kick);
#if SPH_HAVE_AVX2
    if (sph_simd8_on(sim) && k.kind == SPH_KERNEL_VISCOSITY && sim->def.viscosity_form == SPH_VFORM_LAPLACIAN) {
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++)
            if (!wall_still(sim, i)) dim == 3 ? viscosity_one_avx2(sim, &k, i, 3) : viscosity_one_avx2(sim, &k, i, 2);
        return;
    }
#endif
#if SPH_HAVE_AVX512
    if (sph_simd_on(sim) && k.kind == SPH_KERNEL_VISCOSITY && sim->def.viscosity_form == SPH_VFORM_LAPLACIAN) {
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++)
            if (!wall_still(sim, i))
                dim == 3 ? viscosity_one_avx512(sim, &k, i, 3) : viscosity_one_avx512(sim, &k, i, 2);
        return;
    }
#endif
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++)
        if (!wall_still(sim, i)) SPH_SPECIALISE_P(dim, dbl, periodic, viscosity_one, sim, &k, kick, i);
}

const sph_pass sph_pass_viscosity = {
    .name = "viscosity",
    .summary = "viscous force (acceleration)",
    .reads = SPH_BIT(PRED) | SPH_BIT(MASS) | SPH_BIT(VOL) | SPH_BIT(RHO) | SPH_BIT(VEL) | SPH_RES_LISTS,
    .writes = SPH_BIT(ACC_V),
    .group = SPH_GROUP_FORCES,
    .highlight = "viscosity-acc",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
