/* Pass: the state of the wall particles (wall_model = particles), the
 * generalized wall boundary condition of Adami, Hu & Adams 2012 (J. Comput.
 * Phys. 231, 7057-7075), eq. 27-28. For each wall particle w, from the fluid
 * particles f in its support:
 *   p_w   = (sum_f p_f W_wf + (g - a_w) . sum_f rho_f r_wf W_wf) / sum_f W_wf
 *           (r_wf = x_w - x_f; the box stands still, a_w = 0; g the gravity
 *           of the step, ramped as the fluid's during gravity_ramp): the
 *           fluid's pressure extrapolated into the wall with the hydrostatic gradient,
 *   rho_w = the equation of state solved for the density at p_w,
 *   v~_w  = sum_f v_f W_wf / sum_f W_wf, and the velocity the viscous term
 *           sees, vel_visc = 2 v_w - v~_w (no-slip: the velocity mirrored
 *           about the wall's own, zero at the wall) or v~_w (free-slip);
 *           v_w taken in the step's frame, v_w + g dt, as the fluid's v
 *           already carries this step's gravity kick (sph_wall_kick).
 * A wall particle with no fluid in reach keeps p = 0 at rest density.
 * Fluid particles get vel_visc = their velocity. The pass runs after the
 * equation of state: it overwrites the pressure and density that summation
 * gave the wall particles. It reads p and rho of fluid particles only and
 * writes them for wall particles only, so no particle reads a value written
 * in the same sweep. */
#include "sph_search.h"
#include "sph_start.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    if (!(def->effects & SPH_EFFECT(WALLS))) return "effects do not list walls";
    if (def->wall_model != SPH_WALL_PARTICLES) return "no wall particles ([domain] wall_model is not particles)";
    return sph_scene_wall_particles(def) ? NULL : "wall particles need the pressure effect";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    bool mixed = false; /* do some walls slip otherwise than wall_slip says? */
    for (int k = 0; k < 2 * def->dim; k++)
        mixed |= def->wall_slip_side[k] != SPH_SIDE_SLIP_SAME &&
                 (def->wall_slip_side[k] == SPH_SIDE_SLIP_FREE) != (def->wall_slip == SPH_SLIP_FREE);
    for (int k = 0; k < def->n_obstacles; k++) mixed |= def->obstacles[k].slip != def->wall_slip;
    snprintf(out, (size_t)n, "Adami et al. 2012: wall pressure from the fluid, %s walls%s",
             mixed ? "no-slip and free-slip" : def->wall_slip == SPH_SLIP_FREE ? "free-slip" : "no-slip",
             def->n_obstacles ? ", obstacles" : "");
}

/* The density at which the equation of state gives pressure p (its
 * reference rho0 = sim->eos_rho0, as pressure.c's). */
static float eos_density(const sph_scene_def *def, const float rho0, float p)
{
    const float k = def->stiffness;
    if (def->eos == SPH_EOS_TAIT) {
        const float B = k * rho0 / def->tait_gamma;
        return rho0 * powf(fmaxf(1.0f + p / B, 1e-3f), 1.0f / def->tait_gamma);
    }
    return fmaxf(rho0 + p / k, 1e-3f * rho0);
}

/* gscale: the share of g of the step under way (gravity_ramp; 0 without gravity); kick: g dt of
 * the step (sph_wall_kick) */
static inline void wall_one(sph_sim *sim, int w, const int dim, const bool periodic, const float gscale,
                            const float *kick)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const sph_scene_def *def = &sim->def;
    const sph_kernel *k = &sim->k_density;
    const float *per = sim->period, *iper = sim->inv_period;
    double sw = 0, sp = 0, srr[3] = {0, 0, 0}, sv[3] = {0, 0, 0};
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)(w));
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t f = sph_nbr_at(&row, e);
        if (sph_is_wall(P, f)) continue;
        float dx[3], r2 = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = P->pred[d][w] - P->pred[d][f];
            if (periodic) dx[d] = sph_min_image(dx[d], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        double W = sph_kernel_w(k, sqrtf(r2));
        sw += W;
        sp += (double)P->p[f] * W;
        for (int d = 0; d < dim; d++) {
            srr[d] += (double)P->rho[f] * dx[d] * W;
            sv[d] += (double)P->vel[d][f] * W;
        }
    }
    float p = 0.0f, vt[3] = {0, 0, 0};
    if (sw > 0) {
        double q = sp;
        for (int d = 0; d < dim; d++) q += (double)def->gravity[d] * gscale * srr[d];
        p = (float)(q / sw);
        for (int d = 0; d < dim; d++) vt[d] = (float)(sv[d] / sw);
    }
    if (def->negative_pressure == SPH_NEGP_CLAMP) p = fmaxf(p, 0.0f);
    const float rho = eos_density(def, sim->eos_rho0, p);
    P->p[w] = p;
    P->rho[w] = rho;
    P->p_rho2[w] = p / (rho * rho);
    P->vol[w] = P->mass[w] / rho;
    /* the mirror about the wall's velocity in the step's frame, v_w + g dt (kick): the fluid's v already
     * carries this step's gravity kick, which its pressure force is about to take back */
    for (int d = 0; d < dim; d++)
        P->vel_visc[d][w] = P->slip[w] != 0.0f ? vt[d] : 2.0f * (P->vel[d][w] + kick[d]) - vt[d];
}

static void run(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const int n = (int)sim->n, dim = sim->dim;
    const bool periodic = sph_sim_periodic(sim);
    /* the gravity the fluid feels in this step: during gravity_ramp only a
     * share of g (sph_start.h), so the wall's hydrostatic term matches the
     * fluid's weight; the full g there pushed the first rows up */
    const float gscale = (sim->def.effects & SPH_EFFECT(GRAVITY)) ? sph_start_gravity_scale(sim) : 0.0f;
    float kick[3];
    sph_wall_kick(sim, kick);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (!sph_is_wall(P, i)) {
            for (int d = 0; d < dim; d++) P->vel_visc[d][i] = P->vel[d][i];
        } else if (periodic) {
            wall_one(sim, i, dim, true, gscale, kick);
        } else {
            wall_one(sim, i, dim, false, gscale, kick);
        }
    }
}

const sph_pass sph_pass_wall_state = {
    .name = "wall_state",
    .summary = "wall particles' pressure and velocity from the fluid",
    .reads = SPH_BIT(PRED) | SPH_BIT(MASS) | SPH_BIT(RHO) | SPH_BIT(P) | SPH_BIT(VEL) | SPH_BIT(FIXED) | SPH_BIT(SLIP) |
             SPH_RES_LISTS,
    .writes = SPH_BIT(RHO) | SPH_BIT(VOL) | SPH_BIT(P) | SPH_BIT(PRHO2) | SPH_BIT(VEL_VISC),
    .group = SPH_GROUP_DENSITY,
    .highlight = "pressure",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
