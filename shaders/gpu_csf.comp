// uses: PRED MASS NORMAL CURV ACC_S FIXED ENTRIES START
// Pass csf (src/passes/csf.c): the continuum surface force of
// surface_tension = csf (Brackbill, Kothe & Zemach 1992, J. Comput. Phys.
// 100:335, eq. 4-5; Morris 2000, Int. J. Numer. Meth. Fluids 33:333),
//   a_i = sigma kappa_i grad c_i / (B rho0),   grad c_i = normal_i / h,
// for particles whose |normal| passes the cut, kappa_i the divergence of the
// outward unit normals over the neighbours above the cut, renormalised on
// the tangent plane: kappa = trace(A_t^-1 S_t). As on the CPU, A and S are
// summed in double (A is inverted); u_value is sigma / (B h rho0), which the
// host computes as the CPU pass does (gpu_passes.c). Wall particles neither
// get nor give any.
layout(local_size_x = WG) in;
uniform float u_value; // sigma / (B h rho0) [m^2/s^2], csf.c's coef

#define CSF_SUPPORT_MIN 0.1lf // the least eigenvalue of A_t (1 in a full support)
#define CSF_NORMAL_MIN 0.3    // |h grad c| a particle needs to feel the force

dmat3 A, S;     // A = sum V_j grad_i W_ij (x_j - x_i)^T, S = sum V_j grad_i W_ij (u_j - u_i)^T
vec3 ni;        // the particle's normal
float len_i;    // its length
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
    vec3 nj = LOAD3(normal_, j);
    float len_j = 0.0;
    for (int d = 0; d < DIM; d++) len_j += nj[d] * nj[d];
    len_j = sqrt(len_j);
    if (!(len_j > CSF_NORMAL_MIN) || !(r2 > 0.0)) return;
    float r = sqrt(r2);
    // V_j grad_i W_ij = g x_ij, V_j = m_j / rho0 (as the normals)
    double g = double(mass_[j]) * (1.0lf / double(RHO0)) * double(kernel_dw(KD, SIG_D, r)) / double(r);
    for (int a = 0; a < DIM; a++)
        for (int b = 0; b < DIM; b++) {
            // x_j - x_i = -x_ij; u = -n / |n| outward
            A[a][b] += g * double(dx[a]) * double(-dx[b]);
            S[a][b] += g * double(dx[a]) * (-double(nj[b]) / double(len_j) + double(ni[b]) / double(len_i));
        }
}
#include_walk

// kappa = trace(A_t^-1 S_t) on the tangent plane of the outward unit normal
// u; 0 where A_t is nearly singular (csf.c's csf_div, term for term).
double csf_div(dvec3 u)
{
    dvec3 t0 = dvec3(0.0lf), t1 = dvec3(0.0lf);
#if DIM == 2
    t0 = dvec3(-u[1], u[0], 0.0lf);
#else
    // t0 perpendicular to u along its smallest component's axis, t1 = u x t0
    int m = abs(u[0]) <= abs(u[1]) && abs(u[0]) <= abs(u[2]) ? 0 : abs(u[1]) <= abs(u[2]) ? 1 : 2;
    dvec3 e = dvec3(0.0lf);
    e[m] = 1.0lf;
    dvec3 c = dvec3(u[1] * e[2] - u[2] * e[1], u[2] * e[0] - u[0] * e[2], u[0] * e[1] - u[1] * e[0]);
    double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    for (int d = 0; d < 3; d++) t0[d] = c[d] / len;
    t1[0] = u[1] * t0[2] - u[2] * t0[1];
    t1[1] = u[2] * t0[0] - u[0] * t0[2];
    t1[2] = u[0] * t0[1] - u[1] * t0[0];
#endif
    dvec3 t[2] = dvec3[2](t0, t1);
    const int nt = DIM - 1;
    dmat2 At = dmat2(0.0lf), St = dmat2(0.0lf);
    for (int p = 0; p < nt; p++)
        for (int q = 0; q < nt; q++)
            for (int a = 0; a < DIM; a++)
                for (int b = 0; b < DIM; b++) {
                    At[p][q] += t[p][a] * A[a][b] * t[q][b];
                    St[p][q] += t[p][a] * S[a][b] * t[q][b];
                }
#if DIM == 2
    return At[0][0] > CSF_SUPPORT_MIN ? St[0][0] / At[0][0] : 0.0lf;
#else
    double det = At[0][0] * At[1][1] - At[0][1] * At[1][0];
    if (!(det > CSF_SUPPORT_MIN * CSF_SUPPORT_MIN)) return 0.0lf;
    double k = At[1][1] * St[0][0] - At[0][1] * St[1][0] - At[1][0] * St[0][1] + At[0][0] * St[1][1];
    return k / det;
#endif
}

void main()
{
    uint i = gid();
    if (i >= N) return;
    ni = LOAD3(normal_, i);
    len_i = 0.0;
    for (int d = 0; d < DIM; d++) len_i += ni[d] * ni[d];
    len_i = sqrt(len_i);
    float kappa = 0.0;
    if (!is_wall(i) && len_i > CSF_NORMAL_MIN) {
        A = dmat3(0.0lf);
        S = dmat3(0.0lf);
        sph_walk(i, PRED3(i));
        // the outward unit normal, in float as the CPU's
        vec3 uf = vec3(-ni[0] / len_i, -ni[1] / len_i, DIM == 3 ? -ni[2] / len_i : 0.0);
        kappa = float(csf_div(dvec3(uf)));
    }
    curv_[i] = kappa;
    // grad c = n / h; into the fluid for kappa > 0
    for (int d = 0; d < DIM; d++) acc_s_[uint(d) * N + i] = u_value * kappa * ni[d];
}
