// uses: PRED MASS RHO RHO_C GRAD_RHO FIXED ENTRIES START
// Pass density_gradient (src/passes/density_gradient.c): the renormalised
// gradient of the carried density (Antuono et al. 2010, Comput. Phys.
// Commun. 181, 532, eq. 9-10),
//   <grad rho>^L_i = L_i sum_j (rho_j - rho_i) grad_i W_ij V_j,
//   L_i = [sum_j (x_j - x_i) (x) grad_i W_ij V_j]^-1,
// with the density wall_state gave a wall particle, rho_c a fluid one's.
// The sums and the solve are in double, as on the CPU: the sum of
// (rho_j - rho_i) terms cancels to a small part of each. u_count = 0 at the
// start (nothing carried yet): 0.
// M, b and g are arrays, not dmat3/dvec3: NVIDIA's compiler (580) cannot
// write a double vector's component at a loop index ("can't find
// __setVectorIndex"), and the shader then does not link.
layout(local_size_x = WG) in;
uniform uint u_count;
double M[3][3];
double b[3];
double g[3];
float rho_i;
float rho_diffused(uint j)
{
#if HAS_FIXED
    if (fixed_[j] != 0.0) return rho_[j];
#endif
    return rho_c_[j];
}
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    if (r2 < R_MIN * R_MIN) return;
    float r = sqrt(r2);
    float rho_j = rho_diffused(j);
    double gw = double(kernel_dw(KD, SIG_D, r) / r) * double(mass_[j]) / double(rho_j);
    double drho = double(rho_j) - double(rho_i);
    for (int a = 0; a < DIM; a++) {
        b[a] += drho * gw * double(dx[a]);
        for (int c = 0; c < DIM; c++) M[a][c] -= double(dx[a]) * gw * double(dx[c]);
    }
}
#include_walk
// M g = b by Cramer's rule; g = 0 where M is singular relative to its size
// (density_gradient.c's solve_small, term for term).
void solve_small()
{
    g = double[3](0.0lf, 0.0lf, 0.0lf);
    double scale = 0.0;
    for (int d = 0; d < DIM; d++) scale += abs(M[d][d]);
    scale /= double(DIM);
#if DIM == 2
    double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    if (!(abs(det) > 1e-6 * scale * scale)) return;
    g[0] = (b[0] * M[1][1] - M[0][1] * b[1]) / det;
    g[1] = (M[0][0] * b[1] - b[0] * M[1][0]) / det;
#else
    double c00 = M[1][1] * M[2][2] - M[1][2] * M[2][1], c01 = M[1][2] * M[2][0] - M[1][0] * M[2][2],
           c02 = M[1][0] * M[2][1] - M[1][1] * M[2][0];
    double det = M[0][0] * c00 + M[0][1] * c01 + M[0][2] * c02;
    if (!(abs(det) > 1e-6 * scale * scale * scale)) return;
    g[0] = (c00 * b[0] + (M[0][2] * M[2][1] - M[0][1] * M[2][2]) * b[1] +
            (M[0][1] * M[1][2] - M[0][2] * M[1][1]) * b[2]) / det;
    g[1] = (c01 * b[0] + (M[0][0] * M[2][2] - M[0][2] * M[2][0]) * b[1] +
            (M[0][2] * M[1][0] - M[0][0] * M[1][2]) * b[2]) / det;
    g[2] = (c02 * b[0] + (M[0][1] * M[2][0] - M[0][0] * M[2][1]) * b[1] +
            (M[0][0] * M[1][1] - M[0][1] * M[1][0]) * b[2]) / det;
#endif
}
void main()
{
    uint i = gid();
    if (i >= N) return;
    g = double[3](0.0lf, 0.0lf, 0.0lf);
    if (u_count != 0u) {
        for (int a = 0; a < 3; a++) {
            b[a] = 0.0lf;
            for (int c = 0; c < 3; c++) M[a][c] = 0.0lf;
        }
        rho_i = rho_diffused(i);
        sph_walk(i, PRED3(i));
        solve_small();
    }
    for (int d = 0; d < DIM; d++) grad_rho_[uint(d) * N + i] = float(g[d]);
}
