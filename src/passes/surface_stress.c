/* Pass: surface_stress, the surface tension of [physics] surface_tension =
 * stress: the divergence of a surface stress tensor, sigma a stated input.
 *
 * The surface's tension is a stress along it (Lafaurie, Nardone, Scardovelli,
 * Zaleski & Zanetti 1994, "Modelling merging and fragmentation in multiphase
 * flows with SURFER", J. Comput. Phys. 113:134):
 *
 *   f = div Pi,   Pi = sigma (I - n_hat n_hat) delta_s,
 *
 * whose divergence is sigma kappa n_hat delta_s plus nothing more where the
 * surface is uniform, the curvature coming out of the tangents' turning, so
 * no curvature is computed. In SPH it is written as a pressure is, with each
 * pair's terms equal and opposite (Hu & Adams 2006, "A multi-phase SPH
 * method for macroscopic and mesoscopic flows", J. Comput. Phys. 213:844,
 * where Pi stands in for -p I):
 *
 *   m_i a_i = sum_j V_i V_j (Pi_i + Pi_j) . grad_i W_ij,   V = m / rho0,
 *
 * so momentum is conserved to rounding (a pair's forces are not along x_ij,
 * so angular momentum only as far as the stresses are smooth, as with any
 * stress in SPH). surface_tension = csf instead pushes each surface particle
 * along its normal with no reaction: its net force and torque on a drop are
 * not zero, and a drop left alone grows an n = 2 oscillation
 * (docs/accuracy.md, the drop).
 *
 * delta_s, calibrated from sigma alone. Hu & Adams take delta_s = |grad c|
 * with the colour jumping across an interface between two fluids; at a free
 * surface only the fluid's side has particles. Here a particle i carries
 *
 *   delta_s,i = s_i / (V_i c_i),
 *
 * s_i its share of the surface's area (2D: length) as surface_tension = csf
 * computes it (csf.c: w_i / sum_j w_j W_{dim-1}(tangential distance), a
 * partition of unity along the surface, w = |h grad c| - 0.6), and c_i =
 * sum_j V_j W_ij its colour, the share of its kernel inside the fluid. The
 * tension across a cut through the surface is the pairs' sum across it,
 * sum V_i V_j (Pi_i + Pi_j) . grad W_ij, in which each stressed particle j
 * counts with the kernel mass its neighbours in the fluid hold, c_j: so the
 * stress on the cut is Pi_j V_j c_j per share s_j, sigma per unit length
 * of the cut (per unit area in 3D), whatever the surface's depth in rows.
 * The shares are csf's, over the particles with |h grad c| > 0.6 (csf: 0.3;
 * STRESS_NORMAL_MIN says why); wall particles neither take nor give it.
 *
 * The tensile instability. A stress that pulls (a tension) makes the pairs'
 * sum clump the particles along the surface (Swegle, Hicks & Attaway 1995,
 * J. Comput. Phys. 116:123): without a remedy the R/10 drop of validate drop
 * left alone reached a kinetic energy of 0.15 J/m in 3 s. Each pair's term is
 * therefore weighed by 1 - eps f^4, f = W(r) / W(dp), dp the spacing
 * (vol^(1/dim)): Monaghan's artificial stress R = -eps Pi for a tension
 * (Monaghan 2000, "SPH without a tensile instability", J. Comput. Phys.
 * 159:290; Gray, Monaghan & Swift 2001, Comput. Methods Appl. Mech. Eng.
 * 190:6641: eps = 0.3, n = 4), still equal and opposite. It takes its share
 * of the tension too: the terms are then the slope of W - eps W^5 / (5
 * W(dp)^4), whose integral over the fluid's side replaces c's, and the
 * narrow W^5 sees the same side as W, so tau is divided by
 * 1 - eps int W^5 dV / (5 W(dp)^4) (0.865 for the cubic kernel at h = 3
 * spacings; a static disc of R = 20 spacings: -14 % without it, -0.5 % with
 * it; tests/test_surface_stress.c). */
