/* The ladder's levels and the benchmark scene. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "bench.h"

/* The ladder, one line per level. Each line names every search key it
 * relies on, so a level does not change when a default does. To add a
 * level, add a line (any scene key, `sphlab keys` lists them). */
const bench_level bench_levels[] = {
    {"L0", "brute force O(N^2) on 1 thread", "search.method=brute search.reorder=off search.vector=off", 1},
    {"L1", "spatial hash unsorted (linked lists)",
     "search.method=hash search.sort=none search.reorder=off search.vector=off", 1},
    {"L2", "hash + bitonic sort + offsets (the seed)",
     "search.method=hash search.sort=bitonic search.reorder=off search.vector=off", 1},
    {"L3", "counting sort", "search.method=hash search.sort=counting search.reorder=off search.vector=off", 1},
    {"L4", "particle data reordered by cell", "search.method=hash search.sort=counting search.reorder=on search.vector=off",
     1},
    {"L5", "OpenMP on all cores", "search.method=hash search.sort=counting search.reorder=on search.vector=off", 0},
    {"L6", "vectorised inner loops (AVX-512)",
     "search.method=hash search.sort=counting search.reorder=on search.vector=on", 0},
    {"L7", "dense grid: a stencil row is one run",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on", 0},
    /* The seed's GPU steps: the passes as GLSL compute shaders (src/gpu/), on
     * whatever OpenGL 4.3 device EGL gives (llvmpipe without a GPU). */
    {"G0", "GLSL: brute force", "compute.backend=gl search.method=brute search.reorder=off", 0},
    {"G1", "GLSL: hash + bitonic sort (the seed)",
     "compute.backend=gl search.method=hash search.sort=bitonic search.reorder=off", 0},
    {"G2", "GLSL: counting sort + reorder",
     "compute.backend=gl search.method=hash search.sort=counting search.reorder=on", 0},
    {"G3", "GLSL: dense grid: stencil rows",
     "compute.backend=gl search.method=grid search.sort=counting search.reorder=on", 0},
    /* Past L7 (docs/performance.md, "Past L7"): fewer gathers per neighbour. */
    {"L8", "L7 + pressure and viscosity in one walk",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on", 0},
    {"L9", "L8 + lists built in place (one copy less)",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on "
     "search.lists_in_place=on",
     0},
};
const int bench_level_count = (int)(sizeof bench_levels / sizeof bench_levels[0]);

int bench_level_find(const char *name)
{
    for (int i = 0; i < bench_level_count; i++)
        if (strcmp(bench_levels[i].name, name) == 0) return i;
    return -1;
}

bool bench_level_gl(const bench_level *L) { return strstr(L->sets, "compute.backend=gl") != NULL; }

int bench_levels_cores(void)
{
#ifdef _OPENMP
    return omp_get_num_procs();
#else
    return 1;
#endif
}

/* ---- sizes ----------------------------------------------------------------- */

int bench_k_min(int dim)
{
    return 2 * dim; /* n = 2 */
}

void bench_sides(int dim, int k, int side[3])
{
    int n = k / dim, j = k % dim;
    side[0] = n + (j >= 1);
    side[1] = n;
    side[2] = dim == 3 ? n + (j >= 2) : 1;
}

double bench_count(int dim, int k)
{
    int s[3];
    bench_sides(dim, k, s);
    return (double)s[0] * s[1] * s[2];
}

int bench_k_at_least(int dim, double n)
{
    int k = bench_k_min(dim);
    while (bench_count(dim, k) < n && k < 1 << 24) k++;
    return k;
}

int bench_k_near(int dim, double n)
{
    int k = bench_k_at_least(dim, n);
    if (k > bench_k_min(dim) && n - bench_count(dim, k - 1) <= bench_count(dim, k) - n) k--;
    return k;
}

/* ---- the scene ----------------------------------------------------------------- */

void bench_scene_ini(int dim, int k, double jitter, char *out, size_t cap)
{
    int side[3];
    bench_sides(dim, k, side);
    const double s = BENCH_SPACING;
    double L[3], box[3], lo[3], hi[3];
    for (int d = 0; d < 3; d++) {
        L[d] = side[d] * s;
        box[d] = 2 * L[d];       /* a box twice the block's size */
        lo[d] = 0.5 * L[d];      /* the block in its middle: it falls a quarter of the box */
        hi[d] = lo[d] + L[d] + 0.25 * s; /* a quarter spacing over: the node count never rounds down */
    }
    if (dim == 2)
        snprintf(out, cap,
                 "[scene]\nname = bench block 2D\ndimension = 2\neffects = gravity pressure viscosity walls\n"
                 "jitter = %g\n[domain]\nmin = 0 0\nmax = %.9g %.9g\n"
                 "[fluid block]\nmin = %.9g %.9g\nmax = %.9g %.9g\nspacing = %.9g\n",
                 jitter, box[0], box[1], lo[0], lo[1], hi[0], hi[1], s);
    else
        snprintf(out, cap,
                 "[scene]\nname = bench block 3D\ndimension = 3\neffects = gravity pressure viscosity walls\n"
                 "jitter = %g\n[domain]\nmin = 0 0 0\nmax = %.9g %.9g %.9g\n"
                 "[fluid block]\nmin = %.9g %.9g %.9g\nmax = %.9g %.9g %.9g\nspacing = %.9g\n",
                 jitter, box[0], box[1], box[2], lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], s);
    size_t len = strlen(out);
    snprintf(out + len, cap > len ? cap - len : 0,
             "[physics]\nrest_density = 1000\nstiffness = 1000\nviscosity = 0.002\nnegative_pressure = clamp\n"
             "[kernels]\nh = %.9g\n[time]\ncfl = 0.4\ndt = 0.001\n",
             2 * s);
}

/* Applies space-separated "section.key=value" overrides. */
static bool apply_sets(sph_scene_def *def, const char *sets, char *why, size_t n)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", sets ? sets : "");
    char *save = NULL;
    for (char *tok = strtok_r(buf, " \t", &save); tok; tok = strtok_r(NULL, " \t", &save)) {
        sph_error err;
        if (sph_scene_set(def, tok, &err) != SPH_ERR_OK) {
            snprintf(why, n, "%s", err.msg);
            return false;
        }
    }
    return true;
}

