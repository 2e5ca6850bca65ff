/* Obstacles: [obstacle NAME] blocks of a scene (wall_model = particles), solid
 * boxes and circles (spheres in 3D) made of layers of fixed wall particles,
 * like the domain box's (sph_wall_particles.c). sph_obstacles.c holds their
 * geometry (validation, which fluid nodes they remove, their particles);
 * sph_obstacle_force.c the force the fluid exerts on each. */
#ifndef SPH_OBSTACLES_H
#define SPH_OBSTACLES_H

#include <stdbool.h>
#include <stdint.h>

#include "sph_scene.h"

typedef struct sph_sim sph_sim;

/* Checks the obstacles: wall_model = particles, each shape's keys, sizes,
 * and that each keeps some of its particles inside the domain. */
sph_error_code sph_obstacles_validate(const sph_scene_def *def, sph_error *err);
/* Is point p [m] inside obstacle o (closed)? */
bool sph_obstacle_inside(const sph_obstacle_def *o, int dim, const double p[3]);
/* Index of the first obstacle among the first `below` that holds p, or -1. */
int sph_obstacles_holding(const sph_scene_def *def, int below, const double p[3]);
/* Fluid lattice nodes of the blocks that fall inside an obstacle: not created. */
double sph_obstacles_fluid_dropped(const sph_scene_def *def);
/* Wall particles of obstacle k (0 if the scene makes no wall particles). */
double sph_obstacle_wall_count(const sph_scene_def *def, int k);
/* Places obstacle k's wall particles at P[first ..]; returns how many. */
uint32_t sph_obstacle_place(sph_sim *sim, int k, uint32_t first);

/* The force [N] (3D) or [N/m] (2D) the fluid exerts on each obstacle now:
 * minus the pressure and viscous forces its wall particles exert on the fluid
 * (Newton's third law), from the step's latest state. force[k] for obstacle k
 * of the scene; returns the number of obstacles. */
int sph_obstacle_forces(const sph_sim *sim, double force[][3]);

#endif
