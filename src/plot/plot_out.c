/* Output files of one `sphlab plot` command: every file is written through
 * the I/O layer's atomic writer (src/io/io.h) and renamed only when all are
 * complete, so a failure leaves no half-written chart or CSV behind. */
#include <string.h>

#include "plot.h"
#include "../io/io.h"

enum { MAX_STAGED = 64 };

static sph_out g_staged[MAX_STAGED];
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

bool plot_out_commit(bool quiet)
{
    char err[SPH_IO_PATH + 200];
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
