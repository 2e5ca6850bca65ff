/* What the two incompressible pressure solvers (pcisph.c, dfsph.c) share:
 * the density they hold, the non-pressure accelerations, the walls' share at
 * any position, the end of a solve. Internal to src/passes/. */
#ifndef SPH_SOLVER_H
#define SPH_SOLVER_H

#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>

/* The density a particle of the scene's finest lattice reads at rest, with
 * its whole support inside the fluid: rho0 (1 + e), where e is the
 * summation's own excess on a lattice (+3.3 % for poly6 at h = 2 s in 2D).
 * The solvers hold this density, not rho0: holding rho0 would expand every
 * block by e at its first step. Computed from the kernel and the lattice,
 * nothing fitted. */
static inline float sph_solver_rest_density(const sph_sim *sim)
{
    const sph_scene_def *def = &sim->def;
    float s = 0;
    for (int b = 0; b < def->n_blocks; b++)
        if (s == 0 || def->blocks[b].spacing < s) s = def->blocks[b].spacing;
    if (!(s > 0)) return def->rest_density;
    const int dim = sim->dim, r = (int)ceilf(def->h / s);
    const double m = def->rest_density * (dim == 3 ? (double)s * s * s : (double)s * s);
    double sum = 0;
    for (int z = dim == 3 ? -r : 0; z <= (dim == 3 ? r : 0); z++)
        for (int y = -r; y <= r; y++)
            for (int x = -r; x <= r; x++) {
                float d = s * sqrtf((float)(x * x + y * y + z * z));
                if (d < def->h) sum += m * sph_kernel_w(&sim->k_density, d);
            }
    return (float)sum;
}

/* The accelerations other than pressure at particle i (viscosity, cohesion,
 * the mouse; gravity is in the velocity already): every acceleration field
 * of the registry except the solvers' own. */
static inline void sph_solver_other_acc(const sph_sim *sim, int i, float a[3])
{
    const sph_particles *P = &sim->P;
    a[0] = a[1] = a[2] = 0.0f;
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        if ((SPH_MASK_ACCELERATIONS & SPH_FIELD_BIT(f)) && f != SPH_FIELD_ACC_PCI && f != SPH_FIELD_ACC_DF &&
            P->field[f][0])
            for (int d = 0; d < sim->dim; d++) a[d] += P->field[f][d][i];
}

/* The share of the support hidden behind the walls (sph_wall_hidden) at a
 * position x instead of particle i's predicted one. */
static inline float sph_solver_wall_hidden_at(const sph_sim *sim, const sph_kernel *k, const float x[3])
{
    float all = 1.0f, area;
    for (int d = 0; d < sim->dim; d++) {
        if (sim->period[d] > 0) continue; /* no walls on a periodic axis */
        all *= 1.0f - sph_kernel_wall(k, x[d] - sim->def.domain_min[d], &area);
        all *= 1.0f - sph_kernel_wall(k, sim->def.domain_max[d] - x[d], &area);
    }
    return 1.0f - all;
}

/* A solve's iteration ends: another call of the pass, or the step's record. */
static inline bool sph_solver_done(sph_sim *sim, double error, double tolerance)
{
    sph_solver_state *s = &sim->solver;
    s->error = error;
    s->iteration++;
    if (error <= tolerance) return true;
    if (s->iteration >= sim->def.solver_max_iterations) {
        s->capped++;
        return true;
    }
    return false;
}

/* The minimum image along periodic axes (a no-op elsewhere). */
static inline float sph_solver_dx(const sph_sim *sim, float dx, int d)
{
    return sim->period[d] > 0 ? sph_min_image(dx, sim->period[d], sim->inv_period[d]) : dx;
}

#endif
