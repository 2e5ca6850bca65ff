/* The start-up ramps of a scene: gravity that grows in, and velocity damping
 * that fades out ([physics] gravity_ramp, damping_time). Both follow
 *   zeta(t) = (1 - cos(pi t / T)) / 2  for t < T,  1 afterwards,
 * the damping factor of Adami, Hu & Adams 2012 (J. Comput. Phys. 231:7057,
 * hydrostatic tank), written there as (sin((t/T - 1/2) pi) + 1) / 2. Its
 * slope is zero at both ends, so neither the start nor the end of the ramp
 * is a jolt that sends a pressure wave through the fluid; a linear ramp's
 * kink at T does. The external pass and its shader use the same host value,
 * taken at the middle of the step (t + dt/2): summed over the steps, the
 * ramp then gives exactly the integral g T / 2 of the smooth curve, where
 * the start of each step would add a spurious g dt / 2. */
#ifndef SPH_START_H
#define SPH_START_H

#include <math.h>

#include "sph_sim.h"

/* [1] zeta(t) for a ramp of length T seconds; exactly 1 with T = 0 or t >= T. */
static inline float sph_start_ramp(float T, double t)
{
    if (!(T > 0.0f) || t >= (double)T) return 1.0f;
    return (float)(0.5 * (1.0 - cos(3.14159265358979323846 * t / (double)T)));
}

/* [1] share of g applied in the step under way (sim->dt chosen) */
static inline float sph_start_gravity_scale(const sph_sim *sim)
{
    return sph_start_ramp(sim->def.gravity_ramp, sim->t + 0.5 * sim->dt);
}

/* [1] factor the step under way multiplies every velocity by: near 0 (all
 * motion removed) at t = 0, rising to 1 (none) at damping_time */
static inline float sph_start_damping(const sph_sim *sim)
{
    /* a step of no length (the start's force evaluation, sph_sim_create) damps nothing */
    if (!(sim->dt > 0)) return 1.0f;
    return sph_start_ramp(sim->def.damping_time, sim->t + 0.5 * sim->dt);
}

/* [m/s] the velocity the external pass has just added to every fluid particle in the step under way,
 * g dt (ramped; zero without gravity). Wall particles do not get it, but the fluid's pressure force is
 * about to take it back from a fluid at rest, so a rate that compares the fluid's velocity with a wall
 * particle's (the continuity equation, the no-slip mirror) adds it to the wall's: else a column at
 * rest reads as flowing into the floor at g dt (docs/accuracy.md, "hydrostatic"). */
static inline void sph_wall_kick(const sph_sim *sim, float kick[3])
{
    const bool g = sim->def.effects & SPH_EFFECT(GRAVITY);
    const float gdt = g ? sph_start_gravity_scale(sim) * sim->dt : 0.0f;
    for (int d = 0; d < 3; d++) kick[d] = d < sim->dim ? sim->def.gravity[d] * gdt : 0.0f;
}

/* [s/m^2] 1/nu for the no-slip mirror's curvature term (wall_state.c), 0 where no physical viscosity
 * reads the mirror (no viscosity effect, viscosity_form = artificial, nu = 0) */
static inline double sph_wall_mirror_inv_nu(const sph_scene_def *def)
{
    if (!(def->effects & SPH_EFFECT(VISCOSITY)) || def->viscosity_form == SPH_VFORM_ARTIFICIAL) return 0.0;
    return def->viscosity > 0 ? 1.0 / def->viscosity : 0.0;
}

#endif
