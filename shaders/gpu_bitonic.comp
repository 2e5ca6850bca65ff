// uses: ENTRIES
// One step of the seed's bitonic network (sph_sort_bitonic): compare distance
// u_w, the mirror pairs ("flip") on a stage's first step. Pairs reaching past
// N are skipped, as if padded with +inf. The pairs of a step are disjoint.
layout(local_size_x = WG) in;
uniform uint u_w;
uniform uint u_flip;
uniform uint u_count; // pairs: half the next power of two
void main()
{
    uint i = gid();
    if (i >= u_count) return;
    uint w = u_w, h = i & (w - 1u);
    uint left = h + 2u * w * (i / w);
    uint right = u_flip != 0u ? left + (2u * w - 1u) - 2u * h : left + w;
    if (right >= N) return;
    Entry a = ent[left], b = ent[right];
    if (b.key < a.key || (b.key == a.key && b.index < a.index)) {
        ent[left] = b;
        ent[right] = a;
    }
}
