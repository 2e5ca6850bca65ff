// uses: SRC DST
// Not a pass: the smallest and largest finite value of a field (u_count = 1)
// or of its vectors' lengths (u_count = DIM), for the window's colour scale,
// so that drawing needs no read-back. Floats become ordered keys (negative:
// all bits flipped; positive: the sign bit set), whose unsigned order is the
// floats', then one atomicMin and atomicMax per group: dst_[0], dst_[1].
layout(local_size_x = WG) in;
uniform uint u_count;
shared uint smin[WG], smax[WG];
uint ordered(float v)
{
    uint u = floatBitsToUint(v);
    return (u & 0x80000000u) != 0u ? ~u : (u | 0x80000000u);
}
void main()
{
    uint i = gid(), l = gl_LocalInvocationID.x;
    uint lo = 0xFFFFFFFFu, hi = 0u;
    if (i < N) {
        float v;
        if (u_count == 1u) {
            v = uintBitsToFloat(src_[i]);
        } else {
            // as the CPU's vec_norm: squares summed axis by axis, then sqrt
            precise float s = 0.0;
            for (int d = 0; d < DIM; d++) {
                float c = uintBitsToFloat(src_[uint(d) * N + i]);
                s = s + c * c;
            }
            v = sqrt(s);
        }
        if (!isnan(v) && !isinf(v)) {
            lo = ordered(v);
            hi = lo;
        }
    }
    smin[l] = lo;
    smax[l] = hi;
    barrier();
    for (uint off = uint(WG) / 2u; off > 0u; off >>= 1) {
        if (l < off) {
            smin[l] = min(smin[l], smin[l + off]);
            smax[l] = max(smax[l], smax[l + off]);
        }
        barrier();
    }
    if (l == 0u) {
        atomicMin(dst_[0], smin[0]);
        atomicMax(dst_[1], smax[0]);
    }
}
