/* The pages of a chart: PLplot's cairo devices (pngcairo, pdfcairo,
 * svgcairo) drawing one chart function into staged files (plot_out.c), the
 * PDF made reproducible. The charts themselves are drawn in plot_draw.c. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <plplot.h>

#include "plot.h"

static int on_plplot_exit(PLCHAR_VECTOR msg)
{
    fprintf(stderr, "sphlab %s: PLplot stopped: %s\n", plot_out_command_name(), msg ? msg : "");
    plot_out_abort();
    return 1;
}

static bool have_device(const char *name)
{
    const char *menu_a[64], *devs_a[64];
    const char **menu = menu_a, **devs = devs_a;
    int n = 64;
    plgDevs(&menu, &devs, &n);
    for (int i = 0; i < n; i++)
        if (strcmp(devs[i], name) == 0) return true;
    return false;
}

static void render(plot_draw_fn *draw, const void *chart, const char *dev, const char *file, int w, int h, double scale)
{
    plsexit(on_plplot_exit);
    plsdev(dev);
    plsfnam(file);
    plspage(0, 0, w, h, 0, 0);
    plot_style_start(scale);
    plinit();
    pladv(0);
    plschr(0, 1.0);
    draw(chart);
    plend();
}

/* cairo writes the time of day into the PDF as /CreationDate (D:YYYYMMDDHHMMSS...).
 * Overwrite those 14 digits in place (same length: the offsets stay valid). */
static bool fix_pdf_date(const char *path)
{
    FILE *f = fopen(path, "r+b");
    if (!f) return false;
    static char buf[1 << 20];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    const char key[] = "/CreationDate (D:";
    char *p = NULL;
    for (size_t i = 0; i + sizeof key <= n; i++)
        if (memcmp(buf + i, key, sizeof key - 1) == 0) p = buf + i + sizeof key - 1;
    bool ok = true;
    if (p && p + 14 <= buf + n) {
        time_t when = 0;
        const char *sde = getenv("SOURCE_DATE_EPOCH");
        if (sde && *sde) when = (time_t)strtoll(sde, NULL, 10);
        struct tm tm;
        char date[32];
        if (gmtime_r(&when, &tm) && strftime(date, sizeof date, "%Y%m%d%H%M%S", &tm) == 14) {
            ok = fseek(f, (long)(p - buf), SEEK_SET) == 0 && fwrite(date, 1, 14, f) == 14;
        }
    }
    ok &= fclose(f) == 0;
    return ok;
}

static bool g_svg;
void plot_set_svg(bool on) { g_svg = on; }

bool plot_page(plot_draw_fn *draw, const void *chart, const char *dir, const char *base, int width, int height)
{
    for (int i = 0; i < (g_svg ? 3 : 2); i++) {
        const char *dev = i == 2 ? "svgcairo" : i ? "pdfcairo" : "pngcairo";
        if (!have_device(dev)) {
            fprintf(stderr, "sphlab %s: PLplot has no %s driver (Debian: apt-get install plplot-driver-cairo)\n", plot_out_command_name(),
                    dev);
            return false;
        }
    }
    char png[300], pdf[300];
    snprintf(png, sizeof png, "%s.png", base);
    snprintf(pdf, sizeof pdf, "%s.pdf", base);
    const char *png_tmp = plot_out_stage(dir, png);
    if (!png_tmp) return false;
    const char *pdf_tmp = plot_out_stage(dir, pdf);
    if (!pdf_tmp) return false;
    render(draw, chart, "pngcairo", png_tmp, width, height, 1.0);
    /* same layout on a page of half the pixel count in points: the PNG is the PDF at 144 dpi */
    render(draw, chart, "pdfcairo", pdf_tmp, (width + 1) / 2, (height + 1) / 2, 0.5);
    if (!fix_pdf_date(pdf_tmp)) {
        fprintf(stderr, "sphlab %s: %s/%s: cannot finish the PDF\n", plot_out_command_name(), dir, pdf);
        return false;
    }
    if (g_svg) {
        char svg[300];
        snprintf(svg, sizeof svg, "%s.svg", base);
        const char *svg_tmp = plot_out_stage(dir, svg);
        if (!svg_tmp) return false;
        render(draw, chart, "svgcairo", svg_tmp, (width + 1) / 2, (height + 1) / 2, 0.5);
    }
    return true;
}

/* Under LeakSanitizer (`make asan`): fontconfig keeps its font cache, and
 * libltdl the PLplot driver it loaded, to the end of the process; neither is
 * a leak of sphlab's. LeakSanitizer calls this hook, if the binary defines
 * it, for its default suppressions; without the sanitizer it is never called. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
    return "leak:libfontconfig.so\nleak:libltdl.so\nleak:libcairo.so\nleak:libpango\nleak:libplplot.so\n";
}
