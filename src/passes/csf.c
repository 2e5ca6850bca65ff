/* Pass: csf, the continuum surface force of [physics] surface_tension = csf,
 * a surface tension whose sigma is a stated input (Brackbill, Kothe & Zemach
 * 1992, "A continuum method for modeling surface tension", J. Comput. Phys.
 * 100:335, eq. 4-5; in SPH, Morris 2000, "Simulating surface tension with
 * smoothed particle hydrodynamics", Int. J. Numer. Meth. Fluids 33:333):
 *
 *   f = sigma kappa n_hat delta_s,   delta_s ~ |grad c|,   kappa = div n_hat_out
 *
 * a force per unit volume at the surface, pulling a convex surface in. Here
 * c is the colour field (1 in the fluid) and grad c_i = normal_i / h, the
 * normals pass's field (h sum_j V_j grad_i W_ij, into the fluid).
 *
 * Which particles. Morris (his eq. 20-21) keeps only the particles whose
 * normal is long enough to have a direction, |grad c| > 0.01 / h. In a free
 * drop that cut let the disordered interior's normals (0.01 to 0.3) in,
 * whose curvatures were noise. Here a particle has a curvature where
 * |n| = |h grad c| > 0.3 (on a lattice, cubic kernel at h = 3 spacings, the
 * outermost row: 1.23; the second: 0.29), and every sum over such particles
 * weighs them by w = |n| - 0.3, so that a particle crossing the cut enters
 * the sums at zero weight instead of all at once (with a weight of 1 the
 * second row flickered across the cut and the surface frayed).
 *
 * Curvature: the divergence of the outward unit normal u = -normal/|normal|
 * over those neighbours, renormalised (Bonet & Lok 1999) on the
 * tangent plane of u_i: with
 *   A = sum_j w_j V_j grad_i W_ij (x_j - x_i)^T,  S = sum_j w_j V_j grad_i W_ij (u_j - u_i)^T,
 * projected on the tangents t_p (A_t = t_p.A.t_q), kappa_i = trace(A_t^-1 S_t).
 * The unit normal of a curved surface does not change along itself (u.du = 0),
 * so the tangential part is the whole divergence, and it needs no support
 * across the surface, where the rows are few (the full matrix's inverse there
 * amplified the normals' noise). A particle whose tangential support is below
 * 0.1 (1 in a full support) gets no curvature. The curvature is then averaged
 * over the particles that have one (a Shepard average, weights w_j W_ij; the
 * smoothing over h of the normals' own particle-scale noise, as Morris 2000,
 * sec. 3, and Adami, Hu & Adams 2010, J. Comput. Phys. 229:5011, eq. 20,
 * average over the particles with a well-defined normal); a circle's kappa
 * is unchanged by it.
 *
 * The delta: sigma kappa per unit area of surface, shared out. At a free
 * surface the particles carry only the fluid's side of the colour jump, and
 * how much of |grad c| the rows hold depends on how close the outer row sits
 * to the next (the force itself presses it in): a constant calibrated on a
 * flat lattice (this pass's earlier form, B = 0.41) gave a drop of R = 10
 * spacings a Laplace pressure 27 % above sigma / R. Instead each particle
 * taking the force gets the share s_i = w_i / sum_j w_j W_{dim-1}(|x_ij|_t)
 * of the surface's area (2D: length), the sum over the particles taking it
 * (self included), W_{dim-1} the cubic spline of support h in dim - 1
 * dimensions of the tangential distance |x_ij - (x_ij.u_i) u_i|: a partition
 * of unity along the surface (Shepard), whatever the depths and weights, so
 * the shares of a stretch of surface add up to its area. Then
 *
 *   a_i = sigma kappa_i s_i n_hat_i / m_i,   n_hat into the fluid,
 *
 * and the inward force over a closed drop is sigma kappa times its area, the
 * Laplace jump (measured: 10.20 N/m at R = 0.0987 m, sigma/R = 10.13; 10.59
 * at R = 0.0959 m, 10.43). A pair's terms are not equal and opposite, so
 * momentum is conserved only as far as kappa is uniform: tests/test_csf.c
 * measures the net force on a disc. Wall particles get none and are left out
 * of the sums, as in the normals pass. */
#include "csf.h"
#include "sph_search.h"
#include "sph_walls.h"
#include "sph_memory.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CSF_SUPPORT_MIN SPH_CSF_SUPPORT_MIN
#define CSF_NORMAL_MIN SPH_CSF_NORMAL_MIN
/* |h grad c| a particle needs to share the force: the same cut (spreading the force over the second row too,
 * 0.05, read the R/10 drop's period 10.9 % short, its amplitude growing, where 0.3 read it 10.4 % long) */
#define CSF_FORCE_MIN CSF_NORMAL_MIN

