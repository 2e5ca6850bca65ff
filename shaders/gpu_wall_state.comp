// uses: PRED MASS RHO VOL P PRHO2 VEL VEL_VISC FIXED SLIP ENTRIES START
// Pass wall_state (src/passes/wall_state.c): the wall particles' pressure,
// density and the velocity the viscous term sees, from the fluid in their
// support (Adami, Hu & Adams 2012, J. Comput. Phys. 231, 7057, eq. 27-28):
//   p_w = (sum_f p_f W_wf + g . sum_f rho_f r_wf W_wf) / sum_f W_wf,
//   rho_w from the equation of state at p_w, v~_w = sum_f v_f W_wf / sum_f W_wf,
//   vel_visc = 2 v_w - v~_w - (a/nu) (|c|^2/4 + var_c/2) (no-slip) or v~_w (free-slip),
//   the curvature term a_t = -grad_t q / rho0, the gradient along the wall of
//   q_f = p_f + rho_f g . r_wf, as wall_state.c's mirror_curvature.
// Fluid particles get vel_visc = v. It reads p and rho of fluid particles
// only and writes them for wall particles only, as the CPU pass. The sums
// are in float (the CPU's in double): a ratio of sums of like-signed terms,
// a few roundings apart. u_gscale: the share of g of the step (the
// gravity_ramp, src/core/sph_start.h), so the walls' hydrostatic term is the
// fluid's weight in this step, as on the CPU.
// With a pressure solver (pcisph, dfsph) the scene has no p (HAS_P 0): the wall
// particles keep the density the summation gave them, hold no pressure (the
// solvers' walls push with the fluid particle's own) and get the viscous
// term's velocity only, without the curvature term (it needs p), as wall_state.c.
layout(local_size_x = WG) in;
uniform float u_gscale;
uniform vec3 u_kick; // [m/s] the wall's velocity in the step's frame, g dt (wall_state.c)
float sw, sp, sq, qref;
vec3 srr, sv, sc, sqc;
mat3 scc;
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    if (fixed_[j] != 0.0) return; // only the fluid extrapolates into the wall
    float W = kernel_w(KD, SIG_D, sqrt(r2));
    sw += W;
#if !HAS_P
    for (int d = 0; d < DIM; d++) sv[d] += vel_[uint(d) * N + j] * W; // the viscous term's velocity alone
#else
    sp += p_[j] * W;
    float rw = rho_[j] * W;
    vec3 vj = VEL3(j);
    float q = p_[j] - qref; // q_f = p_f + rho_f g . r_wf, less qref (wall_state.c)
    for (int d = 0; d < DIM; d++) {
        srr[d] += rw * dx[d]; // dx = x_w - x_f
        sv[d] += vj[d] * W;
#if HAS_GRAVITY
        q += GRAVITY[d] * u_gscale * rho_[j] * dx[d];
#endif
    }
#if WALL_CURV
    sq += q * W;
    for (int d = 0; d < DIM; d++) {
        sc[d] -= dx[d] * W; // c_f = x_f - x_w
        sqc[d] -= q * dx[d] * W;
        for (int e = 0; e < DIM; e++) scc[d][e] += dx[d] * dx[e] * W;
    }
#endif
#endif
}
// The mirror's curvature term -(a_t/nu) (|c|^2/4 + var_c/2) (wall_state.c's mirror_curvature).
vec3 mirror_curvature()
{
    vec3 cb = vec3(0.0), b = vec3(0.0), n = vec3(0.0), out_ = vec3(0.0);
    mat3 m = mat3(0.0);
    for (int d = 0; d < DIM; d++) cb[d] = sc[d] / sw;
    float c2 = dot(cb, cb);
    if (!(c2 > 0.0) || DIM < 2) return out_;
    for (int d = 0; d < DIM; d++) {
        for (int e = 0; e < DIM; e++) m[d][e] = scc[d][e] / sw - cb[d] * cb[e];
        b[d] = sqc[d] / sw - sq / sw * cb[d];
    }
    n = cb / sqrt(c2);
    float tr = 0.0;
    for (int d = 0; d < DIM; d++) tr += m[d][d];
    float var = dot(n, m * n), var_t = (tr - var) / float(DIM - 1);
    if (!(var_t > 1e-3 * c2) || var_t < var) return out_; // a sliver along the normal: no term (wall_state.c)
    vec3 gt = b - dot(b, n) * n;
    for (int d = 0; d < DIM; d++) out_[d] = gt[d] / var_t / RHO0 * WALL_INV_NU * (0.25 * c2 + 0.5 * var);
    return out_;
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
    sq = 0.0;
#if HAS_P
    qref = p_[i]; // the wall particle's pressure of the last step, q's reference
#else
    qref = 0.0;
#endif
    sc = vec3(0.0);
    sqc = vec3(0.0);
    scc = mat3(0.0);
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
#if HAS_P // with a solver the wall particle keeps the density the summation gave it
#if CLAMP_NEG
    p = max(p, 0.0);
#endif
    float rho = eos_density(p);
    p_[i] = p;
    rho_[i] = rho;
    p_rho2_[i] = p / (rho * rho);
    vol_[i] = mass_[i] / rho;
#endif
    bool free_slip = slip_[i] != 0.0;
    vec3 curv = vec3(0.0);
#if WALL_CURV && HAS_P
    if (sw > 0.0 && !free_slip) {
        curv = mirror_curvature();
        // at most the fluid's speed relative to the wall, |v~_w - v_w|, and off beyond a cell Reynolds number 1
        vec3 rel = vec3(0.0);
        for (int d = 0; d < DIM; d++) rel[d] = vt[d] - (vel_[uint(d) * N + i] + u_kick[d]);
        float c2 = dot(curv, curv), r2 = dot(rel, rel), cc = dot(sc / sw, sc / sw);
        if (sqrt(r2 * cc) * WALL_INV_NU > 1.0) curv = vec3(0.0); // the cell Reynolds number (wall_state.c)
        else if (c2 > r2) curv *= sqrt(r2 / c2);
    }
#endif
    for (int d = 0; d < DIM; d++) {
        uint k = uint(d) * N + i;
        vel_visc_[k] = free_slip ? vt[d] : 2.0 * (vel_[k] + u_kick[d]) - vt[d] + curv[d];
    }
}