bool bench_scene_def(const bench_config *cfg, const bench_level *L, int k, bool check, sph_scene_def *def, char *why,
                     size_t n)
{
    char ini[2048];
    bench_scene_ini(cfg->dim, k, check ? BENCH_CHECK_JITTER : BENCH_JITTER, ini, sizeof ini);
    sph_error err;
    *def = sph_default_scene_def();
    if (sph_scene_load_string(ini, "bench scene", def, &err) != SPH_ERR_OK) {
        snprintf(why, n, "%s", err.msg);
        return false;
    }
    if (L && !apply_sets(def, L->sets, why, n)) return false;
    for (int i = 0; i < cfg->n_sets; i++) {
        if (cfg->set_level[i] && (!L || strcmp(cfg->set_level[i], L->name) != 0)) continue;
        if (!apply_sets(def, cfg->set[i], why, n)) return false;
    }
    if (sph_scene_validate(def, &err) != SPH_ERR_OK) {
        snprintf(why, n, "%s", err.msg);
        return false;
    }
    double want = bench_count(cfg->dim, k), got = sph_scene_particle_count(def);
    if (got != want) {
        snprintf(why, n, "the bench scene of size %d makes %.0f particles, not %.0f", k, got, want);
        return false;
    }
    return true;
}

bool bench_make_sim(const bench_config *cfg, const bench_level *L, int k, bool check, sph_sim **out, char *why,
                    size_t n)
{
    sph_scene_def def;
    if (!bench_scene_def(cfg, L, k, check, &def, why, n)) return false;
    sph_error err;
    if (sph_sim_create(&def, L ? L->threads : 0, out, &err) != SPH_ERR_OK) {
        snprintf(why, n, "%s", err.msg);
        return false;
    }
    return true;
}

/* ---- helpers ----------------------------------------------------------------- */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_median(double *v, int n)
{
    if (n <= 0) return NAN;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void bench_cpu_now(bench_cpu *c)
{
    c->busy_s = -1;
    c->wall_ms = sph_now_ms();
    struct rusage ru;
    c->self_s = getrusage(RUSAGE_SELF, &ru) == 0 ? (double)ru.ru_utime.tv_sec + ru.ru_utime.tv_usec * 1e-6 +
                                                        (double)ru.ru_stime.tv_sec + ru.ru_stime.tv_usec * 1e-6
                                                  : 0;
    FILE *f = fopen("/proc/stat", "r");
    if (!f) return;
    unsigned long long v[10] = {0};
    int n = fscanf(f, "cpu %llu %llu %llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1], &v[2], &v[3], &v[4],
                   &v[5], &v[6], &v[7], &v[8], &v[9]);
    fclose(f);
    long hz = sysconf(_SC_CLK_TCK);
    if (n < 8 || hz <= 0) return;
    /* user nice system idle iowait irq softirq steal: all but idle and iowait */
    c->busy_s = (double)(v[0] + v[1] + v[2] + v[5] + v[6] + v[7]) / (double)hz;
}

double bench_cpu_others(const bench_cpu *a, const bench_cpu *b)
{
    double wall = (b->wall_ms - a->wall_ms) / 1e3;
    if (a->busy_s < 0 || b->busy_s < 0 || wall <= 0) return NAN;
    double others = ((b->busy_s - a->busy_s) - (b->self_s - a->self_s)) / wall;
    return others > 0 ? others : 0;
}

void bench_loadavg(double out[3])
{
    out[0] = out[1] = out[2] = -1;
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f) return;
    if (fscanf(f, "%lf %lf %lf", &out[0], &out[1], &out[2]) != 3) out[0] = out[1] = out[2] = -1;
    fclose(f);
}

void bench_now_iso(char *out, size_t cap)
{
    time_t t = time(NULL);
    struct tm tm;
    if (!localtime_r(&t, &tm) || !strftime(out, cap, "%Y-%m-%dT%H:%M:%S%z", &tm)) snprintf(out, cap, "unknown");
}

void bench_fmt_count(char *out, size_t cap, double v)
{
    char digits[40];
    snprintf(digits, sizeof digits, "%.0f", v);
    size_t len = strlen(digits), o = 0;
    for (size_t i = 0; i < len && o + 2 < cap; i++) {
        out[o++] = digits[i];
        if (digits[i] != '-' && (len - 1 - i) % 3 == 0 && i + 1 < len) out[o++] = ',';
    }
    if (cap) out[o < cap ? o : cap - 1] = '\0';
}
