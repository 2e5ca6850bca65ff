/* The window's layout, without GL (layout.c, camera.c): the domain, fitted to
 * the view, lies inside it and never under the side column (HUD, timings,
 * parameter panel) nor the legend, at the default window size and after
 * resizes; a zoom towards a point keeps that point's pixel; `f` and `r`
 * (zoom 1, no pan) bring the whole domain back in frame. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "camera.h"
#include "layout.h"

typedef struct box {
    float x0, y0, x1, y1; /* [px] */
} box;

static box rect_box(const int rc[4])
{
    return (box){(float)rc[0], (float)rc[1], (float)(rc[0] + rc[2]), (float)(rc[1] + rc[3])};
}

static bool overlap(box a, box b)
{
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

/* The pixels the domain box's corners project to (2D: 4, 3D: 8). */
static box domain_box(const sph_camera *c, int dim, const float lo[3], const float hi[3])
{
    box b = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < (dim == 3 ? 8 : 4); k++) {
        float p[3] = {k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]}, px[2], depth;
        if (dim == 2) p[2] = 0;
        cr_assert(sph_camera_project(c, p, px, &depth));
        b.x0 = fminf(b.x0, px[0]);
        b.y0 = fminf(b.y0, px[1]);
        b.x1 = fmaxf(b.x1, px[0]);
        b.y1 = fmaxf(b.y1, px[1]);
    }
    return b;
}

/* The dam break's boxes: 2D 3 m x 1.5 m; 3D 1.6 x 0.6 x 0.6 m. */
static const float lo2[3] = {0, 0, 0}, hi2[3] = {3, 1.5f, 1}, lo3[3] = {0, 0, 0}, hi3[3] = {1.6f, 0.6f, 0.6f};

static void check_size(int w, int h, bool legend, bool strip)
{
    const int side_w = sph_layout_side_width(w, h);
    cr_assert_gt(side_w, 0);
    sph_layout L;
    sph_layout_compute(w, h, side_w, legend, strip, &L);
    const box view = rect_box(L.view), side = rect_box(L.side);
    cr_expect(!overlap(view, side), "%dx%d: the view overlaps the side column", w, h);
    cr_expect(side.x1 == (float)w && side.y0 == 0 && side.y1 == (float)h, "%dx%d: the column spans the right edge", w, h);
    if (legend) {
        const box lg = rect_box(L.legend);
        cr_expect(!overlap(view, lg) && !overlap(lg, side), "%dx%d: the legend overlaps", w, h);
    }
    if (strip) cr_expect(!overlap(view, rect_box(L.strip)) && !overlap(rect_box(L.strip), side));
    for (int dim = 2; dim <= 3; dim++) {
        sph_camera c;
        sph_orbit o = sph_orbit_default();
        const float *lo = dim == 2 ? lo2 : lo3, *hi = dim == 2 ? hi2 : hi3;
        sph_camera_fit(&c, dim, lo, hi, &o, w, h, L.view);
        box d = domain_box(&c, dim, lo, hi);
        cr_expect(d.x0 >= view.x0 - 0.5f && d.x1 <= view.x1 + 0.5f && d.y0 >= view.y0 - 0.5f && d.y1 <= view.y1 + 0.5f,
                  "%dx%d %dD: the domain [%g %g %g %g] leaves the view [%g %g %g %g]", w, h, dim, d.x0, d.y0, d.x1,
                  d.y1, view.x0, view.y0, view.x1, view.y1);
        cr_expect(!overlap(d, side), "%dx%d %dD: the domain lies under the side column", w, h, dim);
        /* the domain fills the view along one axis at least (the fit wastes nothing) */
        if (dim == 2)
            cr_expect(d.x1 - d.x0 >= view.x1 - view.x0 - 1 || d.y1 - d.y0 >= view.y1 - view.y0 - 1,
                      "%dx%d: the domain does not fill the view", w, h);
    }
}

Test(render_layout, the_domain_stays_beside_the_column_at_the_default_size)
{
    check_size(1024, 720, true, false);
    check_size(1024, 720, true, true);
    check_size(1024, 720, false, false);
}

