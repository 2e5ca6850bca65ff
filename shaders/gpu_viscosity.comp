// uses: PRED VEL MASS VOL RHO ACC_V ENTRIES START VEL_VISC FIXED
// Pass viscosity (src/passes/viscosity.c): reads vel, writes acc_v only. The
// seed's shader added the result to the velocity buffer it was still reading
// for other particles, so its result depended on the order threads ran in.
// The terms are gpu_force_terms.glsl's, shared with the fused walk; with
// [compute] fuse_forces = on that walk writes acc_v and this pass does nothing.
layout(local_size_x = WG) in;
#define FORCE_PRESSURE 0
#define FORCE_VISCOSITY 1
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
