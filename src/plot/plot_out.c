/* Output files of one `sphlab plot` command: every file is written through
 * the I/O layer's atomic writer (src/io/io.h) and renamed only when all are
 * complete, so a failure leaves no half-written chart or CSV behind. */
#include <string.h>

#include "plot.h"
#include "../io/io.h"

enum { MAX_STAGED = 64 };

static sph_out g_staged[MAX_STAGED];
static bool g_chart[MAX_STAGED]; /* written by the chart library, by name: its write errors are not ours to see */
static int g_n;
static const char *g_cmd = "plot"; /* the command named in messages */

void plot_out_command(const char *name) { g_cmd = name; }
const char *plot_out_command_name(void) { return g_cmd; }

bool plot_out_dir(const char *dir)
{
    char err[SPH_IO_PATH + 200];
    if (sph_mkdir_p(dir, err, sizeof err)) return true;
    fprintf(stderr, "sphlab %s: --out: %s\n", g_cmd, err); /* err names dir */
    return false;
}

/* Opens DIR/FILE's temporary; its stream stays open (a CSV) or is closed for
 * a library that writes by name (a chart). */
static sph_out *stage(const char *dir, const char *file)
{
    if (g_n == MAX_STAGED) {
        fprintf(stderr, "sphlab %s: more than %d output files\n", g_cmd, MAX_STAGED);
        return NULL;
    }
    char final[SPH_IO_PATH], err[SPH_IO_PATH + 200];
    int len = snprintf(final, sizeof final, "%s/%s", dir, file);
    if (len < 0 || (size_t)len >= sizeof final) {
        fprintf(stderr, "sphlab %s: %s/%s: path too long\n", g_cmd, dir, file);
        return NULL;
    }
    for (int i = 0; i < g_n; i++)
        if (strcmp(g_staged[i].path, final) == 0) {
            fprintf(stderr, "sphlab %s: %s: two outputs of this command have this name (see --name)\n", g_cmd, final);
            return NULL;
        }
    if (!sph_out_open(&g_staged[g_n], final, err, sizeof err)) {
        fprintf(stderr, "sphlab %s: %s\n", g_cmd, err);
        return NULL;
    }
    g_chart[g_n] = false;
    return &g_staged[g_n++];
}

const char *plot_out_stage(const char *dir, const char *file)
{
    sph_out *o = stage(dir, file);
    if (!o) return NULL;
    char err[SPH_IO_PATH + 200];
    if (!sph_out_release(o, err, sizeof err)) {
        fprintf(stderr, "sphlab %s: %s\n", g_cmd, err);
        g_n--;
        return NULL;
    }
    g_chart[g_n - 1] = true;
    return o->tmp;
}

FILE *plot_out_stage_csv(const char *dir, const char *file)
{
    sph_out *o = stage(dir, file);
    return o ? o->f : NULL;
}

bool plot_out_close_csv(FILE *f, const char *dir, const char *file)
{
    (void)dir;
    (void)file;
    for (int i = 0; i < g_n; i++) {
        if (g_staged[i].f != f) continue;
        char err[SPH_IO_PATH + 200];
        if (sph_out_release(&g_staged[i], err, sizeof err)) return true;
        fprintf(stderr, "sphlab %s: %s\n", g_cmd, err);
        return false; /* the temporary is gone; plot_out_abort removes the others */
    }
    fclose(f);
    fprintf(stderr, "sphlab %s: %s/%s: not a staged output\n", g_cmd, dir, file);
    return false;
}

static bool ends_with(const char *path, const char *ext)
{
    size_t n = strlen(path), m = strlen(ext);
    return n >= m && strcmp(path + n - m, ext) == 0;
}

/* A chart the library wrote is whole: the chart library does not report a
 * failed write (a full disk left a 0-byte PDF and a PNG cut at 12 KiB, and the
 * command said "wrote" and exited 0), so its file's own end is checked: a
 * PNG's IEND chunk, a PDF's %%EOF, an SVG's </svg>. */
bool plot_out_chart_whole(const char *tmp, const char *final, char *err, size_t n)
{
    FILE *f = fopen(tmp, "rb");
    unsigned char tail[64];
    long size = -1;
    size_t got = 0;
    if (f && fseek(f, 0, SEEK_END) == 0 && (size = ftell(f)) >= 0) {
        long from = size > (long)sizeof tail ? size - (long)sizeof tail : 0;
        if (fseek(f, from, SEEK_SET) == 0) got = fread(tail, 1, sizeof tail, f);
    }
    if (f) fclose(f);
    static const unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
    bool whole = size > 0;
    if (ends_with(final, ".png")) whole = got >= 12 && memcmp(tail + got - 12, iend, 12) == 0;
    const char *mark = ends_with(final, ".pdf") ? "%%EOF" : ends_with(final, ".svg") ? "</svg>" : NULL;
    if (mark) {
        whole = false;
        for (size_t i = 0; i + strlen(mark) <= got && !whole; i++) whole = memcmp(tail + i, mark, strlen(mark)) == 0;
    }
    if (!whole)
        snprintf(err, n, "%s: the chart was not written whole (%ld bytes; is the disk full?)", final, size < 0 ? 0 : size);
    return whole;
}

bool plot_out_commit(bool quiet)
{
    char err[SPH_IO_PATH + 200];
    for (int i = 0; i < g_n; i++) /* every chart whole before any file is renamed: all or nothing */
        if (g_chart[i] && !plot_out_chart_whole(g_staged[i].tmp, g_staged[i].path, err, sizeof err)) {
            fprintf(stderr, "sphlab %s: %s\n", g_cmd, err);
            plot_out_abort();
            return false;
        }
    for (int i = 0; i < g_n; i++) {
        if (!sph_out_commit(&g_staged[i], err, sizeof err)) {
            fprintf(stderr, "sphlab %s: %s\n", g_cmd, err);
            for (int j = i + 1; j < g_n; j++) sph_out_abort(&g_staged[j]);
            g_n = 0;
            return false;
        }
        if (!quiet) printf("wrote %s\n", g_staged[i].path);
    }
    g_n = 0;
    return true;
}

void plot_out_abort(void)
{
    for (int i = 0; i < g_n; i++) sph_out_abort(&g_staged[i]);
    g_n = 0;
}
