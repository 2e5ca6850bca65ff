// uses: PRED MASS RHO VOL P PRHO2 ACC_P ENTRIES START WALL FIXED
// Pass pressure_force (src/passes/pressure_force.c): symmetric or shared form,
// coincident pairs pushed apart along x (repulsion only), walls push back.
// Wall particles (wall_model = particles) get no acceleration: they never move.
// The terms are gpu_force_terms.glsl's, shared with the fused walk.
layout(local_size_x = WG) in;
#define FORCE_PRESSURE 1
#define FORCE_VISCOSITY 0
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
