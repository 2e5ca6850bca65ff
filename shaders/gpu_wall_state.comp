// uses: PRED MASS RHO VOL P PRHO2 VEL VEL_VISC FIXED SLIP ENTRIES START
// Pass wall_state (src/passes/wall_state.c): the wall particles' pressure,
// density and the velocity the viscous term sees, from the fluid in their
// support (Adami, Hu & Adams 2012, J. Comput. Phys. 231, 7057, eq. 27-28):
//   p_w = (sum_f p_f W_wf + g . sum_f rho_f r_wf W_wf) / sum_f W_wf,
//   rho_w from the equation of state at p_w, v~_w = sum_f v_f W_wf / sum_f W_wf,
//   vel_visc = 2 v_w - v~_w (no-slip) or v~_w (free-slip).
// Fluid particles get vel_visc = v. It reads p and rho of fluid particles
// only and writes them for wall particles only, as the CPU pass. The sums
// are in float (the CPU's in double): a ratio of sums of like-signed terms,
// a few roundings apart. u_gscale: the share of g of the step (the
// gravity_ramp, src/core/sph_start.h), so the walls' hydrostatic term is the
// fluid's weight in this step, as on the CPU.
layout(local_size_x = WG) in;
uniform float u_gscale;
uniform vec3 u_kick; // [m/s] the wall's velocity in the step's frame, g dt (wall_state.c)
float sw, sp;
vec3 srr, sv;
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    if (fixed_[j] != 0.0) return; // only the fluid extrapolates into the wall
    float W = kernel_w(KD, SIG_D, sqrt(r2));
    sw += W;
    sp += p_[j] * W;
    float rw = rho_[j] * W;
    vec3 vj = VEL3(j);
    for (int d = 0; d < DIM; d++) {
        srr[d] += rw * dx[d]; // dx = x_w - x_f
        sv[d] += vj[d] * W;
    }
}
#include_walk
// The density at which the equation of state gives pressure p (wall_state.c's eos_density).
float eos_density(float p)
{
#if EOS_TAIT
    return EOS_RHO0 * pow(max(1.0 + p / TAIT_B, 1e-3), 1.0 / GAMMA);
#else
    return max(EOS_RHO0 + p / STIFF, 1e-3 * EOS_RHO0);
#endif
}
void main()
{
    uint i = gid();
    if (i >= N) return;
    if (fixed_[i] == 0.0) {
        for (int d = 0; d < DIM; d++) vel_visc_[uint(d) * N + i] = vel_[uint(d) * N + i];
        return;
    }
    sw = 0.0;
    sp = 0.0;
    srr = vec3(0.0);
    sv = vec3(0.0);
    sph_walk(i, PRED3(i));
    float p = 0.0;
    vec3 vt = vec3(0.0);
    if (sw > 0.0) {
        float q = sp;
#if HAS_GRAVITY
        for (int d = 0; d < DIM; d++) q += GRAVITY[d] * u_gscale * srr[d];
#endif
        p = q / sw;
        for (int d = 0; d < DIM; d++) vt[d] = sv[d] / sw;
    }
#if CLAMP_NEG
    p = max(p, 0.0);
#endif
    float rho = eos_density(p);
    p_[i] = p;
    rho_[i] = rho;
    p_rho2_[i] = p / (rho * rho);
    vol_[i] = mass_[i] / rho;
    bool free_slip = slip_[i] != 0.0;
    for (int d = 0; d < DIM; d++) {
        uint k = uint(d) * N + i;
        vel_visc_[k] = free_slip ? vt[d] : 2.0 * (vel_[k] + u_kick[d]) - vt[d];
    }
}
