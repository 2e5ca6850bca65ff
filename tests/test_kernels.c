/* Smoothing kernels against analysis: normalisation, support, gradient and
 * Laplacian against finite differences, the viscosity kernel's closed-form
 * Laplacians, the second moment, lookup by name, and the antisymmetry of the
 * gradient over a symmetric lattice. Every kernel in 2D and 3D, with h = 0.7
 * (not 1) so that a wrong power of h shows. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "test_util.h"

#define H 0.7f
static const double pi = 3.14159265358979323846;

static const char *name_of(const sph_kernel *k) { return sph_kernel_names[k->kind]; }

/* Area of the circle (2D) or sphere (3D) of radius r: the radial weight of dV. */
static double shell(int dim, double r) { return dim == 3 ? 4.0 * pi * r * r : 2.0 * pi * r; }

/* Integral of r^p W dV over the support by the midpoint rule on the radius
 * (20000 intervals, in double). The midpoints never touch r = 0, where the
 * viscosity kernel is singular (ln r in 2D, 1/r in 3D): the singularity is
 * integrable and its first interval contributes O(dr^2 ln dr) at most. */
static double radial_integral(const sph_kernel *k, int p)
{
    const int n = 20000;
    double h = k->h, dr = h / n, sum = 0;
    for (int i = 0; i < n; i++) {
        double r = (i + 0.5) * dr;
        sum += pow(r, p) * sph_kernel_w(k, (float)r) * shell(k->dim, r);
    }
    return sum * dr;
}

/* Radii in (lo h, hi h) for the derivative checks; for the cubic spline they
 * stay 0.01 h away from its knot q = 0.5 (the finite difference steps are
 * 1e-3 h, so no stencil straddles it). */
static int sample_radii(const sph_kernel *k, double lo, double hi, float *r, int cap)
{
    int n = 0;
    const int m = 41;
    for (int j = 0; j < m && n < cap; j++) {
        double q = lo + (hi - lo) * (j + 0.5) / m;
        if (k->kind == SPH_KERNEL_CUBIC && fabs(q - 0.5) < 0.01) continue;
        r[n++] = (float)(q * k->h);
    }
    return n;
}

Test(kernels, normalised_to_one)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int kind = 0; kind < SPH_KERNEL_COUNT; kind++) {
            sph_kernel k = sph_kernel_make((sph_kernel_kind)kind, dim, H);
            double integral = radial_integral(&k, 0);
            /* 1e-3: the midpoint rule with 20000 intervals is far more accurate
             * (float W costs ~1e-7); a wrong constant or power of h is off by
             * far more than 1e-3. */
            cr_assert(fabs(integral - 1.0) <= 1e-3, "%dD %s: integral of W = %.9g, want 1", dim, name_of(&k),
                      integral);
        }
}

/* The midpoint rule does handle the viscosity kernel's singularity at r = 0:
 * halving the intervals changes nothing beyond 1e-4. */
Test(kernels, viscosity_singularity_is_integrated)
{
    for (int dim = 2; dim <= 3; dim++) {
        sph_kernel k = sph_kernel_make(SPH_KERNEL_VISCOSITY, dim, H);
        const int n = 10000;
        double dr = k.h / n, coarse = 0;
        for (int i = 0; i < n; i++) {
            double r = (i + 0.5) * dr;
            coarse += sph_kernel_w(&k, (float)r) * shell(dim, r) * dr;
        }
        double fine = radial_integral(&k, 0);
        cr_assert(fabs(fine - coarse) <= 1e-4, "%dD viscosity: 10000 intervals give %.9g, 20000 give %.9g", dim,
                  coarse, fine);
        /* and the kernel really is singular there: W(1e-3 h) >> W(0.5 h) */
        cr_assert_gt(sph_kernel_w(&k, 1e-3f * k.h), 20.0f * sph_kernel_w(&k, 0.5f * k.h));
    }
}

