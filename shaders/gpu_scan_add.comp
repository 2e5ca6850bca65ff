// uses: SCAN SUMS
// Inclusive prefix sum, 2: adds the scanned totals of the groups before.
layout(local_size_x = WG) in;
uniform uint u_count;
void main()
{
    uint i = gid(), g = group_index();
    if (i < u_count && g > 0u) scan_[i] += sums_[g - 1u];
}