static const char *skip_reason(const sph_scene_def *def)
{
    return def->surface_tension == SPH_STENSION_CSF ? NULL : "surface_tension is not csf";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    /* in 2D sigma is per metre of depth: N (the key's unit), in 3D N/m */
    snprintf(out, (size_t)n, "continuum surface force (Brackbill 1992, Morris 2000), sigma %g %s", def->sigma,
             def->dim == 3 ? "N/m" : "N");
}

/* kappa = trace(A_t^-1 S_t), A and S projected on the tangent plane of the
 * outward unit normal u (2D: one tangent; 3D: two); 0 where A_t is nearly
 * singular. */
static inline float csf_div(const double A[3][3], const double S[3][3], const double u[3], const int dim)
{
    double t[2][3] = {{0}};
    const int nt = dim - 1;
    if (dim == 2) {
        t[0][0] = -u[1], t[0][1] = u[0];
    } else { /* t0 perpendicular to u along its smallest component's axis, t1 = u x t0 */
        int m = fabs(u[0]) <= fabs(u[1]) && fabs(u[0]) <= fabs(u[2]) ? 0 : fabs(u[1]) <= fabs(u[2]) ? 1 : 2;
        double e[3] = {0, 0, 0};
        e[m] = 1;
        double c[3] = {u[1] * e[2] - u[2] * e[1], u[2] * e[0] - u[0] * e[2], u[0] * e[1] - u[1] * e[0]};
        double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        for (int d = 0; d < 3; d++) t[0][d] = c[d] / len;
        t[1][0] = u[1] * t[0][2] - u[2] * t[0][1];
        t[1][1] = u[2] * t[0][0] - u[0] * t[0][2];
        t[1][2] = u[0] * t[0][1] - u[1] * t[0][0];
    }
    double At[2][2] = {{0}}, St[2][2] = {{0}};
    for (int p = 0; p < nt; p++)
        for (int q = 0; q < nt; q++)
            for (int a = 0; a < dim; a++)
                for (int b = 0; b < dim; b++) {
                    At[p][q] += t[p][a] * A[a][b] * t[q][b];
                    St[p][q] += t[p][a] * S[a][b] * t[q][b];
                }
    /* A full support gives A_t = I; below CSF_SUPPORT_MIN along a tangent the
     * neighbours holding a normal do not span the surface (a particle
     * alone, or in a filament across it): no curvature there */
    if (nt == 1) return At[0][0] > CSF_SUPPORT_MIN ? (float)(St[0][0] / At[0][0]) : 0.0f;
    double det = At[0][0] * At[1][1] - At[0][1] * At[1][0];
    if (!(det > CSF_SUPPORT_MIN * CSF_SUPPORT_MIN)) return 0.0f;
    /* trace(At^-1 St), At^-1 = adj(At) / det */
    double k = At[1][1] * St[0][0] - At[0][1] * St[1][0] - At[1][0] * St[0][1] + At[0][0] * St[1][1];
    return (float)(k / det);
}

/* Sweep 1: the raw curvature of a particle whose normal has a direction (|n| > CSF_NORMAL_MIN), and, for
 * every particle that takes a share of the force (|n| > CSF_FORCE_MIN), the surface density lam_i =
 * sum_j w_j W_{dim-1}(tangential distance) / w_i of the particles sharing it, w = |n| - CSF_FORCE_MIN. */
static inline void csf_one(const sph_sim *sim, const sph_kernel *k, float *lam, int i, const int dim, const bool dbl,
                           const bool periodic)
{
    (void)dbl; /* the sums are in double: a few surface particles, and A is inverted */
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const float *per = sim->period, *iper = sim->inv_period;
    float ni[3], len_i = 0;
    for (int d = 0; d < dim; d++) ni[d] = P->normal[d][i], len_i += ni[d] * ni[d];
    len_i = sqrtf(len_i);
    P->curv[i] = 0.0f;
    lam[i] = 0.0f;
    if (sph_is_wall(P, i) || !(len_i > CSF_FORCE_MIN)) return;
    const bool curved = len_i > CSF_NORMAL_MIN;
    const double wi = len_i - CSF_FORCE_MIN;
    double A[3][3] = {{0}}, Sm[3][3] = {{0}}, ls = wi * sph_csf_w_surface(0.0, k->h, dim);
    float xi[3];
    const double inv_rho0 = 1.0 / sim->def.rest_density;
    for (int d = 0; d < dim; d++) xi[d] = P->pred[d][i];
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        if (j == (uint32_t)i || sph_is_wall(P, j)) continue;
        float nj[3], len_j = 0;
        for (int d = 0; d < dim; d++) nj[d] = P->normal[d][j], len_j += nj[d] * nj[d];
        len_j = sqrtf(len_j);
        if (!(len_j > CSF_FORCE_MIN)) continue;
        float dx[3], r2 = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = xi[d] - P->pred[d][j];
            if (periodic) dx[d] = sph_min_image(dx[d], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        if (!(r2 > 0)) continue;
        float r = sqrtf(r2);
        double xn = (dx[0] * ni[0] + dx[1] * ni[1] + (dim == 3 ? dx[2] * ni[2] : 0.0f)) / len_i;
        ls += (len_j - CSF_FORCE_MIN) * sph_csf_w_surface(sqrt(fmax(r2 - xn * xn, 0.0)), k->h, dim);
        if (!curved || !(len_j > CSF_NORMAL_MIN)) continue;
        /* w_j V_j grad_i W_ij = g x_ij */
        double g = (len_j - CSF_NORMAL_MIN) * (double)P->mass[j] * inv_rho0 * sph_kernel_dw(k, r) / r;
        for (int a = 0; a < dim; a++)
            for (int b = 0; b < dim; b++) {
                /* x_j - x_i = -x_ij; u = -n / |n| outward */
                A[a][b] += g * dx[a] * (-dx[b]);
                Sm[a][b] += g * dx[a] * (-(double)nj[b] / len_j + (double)ni[b] / len_i);
            }
    }
    const double u[3] = {-ni[0] / len_i, -ni[1] / len_i, dim == 3 ? -ni[2] / len_i : 0.0};
    if (curved) P->curv[i] = csf_div(A, Sm, u, dim);
    lam[i] = (float)(ls / wi);
}

