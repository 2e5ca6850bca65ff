// Shared by every compute pass of the GL backend (src/gpu/). The host puts
// "#version 430" and the scene's constants (#define N, DIM, H, bindings, ...)
// before this file, so each program is compiled for one scene: loops over
// axes unroll and unused options vanish, as SPH_SPECIALISE does on the CPU.
// Each vector field is one buffer holding the x values, then y, then z (the
// CPU's one-array-per-axis layout end to end): component d of particle i is
// at d * N + i. A pass's first line lists the buffers it uses ("// uses: POS
// VEL ENTRIES"). The particle fields' blocks (pos_, vel_, rho_, acc_v_, ...:
// the registry's names, src/core/sph_fields.h) are written by the host
// before this file (gpu_program.c); for the others below it defines USE_X.
// Only the buffers a pass lists are declared, since Mesa counts every
// declared block against the limit of 16 per shader.

#if USE_ID
layout(std430, binding = B_ID) buffer BufId { uint id_[]; };
#endif
// The seed's (key, hash, index) entries: 12 bytes each, as sph_entry.
struct Entry { uint key; uint hash; uint index; };
#if USE_ENTRIES
layout(std430, binding = B_ENTRIES) buffer BufEntries { Entry ent[]; };
#endif
#if USE_SCRATCH
layout(std430, binding = B_SCRATCH) buffer BufScratch { Entry scr[]; };
#endif
#if USE_START
layout(std430, binding = B_START) buffer BufStart { uint start_[]; };
#endif
#if USE_COUNT
layout(std430, binding = B_COUNT) buffer BufCount { uint count_[]; };
#endif
#if USE_REDUCE
layout(std430, binding = B_REDUCE) buffer BufReduce { uint reduce_[]; };
#endif
#if USE_WALL
layout(std430, binding = B_WALL) buffer BufWall { float wall_[]; }; // psi[WALL_TABLE + 1], then area[WALL_TABLE + 1]
#endif
#if USE_SRC
layout(std430, binding = B_SRC) buffer BufSrc { uint src_[]; };
#endif
#if USE_DST
layout(std430, binding = B_DST) buffer BufDst { uint dst_[]; };
#endif
#if USE_SCAN
layout(std430, binding = B_SCAN) buffer BufScan { uint scan_[]; };
#endif
#if USE_SUMS
layout(std430, binding = B_SUMS) buffer BufSums { uint sums_[]; };
#endif

#define EMPTY 0xFFFFFFFFu

// Dispatches wider than 65535 groups are folded into a second dimension.
uint group_index() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }
uint gid() { return group_index() * uint(WG) + gl_LocalInvocationID.x; }

#define LOAD3(buf, i) vec3(buf[i], buf[N + (i)], DIM == 3 ? buf[2u * N + (i)] : 0.0)
#define POS3(i) LOAD3(pos_, (i))
#define VEL3(i) LOAD3(vel_, (i))
#define PRED3(i) LOAD3(pred_, (i))

// ---- kernels: the formulas of src/core/sph_kernel.h, term for term ---------
// kind: 0 poly6, 1 spiky, 2 viscosity, 3 cubic, 4 wendland (sph_kernel_kind).

float kernel_w(int kind, float s, float r)
{
    if (r >= H) return 0.0;
    if (kind == 0) { float d = H2 - r * r; return s * d * d * d; }
    if (kind == 1) { float d = H - r; return s * d * d * d; }
    if (kind == 2) {
        if (r < R_MIN) r = R_MIN;
        float q = r * INV_H;
#if DIM == 2
        return s * max(0.0, 0.25 * q * q - q * q * q / 9.0 - log(q) / 6.0 - 5.0 / 36.0);
#else
        return s * max(0.0, -0.5 * q * q * q + q * q + 0.5 / q - 1.0);
#endif
    }
    if (kind == 3) {
        float q = r * INV_H;
        if (q <= 0.5) return s * (6.0 * (q * q * q - q * q) + 1.0);
        float d = 1.0 - q;
        return s * 2.0 * d * d * d;
    }
    if (kind == 4) { float q = r * INV_H, d = 1.0 - q; return s * d * d * d * d * (1.0 + 4.0 * q); }
    return 0.0;
}

float kernel_dw(int kind, float s, float r)
{
    if (r >= H || r <= 0.0) return 0.0;
    float ih = INV_H;
    if (kind == 0) { float d = H2 - r * r; return -6.0 * s * r * d * d; }
    if (kind == 1) { float d = H - r; return -3.0 * s * d * d; }
    if (kind == 2) {
        float q = r * ih;
#if DIM == 2
        return s * ih * (0.5 * q - q * q / 3.0 - 1.0 / (6.0 * q));
#else
        return s * ih * (-1.5 * q * q + 2.0 * q - 0.5 / (q * q));
#endif
    }
    if (kind == 3) {
        float q = r * ih;
        if (q <= 0.5) return s * ih * (18.0 * q * q - 12.0 * q);
        float d = 1.0 - q;
        return -6.0 * s * ih * d * d;
    }
    if (kind == 4) { float q = r * ih, d = 1.0 - q; return -20.0 * s * ih * q * d * d * d; }
    return 0.0;
}

