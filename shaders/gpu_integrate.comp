// uses: POS VEL ACCELERATIONS REDUCE FIXED POS_R
// Pass integrate (src/passes/integrate.c): symplectic Euler with the sum of
// every acceleration field (ACC_SUM, written by the host), periodic wrap,
// and the largest |v|^2 and |a|^2 for the CFL step: reduced per group in
// shared memory, then one atomicMax per group on the float bits (non-negative
// floats order as their bits do; a NaN's bits exceed every finite value's, so
// a NaN shows up in the maximum, as the watchdog needs). Wall particles
// (wall_model = particles) never move and count in neither maximum; only the
// periodic wrap applies to them, as on the CPU. With position_sum =
// compensated (HAS_POS_R), x += dt v is Kahan's sum, as integrate.c: pos_r
// keeps what the float x could not hold and adds it to the next move.
layout(local_size_x = WG) in;
uniform float u_dt;
shared uint sv[WG], sa[WG];
void main()
{
    uint i = gid(), l = gl_LocalInvocationID.x;
    float v2 = 0.0, a2 = 0.0;
    bool wall = false;
#if HAS_FIXED
    wall = i < N && fixed_[i] != 0.0;
#endif
    if (wall) {
        for (int d = 0; d < DIM; d++) {
            uint k = uint(d) * N + i;
            if (PER[d] > 0.0) pos_[k] = wrap_coord(pos_[k], DOM_MIN[d], PER[d], INV_PER[d]);
        }
    } else if (i < N) {
        for (int d = 0; d < DIM; d++) {
            uint k = uint(d) * N + i;
            float a = ACC_SUM(k); // every acceleration field, as the CPU sums them
            precise float v = vel_[k] + u_dt * a;
            vel_[k] = v;
#if HAS_POS_R
            precise float y = u_dt * v + pos_r_[k];
            precise float x0 = pos_[k];
            precise float x = x0 + y;
            // precise, or a compiler may fold y - ((x0 + y) - x0) to 0 (NVIDIA's does)
            precise float r = y - (x - x0);
            pos_r_[k] = r;
#else
            precise float x = pos_[k] + u_dt * v;
#endif
            if (PER[d] > 0.0) x = wrap_coord(x, DOM_MIN[d], PER[d], INV_PER[d]);
            pos_[k] = x;
            v2 += v * v;
            a2 += a * a;
        }
    }
    sv[l] = floatBitsToUint(v2);
    sa[l] = floatBitsToUint(a2);
    barrier();
    for (uint off = uint(WG) / 2u; off > 0u; off >>= 1) {
        if (l < off) {
            sv[l] = max(sv[l], sv[l + off]);
            sa[l] = max(sa[l], sa[l + off]);
        }
        barrier();
    }
    if (l == 0u) {
        atomicMax(reduce_[0], sv[0]);
        atomicMax(reduce_[1], sa[0]);
    }
}
