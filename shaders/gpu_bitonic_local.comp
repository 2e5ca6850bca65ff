// uses: ENTRIES
// The bitonic network's short steps in shared memory: every step whose
// stride fits a work group (w <= WG) compares entries within one block of
// 2 WG, so a group loads its block once, runs those steps with a barrier
// between them, and writes it back: one dispatch where the seed's design
// (gpu_bitonic.comp) makes one per step. u_w == 0: the first stages whole
// (w0 = 1 .. WG, each with its mirror step); else the steps w = WG .. 1 that
// end a longer stage (no mirror step: that is its first, done globally).
// Entries past N are padded with the largest (key, index), as the global
// step skips them: they never move below N. Sorting (key, index) pairs,
// all distinct, gives one order whatever the network: the CPU's.
layout(local_size_x = WG) in;
uniform uint u_w;
shared uint s_key[2 * WG];
shared uint s_hash[2 * WG];
shared uint s_index[2 * WG];

void swap_if(uint a, uint b)
{
    uint ka = s_key[a], kb = s_key[b], ia = s_index[a], ib = s_index[b];
    if (kb < ka || (kb == ka && ib < ia)) {
        uint h = s_hash[a];
        s_key[a] = kb;
        s_index[a] = ib;
        s_hash[a] = s_hash[b];
        s_key[b] = ka;
        s_index[b] = ia;
        s_hash[b] = h;
    }
}

// One step within the block: pair t of distance w (mirror pairs if flip).
void step_local(uint t, uint w, bool flip)
{
    uint h = t & (w - 1u);
    uint left = h + 2u * w * (t / w);
    uint right = flip ? left + (2u * w - 1u) - 2u * h : left + w;
    swap_if(left, right);
    barrier();
}

void main()
{
    uint t = gl_LocalInvocationID.x, base = group_index() * uint(2 * WG);
    for (uint k = 0u; k < 2u; k++) {
        uint l = t + k * uint(WG), i = base + l;
        if (i < N) {
            Entry e = ent[i];
            s_key[l] = e.key;
            s_hash[l] = e.hash;
            s_index[l] = e.index;
        } else {
            s_key[l] = 0xFFFFFFFFu;
            s_hash[l] = 0u;
            s_index[l] = 0xFFFFFFFFu;
        }
    }
    barrier();
    if (u_w == 0u) {
        for (uint w0 = 1u; w0 <= uint(WG); w0 <<= 1)
            for (uint w = w0; w >= 1u; w >>= 1) step_local(t, w, w == w0);
    } else {
        for (uint w = uint(WG); w >= 1u; w >>= 1) step_local(t, w, false);
    }
    for (uint k = 0u; k < 2u; k++) {
        uint l = t + k * uint(WG), i = base + l;
        if (i < N) ent[i] = Entry(s_key[l], s_hash[l], s_index[l]);
    }
}
