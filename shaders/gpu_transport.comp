// uses: POS PRED MASS RHO DRIFT FIXED ENTRIES START
// Pass transport (src/passes/transport.c): shifting = tvf, the drift of a
// background pressure after Adami, Hu & Adams 2013 (J. Comput. Phys. 241,
// 292, eq. 13), after integration:
//   dx_i = dt (dt/2) a_b,i,  a_b,i = -(p_b / m_i) sum_j (V_i^2 + V_j^2) grad_i W_ij,
// pressure kernel, V = m / rho, p_b = rho0 c^2. Wall particles count in the
// sum and never move; coincident pairs are left out. The sums read pred,
// the drift is added to pos (then the periodic wrap), so one dispatch.
// u_value = dt (dt/2) p_b [Pa s^2].
layout(local_size_x = WG) in;
uniform float u_value;
float vi;
vec3 g;
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    if (r2 < R_MIN * R_MIN) return;
    float r = sqrt(r2), vj = mass_[j] / rho_[j];
    float f = (vi * vi + vj * vj) * kernel_dw(KP, SIG_P, r) / r; // grad_i W = W'(r) x_ij / r
    for (int d = 0; d < DIM; d++) g[d] += f * dx[d];
}
#include_walk
void main()
{
    uint i = gid();
    if (i >= N) return;
    vec3 s = vec3(0.0);
#if HAS_FIXED
    bool wall = fixed_[i] != 0.0;
#else
    bool wall = false;
#endif
    if (!wall) {
        vi = mass_[i] / rho_[i];
        g = vec3(0.0);
        sph_walk(i, PRED3(i));
        float c = -u_value / mass_[i];
        for (int d = 0; d < DIM; d++) s[d] = c * g[d];
    }
    for (int d = 0; d < DIM; d++) {
        uint k = uint(d) * N + i;
        drift_[k] = s[d];
        float x = pos_[k] + s[d];
        if (PER[d] > 0.0) x = wrap_coord(x, DOM_MIN[d], PER[d], INV_PER[d]);
        pos_[k] = x;
    }
}
