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
// the density kernel's lattice share [WALL_TABLE + 1], its slope
// [WALL_TABLE + 1], the corner share and its slope [(WALL_CORNER + 1)^2
// each] (src/gpu/gpu_backend.c)
layout(std430, binding = B_WALL) buffer BufWall { float wall_[]; };
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
#if USE_CSF
// the csf pass's sweeps (shaders/gpu_csf.comp): each particle's surface
// density lam [1/m^(DIM-1)] at i, its raw curvature [1/m] at N + i
layout(std430, binding = B_CSF) buffer BufCsf { float csf_[]; };
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
// The lattice share and its slope (sph_kernel_wall_lat).
float kernel_wall(int base, float d, out float area)
{
    float t = d * INV_H * float(WALL_TABLE);
    if (!(t < float(WALL_TABLE))) { area = 0.0; return 0.0; }
    if (t < 0.0) t = 0.0;
    int i = int(t);
    float f = t - float(i);
    int p = base + i, a = base + WALL_TABLE + 1 + i;
    area = wall_[a] + f * (wall_[a + 1] - wall_[a]);
    return wall_[p] + f * (wall_[p + 1] - wall_[p]);
}

// Bilinear in a (WALL_CORNER + 1)^2 table at index tab (sph_kernel_corner_lerp).
float corner_lerp(int tab, int a, int b, float fa, float fb)
{
    const int n = WALL_CORNER + 1;
    float lo = wall_[tab + a * n + b] + fb * (wall_[tab + a * n + b + 1] - wall_[tab + a * n + b]);
    float hi = wall_[tab + (a + 1) * n + b] + fb * (wall_[tab + (a + 1) * n + b + 1] - wall_[tab + (a + 1) * n + b]);
    return lo + fa * (hi - lo);
}

// The corner share beyond two walls and its slopes (sph_kernel_wall_corner).
float kernel_corner(int base, float d1, float d2, out float s1, out float s2)
{
    const float c = float(WALL_CORNER);
    float t1 = d1 * INV_H * c, t2 = d2 * INV_H * c;
    if (!(t1 < c) || !(t2 < c)) { s1 = 0.0; s2 = 0.0; return 0.0; }
    if (t1 < 0.0) t1 = 0.0;
    if (t2 < 0.0) t2 = 0.0;
    int i1 = int(t1), i2 = int(t2);
    float f1 = t1 - float(i1), f2 = t2 - float(i2);
    int tab = base + 2 * (WALL_TABLE + 1), slope = tab + (WALL_CORNER + 1) * (WALL_CORNER + 1);
    s1 = corner_lerp(slope, i1, i2, f1, f2);
    s2 = corner_lerp(slope, i2, i1, f2, f1);
    return corner_lerp(tab, i1, i2, f1, f2);
}

// Share of the support hidden behind the domain walls, and its gradient
// (sph_wall_hidden in src/core/sph_walls.h: inclusion-exclusion over the walls),
// of the kernel whose tables start at base in wall_ (full: its lattice sum).
float wall_hidden_of(int base, float full, vec3 x, out vec3 grad)
{
    float dist[6], sgn[6];
    int axis[6], nw = 0;
    float hidden = 0.0;
    grad = vec3(0.0);
    for (int d = 0; d < DIM; d++) {
        if (PER[d] > 0.0) continue;
        for (int side = 0; side < 2; side++) {
            float ds = side == 0 ? x[d] - DOM_MIN[d] : DOM_MAX[d] - x[d], area;
            float share = kernel_wall(base, ds, area);
            if (share == 0.0 && area == 0.0) continue;
            dist[nw] = ds;
            sgn[nw] = side == 1 ? -1.0 : 1.0;
            axis[nw] = d;
            hidden += share;
            grad[d] -= area * sgn[nw];
            nw++;
        }
    }
    for (int a = 0; a < nw; a++)
        for (int b = a + 1; b < nw; b++) {
            if (axis[a] == axis[b]) continue;
            float sa, sb, both = kernel_corner(base, dist[a], dist[b], sa, sb);
            hidden -= both;
            grad[axis[a]] += sa * sgn[a];
            grad[axis[b]] += sb * sgn[b];
            for (int c = b + 1; c < nw; c++) {
                if (axis[c] == axis[a] || axis[c] == axis[b]) continue;
                float ac1, ac3, bc2, bc3;
                float ac = kernel_corner(base, dist[a], dist[c], ac1, ac3);
                float bc = kernel_corner(base, dist[b], dist[c], bc2, bc3);
                if (!(both > 0.0 && ac > 0.0 && bc > 0.0)) continue;
                float all = sqrt(both * ac * bc / full);
                hidden += all;
                grad[axis[a]] -= 0.5 * all * (sa / both + ac1 / ac) * sgn[a];
                grad[axis[b]] -= 0.5 * all * (sb / both + bc2 / bc) * sgn[b];
                grad[axis[c]] -= 0.5 * all * (ac3 / ac + bc3 / bc) * sgn[c];
            }
        }
    return hidden;
}

// The density kernel's (density, continuity, DFSPH).
float wall_hidden(vec3 x, out vec3 grad) { return wall_hidden_of(0, WALL_FULL, x, grad); }

// The pressure solvers' walls (sph_solver_walls in src/passes/solver.h): the
// share of RHO_R the fluid's lattice continued behind the walls adds at x,
// combined over walls as 1 - prod (1 - share), and its gradient [1/m]; the
// table follows the density kernel's in wall_ (src/gpu/gpu_backend.c).
float solver_walls(vec3 x, out vec3 grad)
{
    float vis[6], dvis[6], all = 1.0;
    for (int d = 0; d < DIM; d++)
        for (int side = 0; side < 2; side++) {
            int w = 2 * d + side;
            vis[w] = 1.0;
            dvis[w] = 0.0;
            if (PER[d] > 0.0) continue; // no walls on a periodic axis
            float dist = side == 0 ? x[d] - DOM_MIN[d] : DOM_MAX[d] - x[d];
            float t = max(dist, 0.0) * SOLVER_WALL_SCALE;
            if (!(t < float(SOLVER_WALL_SAMPLES))) continue;
            int i = int(t);
            float f = t - float(i);
            int a = SOLVER_WALL_AT + i, b = SOLVER_WALL_AT + SOLVER_WALL_SAMPLES + 1 + i;
            vis[w] = 1.0 - (wall_[a] + f * (wall_[a + 1] - wall_[a]));
            float slope = wall_[b] + f * (wall_[b + 1] - wall_[b]);
            dvis[w] = side == 0 ? -slope : slope; // d(visible)/dx along the axis
            all *= vis[w];
        }
    grad = vec3(0.0);
    for (int d = 0; d < DIM; d++)
        for (int w = 2 * d; w <= 2 * d + 1; w++) {
            float others = 1.0;
            for (int o = 0; o < 2 * DIM; o++)
                if (o != w) others *= vis[o];
            grad[d] -= dvis[w] * others;
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
