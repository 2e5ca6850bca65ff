// uses: ENTRIES COUNT
// Counting sort, 1: particles per key, counted one slot up (count[key + 1]) so
// that the inclusive prefix sum gives each key's first slot.
layout(local_size_x = WG) in;
void main()
{
    uint i = gid();
    if (i < N) atomicAdd(count_[ent[i].key + 1u], 1u);
}
