#include "sph_kernel.h"

#include <math.h>
#include <string.h>

const char *const sph_kernel_names[SPH_KERNEL_COUNT] = {
#define SPH_KERNEL_NAME(id, name, about) name,
    SPH_KERNELS(SPH_KERNEL_NAME)
#undef SPH_KERNEL_NAME
};

const char *const sph_kernel_about[SPH_KERNEL_COUNT] = {
#define SPH_KERNEL_ABOUT(id, name, about) about,
    SPH_KERNELS(SPH_KERNEL_ABOUT)
#undef SPH_KERNEL_ABOUT
};

/* Normalisation constants for support radius h, from integrating each shape
 * over the disc (2D) or ball (3D) of radius h. */
static double kernel_sigma(sph_kernel_kind kind, int dim, double h)
{
    const double pi = 3.14159265358979323846;
    int three = dim == 3;
    switch (kind) {
    case SPH_KERNEL_POLY6: return three ? 315.0 / (64.0 * pi * pow(h, 9)) : 4.0 / (pi * pow(h, 8));
    case SPH_KERNEL_SPIKY: return three ? 15.0 / (pi * pow(h, 6)) : 10.0 / (pi * pow(h, 5));
    case SPH_KERNEL_VISCOSITY: return three ? 15.0 / (2.0 * pi * pow(h, 3)) : 40.0 / (pi * h * h); /* 2D: 40/(pi h^5) * h^3 */
    case SPH_KERNEL_CUBIC: return three ? 8.0 / (pi * pow(h, 3)) : 40.0 / (7.0 * pi * h * h);
    case SPH_KERNEL_WENDLAND: return three ? 21.0 / (2.0 * pi * pow(h, 3)) : 7.0 / (pi * h * h);
    default: return 0.0;
    }
}

/* Second moment M2 = integral of r^2 W dV, by Simpson's rule on the radius.
 * The velocity-smoothing viscosity uses it to turn a kernel average into a
 * Laplacian: <v> - v ~ (M2 / 2d) lap v. */
static float kernel_second_moment(const sph_kernel *k)
{
    const double pi = 3.14159265358979323846;
    const int n = 2000;
    double dr = k->h / n, sum = 0.0;
    for (int i = 0; i <= n; i++) {
        double r = i * dr;
        double shell = k->dim == 3 ? 4.0 * pi * r * r : 2.0 * pi * r;
        double f = r * r * sph_kernel_w(k, (float)r) * shell;
        sum += f * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
    }
    return (float)(sum * dr / 3.0);
}

/* The wall tables. The plane integral at distance x from the centre is
 *   3D: A(x) = 2 pi int_x^h W(r) r dr  (rings of radius sqrt(r^2 - x^2))
 *   2D: A(x) = 2 int_0^sqrt(h^2-x^2) W(sqrt(x^2 + y^2)) dy
 * and psi(d) = int_d^h A(x) dx, both integrated on a fine grid in double. */
static void kernel_wall_tables(sph_kernel *k)
{
    enum { FINE = 16 * SPH_WALL_TABLE, STEPS = 512 };
    const double pi = 3.14159265358979323846, h = k->h, dx = h / FINE;
    double A[FINE + 1];
    for (int i = 0; i <= FINE; i++) {
        double x = i * dx, sum = 0;
        if (k->dim == 3) {
            double dr = (h - x) / STEPS;
            for (int s = 0; s < STEPS; s++) {
                double r = x + (s + 0.5) * dr;
                sum += sph_kernel_w(k, (float)r) * r * dr;
            }
            sum *= 2 * pi;
        } else {
            double ymax = sqrt(fmax(h * h - x * x, 0)), dy = ymax / STEPS;
            for (int s = 0; s < STEPS; s++) {
                double y = (s + 0.5) * dy;
                sum += sph_kernel_w(k, (float)sqrt(x * x + y * y)) * dy;
            }
            sum *= 2;
        }
        A[i] = sum;
    }
    double psi = 0; /* integrate from h down to 0 */
    for (int i = FINE; i >= 0; i--) {
        if (i < FINE) psi += 0.5 * (A[i] + A[i + 1]) * dx;
        if (i % 16 == 0) {
            k->wall_psi[i / 16] = (float)psi;
            k->wall_area[i / 16] = (float)A[i];
        }
    }
}

sph_kernel sph_kernel_make(sph_kernel_kind kind, int dim, float h)
{
    sph_kernel k;
    memset(&k, 0, sizeof k);
    k.kind = kind;
    k.dim = dim == 2 ? 2 : 3;
    k.h = h;
    k.h2 = h * h;
    k.inv_h = 1.0f / h;
    k.sigma = (float)kernel_sigma(kind, k.dim, h);
    k.m2 = kernel_second_moment(&k);
    kernel_wall_tables(&k);
    return k;
}

int sph_kernel_find(const char *name)
{
    for (int i = 0; i < SPH_KERNEL_COUNT; i++)
        if (strcmp(name, sph_kernel_names[i]) == 0) return i;
    return -1;
}
