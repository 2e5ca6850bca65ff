/* sphlab plot: the charts are checked by their content, not by a file
 * existing. The PNG decodes at the requested size, has a white background,
 * dark axes at its left and bottom frame and curves or bars inside the plot
 * area; the PDF is a PDF of the same layout; the CSV beside a kernel chart
 * holds the kernel's values; the bars of a passes chart are as long as the
 * medians of a stats CSV written here; output is deterministic; errors name
 * the file or value, exit non-zero and leave nothing behind. */
#define _DEFAULT_SOURCE /* mkdtemp */
#include <criterion/criterion.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "plot.h"
#include "stb_image.h"
#include "test_util.h"

/* ---- helpers ------------------------------------------------------------------ */

static char out[16384];

static int plot(const char *fmt, const char *a, const char *b)
{
    char args[2048];
    snprintf(args, sizeof args, fmt, a, b);
    return test_sphlab(args, out, sizeof out);
}

/* Number of entries in dir other than . and .. (temporaries included). */
static int dir_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    for (struct dirent *e; (e = readdir(d));)
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) n++;
    closedir(d);
    return n;
}

static char *read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    cr_assert(f, "cannot open %s", path);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    cr_assert(buf && fread(buf, 1, (size_t)n, f) == (size_t)n);
    buf[n] = '\0';
    fclose(f);
    *len = (size_t)n;
    return buf;
}

typedef struct image {
    unsigned char *px; /* RGB */
    int w, h;
} image;

static image load_png(const char *path)
{
    image im;
    int n;
    im.px = stbi_load(path, &im.w, &im.h, &n, 3);
    cr_assert(im.px, "%s does not decode as an image: %s", path, stbi_failure_reason());
    return im;
}

static const unsigned char *at(const image *im, int x, int y) { return im->px + 3 * ((size_t)y * im->w + x); }
static bool white(const unsigned char *p) { return p[0] >= 250 && p[1] >= 250 && p[2] >= 250; }
static bool dark(const unsigned char *p) { return p[0] + p[1] + p[2] < 3 * 90; }

/* The frame of the plot area: the left axis is the longest vertical run of
 * dark pixels in the left third; the bottom axis the longest horizontal run in
 * the lower half, under the plot area. */
typedef struct frame {
    int left, top, right, bottom; /* pixels */
    int vrun, hrun;
} frame;

static frame find_frame(const image *im)
{
    frame f = {0};
    for (int x = 0; x < im->w / 3; x++)
        for (int y = 0, run = 0; y < im->h; y++) {
            run = dark(at(im, x, y)) ? run + 1 : 0;
            if (run > f.vrun) f.vrun = run, f.left = x, f.top = y - run + 1;
        }
    for (int y = im->h / 2; y < im->h; y++)
        for (int x = 0, run = 0; x < im->w; x++) {
            run = dark(at(im, x, y)) ? run + 1 : 0;
            if (run > f.hrun) f.hrun = run, f.bottom = y, f.right = x;
        }
    return f;
}

/* The checks every chart passes; returns the count of non-white pixels inside
 * the frame (curves, bars, grid). */
static long check_png(const char *path, int w, int h)
{
    image im = load_png(path);
    cr_assert_eq(im.w, w, "%s: width %d, want %d", path, im.w, w);
    cr_assert_eq(im.h, h, "%s: height %d, want %d", path, im.h, h);
    /* white background: the corners and most of the page */
    const int corner[4][2] = {{1, 1}, {w - 2, 1}, {1, h - 2}, {w - 2, h - 2}};
    for (int i = 0; i < 4; i++)
        cr_assert(white(at(&im, corner[i][0], corner[i][1])), "%s: corner %d is not white", path, i);
    long whites = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) whites += white(at(&im, x, y));
    cr_assert(whites > (long)w * h / 2, "%s: only %ld of %d pixels white", path, whites, w * h);
    /* black axes */
    frame f = find_frame(&im);
    cr_assert(f.vrun > h / 6, "%s: no left axis (longest dark vertical run %d px)", path, f.vrun);
    cr_assert(f.left > 10 && f.left < w / 3, "%s: left axis at x = %d", path, f.left);
    cr_assert(f.hrun > w / 3, "%s: no bottom axis (longest dark horizontal run %d px)", path, f.hrun);
    cr_assert(f.bottom > h / 2 && f.bottom < h - 10, "%s: bottom axis at y = %d", path, f.bottom);
    /* something drawn inside the plot area whose left axis that is (one panel
     * of a stacked chart), away from its frame and ticks: dark or coloured
     * pixels (the light grey grid does not count) */
    long ink = 0;
    const int m = 14;
    for (int y = f.top + m; y < f.top + f.vrun - m; y++)
        for (int x = f.left + m; x < f.right - m; x++) {
            const unsigned char *p = at(&im, x, y);
            int lo = p[0], hi = p[0];
            for (int c = 1; c < 3; c++) lo = p[c] < lo ? p[c] : lo, hi = p[c] > hi ? p[c] : hi;
            ink += p[0] + p[1] + p[2] < 3 * 180 || hi - lo > 60;
        }
    stbi_image_free(im.px);
    return ink;
}

