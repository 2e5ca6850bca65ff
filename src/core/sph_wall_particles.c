/* Boundary particles of the domain box (wall_model = particles, after Adami,
 * Hu & Adams 2012): layers of fixed particles outside each wall, on the
 * fluid's lattice continued beyond the box, enough layers to fill a fluid
 * particle's support (ceil(h / spacing)), corners included. They are ordinary
 * particles of sph_particles after the fluid's (ids n_fluid ..), marked by the
 * field `wall` = 1; the wall_state pass gives them pressure, density and the
 * viscous term's velocity each step, and no pass moves them. The obstacles'
 * wall particles follow the box's (sph_obstacles.c). Each wall particle
 * carries its own slip (field `slip`: the side's wall_slip_<side>, or the
 * scene's wall_slip) and, for an obstacle's, its number (field `obstacle`).
 * Those beyond the top wall carry [domain] wall_velocity (zero by default): they stay in
 * place, but the no-slip mirror 2 v_w - v~_w drags the fluid along. */
#include "sph_walls.h"

#include "sph_obstacles.h"

#include <math.h>

bool sph_scene_wall_particles(const sph_scene_def *def)
{
    return (def->effects & SPH_EFFECT(WALLS)) && def->wall_model == SPH_WALL_PARTICLES &&
           (def->effects & SPH_EFFECT(PRESSURE));
}

/* The lattice spacing of the walls: the finest block's. */
static double wall_spacing(const sph_scene_def *def)
{
    double s = INFINITY;
    for (int b = 0; b < def->n_blocks; b++) s = fmin(s, def->blocks[b].spacing);
    return s;
}

/* Nodes along axis a: `inner` inside the box (the lattice of nodes
 * min + (k + 1/2) s), and `layers` outside on each side (none on a periodic
 * axis). */
static void axis_nodes(const sph_scene_def *def, int a, double s, int64_t *inner, int64_t *layers)
{
    double len = (double)def->domain_max[a] - def->domain_min[a];
    *inner = (int64_t)floor(len / s + 0.5);
    if (*inner < 1) *inner = 1;
    *layers = (def->periodic & (1u << a)) ? 0 : (int64_t)ceil(def->h / s - 1e-6);
}

/* The domain box's wall particles; the obstacles' are counted in sph_obstacles.c. */
static double box_count(const sph_scene_def *def)
{
    if (!sph_scene_wall_particles(def) || def->n_blocks == 0) return 0;
    double s = wall_spacing(def);
    if (!(s > 0) || !isfinite(s)) return 0;
    double all = 1, inside = 1;
    for (int a = 0; a < def->dim; a++) {
        int64_t inner, layers;
        axis_nodes(def, a, s, &inner, &layers);
        all *= (double)(inner + 2 * layers);
        inside *= (double)inner;
    }
    return all - inside;
}

double sph_wall_particle_count(const sph_scene_def *def)
{
    double n = box_count(def);
    for (int k = 0; k < def->n_obstacles && n > 0; k++) n += sph_obstacle_wall_count(def, k);
    return n;
}

void sph_wall_particles_bounds(const sph_scene_def *def, float lo[3], float hi[3])
{
    for (int a = 0; a < 3; a++) lo[a] = (float)def->domain_min[a], hi[a] = (float)def->domain_max[a];
    if (!sph_scene_wall_particles(def) || def->n_blocks == 0) return;
    double s = wall_spacing(def);
    if (!(s > 0) || !isfinite(s)) return;
    for (int a = 0; a < def->dim; a++) {
        int64_t inner, layers;
        axis_nodes(def, a, s, &inner, &layers);
        /* the outermost node sits (layers - 1/2) s outside; its disc reaches half a spacing further */
        lo[a] = (float)(def->domain_min[a] - (double)layers * s);
        hi[a] = (float)(def->domain_max[a] + (double)layers * s);
    }
}

/* Side k of the box (xmin, xmax, ymin, ...) is free-slip? */
static bool side_free(const sph_scene_def *def, int k)
{
    sph_side_slip s = def->wall_slip_side[k];
    return s == SPH_SIDE_SLIP_SAME ? def->wall_slip == SPH_SLIP_FREE : s == SPH_SIDE_SLIP_FREE;
}

/* Coordinate of node k along axis a (k < 0 and k >= inner: outside). Nodes
 * beyond the upper wall start half a spacing past it, so that they face the
 * fluid at the same distance even if the box is not a whole number of
 * spacings long. */
static float node_coord(const sph_scene_def *def, int a, double s, int64_t inner, int64_t k)
{
    if (k < inner) return (float)(def->domain_min[a] + ((double)k + 0.5) * s);
    return (float)(def->domain_max[a] + ((double)(k - inner) + 0.5) * s);
}

void sph_wall_particles_place(sph_sim *sim, uint32_t first)
{
    const sph_scene_def *def = &sim->def;
    sph_particles *P = &sim->P;
    const int dim = sim->dim;
    const double s = wall_spacing(def);
    const float mass = def->rest_density * (float)(dim == 3 ? s * s * s : s * s);
    int64_t inner[3] = {1, 1, 1}, layers[3] = {0, 0, 0};
    for (int a = 0; a < dim; a++) axis_nodes(def, a, s, &inner[a], &layers[a]);
    uint32_t i = first;
    for (int64_t z = -layers[2]; z < inner[2] + layers[2]; z++)
        for (int64_t y = -layers[1]; y < inner[1] + layers[1]; y++)
            for (int64_t x = -layers[0]; x < inner[0] + layers[0]; x++) {
                int64_t node[3] = {x, y, z};
                bool outside = false;
                for (int a = 0; a < dim; a++) outside |= node[a] < 0 || node[a] >= inner[a];
                if (!outside || i >= sim->n) continue;
                P->id[i] = i;
                P->mass[i] = mass;
                P->fixed[i] = 1.0f;
                bool free_slip = true; /* a corner is free-slip only if every side it lies beyond is */
                for (int a = 0; a < dim; a++)
                    if (node[a] < 0 || node[a] >= inner[a]) free_slip &= side_free(def, 2 * a + (node[a] >= 0));
                P->slip[i] = free_slip ? 1.0f : 0.0f;
                P->obstacle[i] = 0.0f;
                for (int a = 0; a < dim; a++) {
                    P->pos[a][i] = node_coord(def, a, s, inner[a], node[a]);
                    /* the box stands still, but for a top wall given a velocity (wall_velocity) */
                    P->vel[a][i] = node[1] >= inner[1] ? def->wall_velocity[a] : 0.0f;
                }
                i++;
            }
    for (int k = 0; k < def->n_obstacles; k++) i += sph_obstacle_place(sim, k, i);
}
