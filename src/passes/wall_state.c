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
 *           The mirror continues the fluid's profile as an odd function
 *           about the wall, which is right only where it is straight. At a
 *           no-slip wall the fluid is at rest, so the momentum equation
 *           there reads nu lap v = -a, a = g - grad p / rho the fluid's
 *           non-viscous acceleration: a profile curved by an unbalanced force
 *           (a channel's body force) continues as v(-n) = -v(n) - (a/nu) n^2,
 *           n the distance from the wall, which Adami's mirror places half
 *           way between the wall particle and the centroid of its fluid
 *           neighbours (as Morris, Fox & Zhu 1997 place the wall half a
 *           spacing behind the last fluid row). So, with nu the viscosity:
 *             vel_visc = 2 v_w - v~_w - (a/nu) (|c|^2/4 + var_c/2),
 *           c the W-weighted centroid of the fluid neighbours from x_w and
 *           var_c their W-weighted variance along c (the Shepard average of
 *           a curved profile is off by (v''/2) var_c). a from the fluid:
 *           minus the W-weighted gradient along the wall of the pressure
 *           extrapolated to x_w, q_f = p_f + rho_f g . r_wf, over rho0
 *           (grad q = grad p - rho g; zero in a column at rest, so the
 *           hydrostatic tank gets no term; F along a channel), its part
 *           along the wall only (along c the wall's pressure holds the
 *           fluid), the term at most |v~_w - v_w| (a limiter: see
 *           wall_one). Without it a channel's steady profile ran 2 % of
 *           u_max fast at 10 spacings across (docs/accuracy.md,
 *           "poiseuille and couette").
 * A wall particle with no fluid in reach keeps p = 0 at rest density.
 * With a pressure solver (pcisph, dfsph) there is no p: the wall particles
 * then keep the density the summation gave them, hold no pressure (the
 * solvers' walls push with the fluid particle's own, pcisph.c), and get the
 * viscous term's velocity only, without the curvature term (it needs p).
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
    for (int k = 0; k < 2 * def->dim; k++) /* a periodic axis has no walls: its sides' keys count for nothing */
        mixed |= !(def->periodic & (1u << (k / 2))) && def->wall_slip_side[k] != SPH_SIDE_SLIP_SAME &&
                 (def->wall_slip_side[k] == SPH_SIDE_SLIP_FREE) != (def->wall_slip == SPH_SLIP_FREE);
    for (int k = 0; k < def->n_obstacles; k++) mixed |= def->obstacles[k].slip != def->wall_slip;
    /* under a solver the walls' pressure is the solver's (solver_wall_pressure): this pass gives the velocity */
    /* the slip acts through the viscous term only: without the effect the walls are free-slip, whatever is set
     * (lesson 10's pipeline said "no-slip walls" for a scene without viscosity) */
    const bool viscous = (def->effects & SPH_EFFECT(VISCOSITY)) != 0;
    snprintf(out, (size_t)n, "Adami et al. 2012: %s, %s%s",
             def->pressure_solver != SPH_PSOLVER_EOS ? "wall velocity only (the walls' pressure is the "
                                                       "solver's: solver_wall_pressure)"
                                                     : "wall pressure from the fluid",
             !viscous ? "free-slip walls (no viscosity reads the slip)"
             : mixed  ? "no-slip and free-slip walls"
             : def->wall_slip == SPH_SLIP_FREE ? "free-slip walls"
                                               : "no-slip walls",
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

/* The curvature term of the no-slip mirror (the header): -(a_t/nu) (|c|^2/4 + var_c/2) [m/s] into out[],
 * from the W-weighted sums over the fluid neighbours: sw = sum W, sc = sum W c_f (c_f = x_f - x_w),
 * scc = sum W c_f c_f^T, sq = sum W q_f, sqc = sum W q_f c_f. n = c / |c| is the wall's normal; the
 * gradient of q along the wall is the covariance of q with the neighbours' offsets along the wall over
 * their variance there (the offsets' spread is the same along every direction of a flat wall of the
 * lattice): no matrix to invert, so a few neighbours (a corner) give a small term, not an amplified one.
 * a_t = -grad_t q / rho0: along the normal the wall's pressure, not the mirror, holds the fluid (a normal
 * term cancelled the pressure's push from the wall: a column at rest blew up). */
static void mirror_curvature(int dim, double sw, const double sc[3], const double scc[3][3], double sq,
                             const double sqc[3], double rho0, double inv_nu, float out[3])
{
    double m[3][3], b[3], n[3] = {0, 0, 0}, c2 = 0;
    for (int d = 0; d < 3; d++) out[d] = 0.0f;
    for (int d = 0; d < dim; d++) {
        n[d] = sc[d] / sw;
        c2 += n[d] * n[d];
    }
    if (!(c2 > 0) || dim < 2) return;
    for (int d = 0; d < dim; d++) {
        for (int e = 0; e < dim; e++) m[d][e] = scc[d][e] / sw - n[d] * n[e];
        b[d] = sqc[d] / sw - sq / sw * n[d];
    }
    const double cl = sqrt(c2);
    for (int d = 0; d < dim; d++) n[d] /= cl;
    double tr = 0, var = 0, bn = 0;
    for (int d = 0; d < dim; d++) {
        tr += m[d][d];
        bn += b[d] * n[d];
        for (int e = 0; e < dim; e++) var += n[d] * m[d][e] * n[e];
    }
    const double var_t = (tr - var) / (dim - 1); /* [m^2] the spread along one direction of the wall */
    /* the neighbours must spread along the wall at least as far as across it, as they do at a flat wall
     * (the support's widest chord lies along it); a sliver along the normal (a corner, a free surface
     * meeting the wall) leaves the gradient along the wall undetermined: no term */
    if (!(var_t > 1e-3 * c2) || var_t < var) return; /* 1e-3 |c|^2: above rounding (one neighbour: C = 0) */
    const double len2 = 0.25 * c2 + 0.5 * var; /* [m^2] |c|^2/4 + var_c/2 */
    for (int d = 0; d < dim; d++) /* -(a_t/nu) len2, grad_t q = (b - (b.n) n) / var_t */
        out[d] = (float)((b[d] - bn * n[d]) / var_t / rho0 * inv_nu * len2);
}

/* gscale: the share of g of the step under way (gravity_ramp; 0 without gravity); kick: g dt of
 * the step (sph_wall_kick); inv_nu: 1/nu [s/m^2] for the mirror's curvature term (0: none) */
static inline void wall_one(sph_sim *sim, int w, const int dim, const bool periodic, const float gscale,
                            const float *kick, const double inv_nu)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const sph_scene_def *def = &sim->def;
    const sph_kernel *k = &sim->k_density;
    const float *per = sim->period, *iper = sim->inv_period;
    double sw = 0, sp = 0, srr[3] = {0, 0, 0}, sv[3] = {0, 0, 0};
    double sq = 0, sc[3] = {0, 0, 0}, sqc[3] = {0, 0, 0}, scc[3][3] = {{0}}; /* mirror_curvature's sums */
    /* [Pa] q's reference, the wall particle's pressure of the last step: q's gradient is a small difference of
     * large pressures (1e6 Pa in a stiff tank), which the GL backend sums in float */
    const bool eos = P->p != NULL; /* the solvers (pcisph, dfsph) make no p: the walls then give the velocity only */
    const double qref = eos ? P->p[w] : 0.0;
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
        if (!eos) { /* the viscous term's velocity alone */
            for (int d = 0; d < dim; d++) sv[d] += (double)P->vel[d][f] * W;
            continue;
        }
        sp += (double)P->p[f] * W;
        double q = (double)P->p[f] - qref; /* q_f = p_f + rho_f g . r_wf, less qref */
        for (int d = 0; d < dim; d++) {
            srr[d] += (double)P->rho[f] * dx[d] * W;
            sv[d] += (double)P->vel[d][f] * W;
            q += (double)def->gravity[d] * gscale * P->rho[f] * dx[d];
        }
        if (inv_nu > 0) { /* c_f = x_f - x_w = -dx */
            sq += q * W;
            for (int d = 0; d < dim; d++) {
                sc[d] -= dx[d] * W;
                sqc[d] -= q * dx[d] * W;
                for (int d2 = 0; d2 < dim; d2++) scc[d][d2] += (double)dx[d] * dx[d2] * W;
            }
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
    if (eos) { /* with a solver the wall particle keeps the density the summation gave it */
        const float rho = eos_density(def, sim->eos_rho0, p);
        P->p[w] = p;
        P->rho[w] = rho;
        P->p_rho2[w] = p / (rho * rho);
        P->vol[w] = P->mass[w] / rho;
    }
    /* the mirror about the wall's velocity in the step's frame, v_w + g dt (kick): the fluid's v already
     * carries this step's gravity kick, which its pressure force is about to take back */
    float curv[3] = {0, 0, 0};
    if (eos && inv_nu > 0 && sw > 0 && P->slip[w] == 0.0f) {
        mirror_curvature(dim, sw, sc, scc, sq, sqc, def->rest_density, inv_nu, curv);
        /* The continuation is the viscous sublayer's Taylor series over |c|: only where viscosity rules
         * across it, the cell Reynolds number |v~_w - v_w| |c| / nu <= 1; beyond, the boundary layer is
         * thinner than the spacing and there is no resolved profile to continue (Adami's mirror alone).
         * And a limiter: the term at most |v~_w - v_w|, as a continuation whose curvature outweighs the
         * speed it continues is not a resolved profile either (a fluid still at rest under a force not
         * yet balanced, a corner's few neighbours). Both needed: with neither, a no-slip dam break at
         * nu = 1e-6 m^2/s lost 3 % more kinetic energy by t = 0.25 s (the term braked the floor row by the
         * unbalanced force, as if a boundary layer were resolved); with them, as without the term. In the
         * channels the cap binds only in the first steps of the start-up (up to 0.13 % of u_max at
         * t = 0.0225 s, 10 across), neither at steady state (docs/accuracy.md, "poiseuille and couette"). */
        double c2 = 0, r2 = 0, cc = 0;
        for (int d = 0; d < dim; d++) {
            const double rel = vt[d] - (P->vel[d][w] + kick[d]);
            c2 += (double)curv[d] * curv[d];
            r2 += rel * rel;
            cc += sc[d] / sw * sc[d] / sw;
        }
        if (sqrt(r2 * cc) * inv_nu > 1.0) c2 = r2 = 0.0, curv[0] = curv[1] = curv[2] = 0.0f;
        if (c2 > r2)
            for (int d = 0; d < dim; d++) curv[d] *= (float)sqrt(r2 / c2);
    }
    for (int d = 0; d < dim; d++)
        P->vel_visc[d][w] = P->slip[w] != 0.0f ? vt[d] : 2.0f * (P->vel[d][w] + kick[d]) - vt[d] + curv[d];
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
    const double inv_nu = sph_wall_mirror_inv_nu(&sim->def);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (!sph_is_wall(P, i)) {
            for (int d = 0; d < dim; d++) P->vel_visc[d][i] = P->vel[d][i];
        } else if (periodic) {
            wall_one(sim, i, dim, true, gscale, kick, inv_nu);
        } else {
            wall_one(sim, i, dim, false, gscale, kick, inv_nu);
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