/* Whether buf[0..n) holds needle (PDF streams hold NUL bytes: no strstr). */
static bool contains(const char *buf, size_t n, const char *needle)
{
    size_t m = strlen(needle);
    for (size_t i = 0; i + m <= n; i++)
        if (memcmp(buf + i, needle, m) == 0) return true;
    return false;
}

static void check_pdf(const char *path, int w_pt, int h_pt)
{
    size_t n;
    char *pdf = read_all(path, &n);
    cr_assert(n > 5000, "%s: only %zu bytes", path, n);
    cr_assert(memcmp(pdf, "%PDF-", 5) == 0, "%s does not start with %%PDF-", path);
    cr_assert(contains(pdf + n - 64, 64, "%%EOF"), "%s does not end with %%%%EOF", path);
    char box[64];
    snprintf(box, sizeof box, "/MediaBox [ 0 0 %d %d ]", w_pt, h_pt);
    cr_assert(contains(pdf, n, box), "%s: no %s", path, box);
    /* deterministic creation date: SOURCE_DATE_EPOCH or 1970-01-01 */
    const char *sde = getenv("SOURCE_DATE_EPOCH");
    time_t when = sde && *sde ? (time_t)strtoll(sde, NULL, 10) : 0;
    struct tm tm;
    char date[64];
    strftime(date, sizeof date, "/CreationDate (D:%Y%m%d%H%M%S", gmtime_r(&when, &tm));
    cr_assert(contains(pdf, n, date), "%s: creation date is not %s", path, date + 15);
    free(pdf);
}

/* Splits CSV line into at most cap numbers; returns the count. */
static int parse_row(char *line, double *v, int cap)
{
    int n = 0;
    for (char *tok = strtok(line, ","); tok && n < cap; tok = strtok(NULL, ",")) v[n++] = strtod(tok, NULL);
    return n;
}

/* ---- kernels ------------------------------------------------------------------ */

Test(plot, kernel_chart_png_pdf_and_csv_of_the_kernel_values)
{
    const char *dir = test_temp_dir("plot");
    int rc = plot("plot kernel wendland --dim 3 --h 0.5 --size 800x640 --out %s%s", dir, "");
    cr_assert_eq(rc, 0, "exit %d: %s", rc, out);
    char png[256], pdf[256], csv[256];
    snprintf(png, sizeof png, "%s/kernel-wendland-3d.png", dir);
    snprintf(pdf, sizeof pdf, "%s/kernel-wendland-3d.pdf", dir);
    snprintf(csv, sizeof csv, "%s/kernel-wendland-3d.csv", dir);
    cr_assert(strstr(out, png), "not listed as written: %s", out);
    long ink = check_png(png, 800, 640);
    cr_assert(ink > 500, "%s: only %ld curve pixels in the plot area", png, ink);
    check_pdf(pdf, 400, 320);
    cr_assert_eq(dir_entries(dir), 3, "want exactly csv, png, pdf (no temporaries)");

    /* the CSV beside it: r/h from 0 past 1, values of the core's kernel functions */
    size_t n;
    char *text = read_all(csv, &n);
    char *save, *line = strtok_r(text, "\n", &save);
    cr_assert_str_eq(line, "r_over_h,r,w,dw_dr,lap");
    sph_kernel k = sph_kernel_make(SPH_KERNEL_WENDLAND, 3, 0.5f);
    int rows = 0, nonzero = 0;
    double last_q = -1;
    while ((line = strtok_r(NULL, "\n", &save))) {
        double v[5];
        cr_assert_eq(parse_row(line, v, 5), 5, "row %d: %s", rows + 1, line);
        float r = (float)v[1];
        cr_assert(fabs(v[0] * 0.5 - v[1]) < 1e-6, "row %d: r = %g is not r/h * h", rows + 1, v[1]);
        double want[3] = {sph_kernel_w(&k, r), sph_kernel_dw(&k, r), sph_kernel_lap(&k, r)};
        for (int j = 0; j < 3; j++)
            cr_assert(fabs(v[2 + j] - want[j]) <= 1e-6 * fabs(want[j]) + 1e-12, "r = %g: column %d is %.9g, kernel says %.9g",
                      v[1], 2 + j, v[2 + j], want[j]);
        nonzero += v[2] > 0;
        last_q = v[0];
        rows++;
    }
    cr_assert(rows > 100, "only %d rows", rows);
    cr_assert(last_q > 1.0, "r/h stops at %g, before the end of the support", last_q);
    cr_assert(nonzero > 100 && nonzero < rows, "W > 0 inside the support only (%d of %d rows)", nonzero, rows);
    free(text);
    test_remove_dir(dir);
}

