// uses: POS PRED VEL MASS RHO SHIFT SURFACE FIXED ENTRIES START
// Pass shifting (src/passes/shifting.c): particle shifting after Lind, Xu,
// Stansby & Rogers 2012 (J. Comput. Phys. 231, 1499, eq. 13), D = A h |v| dt
// (Skillen et al. 2013, eq. 12). Two dispatches of this program:
//   u_count = 0: the free-surface mark from the divergence of position,
//                surface = 1 where -sum_j V_j x_ij . grad W_ij < dim - 0.5;
//   u_count = 1: dr_i = -D sum_j V_j (1 + R (W_ij / W(dp_i))^4) grad_i W_ij,
//                none for wall particles, surface particles and particles
//                with a surface particle in their support; x += dr, then
//                the periodic wrap. u_value = A h dt [m s].
layout(local_size_x = WG) in;
uniform uint u_count;
uniform float u_value;
const float LIND_R = 0.2; // Lind et al. 2012, eq. 13 (n = 4 written out below)
float div_r, inv_wdp;
vec3 g;
bool near_surface;
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    if (u_count == 0u) {
        if (r2 < R_MIN * R_MIN) return;
        float r = sqrt(r2);
        div_r -= mass_[j] / rho_[j] * kernel_dw(KD, SIG_D, r) * r;
        return;
    }
    if (surface_[j] != 0.0) near_surface = true;
    if (near_surface || r2 < R_MIN * R_MIN) return;
    float r = sqrt(r2);
    float q = kernel_w(KD, SIG_D, r) * inv_wdp;
    q *= q;
    float f = mass_[j] / rho_[j] * (1.0 + LIND_R * q * q) * kernel_dw(KD, SIG_D, r) / r;
    for (int d = 0; d < DIM; d++) g[d] += f * dx[d];
}
#include_walk
bool is_wall(uint i)
{
#if HAS_FIXED
    return fixed_[i] != 0.0;
#else
    return false;
#endif
}
void main()
{
    uint i = gid();
    if (i >= N) return;
    if (u_count == 0u) {
        div_r = 0.0;
        sph_walk(i, PRED3(i));
        surface_[i] = !is_wall(i) && div_r < float(DIM) - 0.5 ? 1.0 : 0.0;
        return;
    }
    vec3 s = vec3(0.0);
    if (!is_wall(i) && surface_[i] == 0.0) {
        float dp = pow(mass_[i] / rho_[i], 1.0 / float(DIM));
        inv_wdp = 1.0 / max(kernel_w(KD, SIG_D, dp), 1e-30);
        g = vec3(0.0);
        near_surface = false;
        sph_walk(i, PRED3(i));
        if (!near_surface) {
            vec3 v = VEL3(i);
            float v2 = 0.0;
            for (int d = 0; d < DIM; d++) v2 += v[d] * v[d];
            float D = u_value * sqrt(v2);
            for (int d = 0; d < DIM; d++) s[d] = -D * g[d];
        }
    }
    for (int d = 0; d < DIM; d++) {
        uint k = uint(d) * N + i;
        shift_[k] = s[d];
        float x = pos_[k] + s[d];
        if (PER[d] > 0.0) x = wrap_coord(x, DOM_MIN[d], PER[d], INV_PER[d]);
        pos_[k] = x;
    }
}
