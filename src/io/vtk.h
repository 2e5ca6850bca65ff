/* Particles as legacy VTK files (POLYDATA, binary big-endian), which
 * ParaView and VisIt open: positions as points, each particle a vertex, and
 * every field the scene allocates (velocity, density, pressure,
 * accelerations, mass, predicted position) plus the id as point data.
 * GL-free, in the I/O layer: `sphlab run --vtk` and `sphlab render --vtk` both use it. */
#ifndef SPH_VTK_H
#define SPH_VTK_H

#include <stdbool.h>
#include <stddef.h>

#include "io.h" /* sph_output_dir, for the folder the frames go to */
#include "sph_sim.h"

/* Writes PATH through the atomic writer (io.h). */
bool sph_vtk_write(const sph_sim *sim, const char *path, char *err, size_t n);
/* Writes DIR/particles_NNNNN.vtk. */
bool sph_vtk_write_frame(const sph_sim *sim, const char *dir, unsigned frame, char *err, size_t n);

#endif
