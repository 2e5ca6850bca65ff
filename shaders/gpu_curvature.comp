// uses: PRED RHO NORMAL ACC_K FIXED ENTRIES START
// Pass curvature (src/passes/curvature.c): the curvature term of
// surface_tension = akinci (Akinci, Akinci & Teschner 2013, eq. 4-5),
//   a_i = -gamma sum_j 2 rho0 / (rho_i + rho_j) (n_i - n_j),
// with the normals pass's n. Wall particles neither get nor give any.
layout(local_size_x = WG) in;
vec3 acc, ni;
float rho_i;
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
    if (is_wall(j)) return;
    float k_ij = 2.0 * RHO0 / (rho_i + rho_[j]);
    vec3 nj = LOAD3(normal_, j);
    for (int d = 0; d < DIM; d++) acc[d] += k_ij * (ni[d] - nj[d]);
}
#include_walk
void main()
{
    uint i = gid();
    if (i >= N) return;
    acc = vec3(0.0);
    if (!is_wall(i)) {
        ni = LOAD3(normal_, i);
        rho_i = rho_[i];
        sph_walk(i, PRED3(i));
    }
    for (int d = 0; d < DIM; d++) acc_k_[uint(d) * N + i] = -ST_GAMMA * acc[d];
}
