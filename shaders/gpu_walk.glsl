// The neighbour walk of the density and force passes. The GL backend builds
// no neighbour lists: each of those passes visits the 3^DIM cells around the
// particle itself, as the seed's shaders did (a list of variable length per
// particle needs a count pass, a prefix sum and a fill pass; walking three
// times costs less on a GPU than that round trip through memory). The test
// is the CPU neighbour pass's: same cell, same hash, not itself, r^2 < h^2
// with r^2 summed axis by axis without fusing, so both backends pick the
// same pairs. sph_pair receives x_i - x_j (minimum image) and r^2.
void sph_pair(uint i, uint j, vec3 dx, float r2);

// 1 when the particle data are in cell order on a dense grid (this step's
// reorder pass ran): then the three cells of a stencil row along x are one
// contiguous run of particles, and the walk reads 3^(DIM-1) runs instead of
// 3^DIM, with no entry loads but the run's end (as the CPU's L7 level).
uniform uint u_rows;

// x_i - x_j (minimum image) and r^2, the CPU's sum order; sph_pair if within h.
void sph_try(uint i, uint j, vec3 xi)
{
    vec3 xj = PRED3(j), dx = vec3(0.0);
    precise float r2 = 0.0;
    for (int d = 0; d < DIM; d++) {
        dx[d] = min_image(xi[d] - xj[d], d);
        r2 += dx[d] * dx[d];
    }
    if (r2 < H2) sph_pair(i, j, dx, r2);
}

void sph_walk(uint i, vec3 xi)
{
#if SEARCH_BRUTE
    for (uint j = 0u; j < N; j++)
        if (j != i) sph_try(i, j, xi);
#else
    ivec3 c = ivec3(0);
    for (int d = 0; d < DIM; d++) c[d] = cells_coord(d, xi[d]);
    int zr = DIM == 3 ? 1 : 0;
#if DENSE
    if (u_rows != 0u && CELL_WRAP.x == 0) {
        int x0 = max(c.x - 1, 0), x1 = min(c.x + 1, CELL_COUNT.x - 1);
        for (int oz = -zr; oz <= zr; oz++)
            for (int oy = -1; oy <= 1; oy++) {
                ivec3 cc = ivec3(x1, 0, 0);
                if (!cells_step(1, c.y, oy, cc.y)) continue;
                if (DIM == 3 && !cells_step(2, c.z, oz, cc.z)) continue;
                uint last = cells_hash(cc), s = EMPTY; // keys are cell numbers: the row is keys last-2 .. last
                for (uint k = last - uint(x1 - x0); k <= last && s == EMPTY; k++) s = start_[k];
                if (s == EMPTY) continue;
                for (uint j = s; j < N && ent[j].key <= last; j++)
                    if (j != i) sph_try(i, j, xi);
            }
        return;
    }
#endif
    for (int oz = -zr; oz <= zr; oz++)
        for (int oy = -1; oy <= 1; oy++)
            for (int ox = -1; ox <= 1; ox++) {
                ivec3 cc = ivec3(0);
                if (!cells_step(0, c.x, ox, cc.x) || !cells_step(1, c.y, oy, cc.y)) continue;
                if (DIM == 3 && !cells_step(2, c.z, oz, cc.z)) continue;
                uint hash = cells_hash(cc), key = hash % T;
                for (uint e = start_[key]; e < N; e++) {
                    Entry en = ent[e];
                    if (en.key != key) break;
                    if (en.hash != hash || en.index == i) continue;
                    sph_try(i, en.index, xi);
                }
            }
#endif
}