#include "csf.h"
#include "sph_memory.h"
#include "sph_search.h"
#include "sph_walls.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STRESS_EPS 0.3 /* Monaghan 2000's artificial stress, R = -eps Pi for a tension, f = (W(r)/W(dp))^4 */
#define STRESS_PI 3.14159265358979323846
/* |h grad c| a particle needs to carry the stress, w = |h grad c| - this its weight. Not csf's 0.3: at h = 3
 * spacings a flat surface's rows read 1.25 and 0.30 (the second row of validate drop's settled R/20 drop 0.30,
 * R/10 0.32), so csf's cut sits on the second row, whose particles switch the stress on and off as they move;
 * the drop left alone then gained kinetic energy at the particle scale (R/10: 9.6e-4 J/m at 2.5 s; 0.6: 4.1e-4;
 * docs/accuracy.md, the drop). 0.6, about the geometric mean of the two rows, leaves the second row out with a
 * margin either way; the shares s_i are a partition of unity over the rows that carry it, so sigma holds. */
#define STRESS_NORMAL_MIN 0.6f

static const char *skip_reason(const sph_scene_def *def)
{
    return def->surface_tension == SPH_STENSION_STRESS ? NULL : "surface_tension is not stress";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    /* in 2D sigma is per metre of depth: N (the key's unit), in 3D N/m */
    snprintf(out, (size_t)n, "surface stress sigma (I - n n) delta_s (Lafaurie 1994, Hu & Adams 2006), sigma %g %s",
             def->sigma, def->dim == 3 ? "N/m" : "N");
}

/* The share of the tension the artificial stress leaves, 1 - eps int W^5 dV / (5 W(dp)^4), dp = vol^(1/dim):
 * the pairs' terms use the slope W' (1 - eps (W / W(dp))^4) of W - eps W^5 / (5 W(dp)^4), whose integral over
 * the fluid's side of a surface takes the place of c's (a narrow W^5 sees the same side as W). */
static double stress_artificial_share(const sph_kernel *k, double vol, int dim)
{
    const int steps = 400;
    const double h = k->h, w_dp = sph_kernel_w(k, (float)pow(vol, 1.0 / dim));
    double i5 = 0;
    for (int s = 0; s < steps; s++) {
        double r = (s + 0.5) * h / steps, w = sph_kernel_w(k, (float)r);
        i5 += w * w * w * w * w * (dim == 3 ? 4.0 * STRESS_PI * r * r : 2.0 * STRESS_PI * r) * h / steps;
    }
    return 1.0 - STRESS_EPS * i5 / (5.0 * w_dp * w_dp * w_dp * w_dp);
}

/* Sweep 1: tau_i = sigma s_i / (V_i c_i), a stress [Pa; in 2D N/m, per metre of depth], 0 off the surface. */
static inline void stress_one(const sph_sim *sim, const sph_kernel *k, float *tau, const double *share, int i,
                              const int dim, const bool dbl, const bool periodic)
{
    (void)dbl; /* sums in double: a few surface particles */
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const float *per = sim->period, *iper = sim->inv_period;
    const double inv_rho0 = 1.0 / sim->def.rest_density;
    float ni[3], len_i = 0;
    tau[i] = 0.0f;
    for (int d = 0; d < dim; d++) ni[d] = P->normal[d][i], len_i += ni[d] * ni[d];
    len_i = sqrtf(len_i);
    if (sph_is_wall(P, i) || !(len_i > STRESS_NORMAL_MIN)) return;
    const double wi = len_i - STRESS_NORMAL_MIN;
    double ls = wi * sph_csf_w_surface(0.0, k->h, dim), c = P->mass[i] * inv_rho0 * sph_kernel_w(k, 0.0f);
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        if (j == (uint32_t)i || sph_is_wall(P, j)) continue;
        float dx[3], r2 = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = P->pred[d][i] - P->pred[d][j];
            if (periodic) dx[d] = sph_min_image(dx[d], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        c += P->mass[j] * inv_rho0 * sph_kernel_w(k, sqrtf(r2));
        float len_j = 0;
        for (int d = 0; d < dim; d++) len_j += P->normal[d][j] * P->normal[d][j];
        len_j = sqrtf(len_j);
        if (!(len_j > STRESS_NORMAL_MIN)) continue;
        double xn = (dx[0] * ni[0] + dx[1] * ni[1] + (dim == 3 ? dx[2] * ni[2] : 0.0f)) / len_i;
        ls += (len_j - STRESS_NORMAL_MIN) * sph_csf_w_surface(sqrt(fmax(r2 - xn * xn, 0.0)), k->h, dim);
    }
    /* s_i = w_i / ls; V_i = m_i / rho0 */
    /* the artificial stress's share, computed again for a particle of another volume than the first's */
    const double vol = P->mass[i] * inv_rho0;
    const double a = vol == share[0] ? share[1] : stress_artificial_share(k, vol, dim);
    if (ls > 0 && c > 0) tau[i] = (float)(sim->def.sigma * wi / ls / (vol * c * a));
}

