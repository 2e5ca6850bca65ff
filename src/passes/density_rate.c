/* Pass: the density's rate of change, for [physics] density_method =
 * continuity (delta-SPH, Molteni & Colagrossi 2009, Comput. Phys. Commun.
 * 180, 861-872):
 *
 *   drho_i/dt = sum_j m_j (v_i - v_j) . grad W_ij
 *             + delta h_s c sum_j psi_ij . grad W_ij V_j,
 *   psi_ij = 2 (rho_j - rho_i) x_ji / |x_ji|^2,  h_s = h/2, c = sqrt(stiffness),
 *
 * with the density kernel's gradient (so the rate is the time derivative of
 * the summation, and the two agree while the flow is gentle) and V_j = m_j/rho_j.
 * The second term is a diffusion of the density: psi_ij . grad_i W_ij =
 * -2 (rho_j - rho_i) W'(r)/r pulls rho_i towards its neighbours', which
 * damps the high-frequency density noise the bare continuity equation lets
 * grow. It is antisymmetric in the pair, weighted by V_i V_j, so it moves
 * no mass: sum_i V_i drho_i gets nothing from it.
 *
 * The design, kept simple: the carried density is the state field rho_c
 * (moved by reorder, carried over by sph_sim_reconfigure).
 *   - rho_c starts from the lattice's density m / s^dim (sph_sim.c,
 *     place_particles: the summation misses a free surface's outside, and its
 *     top row started 16 % light); only the first step after a
 *     reconfiguration that switched continuity on has this pass write
 *     drho = 0 while the density pass sums, and rho_c starts from that sum;
 *   - from then on this pass, run before density, makes drho from rho_c and
 *     the velocities of this step, and the density pass advances
 *     rho_c += dt drho and sets rho = rho_c, so pressure and every later pass
 *     read `rho` unchanged.
 * Why the rate uses this step's velocities (after the previous step's
 * integration) rather than being applied by integration with the old ones:
 * rho and v are then updated one after the other, symplectic Euler for the
 * sound waves. Updating both from the old state (explicit Euler) made every
 * acoustic mode grow: a jittered box gained 40 times its kinetic energy in
 * 200 steps.
 * With delta_form = antuono (Antuono et al. 2010, Comput. Phys. Commun. 181,
 * 532-549, eq. 9) psi_ij loses the renormalised density gradients that the
 * density_gradient pass just made:
 *   psi_ij = 2 (rho_j - rho_i) x_ji / |x_ji|^2 - (<grad rho>^L_i + <grad rho>^L_j).
 * For a linear density (a hydrostatic column) the two parts cancel pair by
 * pair, so the term is zero; Molteni's alone is not zero where the kernel is
 * cut off (the free surface), and moves density upwards: the column drifts.
 * With delta_form = fourtakas (Fourtakas, Dominguez, Vacondio & Rogers 2019,
 * Comput. Fluids 190:346-361, eq. 14-15; DualSPHysics' "DDT 2") the pair's
 * hydrostatic density difference is taken out instead:
 *   psi_ij = 2 ((rho_j - rho_i) - rho^H_ji) x_ji / |x_ji|^2,
 *   rho^H_ji = EOS^-1(rho0 g . (x_j - x_i)) - rho0,
 * the density the equation of state gives j's depth below i (g the step's
 * gravity, ramped as the fluid's). For a column at rest the term is zero
 * pair by pair, without a gradient estimate, so a truncated support (the
 * free surface, the wall particles, which stay out of the flux) does not
 * drive it; what it diffuses is the dynamic part of the density.
 * The wall particles enter the gradients (passes/density_gradient.c) but
 * not the flux: a flux to a wall particle, whose density wall_state ties to
 * the fluid's pressure, is a source of mass that feeds itself (tried: the
 * wall row gained 200 % of rho0 g H in a second).
 *
 * Walls: with wall_model = volume the summation holds rho0 times the
 * kernel's share hidden behind the walls; its time derivative,
 * rho0 grad(hidden share) . v_i, is added. With wall_model = particles the
 * wall particles enter the velocity term (they are at rest) but not the
 * diffusion term: their density is set by the wall_state pass, from the
 * fluid's pressure, not carried, so only fluid pairs diffuse (as DualSPHysics
 * does too). */
#include "sph_search.h"
#include "sph_start.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    if (!sph_scene_needs_density(def)) return "no effect of the scene needs density (the neighbour search)";
    return def->density_method == SPH_DMETHOD_CONTINUITY ? NULL
                                                         : "[physics] density_method = summation: nothing is carried";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "continuity equation with density diffusion delta = %g (%s)%s", def->delta,
             def->delta_form == SPH_DFORM_ANTUONO     ? "Antuono et al. 2010"
             : def->delta_form == SPH_DFORM_FOURTAKAS ? "Fourtakas et al. 2019"
                                                      : "Molteni & Colagrossi 2009",
             sph_scene_wall_volume(def) ? ", walls' hidden share moved by v" : "");
}

/* Fourtakas et al. 2019's hydrostatic density difference rho^H_ji [kg/m^dim]
 * for the pressure difference ph = rho0 g . (x_j - x_i) [Pa]. */
static inline float hydro_density(const sph_scene_def *def, const float rho0, float ph)
{
    if (def->eos == SPH_EOS_TAIT) { /* rho0: the equation of state's reference, sim->eos_rho0 */
        const float B = def->stiffness * rho0 / def->tait_gamma;
        return rho0 * (powf(fmaxf(1.0f + ph / B, 1e-3f), 1.0f / def->tait_gamma) - 1.0f);
    }
    return ph / def->stiffness;
}

