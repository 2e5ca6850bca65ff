// uses: ENTRIES START
// Pass offsets (src/passes/offsets.c): each entry that begins a key's run
// writes that key's start (the table was filled with EMPTY before).
layout(local_size_x = WG) in;
void main()
{
    uint i = gid();
    if (i >= N) return;
    uint k = ent[i].key;
    if (i == 0u || ent[i - 1u].key != k) start_[k] = i;
}
