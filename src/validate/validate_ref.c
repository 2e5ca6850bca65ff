/* The published numbers and the exact solutions the problems of `sphlab
 * validate` are measured against (validate.h). */
#include "validate.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sph_walls.h"

#define PI 3.14159265358979323846

/* Martin, J. C. & Moyce, W. J. 1952, "Part IV. An experimental study of the
 * collapse of liquid columns on a rigid horizontal plane", Phil. Trans. R.
 * Soc. Lond. A 244:312-324, the n^2 = 2 columns: Z = front/a against
 * T = t sqrt(2g/a), read from their Figure 3 as PySPH's dam-break example
 * keeps them (pysph/examples/db_exp_data.py). */
static const double mm1_T[] = {0.849, 1.212, 1.602, 2.283, 2.950, 3.598, 3.905, 4.592, 4.961, 5.316};
static const double mm1_Z[] = {1.245, 1.443, 1.884, 2.689, 3.728, 4.528, 4.999, 5.841, 6.271, 6.717};
static const double mm2_T[] = {0.832, 1.219, 1.997, 2.547, 3.345, 4.034, 4.418, 5.091,
                               5.685, 6.306, 6.822, 7.439, 8.031, 8.633, 9.237};
static const double mm2_Z[] = {1.217, 1.474, 2.292, 2.995, 4.134, 4.944,  5.881,  6.980,
                               7.945, 8.966, 9.986, 10.963, 11.977, 13.005, 13.970};
/* Koshizuka, S. & Oka, Y. 1996, "Moving-particle semi-implicit method for
 * fragmentation of incompressible fluid", Nucl. Sci. Eng. 123:421-434, their
 * experiment (column L wide, 2L high): z/L against t sqrt(2g/L), as kept by
 * the same PySPH file. */
static const double ko_T[] = {0.0, 0.381, 0.769, 1.153, 1.537, 1.935, 2.323, 2.719, 3.096};
static const double ko_Z[] = {1.000, 1.111, 1.252, 1.505, 1.892, 2.241, 2.615, 3.003, 3.624};

/* Martin & Moyce 1952 (above), Table 6: the residual column of the n^2 = 2,
 * a = 2.25 in column, H = height at the back wall / (n^2 a) against
 * tau = t sqrt(g/a) (not T = n tau), as Ocellaris keeps them (T. Landet,
 * scripts/plot_dam_break.py, "Data from Martin and Moyce (1952), Table 2 and
 * 6", used there with n^2 = 2, a = 0.05715 m). Every H is a whole number of
 * quarter inches over 2a = 4.5 in (k/18, two decimals), as a table read off a
 * scale in the tank would be; and the top never falls faster than free fall
 * (H >= 1 - tau^2/4), which holds for tau = t sqrt(g/a) and not for
 * t sqrt(2g/a). */
static const double mm6_tau[] = {0.56, 0.77, 0.93, 1.08, 1.28, 1.46, 1.66, 1.84, 2.00,
                                 2.21, 2.45, 2.70, 3.06, 3.44, 4.20, 5.25, 7.40};
static const double mm6_H[] = {0.94, 0.89, 0.83, 0.78, 0.72, 0.67, 0.61, 0.56, 0.50,
                               0.44, 0.39, 0.33, 0.28, 0.22, 0.17, 0.11, 0.06};

/* Martin & Moyce 1952 (above), Table 2: the surge front of the same n^2 = 2,
 * a = 2.25 in column, Z = front / a against T = n t sqrt(g/a), as Ocellaris
 * keeps it beside Table 6 (same file). Every Z is a whole number of quarter
 * inches of front travel over a = 2.25 in (Z = 1 + k/9, two decimals), as for
 * Table 6; it agrees with the Figure 3 curve of the same column (val_surge[1])
 * within 3 % (0.09 in Z at most: the figure's points are sparser). */
static const double mm2t_T[] = {0.41, 0.84, 1.19, 1.43, 1.63, 1.83, 1.98, 2.20,
                                2.32, 2.51, 2.65, 2.83, 2.98, 3.11, 3.33};
static const double mm2t_Z[] = {1.11, 1.22, 1.44, 1.67, 1.89, 2.11, 2.33, 2.56,
                                2.78, 3.00, 3.22, 3.44, 3.67, 3.89, 4.11};

