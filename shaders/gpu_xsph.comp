// uses: PRED VEL MASS RHO ACC_X FIXED ENTRIES START
// Pass xsph (src/passes/xsph.c): XSPH velocity smoothing after Monaghan 1989
// (J. Comput. Phys. 82:1, eq. 2.6), applied as an acceleration over the step,
//   a_i = (epsilon / dt) sum_j 2 m_j / (rho_i + rho_j) (v_j - v_i) W_ij,
// density kernel. Wall particles neither get nor give any. u_value =
// epsilon / dt [1/s], 0 before the first step (as the CPU pass).
layout(local_size_x = WG) in;
uniform float u_value;
vec3 acc, vi;
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
    float c = 2.0 * mass_[j] / (rho_i + rho_[j]) * kernel_w(KD, SIG_D, sqrt(r2));
    vec3 vj = VEL3(j);
    for (int d = 0; d < DIM; d++) acc[d] += c * (vj[d] - vi[d]);
}
#include_walk
void main()
{
    uint i = gid();
    if (i >= N) return;
    acc = vec3(0.0);
    if (!is_wall(i)) {
        vi = VEL3(i);
        rho_i = rho_[i];
        sph_walk(i, PRED3(i));
    }
    for (int d = 0; d < DIM; d++) acc_x_[uint(d) * N + i] = u_value * acc[d];
}
