// uses: SRC DST SUMS
// The hash health (src/core/sph_hash_health.c) on the device, so the HUD
// reads back 20 bytes instead of the positions. From the positions the hash
// pass saw (bound as SRC, read as float bits), with its cells, hash and key
// (gpu_hash.comp). u_count = 0: the per-key records (DST, 3 words per key:
// particles, smallest and largest cell hash) cleared; 1: each particle
// counted into its key; 2: summed into SUMS: occupied keys, colliding keys
// (more than one cell hash), the longest run, and the candidates of every
// particle's 3^DIM stencil (the particles of each stencil cell's key, as
// the neighbour walk reads them) as a 64-bit sum in two words.
layout(local_size_x = WG) in;
uniform uint u_count;
shared uint s_occ[WG], s_col[WG], s_run[WG], s_lo[WG], s_hi[WG];

ivec3 health_cell(uint i)
{
    ivec3 c = ivec3(0);
    for (int d = 0; d < DIM; d++) c[d] = cells_coord(d, uintBitsToFloat(src_[uint(d) * N + i]));
    return c;
}

// The particles holding the keys of the stencil's cells around particle i,
// those past the edge of a bounded axis left out (sph_hash_health.c).
uint health_candidates(uint i)
{
    ivec3 c = health_cell(i);
    int zr = DIM == 3 ? 1 : 0;
    uint sum = 0u;
    for (int oz = -zr; oz <= zr; oz++)
        for (int oy = -1; oy <= 1; oy++)
            for (int ox = -1; ox <= 1; ox++) {
                ivec3 cc = ivec3(0);
                if (!cells_step(0, c.x, ox, cc.x) || !cells_step(1, c.y, oy, cc.y)) continue;
                if (DIM == 3 && !cells_step(2, c.z, oz, cc.z)) continue;
                sum += dst_[3u * (cells_hash(cc) % T)];
            }
    return sum;
}

void main()
{
    uint x = gid();
    if (u_count == 0u) {
        if (x < T) {
            dst_[3u * x] = 0u;
            dst_[3u * x + 1u] = EMPTY;
            dst_[3u * x + 2u] = 0u;
        }
        return;
    }
    if (u_count == 1u) {
        if (x < N) {
            uint h = cells_hash(health_cell(x)), k = 3u * (h % T);
            atomicAdd(dst_[k], 1u);
            atomicMin(dst_[k + 1u], h);
            atomicMax(dst_[k + 2u], h);
        }
        return;
    }
    // u_count = 2: invocation x sums key x and particle x; each group's sums
    // reduced in shared memory, then added to SUMS (no invocation returns
    // early: every one reaches the barriers)
    uint l = gl_LocalInvocationID.x, run = x < T ? dst_[3u * x] : 0u;
    s_run[l] = run;
    s_occ[l] = run != 0u ? 1u : 0u;
    s_col[l] = run != 0u && dst_[3u * x + 1u] != dst_[3u * x + 2u] ? 1u : 0u;
    s_lo[l] = x < N ? health_candidates(x) : 0u;
    s_hi[l] = 0u;
    barrier();
    for (uint s = uint(WG) / 2u; s > 0u; s >>= 1u) {
        if (l < s) {
            s_occ[l] += s_occ[l + s];
            s_col[l] += s_col[l + s];
            s_run[l] = max(s_run[l], s_run[l + s]);
            uint carry;
            s_lo[l] = uaddCarry(s_lo[l], s_lo[l + s], carry);
            s_hi[l] += s_hi[l + s] + carry;
        }
        barrier();
    }
    if (l == 0u) {
        atomicAdd(sums_[0], s_occ[0]);
        atomicAdd(sums_[1], s_col[0]);
        atomicMax(sums_[2], s_run[0]);
        uint before = atomicAdd(sums_[3], s_lo[0]);
        atomicAdd(sums_[4], s_hi[0] + (before + s_lo[0] < before ? 1u : 0u));
    }
}