#define N(a) ((int)(sizeof a / sizeof a[0]))
const val_curve val_surge[VAL_SURGE_CURVES] = {
    {"Martin & Moyce 1952, a = 1.125 in (Fig. 3)", "Martin & Moyce 1952, Fig. 3", mm1_T, mm1_Z, N(mm1_T)},
    {"Martin & Moyce 1952, a = 2.25 in (Fig. 3)", "Martin & Moyce 1952, Fig. 3", mm2_T, mm2_Z, N(mm2_T)},
    {"Koshizuka & Oka 1996, experiment", "Koshizuka & Oka 1996", ko_T, ko_Z, N(ko_T)},
};
const val_curve val_surge_table2 = {"Martin & Moyce 1952, a = 2.25 in (Table 2)", "Martin & Moyce 1952, Table 2",
                                    mm2t_T, mm2t_Z, N(mm2t_T)};
const val_curve val_column = {"Martin & Moyce 1952, a = 2.25 in (Table 6)", "Martin & Moyce 1952, Table 6", mm6_tau, mm6_H,
                              N(mm6_tau)};

double val_curve_at(const val_curve *c, double x)
{
    if (c->n < 1 || !(x >= c->x[0]) || !(x <= c->x[c->n - 1])) return NAN;
    for (int i = 1; i < c->n; i++)
        if (x <= c->x[i]) {
            double f = (x - c->x[i - 1]) / (c->x[i] - c->x[i - 1]);
            return c->y[i - 1] + f * (c->y[i] - c->y[i - 1]);
        }
    return c->y[c->n - 1];
}

/* The density the equation of state gives pressure p (validate.h). */
static double eos_rho(const val_eos *e, double p)
{
    if (e->tait_gamma > 0) return e->rho0 * pow(1.0 + p * e->tait_gamma / (e->k * e->rho0), 1.0 / e->tait_gamma);
    return e->rho0 + p / e->k;
}