/* Sweep 2: the curvature averaged (Shepard) over the neighbours that have one, weights (|n| - CSF_NORMAL_MIN) W,
 * and the force, sigma kappa per unit area of surface shared as w_i / lam_i. */
static inline void csf_force(const sph_sim *sim, const sph_kernel *k, const float *lam, float *kap, int i,
                             const int dim, const bool dbl, const bool periodic)
{
    (void)dbl;
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const float *per = sim->period, *iper = sim->inv_period;
    for (int d = 0; d < dim; d++) P->acc_s[d][i] = 0.0f;
    kap[i] = 0.0f;
    if (!(lam[i] > 0)) return;
    float ni[3], len_i = 0;
    for (int d = 0; d < dim; d++) ni[d] = P->normal[d][i], len_i += ni[d] * ni[d];
    len_i = sqrtf(len_i);
    double sw = 0, sk = 0;
    if (len_i > CSF_NORMAL_MIN) sw = sph_kernel_w(k, 0.0f) * (len_i - CSF_NORMAL_MIN), sk = sw * P->curv[i];
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        if (j == (uint32_t)i || sph_is_wall(P, j)) continue;
        float r2 = 0, lj = 0;
        for (int d = 0; d < dim; d++) lj += P->normal[d][j] * P->normal[d][j];
        lj = sqrtf(lj);
        if (!(lj > CSF_NORMAL_MIN)) continue;
        for (int d = 0; d < dim; d++) {
            float dx = P->pred[d][i] - P->pred[d][j];
            if (periodic) dx = sph_min_image(dx, per[d], iper[d]);
            r2 += dx * dx;
        }
        double w = sph_kernel_w(k, sqrtf(r2)) * (lj - CSF_NORMAL_MIN);
        sw += w, sk += w * P->curv[j];
    }
    if (!(sw > 0)) return;
    const double kappa = sk / sw;
    kap[i] = (float)kappa;
    /* sigma kappa times the particle's share of the surface 1 / lam_i, per unit mass, into the fluid */
    const double a = sim->def.sigma * kappa / ((double)lam[i] * P->mass[i] * len_i);
    for (int d = 0; d < dim; d++) P->acc_s[d][i] = (float)(a * ni[d]);
}

static void run(sph_sim *sim)
{
    const sph_kernel k = sim->k_density;
    const int n = (int)sim->n, dim = sim->dim;
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
    const bool periodic = sph_sim_periodic(sim);
    float *lam = malloc(sizeof(float) * (size_t)(2 * n + 1));
    /* returning would leave last step's acc_s in place: a wrong answer in silence */
    if (!lam) sph_memory_fail("the csf pass's %d-particle scratch could not be made (%s)", n, strerror(errno));
    float *kap = lam + n;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) SPH_SPECIALISE_P(dim, dbl, periodic, csf_one, sim, &k, lam, i);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) SPH_SPECIALISE_P(dim, dbl, periodic, csf_force, sim, &k, lam, kap, i);
    for (int i = 0; i < n; i++) sim->P.curv[i] = kap[i];
    free(lam);
}

const sph_pass sph_pass_csf = {
    .name = "csf",
    .summary = "continuum surface force, sigma kappa per unit area of surface (acceleration)",
    .reads = SPH_BIT(PRED) | SPH_BIT(NORMAL) | SPH_BIT(MASS) | SPH_RES_LISTS,
    .writes = SPH_BIT(CURV) | SPH_BIT(ACC_S),
    .group = SPH_GROUP_FORCES,
    .highlight = "curvature",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
