// uses: PRED VEL MASS RHO_C DRHO GRAD_RHO FIXED ENTRIES START WALL
// Pass density_rate (src/passes/density_rate.c), density_method =
// continuity with density diffusion (Molteni & Colagrossi 2009, Comput.
// Phys. Commun. 180, 861):
//   drho_i/dt = sum_j m_j (v_i - v_j) . grad W_ij + delta h_s c sum_j psi_ij . grad W_ij V_j,
//   psi_ij = 2 (rho_j - rho_i) x_ji / r^2 [- (<grad rho>^L_i + <grad rho>^L_j), Antuono et al. 2010, eq. 9],
// density kernel, carried densities rho_c, coincident pairs left out; wall
// particles enter the velocity term only and get drho = 0; with volume
// walls, rho0 grad(hidden share) . v_i is added. u_count = 0 at the start
// (nothing carried yet): drho = 0. u_value = delta h_s c [m^2/s].
// With delta_form = fourtakas (Fourtakas et al. 2019, Comput. Fluids 190,
// 346, eq. 14-15) psi_ij loses the pair's hydrostatic density difference:
//   psi_ij . x_ij += 2 rho^H_ji,  rho^H_ji = EOS^-1(rho0 g . x_ji) - rho0,
// u_g0 = rho0 times the step's (ramped) gravity [kg/(m^dim s^2)].
layout(local_size_x = WG) in;
uniform uint u_count;
uniform float u_value;
uniform vec3 u_kick; // [m/s] the wall particles' velocity in the step's frame, g dt (density_rate.c)
#if DFORM_FOURTAKAS
uniform vec3 u_g0;
// rho^H_ji [kg/m^dim] for the pressure ph = rho0 g . x_ji [Pa] (density_rate.c's hydro_density)
float hydro_density(float ph)
{
#if EOS_TAIT
    return EOS_RHO0 * (pow(max(1.0 + ph / TAIT_B, 1e-3), 1.0 / GAMMA) - 1.0);
#else
    return ph / STIFF;
#endif
}
#endif
float sum, rho_i;
vec3 vi, gi;
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    if (r2 < R_MIN * R_MIN) return;
    vec3 vj = VEL3(j);
    float vx = 0.0;
    for (int d = 0; d < DIM; d++) vx += (vi[d] - vj[d]) * dx[d];
    float r = sqrt(r2);
    float dw_over_r = kernel_dw(KD, SIG_D, r) / r;
    float t = mass_[j] * vx * dw_over_r;
#if HAS_FIXED
    bool wall_j = fixed_[j] != 0.0;
#else
    bool wall_j = false;
#endif
    if (wall_j) { // the wall's velocity in the step's frame, v_w + g dt (density_rate.c)
        for (int d = 0; d < DIM; d++) vx -= u_kick[d] * dx[d];
        t = mass_[j] * vx * dw_over_r;
    }
    if (u_value != 0.0 && !wall_j) {
        float psi = -2.0 * (rho_c_[j] - rho_i);
#if HAS_GRAD_RHO
        for (int d = 0; d < DIM; d++) psi -= (gi[d] + grad_rho_[uint(d) * N + j]) * dx[d];
#endif
#if DFORM_FOURTAKAS
        float ph = 0.0;
        for (int d = 0; d < DIM; d++) ph -= u_g0[d] * dx[d];
        psi += 2.0 * hydro_density(ph);
#endif
        t += u_value * psi * dw_over_r * mass_[j] / rho_c_[j];
    }
    sum += t;
}
#include_walk
void main()
{
    uint i = gid();
    if (i >= N) return;
    bool wall = false;
#if HAS_FIXED
    wall = fixed_[i] != 0.0;
#endif
    if (u_count == 0u || wall) {
        drho_[i] = 0.0;
        return;
    }
    vec3 xi = PRED3(i);
    vi = VEL3(i);
    rho_i = rho_c_[i];
    gi = vec3(0.0);
#if HAS_GRAD_RHO
    for (int d = 0; d < DIM; d++) gi[d] = grad_rho_[uint(d) * N + i];
#endif
    sum = 0.0;
    sph_walk(i, xi);
    float rate = sum;
#if WALL_VOLUME
    vec3 g;
    wall_hidden(xi, g);
    for (int d = 0; d < DIM; d++) rate += RHO0 * g[d] * (vi[d] - u_kick[d]); // the walls in the step's frame
#endif
    drho_[i] = rate;
}
