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
 * whose curvatures were noise and whose forces stirred the drop until it
 * flew apart; at 0.1 and 0.3 the second row (|h grad c| 0.29 on a lattice,
 * cubic kernel at h = 3 spacings) flickered across the cut and the surface
 * frayed within a period (0.1) or two (0.3, cut 0.6: sooner). The cut is
 * 0.3, so that on a lattice the force acts on the outermost row (|n| 1.23)
 * alone; a drop of R = 20 spacings still frays after about one period
 * (docs/accuracy.md, the drop): this is not solved.
 *
 * Curvature: the divergence of the outward unit normal u = -normal/|normal|
 * over the neighbours above the cut, renormalised (Bonet & Lok 1999) on the
 * tangent plane of u_i: with
 *   A = sum_j V_j grad_i W_ij (x_j - x_i)^T,  S = sum_j V_j grad_i W_ij (u_j - u_i)^T,
 * projected on the tangents t_p (A_t = t_p.A.t_q), kappa_i = trace(A_t^-1 S_t).
 * The unit normal of a curved surface does not change along itself (u.du = 0
 * and, for concentric surfaces, du/dn = 0), so the tangential part is the
 * whole divergence, and it needs no support across the surface, where the
 * rows are few (the full matrix's inverse there amplified the normals' noise
 * and gave a disc of 20 spacings curvatures of -50 to 300 1/m for 10). A
 * particle whose tangential support is below 0.1 (1 in a full support) gets
 * no curvature.
 *
 * The delta. At a free surface the particles carry only the fluid's side of
 * the colour jump: across a flat surface s sum_rows |grad c| is B (0.41 for
 * the cubic kernel at h = 3 spacings with the cut), not 1. The force is
 * divided by B, computed on the scene's lattice (a half-space of the finest
 * block's spacing, the density kernel, volumes s^dim, the same cut), so that
 * a flat-lattice surface feels sigma kappa per unit area. This is the
 * discretisation's own constant, not a fit to any result.
 *
 * Per unit mass: a_i = sigma kappa_i grad c_i / (B rho0), only for
 * particles above the cut. A pair's terms are not equal and opposite (kappa
 * differs between particles), so momentum is conserved only as far as kappa
 * is uniform: tests/test_csf.c measures the net force on a disc. Wall
 * particles get none and are left out of the sums, as in the normals pass. */
#include "csf.h"
#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>

#define CSF_SUPPORT_MIN 0.1 /* the tangential renormalisation's least eigenvalue (1 in a full support) */
#define CSF_NORMAL_MIN 0.3f /* |h grad c| a particle needs to feel the force (Morris 2000: 0.01; see above) */

static const char *skip_reason(const sph_scene_def *def)
{
    return def->surface_tension == SPH_STENSION_CSF ? NULL : "surface_tension is not csf";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "continuum surface force (Brackbill 1992, Morris 2000), sigma %g N/m", def->sigma);
}

/* The finest block's spacing [m]: the lattice of the delta's integral B. */
static double csf_spacing(const sph_scene_def *def)
{
    double s = def->n_blocks ? def->blocks[0].spacing : def->h / 2;
    for (int b = 1; b < def->n_blocks; b++) s = fmin(s, def->blocks[b].spacing);
    return s;
}

/* B, the integral of |grad c| across a flat surface, on a lattice of
 * spacing s filling the half-space below it (the rows at depth l s, l = 0
 * at the surface, each particle of volume s^dim as in the normals pass):
 * s times the sum over the rows of |grad c| where it passes the cut. */
double sph_csf_delta_integral(const sph_kernel *k, int dim, double s)
{
    const int reach = (int)ceil(k->h / s), ny = dim == 3 ? reach : 0;
    if (!(s > 0) || reach > 1000) return 0.0;
    const double vol0 = pow(s, dim);
    double B = 0;
    for (int l = 0; l <= reach; l++) { /* deeper rows have a full support: no normal */
        double g = 0;
        for (int m = l > reach ? l - reach : 0; m <= l + reach; m++)
            for (int a = -reach; a <= reach; a++)
                for (int b = -ny; b <= ny; b++) {
                    double dz = (double)(m - l) * s, r = sqrt(dz * dz + (double)(a * a + b * b) * s * s);
                    if (r >= k->h || !(r > 0)) continue;
                    g += vol0 * sph_kernel_dw(k, (float)r) * (-dz) / r; /* x_ij along the depth: -dz */
                }
        if (fabs(g) * k->h > CSF_NORMAL_MIN) B += s * fabs(g);
    }
    return B;
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

static inline void csf_one(const sph_sim *sim, const sph_kernel *k, float coef, int i, const int dim, const bool dbl,
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
    for (int d = 0; d < dim; d++) P->acc_s[d][i] = 0.0f;
    if (sph_is_wall(P, i) || !(len_i > CSF_NORMAL_MIN)) return;
    double A[3][3] = {{0}}, Sm[3][3] = {{0}};
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
        if (!(len_j > CSF_NORMAL_MIN)) continue;
        float dx[3], r2 = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = xi[d] - P->pred[d][j];
            if (periodic) dx[d] = sph_min_image(dx[d], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        if (!(r2 > 0)) continue;
        float r = sqrtf(r2);
        double g = (double)P->mass[j] * inv_rho0 * sph_kernel_dw(k, r) / r; /* V_j grad_i W_ij = g x_ij */
        for (int a = 0; a < dim; a++)
            for (int b = 0; b < dim; b++) {
                /* x_j - x_i = -x_ij; u = -n / |n| outward */
                A[a][b] += g * dx[a] * (-dx[b]);
                Sm[a][b] += g * dx[a] * (-(double)nj[b] / len_j + (double)ni[b] / len_i);
            }
    }
    const double u[3] = {-ni[0] / len_i, -ni[1] / len_i, dim == 3 ? -ni[2] / len_i : 0.0};
    const float kappa = csf_div(A, Sm, u, dim);
    P->curv[i] = kappa;
    /* grad c = n / h; force per unit volume sigma kappa grad c / B, into the fluid for kappa > 0 */
    for (int d = 0; d < dim; d++) P->acc_s[d][i] = coef * kappa * ni[d];
}

/* a few hundred kernel values: cheaper to recompute each step than to keep */
float sph_csf_coefficient(const sph_sim *sim)
{
    const sph_kernel *k = &sim->k_density;
    const double B = sph_csf_delta_integral(k, sim->dim, csf_spacing(&sim->def));
    return B > 0 ? (float)(sim->def.sigma / (B * k->h * sim->def.rest_density)) : 0.0f;
}

static void run(sph_sim *sim)
{
    const sph_kernel k = sim->k_density;
    const int n = (int)sim->n, dim = sim->dim;
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
    const bool periodic = sph_sim_periodic(sim);
    const float coef = sph_csf_coefficient(sim);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) SPH_SPECIALISE_P(dim, dbl, periodic, csf_one, sim, &k, coef, i);
}

const sph_pass sph_pass_csf = {
    .name = "csf",
    .summary = "continuum surface force, sigma kappa grad c (acceleration)",
    .reads = SPH_BIT(PRED) | SPH_BIT(NORMAL) | SPH_BIT(MASS) | SPH_RES_LISTS,
    .writes = SPH_BIT(CURV) | SPH_BIT(ACC_S),
    .group = SPH_GROUP_FORCES,
    .highlight = "curvature",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