Test(render_layout, the_domain_stays_beside_the_column_after_resizes)
{
    const int sizes[][2] = {{1600, 900}, {700, 900}, {2560, 1440}, {480, 320}, {240, 180}, {160, 120}};
    for (size_t k = 0; k < sizeof sizes / sizeof *sizes; k++) check_size(sizes[k][0], sizes[k][1], true, k % 2);
}

/* Without a column (sphlab render) the view takes the width as before: the
 * legend ends at the image's right edge. */
Test(render_layout, no_column_is_the_former_layout)
{
    sph_layout L;
    sph_layout_compute(800, 600, 0, true, false, &L);
    cr_expect_eq(L.side[2], 0);
    cr_expect_eq(L.legend[0] + (int)roundf(6.0f * 14.0f), 800, "legend at %d", L.legend[0]);
    cr_expect_eq(L.view[0] + L.view[2] + L.view[0], L.legend[0]);
}

Test(render_layout, the_side_column_never_takes_more_than_half)
{
    sph_layout L;
    sph_layout_compute(300, 1000, 5000, false, false, &L);
    cr_expect_leq(L.side[2], 150);
    cr_expect_geq(L.view[2], 100);
}

Test(render_layout, zooming_towards_a_point_keeps_its_pixel)
{
    sph_layout L;
    sph_layout_compute(1024, 720, sph_layout_side_width(1024, 720), true, false, &L);
    sph_orbit o = sph_orbit_default();
    const float at[3] = {2.3f, 0.4f, 0};
    sph_camera c;
    float before[2], after[2], depth;
    sph_camera_fit(&c, 2, lo2, hi2, &o, 1024, 720, L.view);
    sph_camera_project(&c, at, before, &depth);
    for (int k = 0; k < 5; k++) sph_orbit_zoom_at(&o, lo2, hi2, at, 1.25f);
    sph_camera_fit(&c, 2, lo2, hi2, &o, 1024, 720, L.view);
    sph_camera_project(&c, at, after, &depth);
    cr_expect(fabsf(after[0] - before[0]) < 0.05f && fabsf(after[1] - before[1]) < 0.05f,
              "the point moved from (%g, %g) to (%g, %g)", before[0], before[1], after[0], after[1]);
    cr_expect_float_eq(o.zoom, powf(1.25f, 5), 1e-4f);
    /* another point did move: the zoom is a zoom */
    const float far[3] = {0.2f, 1.2f, 0};
    float p[2];
    sph_camera_project(&c, far, p, &depth);
    sph_camera o0;
    sph_orbit fitted = sph_orbit_default();
    sph_camera_fit(&o0, 2, lo2, hi2, &fitted, 1024, 720, L.view);
    float q[2];
    sph_camera_project(&o0, far, q, &depth);
    cr_expect(fabsf(p[0] - q[0]) > 10, "a far point should move when zooming");
}

/* The legend's three labels differ when the range is narrow against the values (a density from 999.2
 * to 1000.9 read "1000 / 1000 / 1000" with 4 digits), and keep 4 digits on a wide range. */
Test(render_layout, legend_labels_tell_a_narrow_range_apart)
{
    const float ranges[][2] = {{999.2f, 1000.9f}, {999.98f, 1000.02f}, {0.0f, 2.5f}, {-3.0f, 3.0f}, {1000, 1000}};
    for (size_t k = 0; k < sizeof ranges / sizeof ranges[0]; k++) {
        const float lo = ranges[k][0], hi = ranges[k][1];
        char a[32], m[32], b[32];
        sph_legend_label(a, sizeof a, lo, lo, hi);
        sph_legend_label(m, sizeof m, 0.5f * (lo + hi), lo, hi);
        sph_legend_label(b, sizeof b, hi, lo, hi);
        if (hi > lo)
            cr_expect(strcmp(a, m) != 0 && strcmp(m, b) != 0, "range %g to %g: labels %s / %s / %s", lo, hi, a, m, b);
    }
    char s[32];
    sph_legend_label(s, sizeof s, 2.5f, 0.0f, 2.5f);
    cr_expect_str_eq(s, "2.5");
    sph_legend_label(s, sizeof s, 1234.5678f, 0.0f, 2000.0f);
    cr_expect_str_eq(s, "1235", "a wide range keeps 4 significant digits");
}