/* --svg adds BASE.svg: an SVG document of the PDF's page size (points) that
 * draws the chart (paths for the curves, glyphs for the text); without it no
 * SVG is written. */
Test(plot, svg_on_request)
{
    const char *dir = test_temp_dir("plot");
    int rc = plot("plot kernel poly6 --size 800x640 --svg --out %s%s", dir, "");
    cr_assert_eq(rc, 0, "exit %d: %s", rc, out);
    char svg[256];
    snprintf(svg, sizeof svg, "%s/kernel-poly6-2d.svg", dir);
    cr_assert(strstr(out, svg), "not listed as written: %s", out);
    cr_assert_eq(dir_entries(dir), 4, "want csv, png, pdf and svg (no temporaries)");
    size_t n;
    char *text = read_all(svg, &n);
    cr_assert(strncmp(text, "<?xml", 5) == 0, "%s does not start as XML", svg);
    cr_assert(strstr(text, "<svg") && strstr(text, "width=\"400pt\"") && strstr(text, "height=\"320pt\""),
              "%s: not an SVG page of 400 x 320 pt", svg);
    int paths = 0;
    for (const char *p = text; (p = strstr(p, "<path")); p++) paths++;
    cr_assert(paths > 20, "%s: only %d paths", svg, paths);
    cr_assert(strstr(text, "</svg>"), "%s is cut short", svg);
    free(text);
    test_remove_dir(dir);

    dir = test_temp_dir("plot");
    rc = plot("plot kernel poly6 --out %s%s", dir, "");
    cr_assert_eq(rc, 0, "exit %d: %s", rc, out);
    cr_assert_eq(dir_entries(dir), 3, "without --svg: csv, png and pdf only");
    test_remove_dir(dir);
}

/* Curves differ by colour and style: the dW/dr panel is drawn in blue, the
 * Laplacian's in red; the W panel in black. Each colour has pixels, and the
 * blue ones lie above the red ones (panels stacked W, dW/dr, Laplacian). */
Test(plot, kernel_panels_hold_their_curves)
{
    const char *dir = test_temp_dir("plot");
    int rc = plot("plot kernel cubic --out %s --quiet%s", dir, "");
    cr_assert_eq(rc, 0, "exit %d: %s", rc, out);
    char png[256];
    snprintf(png, sizeof png, "%s/kernel-cubic-2d.png", dir);
    image im = load_png(png);
    long blue = 0, red = 0;
    double blue_y = 0, red_y = 0;
    for (int y = 0; y < im.h; y++)
        for (int x = 0; x < im.w * 3 / 4; x++) { /* the plot areas, not the legends */
            const unsigned char *p = at(&im, x, y);
            if (p[2] > p[0] + 80 && p[2] > p[1] + 40) blue++, blue_y += y;
            if (p[0] > p[1] + 80 && p[0] > p[2] + 80) red++, red_y += y;
        }
    cr_assert(blue > 300 && red > 300, "curve pixels: blue %ld, red %ld", blue, red);
    cr_assert(blue_y / blue < red_y / red, "the dW/dr curve should be above the Laplacian's");
    stbi_image_free(im.px);
    test_remove_dir(dir);
}

