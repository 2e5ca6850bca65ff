// uses: ENTRIES SCRATCH COUNT
// Counting sort, 3: makes the sort stable, so it gives the CPU's order (key,
// then index). After the scatter, count_[k] is the end of key k's run and
// count_[k - 1] its start; an entry's place in its run is the number of
// entries of the run with a smaller index. O(run length) per entry: runs hold
// a cell's particles (a few to a few tens), not the whole table.
layout(local_size_x = WG) in;
void main()
{
    uint s = gid();
    if (s >= N) return;
    Entry e = scr[s];
    uint lo = e.key == 0u ? 0u : count_[e.key - 1u], hi = count_[e.key], rank = 0u;
    for (uint q = lo; q < hi; q++) rank += scr[q].index < e.index ? 1u : 0u;
    ent[lo + rank] = e;
}
