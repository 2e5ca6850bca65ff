// The neighbour walk of the density and force passes. The GL backend builds
// no neighbour lists: each of those passes visits the 3^DIM cells around the
// particle itself, as the seed's shaders did (a list of variable length per
// particle needs a count pass, a prefix sum and a fill pass; walking three
// times costs less on a GPU than that round trip through memory). The test
// is the CPU neighbour pass's: same cell, same hash, not itself, r^2 < h^2
// with r^2 summed axis by axis without fusing, so both backends pick the
// same pairs. sph_pair receives x_i - x_j (minimum image) and r^2.
void sph_pair(uint i, uint j, vec3 dx, float r2);

void sph_walk(uint i, vec3 xi)
{
#if SEARCH_BRUTE
    for (uint j = 0u; j < N; j++) {
        if (j == i) continue;
        vec3 xj = PRED3(j), dx = vec3(0.0);
        precise float r2 = 0.0;
        for (int d = 0; d < DIM; d++) {
            dx[d] = min_image(xi[d] - xj[d], d);
            r2 += dx[d] * dx[d];
        }
        if (r2 < H2) sph_pair(i, j, dx, r2);
    }
#else
    ivec3 c = ivec3(0);
    for (int d = 0; d < DIM; d++) c[d] = cells_coord(d, xi[d]);
    int zr = DIM == 3 ? 1 : 0;
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
                    uint j = en.index;
                    vec3 xj = PRED3(j), dx = vec3(0.0);
                    precise float r2 = 0.0;
                    for (int d = 0; d < DIM; d++) {
                        dx[d] = min_image(xi[d] - xj[d], d);
                        r2 += dx[d] * dx[d];
                    }
                    if (r2 < H2) sph_pair(i, j, dx, r2);
                }
            }
#endif
}
