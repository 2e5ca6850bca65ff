// uses: ENTRIES SCRATCH COUNT
// Counting sort, 2: each entry takes a slot in its key's run (atomic, so in
// no fixed order within the run; gpu_rank puts each run in index order).
layout(local_size_x = WG) in;
void main()
{
    uint i = gid();
    if (i >= N) return;
    Entry e = ent[i];
    scr[atomicAdd(count_[e.key], 1u)] = e;
}
