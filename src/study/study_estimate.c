/* Kernel estimation, the first step of the seed: estimate a known smooth
 * function from scattered samples with the SPH sum
 *     <f>(x) = sum_j (m_j / rho_j) f(x_j) W(x - x_j, h)
 * and compare with f. Two errors add up:
 *   - the smoothing bias, <f> - f = (M2 / 2d) lap f + O(h^4): it grows as h^2;
 *   - the discreteness (noise) of the sum, which grows as the support holds
 *     fewer samples: small h, few samples.
 * In 1D the core has no kernels; the same shapes get their 1D normalisation
 * here (docs/accuracy.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "study.h"

const char *const study_function_names[STUDY_FN_COUNT] = {"sin", "gauss"};
const char *const study_samples_names[STUDY_SAMPLES_COUNT] = {"lattice", "jitter", "random"};

#define PI 3.14159265358979323846
#define GAUSS_WIDTH 0.1 /* sigma of the bump */

double study_kernel1d_sigma(sph_kernel_kind kind, double h)
{
    switch (kind) {
    case SPH_KERNEL_POLY6: return 35.0 / (32.0 * pow(h, 7)); /* 2 int_0^h (h^2-r^2)^3 dr = 32/35 h^7 */
    case SPH_KERNEL_SPIKY: return 2.0 / pow(h, 4);           /* 2 int_0^h (h-r)^3 dr = h^4/2 */
    case SPH_KERNEL_CUBIC: return 4.0 / (3.0 * h);           /* 2 h (11/32 + 1/32) = 3h/4 */
    case SPH_KERNEL_WENDLAND: return 3.0 / (2.0 * h);        /* 2 h int_0^1 (1-q)^4 (1+4q) dq = 2h/3 */
    default: return 0.0;
    }
}

double study_kernel1d_w(sph_kernel_kind kind, double h, double r)
{
    r = fabs(r);
    if (r >= h) return 0.0;
    double s = study_kernel1d_sigma(kind, h), q = r / h;
    switch (kind) {
    case SPH_KERNEL_POLY6: {
        double d = h * h - r * r;
        return s * d * d * d;
    }
    case SPH_KERNEL_SPIKY: {
        double d = h - r;
        return s * d * d * d;
    }
    case SPH_KERNEL_CUBIC:
        if (q <= 0.5) return s * (6.0 * (q * q * q - q * q) + 1.0);
        return s * 2.0 * (1.0 - q) * (1.0 - q) * (1.0 - q);
    case SPH_KERNEL_WENDLAND: {
        double d = 1.0 - q;
        return s * d * d * d * d * (1.0 + 4.0 * q);
    }
    default: return 0.0;
    }
}

double study_kernel_m2(sph_kernel_kind kind, int dim, double h)
{
    if (dim != 1) {
        sph_kernel k = sph_kernel_make(kind, dim, (float)h);
        return k.m2;
    }
    const int n = 20000; /* midpoint rule over [0, h), twice for both sides */
    double sum = 0, dr = h / n;
    for (int i = 0; i < n; i++) {
        double r = (i + 0.5) * dr;
        sum += r * r * study_kernel1d_w(kind, h, r);
    }
    return 2.0 * sum * dr;
}

/* f and its Laplacian at x (dim components). */
static double fn_value(study_function fn, int dim, const double *x, double *lap)
{
    if (fn == STUDY_FN_SIN) {
        double f = 1;
        for (int d = 0; d < dim; d++) f *= sin(2 * PI * x[d]);
        *lap = -dim * 4 * PI * PI * f;
        return f;
    }
    double r2 = 0, s2 = GAUSS_WIDTH * GAUSS_WIDTH;
    for (int d = 0; d < dim; d++) r2 += (x[d] - 0.5) * (x[d] - 0.5);
    double f = exp(-r2 / (2 * s2));
    *lap = f * (r2 / (s2 * s2) - dim / s2);
    return f;
}