/* The rate for one particle; dim and dbl are constants (SPH_SPECIALISE_P).
 * g0: rho0 times the step's gravity [kg/(m^dim s^2)], with delta_form =
 * fourtakas (else NULL). */
static inline void rate_one(const sph_sim *sim, const sph_kernel *k, float diffusion, const float *g0,
                            const float *kick, int i, const int dim, const bool dbl, const bool periodic)
{
    sph_particles *P = (sph_particles *)&sim->P;
    const sph_search_data *S = &sim->S;
    if (sph_is_wall(P, i)) { /* wall particles never move, their density comes from wall_state */
        P->drho[i] = 0.0f;
        return;
    }
    const float r_min = SPH_KERNEL_R_MIN * k->h; /* a coincident pair has no direction: left out */
    const float *per = sim->period, *iper = sim->inv_period;
    const float rho_i = P->rho_c[i];
    const bool antuono = P->grad_rho[0] != NULL;
    float xi[3], vi[3];
    for (int d = 0; d < dim; d++) {
        xi[d] = P->pred[d][i];
        vi[d] = P->vel[d][i];
    }
    float sf = 0.0f;
    double sd = 0.0;
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        float dx[3], r2 = 0, vx = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = xi[d] - P->pred[d][j];
            if (periodic) dx[d] = sph_min_image(dx[d], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        if (r2 < r_min * r_min) continue;
        if (sph_is_wall(P, j)) /* the wall's velocity in the step's frame (sph_wall_kick) */
            for (int d = 0; d < dim; d++) vx += (vi[d] - P->vel[d][j] - kick[d]) * dx[d];
        else
            for (int d = 0; d < dim; d++) vx += (vi[d] - P->vel[d][j]) * dx[d];
        const float r = sqrtf(r2);
        const float dw_over_r = sph_kernel_dw(k, r) / r; /* grad_i W_ij = dw_over_r x_ij */
        float t = P->mass[j] * vx * dw_over_r;
        if (diffusion != 0.0f && !sph_is_wall(P, j)) {
            float psi = -2.0f * (P->rho_c[j] - rho_i); /* psi_ij . x_ij, Molteni's part */
            if (antuono)                               /* Antuono's: - (grad_i + grad_j) . x_ij */
                for (int d = 0; d < dim; d++) psi -= (P->grad_rho[d][i] + P->grad_rho[d][j]) * dx[d];
            if (g0) { /* Fourtakas's: + 2 rho^H_ji, at p = rho0 g . x_ji = -rho0 g . x_ij */
                float ph = 0.0f;
                for (int d = 0; d < dim; d++) ph -= g0[d] * dx[d];
                psi += 2.0f * hydro_density(&sim->def, sim->eos_rho0, ph);
            }
            t += diffusion * psi * dw_over_r * P->mass[j] / P->rho_c[j];
        }
        if (dbl) sd += t;
        else sf += t;
    }
    float rate = dbl ? (float)sd : sf;
    if (sph_sim_wall_volume(sim)) {
        float grad[3];
        sph_wall_hidden(sim, k, i, grad);
        /* the walls at rest in the step's frame (sph_wall_kick), as the wall particles: else a column at
         * rest reads as flowing into the floor at g dt and its row at the floor is compressed */
        for (int d = 0; d < dim; d++) rate += sim->def.rest_density * grad[d] * (vi[d] - kick[d]);
    }
    P->drho[i] = rate;
}

static void run(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const sph_kernel k = sim->k_density;
    const int n = (int)sim->n, dim = sim->dim;
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
    const bool periodic = sph_sim_periodic(sim);
    if (!sim->rho_carried) { /* the start: the density pass sums, and rho_c starts from it */
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++) P->drho[i] = 0.0f;
        return;
    }
    const float diffusion = sim->def.delta * 0.5f * sim->def.h * sqrtf(sim->def.stiffness); /* delta h_s c [m^2/s] */
    float g0[3] = {0, 0, 0}; /* rho0 g of the step, for delta_form = fourtakas */
    const bool fourtakas = sim->def.delta_form == SPH_DFORM_FOURTAKAS;
    float kick[3];
    sph_wall_kick(sim, kick);
    if (fourtakas && (sim->def.effects & SPH_EFFECT(GRAVITY))) {
        const float gs = sph_start_gravity_scale(sim);
        for (int d = 0; d < dim; d++) g0[d] = sim->def.rest_density * sim->def.gravity[d] * gs;
    }
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++)
        SPH_SPECIALISE_P(dim, dbl, periodic, rate_one, sim, &k, diffusion, fourtakas ? g0 : NULL, kick, i);
}

const sph_pass sph_pass_density_rate = {
    .name = "density_rate",
    .summary = "drho/dt: continuity equation with density diffusion (delta-SPH)",
    /* and grad_rho with delta_form = antuono (not in reads: it exists only in those scenes) */
    .reads = SPH_BIT(PRED) | SPH_BIT(VEL) | SPH_BIT(MASS) | SPH_BIT(RHO_C) | SPH_RES_LISTS,
    .writes = SPH_BIT(DRHO),
    .group = SPH_GROUP_DENSITY,
    .highlight = "density-rate",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
