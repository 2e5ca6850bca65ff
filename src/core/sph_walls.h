/* Walls of the volume model: the share of a particle's support hidden
 * behind the domain walls, which density and the pressure force count as
 * fluid at rest. In the core (the passes and the overlays use it); inline,
 * because the density and force loops call it once per particle. */
#ifndef SPH_WALLS_H
#define SPH_WALLS_H

#include "sph_sim.h"

/* Boundary particles (wall_model = particles, sph_wall_particles.c): how many
 * the scene's box makes, and placing them at P[first ..] (after the fluid). */
double sph_wall_particle_count(const sph_scene_def *def);
void sph_wall_particles_place(sph_sim *sim, uint32_t first);
/* Is particle i a wall particle? (Never, without wall particles: no field.) */
#define sph_is_wall(P, i) ((P)->fixed && (P)->fixed[i] != 0.0f)

/* 1 - prod_w (1 - psi(d_w)), which is exact at one wall and at a corner's tip
 * and counts corners once, not twice. If grad is not NULL it receives the
 * gradient of that share [1/m] with respect to the particle's position. */
static inline float sph_wall_hidden(const sph_sim *sim, const sph_kernel *k, int i, float grad[3])
{
    const int dim = sim->dim;
    float vis[6], dvis[6]; /* per wall: visible share 1 - psi, and its derivative along the axis */
    float all = 1.0f;
    for (int d = 0; d < dim; d++) {
        if (sim->period[d] > 0) { /* no walls on a periodic axis */
            vis[2 * d] = vis[2 * d + 1] = 1.0f;
            dvis[2 * d] = dvis[2 * d + 1] = 0.0f;
            continue;
        }
        float x = sim->P.pred[d][i], area;
        float lo = sph_kernel_wall(k, x - (float)sim->def.domain_min[d], &area);
        vis[2 * d] = 1.0f - lo;
        dvis[2 * d] = area; /* moving away from the low wall uncovers support */
        float hi = sph_kernel_wall(k, (float)sim->def.domain_max[d] - x, &area);
        vis[2 * d + 1] = 1.0f - hi;
        dvis[2 * d + 1] = -area;
        all *= vis[2 * d] * vis[2 * d + 1];
    }
    if (grad) {
        for (int d = 0; d < dim; d++) {
            float g = 0;
            for (int w = 2 * d; w <= 2 * d + 1; w++) {
                float others = 1.0f; /* product of the other walls' visible shares */
                for (int o = 0; o < 2 * dim; o++)
                    if (o != w) others *= vis[o];
                g += dvis[w] * others;
            }
            grad[d] = -g; /* hidden = 1 - visible */
        }
    }
    return 1.0f - all;
}

#endif
