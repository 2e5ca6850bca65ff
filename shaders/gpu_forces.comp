// uses: PRED VEL MASS VOL RHO P PRHO2 ACC_P ACC_V ENTRIES START WALL VEL_VISC FIXED
// [compute] fuse_forces = on: the passes pressure_force and viscosity in one
// walk of the neighbours (as the CPU's fused loop, level L8): each pair's
// position, distance and r = sqrt(r^2) are read once for both, and the
// terms are the two passes' own (gpu_force_terms.glsl), so the result is
// theirs. Run as the pressure_force pass; the viscosity pass then does
// nothing (gpu_passes.c). A scene without acc_v gets the pressure force alone.
layout(local_size_x = WG) in;
#define FORCE_PRESSURE 1
#define FORCE_VISCOSITY HAS_ACC_V
#include_forces
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    forces_pair(i, j, dx, r2);
}
#include_walk
void main()
{
    uint i = gid();
    if (i >= N || forces_still(i)) return;
    vec3 xi = PRED3(i);
    forces_begin(i);
    sph_walk(i, xi);
    forces_end(i, xi);
}
