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

#endif
