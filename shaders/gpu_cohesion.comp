// uses: PRED MASS RHO ACC_C ENTRIES START
// Pass cohesion (src/passes/cohesion.c): Akinci et al. 2013's cohesion term,
// a_i = -gamma sum_j 2 rho0 / (rho_i + rho_j) m_j C(r) x_ij / r.
layout(local_size_x = WG) in;
vec3 acc;
float rho_i;
// The spline C(r) (Akinci 2013, eq. 2) with the constant of sph_cohesion_c.
float cohesion_c(float r)
{
    float q = r * INV_H;
    if (q >= 1.0 || q <= 0.0) return 0.0;
    float u = 1.0 - q, s = u * u * u * q * q * q;
    float shape = 2.0 * q > 1.0 ? s : 2.0 * s - 1.0 / 64.0;
#if DIM == 3
    float sigma = 32.0 / 3.14159265358979, hd = H * H * H;
#else
    float sigma = 25280.0 / (627.0 * 3.14159265358979), hd = H * H;
#endif
    return sigma / hd * shape;
}
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    if (r2 < R_MIN * R_MIN) return; // coincident: no direction to pull along
    float r = sqrt(r2);
    float coef = 2.0 * RHO0 / (rho_i + rho_[j]) * mass_[j] * cohesion_c(r) / r;
    for (int d = 0; d < DIM; d++) acc[d] += coef * dx[d]; // dx = x_i - x_j

}
#include_walk
void main()
{
    uint i = gid();
    if (i >= N) return;
    acc = vec3(0.0);
    rho_i = rho_[i];
    sph_walk(i, PRED3(i));
    for (int d = 0; d < DIM; d++) acc_c_[uint(d) * N + i] = -COHESION * acc[d];
}
