// uses: PRED FIXED ENTRIES START DST
// [physics] solver_wall_pressure = extrapolated (src/passes/solver_walls.c): after each correction of the
// pressure solvers (run_pcisph, run_dfsph in src/gpu/gpu_passes.c) every wall particle w takes Adami, Hu & Adams
// 2012's (J. Comput. Phys. 231:7057, eq. 27)
//   q_w = (sum_f q_f W_wf + u_g0 . sum_f r_wf W_wf) / sum_f W_wf,  r_wf = x_w - x_f,
// over its fluid neighbours f within h at pred (the CPU's lists), at least 0 where u_count = 1; 0 with no fluid
// in reach. q is the buffer bound at DST (PCISPH's p_pci, DFSPH's kappa or kappa_v, read and written as bits);
// u_g0 = c g of the step, g ramped as the fluid's (sph_start_gravity_scale), c = rho_rest for p, 1 for kappa,
// 0 for kappa_v (no hydrostatic term). It reads q of fluid particles only and writes it for wall particles only:
// no invocation reads a value another writes. The sums are in float (the CPU's in double), a few roundings apart.
layout(local_size_x = WG) in;
uniform uint u_count;
uniform vec3 u_g0;
float sw, sq;

void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    if (fixed_[j] != 0.0) return; // only the fluid extrapolates into the wall
    float W = kernel_w(KD, SIG_D, sqrt(r2));
    precise float gr = 0.0;
    for (int d = 0; d < DIM; d++) gr += u_g0[d] * dx[d]; // dx = x_w - x_f
    sw += W;
    sq += (uintBitsToFloat(dst_[j]) + gr) * W;
}
#include_walk

void main()
{
    uint i = gid();
    if (i >= N || fixed_[i] == 0.0) return;
    sw = 0.0;
    sq = 0.0;
    sph_walk(i, PRED3(i));
    float q = 0.0;
    if (sw > 0.0) {
        q = sq / sw;
        if (u_count != 0u) q = max(q, 0.0);
    }
    dst_[i] = floatBitsToUint(q);
}
