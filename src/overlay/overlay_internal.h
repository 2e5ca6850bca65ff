/* Shared by the overlay's files (sph_overlay.c, sph_colour.c, sph_hud.c); not an interface. */
#ifndef SPH_OVERLAY_INTERNAL_H
#define SPH_OVERLAY_INTERNAL_H

#include "sph_overlay.h"

/* The hash pass has filled the index at least once since the simulation was made. */
bool sph_ov_index_built(const sph_sim *sim);
/* The neighbour lists exist and have been built at least once. */
bool sph_ov_lists_built(const sph_sim *sim);
/* |v| of particle i of a vector field. */
float sph_ov_vec_norm(float *const v[3], int dim, uint32_t i);
/* The hash the hash pass gives a cell (the dense cell number for the grid search). */
uint32_t sph_ov_cell_hash(const sph_sim *sim, const int32_t c[3]);

#endif
