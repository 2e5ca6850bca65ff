// uses: PRED MASS KAPPA KAPPA_V DV_DF ACC_DF ACCELERATIONS ENTRIES START WALL FIXED
// Pass dfsph's force (src/passes/dfsph.c, force()), a program of its own
// beside gpu_dfsph.comp: a_i = -sum_j m_j (K_i + K_j) / rho_r grad W^p_ij -
// K_i grad(walls' share) over the pairs within h at pred, dv = dt (the other
// accelerations + a), K = kappa_v, plus kappa where u_count = 1 (the
// constant-density solve); u_count = 2: the start-up evaluation (dt = 0), a = 0.
// Wall particles (FIXED) stay where they are: a = dv = 0 (dfsph.c); as neighbours their K is 0, or the fluid's
// with solver_wall_pressure = extrapolated (gpu_wall_extrapolate.comp).
layout(local_size_x = WG) in;
uniform uint u_count;
uniform float u_dt;
vec3 acc;
float k_i;

float kappa_sum(uint j)
{
    return kappa_v_[j] + (u_count == 1u ? kappa_[j] : 0.0);
}

void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    float r = sqrt(r2), gf = r > 0.0 ? kernel_dw(KP, SIG_P, r) / r : 0.0;
    float c = mass_[j] * (k_i + kappa_sum(j)) * INV_RHO_R * gf;
    for (int d = 0; d < DIM; d++) acc[d] -= c * dx[d];
}
#include_walk

void main()
{
    uint i = gid();
    if (i >= N) return;
    if (u_count == 2u) {
        for (int d = 0; d < DIM; d++) acc_df_[uint(d) * N + i] = 0.0;
        return;
    }
#if HAS_FIXED
    if (fixed_[i] != 0.0) {
        for (int d = 0; d < DIM; d++) acc_df_[uint(d) * N + i] = dv_df_[uint(d) * N + i] = 0.0;
        return;
    }
#endif
    vec3 xi = PRED3(i);
    k_i = kappa_sum(i);
    acc = vec3(0.0);
    sph_walk(i, xi);
#if WALL_VOLUME
    vec3 g;
    solver_walls(xi, g);
    for (int d = 0; d < DIM; d++) acc[d] -= k_i * g[d];
#endif
    for (int d = 0; d < DIM; d++) {
        uint k = uint(d) * N + i;
        acc_df_[k] = acc[d];
        precise float dv = u_dt * (ACC_OTHER(k) + acc[d]);
        dv_df_[k] = dv;
    }
}