Test(plot, kernels_writes_every_kernel_and_the_comparison)
{
    const char *dir = test_temp_dir("plot");
    int rc = plot("plot kernels --dim 2 --out %s --quiet%s", dir, "");
    cr_assert_eq(rc, 0, "exit %d: %s", rc, out);
    cr_assert_eq(dir_entries(dir), 3 * (SPH_KERNEL_COUNT + 1), "want csv, png, pdf for 5 kernels and the comparison");
    char path[256];
    snprintf(path, sizeof path, "%s/kernels-2d.png", dir);
    long ink = check_png(path, 1000, 1000);
    cr_assert(ink > 4000, "only %ld curve pixels", ink);
    snprintf(path, sizeof path, "%s/kernels-2d.csv", dir);
    size_t n;
    char *text = read_all(path, &n);
    char *nl = strchr(text, '\n');
    *nl = '\0';
    cr_assert_str_eq(text, "r_over_h,r,w_poly6,w_spiky,w_viscosity,w_cubic,w_wendland,dw_dr_poly6,dw_dr_spiky,"
                           "dw_dr_viscosity,dw_dr_cubic,dw_dr_wendland,lap_poly6,lap_spiky,lap_viscosity,lap_cubic,"
                           "lap_wendland");
    /* row 41: r/h = 0.2; W of each kernel there */
    char *line = nl + 1;
    for (int i = 0; i < 40; i++) line = strchr(line, '\n') + 1;
    double v[17];
    cr_assert_eq(parse_row(line, v, 17), 17);
    cr_assert(fabs(v[0] - 0.2) < 1e-9, "row 41 has r/h = %g", v[0]);
    for (int kk = 0; kk < SPH_KERNEL_COUNT; kk++) {
        sph_kernel k = sph_kernel_make((sph_kernel_kind)kk, 2, 0.04f);
        double want = sph_kernel_w(&k, (float)v[1]);
        cr_assert(fabs(v[2 + kk] - want) <= 1e-6 * fabs(want), "%s: W = %g, kernel says %g", sph_kernel_names[kk],
                  v[2 + kk], want);
    }
    free(text);
    test_remove_dir(dir);
}

Test(plot, same_input_same_bytes)
{
    const char *a = test_temp_dir("plot"), *b = test_temp_dir("plot");
    cr_assert_eq(plot("plot kernel spiky --quiet --out %s%s", a, ""), 0, "%s", out);
    cr_assert_eq(plot("plot kernel spiky --quiet --out %s%s", b, ""), 0, "%s", out);
    const char *ext[3] = {"csv", "png", "pdf"};
    for (int i = 0; i < 3; i++) {
        char pa[256], pb[256];
        snprintf(pa, sizeof pa, "%s/kernel-spiky-2d.%s", a, ext[i]);
        snprintf(pb, sizeof pb, "%s/kernel-spiky-2d.%s", b, ext[i]);
        size_t na, nb;
        char *da = read_all(pa, &na), *db = read_all(pb, &nb);
        cr_assert(na == nb && memcmp(da, db, na) == 0, "%s differs between two runs", ext[i]);
        free(da);
        free(db);
    }
    test_remove_dir(a);
    test_remove_dir(b);
}

/* ---- from --stats ---------------------------------------------------------------- */

/* Three passes with medians 1, 0.5 and 2 ms; the last row is an outlier that
 * a median ignores. */
static const char *synthetic_stats(void)
{
    static char csv[8192];
    size_t m = (size_t)snprintf(csv, sizeof csv,
                                "step,t,dt,n,ekin,rho_min,rho_mean,rho_max,max_speed,external_ms,hash_ms,sort_ms\n");
    for (int i = 1; i <= 40; i++) {
        double ext = i == 40 ? 50.0 : 1.0 + 0.01 * (i % 3 - 1), hash = 0.5, sort = i == 40 ? 0.01 : 2.0;
        m += (size_t)snprintf(csv + m, sizeof csv - m, "%d,%g,0.001,100,%g,900,1000,1100,%g,%g,%g,%g\n", i, 0.001 * i,
                              0.5 * i, 0.1 * i, ext, hash, sort);
    }
    return test_write_temp(csv, ".csv");
}

static long count_grey(const image *im, int level)
{
    long n = 0;
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++) {
            const unsigned char *p = at(im, x, y);
            n += p[0] == level && p[1] == level && p[2] == level;
        }
    return n;
}