Test(kernels, non_negative_with_compact_support)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int kind = 0; kind < SPH_KERNEL_COUNT; kind++) {
            sph_kernel k = sph_kernel_make((sph_kernel_kind)kind, dim, H);
            /* Every kernel but the viscosity one is a product of non-negative
             * float factors: W >= 0 exactly. The viscosity kernel is a sum of
             * terms of size ~0.5 sigma that cancel to sigma (1 - q)^3 / 6 near
             * h (2D; alike in 3D), so float can dip below 0 by a few rounding
             * errors of the terms: allowed down to -FLT_EPSILON sigma. */
            float floor_w = kind == SPH_KERNEL_VISCOSITY ? -FLT_EPSILON * k.sigma : 0.0f;
            const int n = 20000;
            for (int i = 0; i < n; i++) {
                float r = (float)((double)i / n * k.h);
                float w = sph_kernel_w(&k, r);
                cr_assert(w >= floor_w, "%dD %s: W(%.9g) = %g < %g", dim, name_of(&k), r, w, floor_w);
            }
            float below = nextafterf(k.h, 0.0f);
            cr_assert(sph_kernel_w(&k, below) >= floor_w, "%dD %s: W just below h is %g", dim, name_of(&k),
                      sph_kernel_w(&k, below));
            /* at and beyond the support radius: exactly 0, value and derivatives */
            const float outside[] = {k.h, nextafterf(k.h, 2.0f * k.h), 1.001f * k.h, 2.0f * k.h, 100.0f * k.h};
            for (int j = 0; j < 5; j++) {
                cr_assert(sph_kernel_w(&k, outside[j]) == 0.0f, "%dD %s: W(%.9g) = %g, want 0", dim, name_of(&k),
                          outside[j], sph_kernel_w(&k, outside[j]));
                cr_assert(sph_kernel_dw(&k, outside[j]) == 0.0f, "%dD %s: dW(%.9g) != 0", dim, name_of(&k),
                          outside[j]);
                cr_assert(sph_kernel_lap(&k, outside[j]) == 0.0f, "%dD %s: lap W(%.9g) != 0", dim, name_of(&k),
                          outside[j]);
            }
            /* positive inside the support (so W >= 0 above is not vacuous) */
            cr_assert_gt(sph_kernel_w(&k, 0.5f * k.h), 0.0f);
        }
}

/* dW/dr against the central difference (W(r + d) - W(r - d)) / 2d, d = 1e-3 h.
 * Error budget: truncation d^2 W'''/6 ~ 1e-6 of the scale; float round-off in
 * W (~1e-7 relative) divided by 2d gives ~1e-4 of max|dW|. Tolerance 2e-3 of
 * max|dW| over the samples: 20x the budget, still far below the error of a
 * wrong factor or sign. */
Test(kernels, gradient_matches_finite_difference)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int kind = 0; kind < SPH_KERNEL_COUNT; kind++) {
            sph_kernel k = sph_kernel_make((sph_kernel_kind)kind, dim, H);
            float r[64];
            int n = sample_radii(&k, 0.05, 0.95, r, 64);
            double scale = 0;
            for (int j = 0; j < n; j++) scale = fmax(scale, fabs(sph_kernel_dw(&k, r[j])));
            cr_assert_gt(scale, 0.0);
            const float d = 1e-3f * k.h;
            for (int j = 0; j < n; j++) {
                double fd = ((double)sph_kernel_w(&k, r[j] + d) - sph_kernel_w(&k, r[j] - d)) /
                            ((double)(r[j] + d) - (double)(r[j] - d));
                double dw = sph_kernel_dw(&k, r[j]);
                cr_assert(fabs(dw - fd) <= 2e-3 * scale, "%dD %s at r = %.4g h: dW = %.7g, finite difference %.7g",
                          dim, name_of(&k), r[j] / k.h, dw, fd);
            }
            /* the gradient points inwards (every kernel decreases): dW < 0 */
            cr_assert_lt(sph_kernel_dw(&k, 0.5f * k.h), 0.0f, "%dD %s", dim, name_of(&k));
            cr_assert(sph_kernel_dw(&k, 0.0f) == 0.0f, "%dD %s: dW(0) must be 0", dim, name_of(&k));
        }
}

/* lap W = W'' + (d - 1) W'/r with W'' the central difference of dW (step
 * 1e-3 h). For the viscosity kernel the two terms are ~1/q^3 each and cancel
 * to ~(1 - q), so the tolerance is relative to the size of the terms, not of
 * the result: 2e-3 (|W''| + (d - 1)|W'/r|) at each r. Truncation error
 * d^2 W''''/6 is below 1e-4 of that scale at r >= 0.1 h, float round-off in
 * dW / 2d about 1e-4. */
