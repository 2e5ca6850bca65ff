/* What surface_tension = csf's pass (csf.c) shares with the GL backend's
 * csf shaders (shaders/gpu_csf.comp, gpu_csf_force.comp), which take these
 * as #defines (gpu_program.c), so that both backends cut at the same place. */
#ifndef SPH_CSF_H
#define SPH_CSF_H

/* |h grad c| a particle needs to have a curvature and to share the force
 * (Morris 2000: 0.01; csf.c says why 0.3) */
#define SPH_CSF_NORMAL_MIN 0.3f
/* the tangential renormalisation's least eigenvalue (1 in a full support) */
#define SPH_CSF_SUPPORT_MIN 0.1

/* The cubic B-spline of support radius h in dim - 1 dimensions (1D: 4/(3h), 2D: 40/(7 pi h^2)): the
 * particles' density along the surface (csf.c; surface_stress.c shares the surface out the same way). */
static inline double sph_csf_w_surface(double r, double h, int dim)
{
    double q = r / h, f;
    if (q >= 1) return 0.0;
    f = q <= 0.5 ? 1 - 6 * q * q + 6 * q * q * q : 2 * (1 - q) * (1 - q) * (1 - q);
    return (dim == 2 ? 4.0 / (3.0 * h) : 40.0 / (7.0 * 3.14159265358979 * h * h)) * f;
}

#endif
