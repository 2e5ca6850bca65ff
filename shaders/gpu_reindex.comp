// uses: ENTRIES
// Pass reorder, last: particle k is now sorted entry k.
layout(local_size_x = WG) in;
void main()
{
    uint k = gid();
    if (k < N) ent[k].index = k;
}
