// uses: SCAN SUMS
// Inclusive prefix sum, 1: each group scans its WG values in shared memory
// (Hillis-Steele) and writes its total to sums_[group]; the totals are then
// scanned the same way, and gpu_scan_add adds them back.
layout(local_size_x = WG) in;
uniform uint u_count;
shared uint s[WG];
void main()
{
    uint i = gid(), l = gl_LocalInvocationID.x;
    s[l] = i < u_count ? scan_[i] : 0u;
    barrier();
    for (uint off = 1u; off < uint(WG); off <<= 1) {
        uint t = l >= off ? s[l - off] : 0u;
        barrier();
        s[l] += t;
        barrier();
    }
    if (i < u_count) scan_[i] = s[l];
    if (l == uint(WG) - 1u && group_index() * uint(WG) < u_count) sums_[group_index()] = s[l];
}
