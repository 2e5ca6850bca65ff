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
    return k;
}

int sph_kernel_find(const char *name)
{
    for (int i = 0; i < SPH_KERNEL_COUNT; i++)
        if (strcmp(name, sph_kernel_names[i]) == 0) return i;
    return -1;
}
