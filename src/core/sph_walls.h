/* Walls of the volume model: the share of a particle's support hidden
 * behind the domain walls, which density and the pressure force count as
 * fluid at rest. In the core (the passes and the overlays use it); inline,
 * because the density and force loops call it once per particle. */
#ifndef SPH_WALLS_H
#define SPH_WALLS_H

#include "sph_sim.h"
#include "sph_start.h"

/* Boundary particles (wall_model = particles, sph_wall_particles.c): how many
 * the scene's box makes, and placing them at P[first ..] (after the fluid). */
double sph_wall_particle_count(const sph_scene_def *def);
void sph_wall_particles_place(sph_sim *sim, uint32_t first);
/* [m] the box the particles fill: the domain, widened on each side that has
 * wall particles by their layers, so a picture framed on it shows the floor's
 * particles too (the domain itself without wall particles). */
void sph_wall_particles_bounds(const sph_scene_def *def, float lo[3], float hi[3]);
/* Is particle i a wall particle? (Never, without wall particles: no field.) */
#define sph_is_wall(P, i) ((P)->fixed && (P)->fixed[i] != 0.0f)
/* [kg/m^dim] the density Antuono's diffusion term sees: the carried one of a
 * fluid particle, the one wall_state set for a wall particle */
#define sph_rho_diffused(P, j) (sph_is_wall(P, j) ? (P)->rho[j] : (P)->rho_c[j])

/* The share of particle i's support hidden behind the walls: the fluid's
 * lattice continued behind each wall (sph_kernel_wall_lattice), the nodes
 * beyond two walls counted once by inclusion-exclusion,
 *   H = sum_w H_w - sum_{w < v} H_wv + H_uvw,
 * H_wv the corner table (zero for the two walls of one axis: nothing lies
 * beyond both), exact for a lattice at a wall and in a 2D corner. The 3D
 * vertex term H_uvw is estimated as sqrt(H_uv H_uw H_vw / H_full), exact for
 * a kernel that factorises along the axes. If grad is not NULL it receives
 * the gradient of H [1/m] with respect to the particle's position. At a
 * position pos [m] (the pressure solvers ask at predicted positions). */
static inline float sph_wall_hidden_near(const sph_sim *sim, const sph_kernel *k, const float pos[3], float grad[3])
{
    const int dim = sim->dim;
    float dist[6], sgn[6], g[3] = {0, 0, 0}; /* per wall within reach: distance [m], d dist / dx */
    int axis[6], nw = 0;
    float hidden = 0.0f;
    for (int d = 0; d < dim; d++) {
        if (sim->period[d] > 0) continue; /* no walls on a periodic axis */
        const float x = pos[d];
        const float ds[2] = {x - (float)sim->def.domain_min[d], (float)sim->def.domain_max[d] - x};
        for (int side = 0; side < 2; side++) {
            float area, share = sph_kernel_wall_lat(k, ds[side], &area);
            if (share == 0.0f && area == 0.0f) continue; /* beyond reach */
            dist[nw] = ds[side];
            sgn[nw] = side ? -1.0f : 1.0f;
            axis[nw] = d;
            hidden += share;
            g[d] -= area * sgn[nw]; /* moving away from the wall uncovers support */
            nw++;
        }
    }
    for (int a = 0; a < nw; a++)
        for (int b = a + 1; b < nw; b++) {
            if (axis[a] == axis[b]) continue;
            float sa, sb, both = sph_kernel_wall_corner(k, dist[a], dist[b], &sa, &sb);
            hidden -= both;
            g[axis[a]] += sa * sgn[a];
            g[axis[b]] += sb * sgn[b];
            for (int c = b + 1; c < nw; c++) {
                if (axis[c] == axis[a] || axis[c] == axis[b]) continue;
                float ac1, ac3, bc2, bc3;
                float ac = sph_kernel_wall_corner(k, dist[a], dist[c], &ac1, &ac3);
                float bc = sph_kernel_wall_corner(k, dist[b], dist[c], &bc2, &bc3);
                if (!(both > 0.0f && ac > 0.0f && bc > 0.0f)) continue;
                float all = sqrtf(both * ac * bc / k->wall_lat_full);
                hidden += all;
                /* d all / d dist_a = -all/2 (sa / both + ac1 / ac), and so on */
                g[axis[a]] -= 0.5f * all * (sa / both + ac1 / ac) * sgn[a];
                g[axis[b]] -= 0.5f * all * (sb / both + bc2 / bc) * sgn[b];
                g[axis[c]] -= 0.5f * all * (ac3 / ac + bc3 / bc) * sgn[c];
            }
        }
    if (grad)
        for (int d = 0; d < dim; d++) grad[d] = g[d];
    return hidden;
}

