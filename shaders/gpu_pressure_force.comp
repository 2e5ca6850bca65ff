// uses: PRED MASS RHO VOL P PRHO2 ACC_P ENTRIES START WALL FIXED
// Pass pressure_force (src/passes/pressure_force.c): symmetric or shared form,
// coincident pairs pushed apart along x (repulsion only), walls push back.
// Wall particles (wall_model = particles) get no acceleration: they never move.
layout(local_size_x = WG) in;
vec3 acc;
float pi_over, p_i, rho_i;
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    float r;
    if (r2 < R_MIN * R_MIN) {
        dx = vec3(i < j ? -R_MIN : R_MIN, 0.0, 0.0);
        r = R_MIN;
    } else {
        r = sqrt(r2);
    }
    float dw_over_r = kernel_dw(KP, SIG_P, r) / r;
#if PFORM_SYM
    float coef = mass_[j] * (pi_over + p_rho2_[j]);
#else
    float coef = vol_[j] * 0.5 * (p_i + p_[j]) / rho_i;
#endif
    if (r2 < R_MIN * R_MIN && coef < 0.0) coef = 0.0; // a coincident pair only repels
    for (int d = 0; d < DIM; d++) acc[d] -= coef * dw_over_r * dx[d];
}
#include_walk
void main()
{
    uint i = gid();
    if (i >= N) return;
#if HAS_FIXED
    if (fixed_[i] != 0.0) {
        for (int d = 0; d < DIM; d++) acc_p_[uint(d) * N + i] = 0.0;
        return;
    }
#endif
    vec3 xi = PRED3(i);
    acc = vec3(0.0);
    pi_over = p_rho2_[i];
    p_i = p_[i];
    rho_i = rho_[i];
    sph_walk(i, xi);
#if WALL_VOLUME
    vec3 grad;
    wall_hidden(xi, grad);
    for (int d = 0; d < DIM; d++) acc[d] -= RHO0 * pi_over * grad[d];
#endif
    for (int d = 0; d < DIM; d++) acc_p_[uint(d) * N + i] = acc[d];
}
