// uses: PRED MASS NORMAL FIXED ENTRIES START CSF
// Pass csf (src/passes/csf.c), sweep 1 of 2: the continuum surface force of
// surface_tension = csf (Brackbill, Kothe & Zemach 1992, J. Comput. Phys.
// 100:335, eq. 4-5; Morris 2000, Int. J. Numer. Meth. Fluids 33:333). For
// each particle whose |normal| passes the cut, with w = |normal| - cut:
// its raw curvature, the divergence of the outward unit normals over the
// neighbours above the cut weighed by w_j, renormalised on the tangent plane
// (kappa = trace(A_t^-1 S_t)), and its surface density
//   lam_i = sum_j w_j W_{DIM-1}(tangential distance) / w_i   (self included),
// written to the scratch csf_: lam at i, the raw curvature at N + i (0 for a
// particle below the cut or a wall). gpu_csf_force.comp then averages the
// curvature and makes the force. As on the CPU, A, S and lam's sum are in
// double (A is inverted). Wall particles neither get nor give any.
layout(local_size_x = WG) in;

// Arrays, not dmat3/dvec3, wherever a component is written at a loop
// index: NVIDIA's compiler (580) cannot ("can't find __setVectorIndex").
double A[3][3], S[3][3];     // A = sum w_j V_j grad_i W_ij (x_j - x_i)^T, S = sum w_j V_j grad_i W_ij (u_j - u_i)^T
double ls;      // sum_j w_j W_{DIM-1}(r_t), self included
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

// The cubic B-spline of support radius H in DIM - 1 dimensions (1D: 4/(3h),
// 2D: 40/(7 pi h^2)), csf.c's csf_w_surface.
double csf_w_surface(double r)
{
    double h = double(H), q = r / h;
    if (q >= 1.0lf) return 0.0lf;
    double f = q <= 0.5lf ? 1.0lf - 6.0lf * q * q + 6.0lf * q * q * q : 2.0lf * (1.0lf - q) * (1.0lf - q) * (1.0lf - q);
    return (DIM == 2 ? 4.0lf / (3.0lf * h) : 40.0lf / (7.0lf * 3.14159265358979lf * h * h)) * f;
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
    // the tangential distance: x_ij less its part along the normal (in float, as the CPU's)
    precise float xnf = dx[0] * ni[0] + dx[1] * ni[1] + (DIM == 3 ? dx[2] * ni[2] : 0.0);
    double xn = double(xnf / len_i);
    double wj = double(len_j - CSF_NORMAL_MIN);
    ls += wj * csf_w_surface(sqrt(max(double(r2) - xn * xn, 0.0lf)));
    // w_j V_j grad_i W_ij = g x_ij, V_j = m_j / rho0 (as the normals)
    double g = wj * double(mass_[j]) * (1.0lf / double(RHO0)) * double(kernel_dw(KD, SIG_D, r)) / double(r);
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
    double t[2][3] = double[2][3](double[3](0.0lf, 0.0lf, 0.0lf), double[3](0.0lf, 0.0lf, 0.0lf));
#if DIM == 2
    t[0] = double[3](-u[1], u[0], 0.0lf);
#else
    // t0 perpendicular to u along its smallest component's axis, t1 = u x t0
    int m = abs(u[0]) <= abs(u[1]) && abs(u[0]) <= abs(u[2]) ? 0 : abs(u[1]) <= abs(u[2]) ? 1 : 2;
    double e[3] = double[3](0.0lf, 0.0lf, 0.0lf);
    e[m] = 1.0lf;
    double c[3] = double[3](u[1] * e[2] - u[2] * e[1], u[2] * e[0] - u[0] * e[2], u[0] * e[1] - u[1] * e[0]);
    double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    for (int d = 0; d < 3; d++) t[0][d] = c[d] / len;
    t[1][0] = u[1] * t[0][2] - u[2] * t[0][1];
    t[1][1] = u[2] * t[0][0] - u[0] * t[0][2];
    t[1][2] = u[0] * t[0][1] - u[1] * t[0][0];
#endif
    const int nt = DIM - 1;
    double At[2][2] = double[2][2](double[2](0.0lf, 0.0lf), double[2](0.0lf, 0.0lf));
    double St[2][2] = double[2][2](double[2](0.0lf, 0.0lf), double[2](0.0lf, 0.0lf));
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
    float kappa = 0.0, lam = 0.0;
    if (!is_wall(i) && len_i > CSF_NORMAL_MIN) {
        double wi = double(len_i - CSF_NORMAL_MIN);
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) A[a][b] = S[a][b] = 0.0lf;
        ls = wi * csf_w_surface(0.0lf);
        sph_walk(i, PRED3(i));
        // the outward unit normal, in float as the CPU's
        vec3 uf = vec3(-ni[0] / len_i, -ni[1] / len_i, DIM == 3 ? -ni[2] / len_i : 0.0);
        kappa = float(csf_div(dvec3(uf)));
        lam = float(ls / wi);
    }
    csf_[i] = lam;
    csf_[N + i] = kappa;
}