/* sph_wall_hidden_near, with its answer for a particle beyond the reach of
 * every wall (most of them) found first, inline: the same test of each wall
 * as sph_kernel_wall_table's, so the same zeros, without the call. */
static inline float sph_wall_hidden_at(const sph_sim *sim, const sph_kernel *k, const float pos[3], float grad[3])
{
    const int dim = sim->dim;
    const float scale = k->inv_h * (float)SPH_WALL_TABLE;
    bool near = false;
    for (int d = 0; d < dim; d++) {
        if (sim->period[d] > 0) continue; /* no walls on a periodic axis */
        const float lo = (pos[d] - (float)sim->def.domain_min[d]) * scale;
        const float hi = ((float)sim->def.domain_max[d] - pos[d]) * scale;
        near |= (lo < (float)SPH_WALL_TABLE) | (hi < (float)SPH_WALL_TABLE); /* NaN: far, as in the table */
    }
    if (near) return sph_wall_hidden_near(sim, k, pos, grad);
    if (grad)
        for (int d = 0; d < dim; d++) grad[d] = 0.0f;
    return 0.0f;
}

/* The same at particle i's position of the step (pred: where the lists were made). */
static inline float sph_wall_hidden(const sph_sim *sim, const sph_kernel *k, int i, float grad[3])
{
    float pos[3] = {0.0f, 0.0f, 0.0f};
    for (int d = 0; d < sim->dim; d++) pos[d] = sim->P.pred[d][i];
    return sph_wall_hidden_at(sim, k, pos, grad);
}

/* The pressure force of the hidden lattice on particle i [m/s^2], added to
 * a[]. wall_force = energy: the energy's gradient (below). ghost: the lattice's nodes as ghost particles of mass rho0 s^dim and
 * density rho_i, in the pair term of the pressure form, with the ghost
 * pressure extrapolated from the particle with the step's gravity,
 * p_k = p_i + rho_i g . (x_k - x_i) (Adami, Hu & Adams 2012, J. Comput.
 * Phys. 231, eq. 27, with the particle itself as the only fluid neighbour):
 *   sum_k s^dim (p_i + p_k) grad W_ik = 2 p_i grad H + rho_i T g,
 * H the pressure kernel's hidden share, T its second-moment table. For the
 * symmetric form a -= (rho0 / rho_i^2) times that, half of it for the shared
 * form. A lattice at uniform pressure is then held exactly (the hidden nodes
 * stand for the missing neighbours' pair terms), and a hydrostatic column
 * gets the missing share of -grad p / rho at the floor and at the side
 * walls. Corners count T of each wall (the corner's nodes twice). */
static inline void sph_wall_ghost_accel(const sph_sim *sim, int i, float a[3])
{
    if (sim->def.wall_force == SPH_WFORCE_ENERGY) {
        /* the gradient of the walls' density term, a = -(p_i / rho_i^2)
         * grad(rho0 H) with the density kernel: walls neither add nor remove
         * energy, but it is half the pair term the hidden nodes would exert,
         * so a lattice's overpressure pushes the first rows into the wall */
        float grad[3];
        sph_wall_hidden(sim, &sim->k_density, i, grad);
        for (int d = 0; d < sim->dim; d++) a[d] -= sim->def.rest_density * sim->P.p_rho2[i] * grad[d];
        return;
    }
    const sph_kernel *k = &sim->k_pressure;
    const sph_particles *P = &sim->P;
    const int dim = sim->dim;
    const float rho0 = sim->def.rest_density, rho_i = P->rho[i];
    const float form = sim->def.pressure_form == SPH_PFORM_SYMMETRIC ? 1.0f : 0.5f;
    float grad[3], g[3] = {0, 0, 0}, tg[3] = {0, 0, 0};
    sph_wall_hidden(sim, k, i, grad);
    if (sim->def.effects & SPH_EFFECT(GRAVITY)) {
        const float gs = sph_start_gravity_scale(sim);
        for (int d = 0; d < dim; d++) g[d] = sim->def.gravity[d] * gs;
        for (int d = 0; d < dim; d++) {
            if (sim->period[d] > 0) continue;
            const float x = P->pred[d][i];
            const float ds[2] = {x - (float)sim->def.domain_min[d], (float)sim->def.domain_max[d] - x};
            for (int side = 0; side < 2; side++) {
                float tn, tt = sph_kernel_wall_table(k, k->wall_lat_tt, k->wall_lat_tn, ds[side], &tn);
                for (int e = 0; e < dim; e++) tg[e] += (e == d ? tn : tt) * g[e];
            }
        }
    }
    const float c = form * rho0 * P->p_rho2[i] * 2.0f, cg = form * rho0 / rho_i;
    for (int d = 0; d < dim; d++) a[d] -= c * grad[d] + cg * tg[d];
}

#endif
