// uses: PRED ENTRIES
// Pass hash (src/passes/hash.c): the (key, hash, index) entry of each particle's cell.
layout(local_size_x = WG) in;
void main()
{
    uint i = gid();
    if (i >= N) return;
    ivec3 c = ivec3(0);
    for (int d = 0; d < DIM; d++) c[d] = cells_coord(d, pred_[uint(d) * N + i]);
    uint h = cells_hash(c);
    ent[i] = Entry(h % T, h, i);
}