/* splitmix64, as the core's jitter */
static uint64_t rng_next(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static double rng_unit(uint64_t *s) /* uniform in [0, 1) */
{
    return (double)(rng_next(s) >> 11) * (1.0 / 9007199254740992.0);
}

/* The samples in cells of size >= h over the unit square: a counting sort. */
typedef struct grid {
    int dim, cells;       /* cells per axis */
    double inv;           /* cells per unit length */
    long *start;          /* [cells^dim + 1] */
    long *order;          /* sample indices by cell */
} grid;

static int cell_of(const grid *g, double x)
{
    int c = (int)(x * g->inv);
    return c < 0 ? 0 : c >= g->cells ? g->cells - 1 : c;
}

static bool grid_build(grid *g, int dim, double h, const double *pos, long n)
{
    g->dim = dim;
    g->cells = (int)floor(1.0 / h);
    if (g->cells < 1) g->cells = 1;
    g->inv = g->cells;
    long nc = dim == 1 ? g->cells : (long)g->cells * g->cells;
    g->start = calloc((size_t)nc + 1, sizeof *g->start);
    g->order = malloc((size_t)(n ? n : 1) * sizeof *g->order);
    long *fill = calloc((size_t)nc + 1, sizeof *fill);
    if (!g->start || !g->order || !fill) {
        free(fill);
        return false;
    }
    long *key = malloc((size_t)(n ? n : 1) * sizeof *key);
    if (!key) {
        free(fill);
        return false;
    }
    for (long i = 0; i < n; i++) {
        long c = cell_of(g, pos[i * dim]);
        if (dim == 2) c += (long)cell_of(g, pos[i * dim + 1]) * g->cells;
        key[i] = c;
        g->start[c + 1]++;
    }
    for (long c = 0; c < nc; c++) g->start[c + 1] += g->start[c];
    for (long i = 0; i < n; i++) g->order[g->start[key[i]] + fill[key[i]]++] = i;
    free(key);
    free(fill);
    return true;
}

static void grid_free(grid *g)
{
    free(g->start);
    free(g->order);
}

typedef struct kern {
    int dim;
    sph_kernel k2; /* 2D: the core's kernel */
    sph_kernel_kind kind;
    double h;
} kern;

static double kern_w(const kern *k, double r)
{
    return k->dim == 1 ? study_kernel1d_w(k->kind, k->h, r) : (double)sph_kernel_w(&k->k2, (float)r);
}

/* sum_j c_j W(x - x_j), over the samples in the cells around x; also counts them. */
static double kernel_sum(const grid *g, const kern *k, const double *pos, const double *c, const double *x, long *count)
{
    int dim = g->dim;
    int cx = cell_of(g, x[0]), cy = dim == 2 ? cell_of(g, x[1]) : 0;
    double sum = 0, h2 = k->h * k->h;
    long cnt = 0;
    for (int oy = dim == 2 ? -1 : 0; oy <= (dim == 2 ? 1 : 0); oy++) {
        int yy = cy + oy;
        if (yy < 0 || yy >= g->cells) continue;
        for (int ox = -1; ox <= 1; ox++) {
            int xx = cx + ox;
            if (xx < 0 || xx >= g->cells) continue;
            long cell = xx + (long)yy * g->cells;
            for (long e = g->start[cell]; e < g->start[cell + 1]; e++) {
                long j = g->order[e];
                double r2 = 0;
                for (int d = 0; d < dim; d++) {
                    double dx = x[d] - pos[j * dim + d];
                    r2 += dx * dx;
                }
                if (r2 >= h2) continue;
                cnt++;
                sum += c[j] * kern_w(k, sqrt(r2));
            }
        }
    }
    if (count) *count = cnt;
    return sum;
}

bool study_estimate(const study_est_opts *o, double h, int n, study_est_result *r, char *why, size_t wn)
{
    memset(r, 0, sizeof *r);
    const int dim = o->dim;
    if (dim != 1 && dim != 2) {
        snprintf(why, wn, "dimension %d: 1 or 2", dim);
        return false;
    }
    if (o->kernel == SPH_KERNEL_VISCOSITY || (int)o->kernel < 0 || o->kernel >= SPH_KERNEL_COUNT) {
        snprintf(why, wn, "the viscosity kernel is meant for its Laplacian (it is singular at r = 0): "
                          "estimate with poly6, spiky, cubic or wendland");
        return false;
    }
    if (!(h > 0) || h > STUDY_EST_H_MAX) {
        snprintf(why, wn, "h = %g: want 0 < h <= %g (the support must stay inside the sampled unit %s)", h,
                 STUDY_EST_H_MAX, dim == 1 ? "interval" : "square");
        return false;
    }
    if (n < 2 || (dim == 1 && n > 10000000) || (dim == 2 && n > 4000)) {
        snprintf(why, wn, "%d samples per unit length: want 2 to %d", n, dim == 1 ? 10000000 : 4000);
        return false;
    }
    const long count = dim == 1 ? n : (long)n * n;
    const double spacing = 1.0 / n, vol = pow(spacing, dim);
    double *pos = malloc((size_t)count * dim * sizeof *pos);
    double *mass = malloc((size_t)count * sizeof *mass), *c = malloc((size_t)count * sizeof *c);
    double *rho = malloc((size_t)count * sizeof *rho);
    grid g = {0};
    bool ok = pos && mass && c && rho;
    if (ok) {
        uint64_t rng = o->seed;
        for (long i = 0; i < count; i++) {
            long node[2] = {i % n, i / n};
            for (int d = 0; d < dim; d++) {
                double x;
                if (o->samples == STUDY_SAMPLES_RANDOM)
                    x = rng_unit(&rng);
                else {
                    x = (node[d] + 0.5) * spacing;
                    if (o->samples == STUDY_SAMPLES_JITTER) x += o->jitter * spacing * (2 * rng_unit(&rng) - 1);
                    x = x < 0 ? 0 : x > 1 ? 1 : x;
                }
                pos[i * dim + d] = x;
            }
            mass[i] = vol; /* rho0 = 1 */
        }
        ok = grid_build(&g, dim, h, pos, count);
    }
    if (!ok) {
        snprintf(why, wn, "out of memory for %ld samples", count);
        free(pos), free(mass), free(c), free(rho), grid_free(&g);
        return false;
    }
    kern k = {dim, {0}, o->kernel, h};
    if (dim == 2) k.k2 = sph_kernel_make(o->kernel, 2, (float)h);
    /* rho_j by summation, for the samples that reach an evaluation point */
    const double lo = 0.25 - h - 1e-12, hi = 0.75 + h + 1e-12;
#pragma omp parallel for schedule(dynamic, 256)
    for (long j = 0; j < count; j++) {
        bool need = true;
        for (int d = 0; d < dim; d++) need &= pos[j * dim + d] >= lo && pos[j * dim + d] <= hi;
        rho[j] = need ? kernel_sum(&g, &k, pos, mass, pos + j * dim, NULL) : 0;
    }
    double lap;
    for (long j = 0; j < count; j++) c[j] = rho[j] > 0 ? mass[j] / rho[j] * fn_value(o->fn, dim, pos + j * dim, &lap) : 0;
    /* the evaluation points: a fixed grid over the centre */
    const int ne = dim == 1 ? 201 : 41;
    const long ntot = dim == 1 ? ne : (long)ne * ne;
    double se = 0, smax = 0, sb = 0, snb = 0;
    const double m2 = study_kernel_m2(o->kernel, dim, h);
#pragma omp parallel for schedule(static) reduction(+ : se, sb, snb) reduction(max : smax)
    for (long e = 0; e < ntot; e++) {
        double x[2] = {0.25 + 0.5 * (double)(e % ne) / (ne - 1), 0.25 + 0.5 * (double)(e / ne) / (ne - 1)};
        long cnt;
        double est = kernel_sum(&g, &k, pos, c, x, &cnt);
        double l, f = fn_value(o->fn, dim, x, &l);
        double err = est - f, b = m2 / (2.0 * dim) * l;
        se += err * err;
        smax = fmax(smax, fabs(err));
        sb += b * b;
        snb += (double)cnt;
    }
    r->error = sqrt(se / ntot);
    r->max_error = smax;
    r->bias = sqrt(sb / ntot);
    r->samples = (double)count;
    r->neighbours = snb / ntot;
    free(pos), free(mass), free(c), free(rho), grid_free(&g);
    return true;
}