double val_hydrostatic_p(const val_eos *e, double g, double H0, double y)
{
    /* dp/dy = -rho(p) g from the floor, where the column's whole weight
     * rho0 g H0 rests: classic RK4 in steps of at most H0 / 1000 */
    double p = e->rho0 * g * H0;
    int n = (int)ceil(fabs(y) / (H0 / 1000.0));
    if (n < 1) return p;
    double dy = y / n;
    for (int i = 0; i < n; i++) {
        double k1 = -g * eos_rho(e, p), k2 = -g * eos_rho(e, p + 0.5 * dy * k1);
        double k3 = -g * eos_rho(e, p + 0.5 * dy * k2), k4 = -g * eos_rho(e, p + dy * k3);
        p += dy / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    return p;
}

double val_hydrostatic_column(const sph_sim *sim, val_eos *e)
{
    const sph_scene_def *def = &sim->def;
    double mass = 0;
    for (uint32_t i = 0; i < sim->n; i++)
        if (!sph_is_wall(&sim->P, i)) mass += sim->P.mass[i];
    if (def->pressure_solver != SPH_PSOLVER_EOS) { /* pcisph, dfsph: incompressible, p = rho0 g (H - y) */
        *e = (val_eos){def->rest_density, INFINITY, 0.0};
        return mass / (def->rest_density * ((double)def->domain_max[0] - def->domain_min[0]));
    }
    const double rho0 = sim->eos_rho0; /* the equation of state's p = 0, as pressure.c's */
    *e = (val_eos){rho0, def->stiffness, def->eos == SPH_EOS_TAIT ? def->tait_gamma : 0.0};
    return mass / (rho0 * ((double)def->domain_max[0] - def->domain_min[0]));
}

double val_poiseuille_steady(double y, double F, double nu, double L)
{
    return F / (2.0 * nu) * y * (L - y);
}

double val_poiseuille(double y, double t, double F, double nu, double L, int terms)
{
    double u = val_poiseuille_steady(y, F, nu, L);
    for (int n = 0; n < terms; n++) {
        double m = 2.0 * n + 1.0;
        u -= 4.0 * F * L * L / (nu * PI * PI * PI * m * m * m) * sin(PI * y * m / L) * exp(-m * m * PI * PI * nu * t / (L * L));
    }
    return u;
}

double val_couette(double y, double t, double U, double nu, double L, int terms)
{
    double u = U * y / L;
    for (int n = 1; n <= terms; n++)
        u += 2.0 * U * (n % 2 ? -1.0 : 1.0) / (n * PI) * sin(n * PI * y / L) * exp(-(double)n * n * PI * PI * nu * t / (L * L));
    return u;
}

double val_tg_decay(double nu, double L, double t)
{
    return exp(-8.0 * PI * PI * nu / (L * L) * t);
}

void val_tg_velocity(double x, double y, double t, double U, double nu, double L, double v[2])
{
    double e = U * val_tg_decay(nu, L, t), k = 2.0 * PI / L;
    v[0] = e * sin(k * x) * cos(k * y);
    v[1] = -e * cos(k * x) * sin(k * y);
}

double val_order(double r1, double e1, double r2, double e2)
{
    if (!(e1 > 0) || !(e2 > 0) || !(r1 > 0) || !(r2 > 0) || r1 == r2) return NAN;
    return log(e1 / e2) / log(r2 / r1);
}

double val_period_crossings(const double *x, const double *y, size_t n, int *k)
{
    double mean = 0;
    for (size_t i = 0; i < n; i++) mean += y[i];
    mean /= (double)(n ? n : 1);
    double first = NAN, last_even = NAN;
    *k = 0;
    for (size_t i = 1; i < n; i++) {
        double a = y[i - 1] - mean, b = y[i] - mean;
        if ((a < 0) == (b < 0) || a == b) continue;
        double t = x[i - 1] + (x[i] - x[i - 1]) * a / (a - b);
        if (*k == 0) first = t;
        if (*k % 2 == 0) last_even = t; /* an even number of half periods after the first */
        (*k)++;
    }
    return *k >= 3 ? 2.0 * (last_even - first) / (double)(2 * ((*k - 1) / 2)) : NAN;
}

int val_crossing_times(const double *x, const double *y, size_t n, double *t, int max)
{
    double mean = 0;
    for (size_t i = 0; i < n; i++) mean += y[i];
    mean /= (double)(n ? n : 1);
    int k = 0;
    for (size_t i = 1; i < n && k < max; i++) {
        double a = y[i - 1] - mean, b = y[i] - mean;
        if ((a < 0) == (b < 0) || a == b) continue;
        t[k++] = x[i - 1] + (x[i] - x[i - 1]) * a / (a - b);
    }
    return k;
}

double val_half_period_spread(const double *t, int k)
{
    if (k < 3) return NAN;
    double lo = INFINITY, hi = 0, sum = 0;
    for (int i = 1; i < k; i++) {
        double h = t[i] - t[i - 1];
        lo = fmin(lo, h), hi = fmax(hi, h), sum += h;
    }
    return (hi - lo) / (sum / (k - 1));
}

double val_half_period_bound(double periods, double decay)
{
    if (!(periods > 0) || !(decay >= 1)) return NAN;
    return 4.0 * asin(fmin(1.0, decay / (PI * periods))) / PI;
}

double val_amplitude_ratio(const double *x, const double *y, size_t n, const double *t, int k)
{
    if (k < 3) return NAN;
    double mean = 0, first = 0, last = 0;
    for (size_t i = 0; i < n; i++) mean += y[i];
    mean /= (double)n;
    for (size_t i = 0; i < n; i++) {
        if (x[i] >= t[0] && x[i] <= t[1]) first = fmax(first, fabs(y[i] - mean));
        if (x[i] >= t[k - 2] && x[i] <= t[k - 1]) last = fmax(last, fabs(y[i] - mean));
    }
    return last > 0 ? fmax(1.0, first / last) : NAN;
}

void val_period_text(char *buf, size_t n, double T, double T_ray, int crossings)
{
    /* which half periods the period is read from (val_period_crossings: whole periods only), so that a reader
     * who averages the listed half periods knows why the figure differs */
    char over[96] = "";
    const int halves = crossings - 1, used = 2 * (halves / 2);
    if (isfinite(T) && used == halves)
        snprintf(over, sizeof over, " (from its %d half periods)", halves);
    else if (isfinite(T))
        snprintf(over, sizeof over, " (from the first %d of its %d half periods: whole periods only)", used, halves);
    if (isfinite(T) && isfinite(T_ray))
        snprintf(buf, n, "period %.4g s%s vs Rayleigh %.4g s (%+.1f%%)", T, over, T_ray, 100 * (T / T_ray - 1));
    else if (isfinite(T))
        snprintf(buf, n, "period %.4g s%s; no Rayleigh period (sigma not measurable)", T, over);
    else if (isfinite(T_ray)) /* a NaN is no figure: say why there is none */
        snprintf(buf, n, "no period: %d crossing%s of the mean in the run (3 needed), Rayleigh %.4g s", crossings,
                 crossings == 1 ? "" : "s", T_ray);
    else
        snprintf(buf, n, "no period: %d crossing%s of the mean in the run (3 needed)", crossings,
                 crossings == 1 ? "" : "s");
}

static size_t uf_root(size_t *parent, size_t i)
{
    while (parent[i] != i) i = parent[i] = parent[parent[i]]; /* path halving */
    return i;
}

double val_front_connected(const double *x, const double *y, size_t n, double link, size_t *body)
{
    if (body) *body = 0;
    if (n == 0 || !(link > 0)) return NAN;
    double x0 = x[0], x1 = x[0], y0 = y[0], y1 = y[0];
    for (size_t i = 1; i < n; i++) x0 = fmin(x0, x[i]), x1 = fmax(x1, x[i]), y0 = fmin(y0, y[i]), y1 = fmax(y1, y[i]);
    /* cells at least `link` wide, so a link joins the same or a neighbouring
     * cell; widened when the box would need more than 4 n cells */
    double cell = link;
    size_t nx, ny;
    for (;;) {
        nx = (size_t)((x1 - x0) / cell) + 1;
        ny = (size_t)((y1 - y0) / cell) + 1;
        if ((double)nx * (double)ny <= 4.0 * (double)n + 64) break;
        cell *= 2;
    }
    size_t *parent = malloc(n * sizeof *parent), *cell_of = malloc(n * sizeof *cell_of);
    size_t *order = malloc(n * sizeof *order), *start = calloc(nx * ny + 1, sizeof *start);
    size_t *size = NULL;
    double front = NAN;
    if (!parent || !cell_of || !order || !start) goto out;
    for (size_t i = 0; i < n; i++) {
        size_t cx = (size_t)((x[i] - x0) / cell), cy = (size_t)((y[i] - y0) / cell);
        cell_of[i] = (cy < ny ? cy : ny - 1) * nx + (cx < nx ? cx : nx - 1);
        start[cell_of[i] + 1]++;
        parent[i] = i;
    }
    for (size_t c = 0; c < nx * ny; c++) start[c + 1] += start[c];
    for (size_t i = 0; i < n; i++) order[start[cell_of[i]]++] = i; /* start[c] now ends cell c */
    for (size_t c = nx * ny; c > 0; c--) start[c] = start[c - 1];
    start[0] = 0;
    double link2 = link * link;
    for (size_t i = 0; i < n; i++) {
        size_t cx = cell_of[i] % nx, cy = cell_of[i] / nx;
        for (size_t yy = cy ? cy - 1 : 0; yy <= cy + 1 && yy < ny; yy++)
            for (size_t xx = cx ? cx - 1 : 0; xx <= cx + 1 && xx < nx; xx++)
                for (size_t k = start[yy * nx + xx]; k < start[yy * nx + xx + 1]; k++) {
                    size_t j = order[k];
                    double dx = x[i] - x[j], dy = y[i] - y[j];
                    if (j <= i || dx * dx + dy * dy >= link2) continue;
                    size_t a = uf_root(parent, i), b = uf_root(parent, j);
                    if (a != b) parent[a] = b;
                }
    }
    size = calloc(n, sizeof *size);
    if (!size) goto out;
    size_t best = 0;
    for (size_t i = 0; i < n; i++) {
        size_t r = uf_root(parent, i);
        if (++size[r] > size[best] || (size[r] == size[best] && r < best)) best = r;
    }
    for (size_t i = 0; i < n; i++)
        if (uf_root(parent, i) == best && !(x[i] <= front)) front = x[i];
    if (body) *body = size[best];
out:
    free(parent), free(cell_of), free(order), free(start), free(size);
    return front;
}
