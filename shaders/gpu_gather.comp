// uses: ENTRIES SRC DST
// Pass reorder (src/passes/reorder.c): dst = src in sorted order, for a field
// of u_count components (copied as bits, so floats and ids alike).
layout(local_size_x = WG) in;
uniform uint u_count;
void main()
{
    uint k = gid();
    if (k >= N) return;
    uint from = ent[k].index;
    for (uint c = 0u; c < u_count; c++) dst_[c * N + k] = src_[c * N + from];
}
