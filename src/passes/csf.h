/* What surface_tension = csf's pass (csf.c) gives the GL backend's csf
 * shader and the tests: the delta's integral B and the force's factor. */
#ifndef SPH_CSF_H
#define SPH_CSF_H

#include "sph_sim.h"

/* B, the integral of |grad c| across a flat surface on a lattice of spacing
 * s [m] (dimensionless: s times the rows' |grad c| [1/m]). */
double sph_csf_delta_integral(const sph_kernel *k, int dim, double s);

/* sigma / (B h rho0) [m^2/s^2]: a_s = this kappa normal (0 where B is 0). */
float sph_csf_coefficient(const sph_sim *sim);

#endif
