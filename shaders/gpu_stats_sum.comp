// uses: SRC DST
// The statistics' second stage (see gpu_stats.comp): one work group reduces
// the u_count groups' rows of STATS_Q floats (src_) into one row (dst_):
// each invocation its share of the rows in turn, then a tree in shared memory.
layout(local_size_x = WG) in;
#define STATS_Q 12
uniform uint u_count;
shared float s[STATS_Q][WG];
float combine(int k, float a, float b)
{
    return k == 7 ? min(a, b) : (k == 8 || k == 9 || k == 11) ? max(a, b) : a + b;
}
void main()
{
    uint l = gl_LocalInvocationID.x;
    float q[STATS_Q];
    for (int k = 0; k < STATS_Q; k++) q[k] = 0.0;
    q[7] = uintBitsToFloat(0x7F800000u);
    q[8] = -uintBitsToFloat(0x7F800000u);
    q[9] = q[8];
    q[11] = q[8];
    for (uint g = l; g < u_count; g += uint(WG))
        for (int k = 0; k < STATS_Q; k++) q[k] = combine(k, q[k], uintBitsToFloat(src_[g * uint(STATS_Q) + uint(k)]));
    for (int k = 0; k < STATS_Q; k++) s[k][l] = q[k];
    barrier();
    for (uint off = uint(WG) / 2u; off > 0u; off >>= 1) {
        if (l < off)
            for (int k = 0; k < STATS_Q; k++) s[k][l] = combine(k, s[k][l], s[k][l + off]);
        barrier();
    }
    if (l < uint(STATS_Q)) dst_[l] = floatBitsToUint(s[l][0]);
}
