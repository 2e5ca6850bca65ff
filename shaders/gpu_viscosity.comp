// uses: PRED VEL VOL RHO ACC_V ENTRIES START
// Pass viscosity (src/passes/viscosity.c): reads vel, writes acc_v only. The
// seed's shader added the result to the velocity buffer it was still reading
// for other particles, so its result depended on the order threads ran in.
layout(local_size_x = WG) in;
vec3 acc, vi;
void sph_pair(uint i, uint j, vec3 dx, float r2)
{
    float r = sqrt(r2);
#if VFORM_LAP
    float w = kernel_lap(KV, SIG_V, r);
#else
    float w = kernel_w(KV, SIG_V, r);
#endif
    float coef = vol_[j] * w;
    vec3 vj = VEL3(j);
    for (int d = 0; d < DIM; d++) acc[d] += coef * (vj[d] - vi[d]);
}
#include_walk
void main()
{
    uint i = gid();
    if (i >= N) return;
    acc = vec3(0.0);
    vi = VEL3(i);
    sph_walk(i, PRED3(i));
#if VFORM_LAP
    float s = NU * RHO0 / rho_[i];
#else
    float s = NU * 2.0 * float(DIM) / M2_V;
#endif
    for (int d = 0; d < DIM; d++) accv_[uint(d) * N + i] = s * acc[d];
}
