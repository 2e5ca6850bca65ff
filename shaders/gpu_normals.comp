// uses: PRED VOL MASS NORMAL FIXED ENTRIES START
// Pass normals (src/passes/normals.c): the surface normal of surface_tension
// = akinci (Akinci, Akinci & Teschner 2013, ACM TOG 32(6), eq. 3),
//   n_i = h sum_j V_j W'(r) x_ij / r,
// density kernel, pointing into the fluid. Wall particles are left out of
// the sum and get n = 0; coincident pairs (no direction) are left out.
// surface_tension = csf sums with the volumes m_j / rho0 instead (normals.c
// says why), its 1 / rho0 the CPU's float.
layout(local_size_x = WG) in;
vec3 nsum;
bool is_wall(uint i)
{
#if HAS_FIXED
    return fixed_[i] != 0.0;
#else
    return false;
#endif
}
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    if (is_wall(j) || !(r2 > 0.0)) return;
    float r = sqrt(r2);
#if ST_CSF
    float c = mass_[j] * INV_RHO0 * kernel_dw(KD, SIG_D, r) / r;
#else
    float c = vol_[j] * kernel_dw(KD, SIG_D, r) / r;
#endif
    for (int d = 0; d < DIM; d++) nsum[d] += c * dx[d];
}
#include_walk
void main()
{
    uint i = gid();
    if (i >= N) return;
    nsum = vec3(0.0);
    if (!is_wall(i)) sph_walk(i, PRED3(i));
    for (int d = 0; d < DIM; d++) normal_[uint(d) * N + i] = H * nsum[d];
}