Test(plot, passes_bars_are_the_medians)
{
    const char *dir = test_temp_dir("plot"), *stats = synthetic_stats();
    int rc = plot("plot passes %s --out %s --quiet", stats, dir);
    cr_assert_eq(rc, 0, "exit %d: %s", rc, out);
    char path[256];
    snprintf(path, sizeof path, "%s/passes.csv", dir);
    size_t n;
    char *text = read_all(path, &n);
    cr_assert(strncmp(text, "pass,median_ms,mean_ms,min_ms,max_ms,share_percent\n", 51) == 0, "%s", text);
    const char *name[3] = {"external", "hash", "sort"};
    const double med[3] = {1.0, 0.5, 2.0};
    for (int i = 0; i < 3; i++) {
        char key[32];
        snprintf(key, sizeof key, "\n%s,", name[i]);
        const char *row = strstr(text, key);
        cr_assert(row, "no row for %s in %s", name[i], text);
        double v = strtod(row + strlen(key), NULL);
        cr_assert(fabs(v - med[i]) < 1e-9, "%s: median %g, want %g", name[i], v, med[i]);
    }
    free(text);

    /* bars: the first pass is filled with grey 225, the third with grey 140
     * (plot_draw.c's fill table), bars are equally tall, so their areas are in
     * the ratio of the medians, 2 : 1. */
    snprintf(path, sizeof path, "%s/passes.png", dir);
    long ink = check_png(path, 1000, 700);
    cr_assert(ink > 3000, "only %ld bar pixels", ink);
    image im = load_png(path);
    long g225 = count_grey(&im, 225), g140 = count_grey(&im, 140);
    cr_assert(g225 > 1000, "first bar: %ld pixels", g225);
    cr_assert(fabs((double)g140 / g225 - 2.0) < 0.15, "bar areas %ld and %ld, want the ratio 2", g140, g225);
    stbi_image_free(im.px);
    snprintf(path, sizeof path, "%s/passes.pdf", dir);
    check_pdf(path, 500, 350);

    /* over time: stacked, with its own CSV of binned medians */
    snprintf(path, sizeof path, "%s/passes-time.png", dir);
    cr_assert(check_png(path, 1000, 700) > 5000, "too few filled pixels");
    snprintf(path, sizeof path, "%s/passes-time.csv", dir);
    text = read_all(path, &n);
    cr_assert(strncmp(text, "t,step_first,step_last,external_ms,hash_ms,sort_ms\n", 51) == 0, "%s", text);
    free(text);
    cr_assert_eq(dir_entries(dir), 6);
    test_remove_dir(dir);
}

Test(plot, series_of_stats_columns)
{
    const char *dir = test_temp_dir("plot"), *stats = synthetic_stats();
    int rc = plot("plot series %s --y ekin,rho_max,rho_min --dim 2 --size 900x800 --out %s", stats, dir);
    cr_assert_eq(rc, 0, "exit %d: %s", rc, out);
    char path[256];
    snprintf(path, sizeof path, "%s/series-ekin-rho_max-rho_min.png", dir);
    long ink = check_png(path, 900, 800);
    cr_assert(ink > 800, "only %ld curve pixels", ink);
    snprintf(path, sizeof path, "%s/series-ekin-rho_max-rho_min.csv", dir);
    size_t n;
    char *text = read_all(path, &n);
    cr_assert(strncmp(text, "t,ekin,rho_max,rho_min\n0.001,0.5,1100,900\n", 42) == 0, "%s", text);
    free(text);
    test_remove_dir(dir);
}

/* A y-axis up to 0.0103 (the hydrostatic chart's pressure error) is scaled, as one below 0.01 was: its ticks
 * -0.002 and 0.010 took six characters and the axis title stood on them. */
Test(plot, small_axes_are_scaled_by_a_power_of_ten)
{
    cr_assert_eq(plot_axis_exponent(0.0103), -2);
    cr_assert_eq(plot_axis_exponent(0.05), -2);
    cr_assert_eq(plot_axis_exponent(0.002), -3);
    cr_assert_eq(plot_axis_exponent(0.1), 0);
    cr_assert_eq(plot_axis_exponent(6.0), 0);
    cr_assert_eq(plot_axis_exponent(9999.0), 0);
    cr_assert_eq(plot_axis_exponent(25000.0), 4);
    cr_assert_eq(plot_axis_exponent(0.0), 0);
    cr_assert_eq(plot_axis_exponent(NAN), 0);
}

