// uses: PRED MASS RHO VOL ENTRIES START WALL RHO_C DRHO
// Pass density (src/passes/density.c): rho_i = sum_j m_j W_ij, itself
// included, plus rho0 times the share of the support hidden by the walls.
// With density_method = continuity: at the start the sum, which rho_c
// takes; afterwards (u_count = 1) no sum, rho_c += dt drho and rho = rho_c.
layout(local_size_x = WG) in;
uniform uint u_count;
uniform float u_dt;
float sum;
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    sum += mass_[j] * kernel_w(KD, SIG_D, sqrt(r2));
}
#include_walk
void main()
{
    uint i = gid();
    if (i >= N) return;
#if HAS_RHO_C
    if (u_count != 0u) { // carried: moved on by the rate the density_rate pass just made
        float rc = rho_c_[i] + u_dt * drho_[i];
        rho_c_[i] = rc;
        rho_[i] = rc;
        vol_[i] = mass_[i] / rc;
        return;
    }
#endif
    vec3 xi = PRED3(i);
    sum = mass_[i] * kernel_w(KD, SIG_D, 0.0);
    sph_walk(i, xi);
    float rho = sum;
#if WALL_VOLUME
    vec3 g;
    rho += RHO0 * wall_hidden(xi, g);
#endif
    rho_[i] = rho;
    vol_[i] = mass_[i] / rho;
#if HAS_RHO_C
    rho_c_[i] = rho; // the carried density starts from the sum
#endif
}