Test(kernels, laplacian_matches_finite_difference)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int kind = 0; kind < SPH_KERNEL_COUNT; kind++) {
            sph_kernel k = sph_kernel_make((sph_kernel_kind)kind, dim, H);
            float r[64];
            int n = sample_radii(&k, 0.1, 0.9, r, 64);
            const float d = 1e-3f * k.h;
            for (int j = 0; j < n; j++) {
                double w2 = ((double)sph_kernel_dw(&k, r[j] + d) - sph_kernel_dw(&k, r[j] - d)) /
                            ((double)(r[j] + d) - (double)(r[j] - d));
                double w1r = (double)sph_kernel_dw(&k, r[j]) / r[j];
                double want = w2 + (dim - 1) * w1r;
                double lap = sph_kernel_lap(&k, r[j]);
                double tol = 2e-3 * (fabs(w2) + (dim - 1) * fabs(w1r));
                cr_assert(fabs(lap - want) <= tol, "%dD %s at r = %.4g h: lap = %.7g, W'' + (d-1) W'/r = %.7g", dim,
                          name_of(&k), r[j] / k.h, lap, want);
            }
        }
}

/* The viscosity kernel's Laplacians in closed form (sph_kernel.h):
 * 45/(pi h^6)(h - r) in 3D, 40/(pi h^5)(h - r) in 2D. The 2D form is one
 * product (tolerance 1e-5 of lap(0): float round-off). The 3D one cancels two
 * terms ~1/q^3 in float: tolerance 1e-5 of lap(0) plus 16 float epsilons of
 * the cancelled terms' size, sigma/h^2 / q^3 (checked from r = 0.05 h). */
Test(kernels, viscosity_laplacian_closed_form)
{
    for (int dim = 2; dim <= 3; dim++) {
        sph_kernel k = sph_kernel_make(SPH_KERNEL_VISCOSITY, dim, H);
        double h = k.h;
        double c = dim == 3 ? 45.0 / (pi * pow(h, 6)) : 40.0 / (pi * pow(h, 5));
        const int m = 200;
        for (int j = 0; j < m; j++) {
            double q = 0.05 + 0.95 * j / m;
            float r = (float)(q * h);
            double want = c * (h - r);
            double tol = 1e-5 * c * h;
            if (dim == 3) tol += 16 * FLT_EPSILON * k.sigma / (h * h) / (q * q * q);
            double lap = sph_kernel_lap(&k, r);
            cr_assert(fabs(lap - want) <= tol, "%dD viscosity at r = %.4g h: lap = %.9g, want %.9g", dim, q, lap,
                      want);
        }
    }
}

/* k.m2 = integral of r^2 W dV (the library's Simpson rule, n = 2000, stored
 * in float) against the midpoint rule with 20000 intervals: 1e-3 relative
 * (both rules are good to ~1e-6 here; float storage ~1e-7). For poly6 also
 * against the closed form, within 1e-4:
 *   3D: 315/(64 pi h^9) 4 pi h^11 int_0^1 x^4 (1-x^2)^3 dx = (315/16)(16/1155) h^2 = 3 h^2 / 11
 *   2D: 4/(pi h^8) 2 pi h^10 int_0^1 x^3 (1-x^2)^3 dx = 8 h^2 / 40 = h^2 / 5 */
Test(kernels, second_moment)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int kind = 0; kind < SPH_KERNEL_COUNT; kind++) {
            sph_kernel k = sph_kernel_make((sph_kernel_kind)kind, dim, H);
            double m2 = radial_integral(&k, 2);
            cr_assert(m2 > 0);
            cr_assert(fabs(k.m2 - m2) <= 1e-3 * m2, "%dD %s: m2 = %.7g, numerical integral %.7g", dim, name_of(&k),
                      k.m2, m2);
        }
    sph_kernel k = sph_kernel_make(SPH_KERNEL_POLY6, 3, H);
    double want = 3.0 * H * H / 11.0;
    cr_assert(fabs(k.m2 - want) <= 1e-4 * want, "poly6 3D m2 = %.7g, analytic %.7g", k.m2, want);
    k = sph_kernel_make(SPH_KERNEL_POLY6, 2, H);
    want = (double)H * H / 5.0;
    cr_assert(fabs(k.m2 - want) <= 1e-4 * want, "poly6 2D m2 = %.7g, analytic %.7g", k.m2, want);
}