float kernel_lap(int kind, float s, float r)
{
    if (r >= H) return 0.0;
    float ih = INV_H, ih2 = ih * ih, dm1 = float(DIM - 1);
    if (kind == 0) { float d = H2 - r * r; return -6.0 * s * d * (H2 - 5.0 * r * r + dm1 * d); }
    if (kind == 1) {
        if (r < R_MIN) r = R_MIN;
        float d = H - r;
        return 6.0 * s * d - dm1 * 3.0 * s * d * d / r;
    }
    if (kind == 2) {
        float q = r * ih;
        return DIM == 2 ? s * ih2 * (1.0 - q) : s * ih2 * 6.0 * (1.0 - q);
    }
    if (kind == 3) {
        float q = r * ih;
        if (q <= 0.5) return s * ih2 * ((36.0 * q - 12.0) + dm1 * (18.0 * q - 12.0));
        float d = 1.0 - q;
        float d1_over_q = q > 0.0 ? -6.0 * d * d / q : 0.0;
        return s * ih2 * (12.0 * d + dm1 * d1_over_q);
    }
    if (kind == 4) { float q = r * ih, d = 1.0 - q; return -20.0 * s * ih2 * d * d * ((1.0 - 4.0 * q) + dm1 * d); }
    return 0.0;
}

#if USE_WALL
// The density kernel's wall tables (sph_kernel_wall): psi(d) and the plane integral.
float kernel_wall(float d, out float area)
{
    float t = d * INV_H * float(WALL_TABLE);
    if (!(t < float(WALL_TABLE))) { area = 0.0; return 0.0; }
    if (t < 0.0) t = 0.0;
    int i = int(t);
    float f = t - float(i);
    int a = WALL_TABLE + 1 + i;
    area = wall_[a] + f * (wall_[a + 1] - wall_[a]);
    return wall_[i] + f * (wall_[i + 1] - wall_[i]);
}

// Share of the support hidden behind the domain walls, and its gradient
// (sph_wall_hidden in src/passes/density.c).
float wall_hidden(vec3 x, out vec3 grad)
{
    float vis[6], dvis[6];
    float all = 1.0;
    for (int d = 0; d < DIM; d++) {
        if (PER[d] > 0.0) { vis[2 * d] = 1.0; vis[2 * d + 1] = 1.0; dvis[2 * d] = 0.0; dvis[2 * d + 1] = 0.0; continue; }
        float area;
        float lo = kernel_wall(x[d] - DOM_MIN[d], area);
        vis[2 * d] = 1.0 - lo;
        dvis[2 * d] = area;
        float hi = kernel_wall(DOM_MAX[d] - x[d], area);
        vis[2 * d + 1] = 1.0 - hi;
        dvis[2 * d + 1] = -area;
        all *= vis[2 * d] * vis[2 * d + 1];
    }
    grad = vec3(0.0);
    for (int d = 0; d < DIM; d++) {
        float g = 0.0;
        for (int w = 2 * d; w <= 2 * d + 1; w++) {
            float others = 1.0;
            for (int o = 0; o < 2 * DIM; o++)
                if (o != w) others *= vis[o];
            g += dvis[w] * others;
        }
        grad[d] = -g;
    }
    return 1.0 - all;
}
#endif

// ---- cells and the seed's hash (src/core/sph_search.h) ----------------------
// floor, not truncation: the seed's int(x / h) made cell 0 twice as wide
// (everything in (-h, h)) and numbered negative cells one off. The hash is
// computed in uint, where overflow wraps; the seed's int arithmetic
// overflowed, which GLSL leaves undefined. Both bugs are fixed here.

int cell_coord(float x, float inv)
{
    float q = floor(x * inv);
    if (!(q > -1073741824.0)) return isnan(q) ? 0 : -1073741823;
    if (q >= 1073741824.0) return 1073741823;
    return int(q);
}

int cells_coord(int d, float x)
{
    int c = cell_coord(x - CELL_ORIGIN[d], CELL_INV[d]);
    if (CELL_COUNT[d] != 0) c = clamp(c, 0, CELL_COUNT[d] - 1);
    return c;
}

bool cells_step(int d, int c, int delta, out int o)
{
    int n = c + delta;
    o = n;
    if (CELL_COUNT[d] != 0 && (n < 0 || n >= CELL_COUNT[d])) {
        if (CELL_WRAP[d] == 0) return false;
        o = n < 0 ? n + CELL_COUNT[d] : n - CELL_COUNT[d];
    }
    return true;
}

uint cells_hash(ivec3 c)
{
#if DENSE
    return uint(c.x) + uint(CELL_COUNT.x) * (uint(c.y) + uint(CELL_COUNT.y) * uint(c.z));
#else
    uint h = uint(c.x) * 15823u + uint(c.y) * 9737333u;
    if (DIM == 3) h += uint(c.z) * 440817757u;
    return h;
#endif
}

float min_image(float dx, int d)
{
#if PERIODIC
    return dx - PER[d] * roundEven(dx * INV_PER[d]);
#else
    return dx;
#endif
}

float wrap_coord(float x, float lo, float p, float ip)
{
    float w = x - p * floor((x - lo) * ip);
    return w >= lo + p ? lo : w < lo ? lo : w;
}