/* A log axis keeps its points off its ends: a study's errors all at 0.000997 (log10 -3.0013) sat on the top of a
 * 1e-4..1e-3 frame, their row numbers outside it; now the axis runs to 1e-2. Points at a decade itself get one
 * more decade on that side; points well inside a decade keep it. */
Test(plot, log_axis_keeps_points_off_its_ends)
{
    double a, b;
    plot_log_axis_ends(log10(0.000997), log10(0.000997), &a, &b);
    cr_expect(a == -4 && b == -2, "0.000997: %g..%g", a, b);
    plot_log_axis_ends(-3.0, -3.0, &a, &b);
    cr_expect(a == -4 && b == -2, "1e-3: %g..%g", a, b);
    plot_log_axis_ends(-2.5, -1.3, &a, &b);
    cr_expect(a == -3 && b == -1, "-2.5..-1.3: %g..%g", a, b);
    plot_log_axis_ends(-0.98, 2.97, &a, &b);
    cr_expect(a == -2 && b == 4, "-0.98..2.97: %g..%g", a, b);
}

/* Three stacked panels without --dim: the energy's and the density's axis
 * titles name both units and are longer than a panel is tall. Each must stay
 * beside its own panel: along the strip left of the tick labels, the titles'
 * ink makes three separate runs, not one title running into the next. */
Test(plot, series_axis_titles_stay_beside_their_panels)
{
    const char *dir = test_temp_dir("plot"), *stats = synthetic_stats();
    int rc = plot("plot series %s --y ekin,rho_max,max_speed --size 1000x1000 --out %s --quiet", stats, dir);
    cr_assert_eq(rc, 0, "exit %d: %s", rc, out);
    char path[256];
    snprintf(path, sizeof path, "%s/series-ekin-rho_max-max_speed.png", dir);
    image im = load_png(path);
    int runs = 0, blank = 1000; /* blank: rows since the last ink */
    for (int y = 0; y < im.h; y++) {
        bool ink = false;
        for (int x = 2; x < 55 && !ink; x++) ink = dark(at(&im, x, y));
        if (ink && blank > 20) runs++; /* gaps between letters and words are narrower */
        blank = ink ? 0 : blank + 1;
    }
    stbi_image_free(im.px);
    cr_assert_eq(runs, 3, "%d runs of axis-title ink left of the panels, want 3 (one title per panel)", runs);
    test_remove_dir(dir);
}

/* An obstacle's force columns have a unit and share one panel: with the
 * energy, two densities and the speed that makes four panels, the most a
 * chart holds (each column its own panel would make five, refused). */
Test(plot, series_obstacle_force_columns_share_a_panel)
{
    const char *dir = test_temp_dir("plot");
    char csv[4096];
    size_t m = (size_t)snprintf(csv, sizeof csv, "step,t,ekin,rho_max,max_speed,obstacle_rock_fx,obstacle_rock_fy\n");
    for (int i = 1; i <= 20; i++)
        m += (size_t)snprintf(csv + m, sizeof csv - m, "%d,%g,%g,1000,%g,%g,%g\n", i, 0.01 * i, 0.5 * i, 0.1 * i,
                              2.0 * i, -1.0 * i);
    const char *stats = test_write_temp(csv, ".csv");
    int rc = plot("plot series %s --y ekin,rho_max,max_speed,obstacle_rock_fx,obstacle_rock_fy --dim 2 --out %s --quiet",
                  stats, dir);
    cr_assert_eq(rc, 0, "exit %d (the force columns took a panel each?): %s", rc, out);
    test_remove_dir(dir);
}

Test(plot, series_beside_the_csv_by_default)
{
    const char *dir = test_temp_dir("plot");
    char csv[256], path[256];
    snprintf(csv, sizeof csv, "%s/stats.csv", dir);
    FILE *f = fopen(csv, "w");
    fputs("step,t,ekin\n1,0.1,1\n2,0.2,4\n3,0.3,9\n", f);
    fclose(f);
    int rc = plot("plot series %s --y ekin --name energy%s", csv, "");
    cr_assert_eq(rc, 0, "exit %d: %s", rc, out);
    snprintf(path, sizeof path, "%s/energy.png", dir);
    cr_assert(check_png(path, 1000, 700) > 500, "too few curve pixels");
    test_remove_dir(dir);
}

