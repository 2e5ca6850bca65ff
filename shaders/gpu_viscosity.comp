// uses: PRED VEL MASS VOL RHO ACC_V ENTRIES START VEL_VISC FIXED
// Pass viscosity (src/passes/viscosity.c): reads vel, writes acc_v only. The
// seed's shader added the result to the velocity buffer it was still reading
// for other particles, so its result depended on the order threads ran in.
// With wall particles the neighbours' velocities are vel_visc (the wall_state
// pass: the fluid's own, a no-slip wall's mirrored) and walls get none.
#if VFORM != VFORM_LAPLACIAN && VFORM != VFORM_SMOOTHING && VFORM != VFORM_MORRIS && VFORM != VFORM_ARTIFICIAL
#error "a viscosity form this shader does not implement"
#endif
layout(local_size_x = WG) in;
vec3 acc, vi;
float rho_i;
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    float r = sqrt(r2);
#if VFORM == VFORM_ARTIFICIAL
    // Monaghan 1992: -m_j Pi_ij grad W_ij for approaching pairs, along x_ij,
    // with the pressure kernel's gradient
    vec3 vj = VEL3(j);
    float vx = 0.0;
    for (int d = 0; d < DIM; d++) vx += (vi[d] - vj[d]) * dx[d];
    if (!(vx < 0.0) || r <= 0.0) return;
    float pi_ij = -AV_ACH * vx / (0.5 * (rho_i + rho_[j]) * (r2 + AV_EPS2));
    float f = -mass_[j] * pi_ij * kernel_dw(KP, SIG_P, r) / r;
    for (int d = 0; d < DIM; d++) acc[d] += f * dx[d];
    return;
#elif VFORM == VFORM_MORRIS
    // -(x_ij . grad W) / (r^2 + eta^2), eta = 0.01 h, symmetrised in density (Morris 1997)
    float coef = -mass_[j] * (rho_i + rho_[j]) / (rho_i * rho_[j]) * r * kernel_dw(KV, SIG_V, r) / (r2 + 1e-4 * H2);
#elif VFORM == VFORM_LAPLACIAN
    float coef = vol_[j] * kernel_lap(KV, SIG_V, r);
#else
    float coef = vol_[j] * kernel_w(KV, SIG_V, r);
#endif
#if VFORM != VFORM_ARTIFICIAL
#if HAS_VEL_VISC
    vec3 vj = LOAD3(vel_visc_, j);
#else
    vec3 vj = VEL3(j);
#endif
    for (int d = 0; d < DIM; d++) acc[d] += coef * (vj[d] - vi[d]);
#endif
}
#include_walk
void main()
{
    uint i = gid();
    if (i >= N) return;
#if HAS_FIXED
    if (fixed_[i] != 0.0) {
        for (int d = 0; d < DIM; d++) acc_v_[uint(d) * N + i] = 0.0;
        return;
    }
#endif
    acc = vec3(0.0);
    vi = VEL3(i);
    rho_i = rho_[i];
    sph_walk(i, PRED3(i));
#if VFORM == VFORM_ARTIFICIAL
    float s = 1.0;
#elif VFORM == VFORM_MORRIS
    float s = NU;
#elif VFORM == VFORM_LAPLACIAN
    float s = NU * RHO0 / rho_[i];
#else
    float s = NU * 2.0 * float(DIM) / M2_V;
#endif
    for (int d = 0; d < DIM; d++) acc_v_[uint(d) * N + i] = s * acc[d];
}
