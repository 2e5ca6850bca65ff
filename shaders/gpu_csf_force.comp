// uses: PRED MASS NORMAL CURV ACC_S FIXED ENTRIES START CSF
// Pass csf (src/passes/csf.c), sweep 2 of 2, after gpu_csf.comp: for each
// particle with a surface density lam_i > 0 (csf_[i]), the curvature
// averaged (Shepard) over the neighbours above the normal's cut, self
// included, weights (|n_j| - cut) W_ij with the density kernel, of their raw
// curvatures (csf_[N + j]), which the curv field takes, and the force
//   a_i = sigma kappa_i n_i / (lam_i m_i |n_i|),   n into the fluid,
// sigma kappa per unit area of surface shared as w_i / lam_i. u_value is
// sigma [N/m; 2D: N]. Others get no force and curvature 0.
layout(local_size_x = WG) in;
uniform float u_value; // sigma

double sw, sk; // sum_j w_j W_ij and sum_j w_j W_ij kappa_j
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
    float lj = 0.0;
    for (int d = 0; d < DIM; d++) lj += nj[d] * nj[d];
    lj = sqrt(lj);
    if (!(lj > CSF_NORMAL_MIN)) return;
    double w = double(kernel_w(KD, SIG_D, sqrt(r2)) * (lj - CSF_NORMAL_MIN));
    sw += w;
    sk += w * double(csf_[N + j]);
}
#include_walk

void main()
{
    uint i = gid();
    if (i >= N) return;
    float lam = csf_[i];
    vec3 acc = vec3(0.0);
    float kappa = 0.0;
    if (lam > 0.0) {
        vec3 ni = LOAD3(normal_, i);
        float len_i = 0.0;
        for (int d = 0; d < DIM; d++) len_i += ni[d] * ni[d];
        len_i = sqrt(len_i);
        sw = 0.0lf;
        sk = 0.0lf;
        if (len_i > CSF_NORMAL_MIN) {
            sw = double(kernel_w(KD, SIG_D, 0.0) * (len_i - CSF_NORMAL_MIN));
            sk = sw * double(csf_[N + i]);
        }
        sph_walk(i, PRED3(i));
        if (sw > 0.0lf) {
            double k = sk / sw;
            kappa = float(k);
            // sigma kappa times the particle's share of the surface 1 / lam_i, per unit mass, into the fluid
            double a = double(u_value) * k / (double(lam) * double(mass_[i]) * double(len_i));
            for (int d = 0; d < DIM; d++) acc[d] = float(a * double(ni[d]));
        }
    }
    curv_[i] = kappa;
    for (int d = 0; d < DIM; d++) acc_s_[uint(d) * N + i] = acc[d];
}