/* The stress's projector applied to g: tau (g - u (u . g)), u the unit normal of particle j. */
static inline void stress_apply(const sph_particles *P, uint32_t j, double tau, const double g[3], double out[3],
                                const int dim)
{
    double u[3] = {0, 0, 0}, len = 0, ug = 0;
    for (int d = 0; d < dim; d++) u[d] = P->normal[d][j], len += u[d] * u[d];
    len = sqrt(len);
    for (int d = 0; d < dim; d++) u[d] /= len, ug += u[d] * g[d];
    for (int d = 0; d < dim; d++) out[d] += tau * (g[d] - u[d] * ug);
}

/* Sweep 2: a_i = (1 / m_i) sum_j V_i V_j (Pi_i + Pi_j) . grad_i W_ij. */
static inline void stress_force(const sph_sim *sim, const sph_kernel *k, const float *tau, int i, const int dim,
                                const bool dbl, const bool periodic)
{
    (void)dbl;
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const float *per = sim->period, *iper = sim->inv_period;
    const double inv_rho0 = 1.0 / sim->def.rest_density;
    double a[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) P->acc_t[d][i] = 0.0f;
    if (sph_is_wall(P, i)) return;
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        if (j == (uint32_t)i || sph_is_wall(P, j) || !(tau[i] > 0 || tau[j] > 0)) continue;
        float dx[3], r2 = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = P->pred[d][i] - P->pred[d][j];
            if (periodic) dx[d] = sph_min_image(dx[d], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        if (!(r2 > 0)) continue; /* coincident: no direction */
        float r = sqrtf(r2);
        /* V_j grad_i W_ij (V_i and 1 / m_i: 1 / rho0 after the sum) */
        /* Monaghan's f = W / W(dp), dp from the pair's mean volume (symmetric in i, j) */
        const double dp = pow(0.5 * (P->mass[i] + P->mass[j]) * inv_rho0, 1.0 / dim);
        const double f = sph_kernel_w(k, r) / sph_kernel_w(k, (float)dp), f2 = f * f;
        const double gs = P->mass[j] * inv_rho0 * sph_kernel_dw(k, r) / r * (1.0 - STRESS_EPS * f2 * f2);
        double g[3] = {gs * dx[0], gs * dx[1], dim == 3 ? gs * dx[2] : 0.0};
        if (tau[i] > 0) stress_apply(P, (uint32_t)i, tau[i], g, a, dim);
        if (tau[j] > 0) stress_apply(P, j, tau[j], g, a, dim);
    }
    for (int d = 0; d < dim; d++) P->acc_t[d][i] = (float)(a[d] * inv_rho0);
}

static void run(sph_sim *sim)
{
    const sph_kernel k = sim->k_density;
    const int n = (int)sim->n, dim = sim->dim;
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
    const bool periodic = sph_sim_periodic(sim);
    float *tau = malloc(sizeof(float) * (size_t)(n + 1));
    /* returning would leave last step's acc_t in place: a wrong answer in silence */
    if (!tau)
        sph_memory_fail("the surface_stress pass's %d-particle scratch could not be made (%s)", n, strerror(errno));
    double share[2] = {n ? sim->P.mass[0] * (1.0 / sim->def.rest_density) : 0.0, 1.0};
    if (n) share[1] = stress_artificial_share(&k, share[0], dim);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) SPH_SPECIALISE_P(dim, dbl, periodic, stress_one, sim, &k, tau, share, i);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) SPH_SPECIALISE_P(dim, dbl, periodic, stress_force, sim, &k, tau, i);
    free(tau);
}

const sph_pass sph_pass_surface_stress = {
    .name = "surface_stress",
    .summary = "surface tension as the divergence of a surface stress, sigma (I - n n) delta_s (acceleration)",
    .reads = SPH_BIT(PRED) | SPH_BIT(NORMAL) | SPH_BIT(MASS) | SPH_RES_LISTS,
    .writes = SPH_BIT(ACC_T),
    .group = SPH_GROUP_FORCES,
    .highlight = "stress-acc",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
