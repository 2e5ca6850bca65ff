// uses: PRED MASS RHO VOL ENTRIES START WALL
// Pass density (src/passes/density.c): rho_i = sum_j m_j W_ij, itself
// included, plus rho0 times the share of the support hidden by the walls.
layout(local_size_x = WG) in;
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
}