/* ---- errors ------------------------------------------------------------------------ */

Test(plot, missing_csv)
{
    const char *dir = test_temp_dir("plot");
    int rc = plot("plot passes /nonexistent/stats.csv --out %s%s", dir, "");
    cr_assert_neq(rc, 0);
    cr_assert(strstr(out, "/nonexistent/stats.csv"), "message does not name the file: %s", out);
    cr_assert_eq(dir_entries(dir), 0);
    test_remove_dir(dir);
}

Test(plot, csv_without_the_columns)
{
    const char *dir = test_temp_dir("plot"), *csv = test_write_temp("step,t,ekin\n1,0.1,2\n", ".csv");
    int rc = plot("plot passes %s --out %s", csv, dir);
    cr_assert_neq(rc, 0);
    cr_assert(strstr(out, csv) && strstr(out, "_ms"), "message does not name the file and PASS_ms: %s", out);
    rc = plot("plot series %s --y rho_max --out %s", csv, dir);
    cr_assert_neq(rc, 0);
    cr_assert(strstr(out, "'rho_max'"), "message does not name the column: %s", out);
    csv = test_write_temp("step,ekin\n1,2\n", ".csv");
    rc = plot("plot series %s --y ekin --out %s", csv, dir);
    cr_assert_neq(rc, 0);
    cr_assert(strstr(out, "'t'"), "message does not name the missing column t: %s", out);
    csv = test_write_temp("step,t,ekin\n1,0.1,abc\n", ".csv");
    rc = plot("plot series %s --y ekin --out %s", csv, dir);
    cr_assert_neq(rc, 0);
    cr_assert(strstr(out, ":2:") && strstr(out, "'abc'"), "message does not name the line and value: %s", out);
    cr_assert_eq(dir_entries(dir), 0, "an error left files behind");
    test_remove_dir(dir);
}

Test(plot, unknown_kernel_and_column)
{
    const char *dir = test_temp_dir("plot");
    int rc = plot("plot kernel gaussian --out %s%s", dir, "");
    cr_assert_eq(rc, 2, "a bad command line exits 2, as `plot chart` does (it exited 1): %d", rc);
    cr_assert(strstr(out, "'gaussian'") && strstr(out, "wendland"), "message: %s", out);
    rc = plot("plot series %s --y ekin,nosuch --out %s", synthetic_stats(), dir);
    cr_assert_neq(rc, 0);
    cr_assert(strstr(out, "'nosuch'"), "message does not name the column: %s", out);
    rc = plot("plot chart --out %s%s", dir, "");
    cr_assert_neq(rc, 0);
    cr_assert(strstr(out, "'chart'"), "message: %s", out);
    cr_assert_eq(dir_entries(dir), 0, "an error left files behind");
    test_remove_dir(dir);
}

Test(plot, unwritable_out_directory)
{
    const char *file = test_write_temp("not a directory\n", ".txt");
    char bad[256];
    snprintf(bad, sizeof bad, "%s/charts", file);
    int rc = plot("plot kernel poly6 --out %s%s", bad, "");
    cr_assert_neq(rc, 0);
    cr_assert(strstr(out, bad), "message does not name the directory: %s", out);
    rc = plot("plot passes %s --out %s", synthetic_stats(), bad);
    cr_assert_neq(rc, 0);
    cr_assert(strstr(out, bad), "message does not name the directory: %s", out);
    remove(file);
}

/* --h below what a scene takes: poly6's 1/h^9 overflowed a float in 3D, and the CSV held inf and the chart
 * nothing, exit 0. Refused as a scene refuses it. */
Test(plot, kernel_h_below_a_scenes_bound_is_refused)
{
    int rc = plot("plot kernel poly6 --dim 3 --h 1e-9 --out %s%s", "/tmp/sphlab-plot-h-tiny", "");
    cr_assert_eq(rc, 2, "exit %d: %s", rc, out);
    cr_assert(strstr(out, "--h 1e-9") && strstr(out, "0.0001"), "message does not name --h, its value and the bound: %s", out);
}

/* A directory that exists but cannot be written (not even by root: /proc). */
Test(plot, read_only_directory_leaves_nothing)
{
    int rc = plot("plot kernels --out /proc/self%s%s", "", "");
    cr_assert_neq(rc, 0);
    cr_assert(strstr(out, "/proc/self"), "message does not name the directory: %s", out);
}