Test(kernels, find_by_name)
{
    for (int kind = 0; kind < SPH_KERNEL_COUNT; kind++)
        cr_assert_eq(sph_kernel_find(sph_kernel_names[kind]), kind, "%s", sph_kernel_names[kind]);
    cr_assert_eq(sph_kernel_find("poly6"), SPH_KERNEL_POLY6);
    cr_assert_eq(sph_kernel_find("spiky"), SPH_KERNEL_SPIKY);
    cr_assert_eq(sph_kernel_find("viscosity"), SPH_KERNEL_VISCOSITY);
    cr_assert_eq(sph_kernel_find("cubic"), SPH_KERNEL_CUBIC);
    cr_assert_eq(sph_kernel_find("wendland"), SPH_KERNEL_WENDLAND);
    const char *unknown[] = {"gaussian", "", "poly", "poly66", "cubic "};
    for (int i = 0; i < 5; i++) cr_assert_eq(sph_kernel_find(unknown[i]), -1, "'%s' is no kernel", unknown[i]);
}

/* The lattice at spacing h/3 within h of a particle, particle excluded.
 * Each point is (i, j, l) * s computed in float; returns the count. */
static void gradient_sums(const sph_kernel *k, int dim, double s_over_h, double sum[3], double *abs_sum,
                          double moment[3][3], int *count)
{
    const float s = (float)(s_over_h * k->h);
    const int m = (int)ceil(1.0 / s_over_h);
    const int mz = dim == 3 ? m : 0;
    *abs_sum = 0;
    *count = 0;
    for (int a = 0; a < 3; a++) {
        sum[a] = 0;
        for (int b = 0; b < 3; b++) moment[a][b] = 0;
    }
    for (int l = -mz; l <= mz; l++)
        for (int j = -m; j <= m; j++)
            for (int i = -m; i <= m; i++) {
                if (!i && !j && !l) continue;
                float x[3] = {(float)i * s, (float)j * s, (float)l * s};
                float r = sqrtf(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
                if (r >= k->h) continue;
                double dw = sph_kernel_dw(k, r);
                (*count)++;
                *abs_sum += fabs(dw);
                for (int a = 0; a < dim; a++) {
                    double g = dw * x[a] / r;
                    sum[a] += g;
                    for (int b = 0; b < dim; b++) moment[a][b] += x[b] * g; /* x_b dW/dx_a */
                }
            }
}

/* sum_j grad W(x_j) = 0 over a lattice symmetric about the particle: the
 * gradient is odd. Each +x / -x pair cancels in exact arithmetic; what is left
 * is double round-off, so 1e-9 of sum |dW| is a tight bound. */
Test(kernels, gradient_sum_vanishes_on_symmetric_lattice)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int kind = 0; kind < SPH_KERNEL_COUNT; kind++) {
            sph_kernel k = sph_kernel_make((sph_kernel_kind)kind, dim, H);
            double sum[3], abs_sum, moment[3][3];
            int count;
            gradient_sums(&k, dim, 1.0 / 3.0, sum, &abs_sum, moment, &count);
            /* 24 (2D) and 92 (3D) nodes with i^2 + j^2 (+ l^2) < 9 */
            cr_assert_geq(count, dim == 3 ? 92 : 24, "%dD: %d lattice points within h", dim, count);
            cr_assert_gt(abs_sum, 0.0);
            for (int a = 0; a < dim; a++)
                cr_assert(fabs(sum[a]) <= 1e-9 * abs_sum, "%dD %s: sum of grad W along %d = %g (sum |dW| %g)", dim,
                          name_of(&k), a, sum[a], abs_sum);
        }
}

/* A finer lattice (spacing h/40) approximates the integral of x_b dW/dx_a,
 * which by parts is -delta_ab * int W = -delta_ab: a check of the gradient's
 * sign and size together. The lattice sum is a midpoint rule; with the
 * kernels' kinks (spiky and viscosity at r = 0, cubic at h/2) it is accurate
 * to O(s/h), measured below 1% here: tolerance 2% of the identity. */
Test(kernels, gradient_moment_is_minus_identity)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int kind = 0; kind < SPH_KERNEL_COUNT; kind++) {
            sph_kernel k = sph_kernel_make((sph_kernel_kind)kind, dim, H);
            double sum[3], abs_sum, moment[3][3];
            int count;
            const double s_over_h = 1.0 / 40.0;
            gradient_sums(&k, dim, s_over_h, sum, &abs_sum, moment, &count);
            double vol = pow(s_over_h * k.h, dim);
            for (int a = 0; a < dim; a++)
                for (int b = 0; b < dim; b++) {
                    double got = moment[a][b] * vol, want = a == b ? -1.0 : 0.0;
                    cr_assert(fabs(got - want) <= 0.02, "%dD %s: int x_%d dW/dx_%d = %.5f, want %g", dim,
                              name_of(&k), b, a, got, want);
                }
        }
}
