/* What the lessons' exports share: scenes, the pipeline into the report,
 * scratch paths, fits, the particle dumps read back by id, frames moved into
 * the output. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "lesson_steps.h"

bool lx_load_def(lx *x, const char *path, sph_scene_def *def)
{
    sph_error err;
    *def = sph_default_scene_def();
    if (sph_scene_load(path, def, &err) == SPH_ERR_OK && sph_scene_validate(def, &err) == SPH_ERR_OK) return true;
    fprintf(stderr, "sphlab lesson: %s\n", err.msg);
    lx_md(x, "\n**The scene does not load:** %s\n\n", err.msg);
    x->failed++;
    return false;
}

/* `sphlab check` of a scene, into the report; fills the pipeline's pass names. */
int lx_pipeline(lx *x, const char *file, char names[][24], int cap)
{
    char none[1][24];
    lx_block(x, "pipeline");
    int n = lx_check(x, lx_src(x, file), names ? names : none, names ? cap : 0);
    lx_block_end(x);
    return n;
}

const char *lx_work(lx *x, const char *sub)
{
    return lx_fmt("%s/%s", x->scratch, sub);
}


/* Least-squares slope of y against x. */
double lx_slope(const double *xs, const double *ys, size_t n)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < n; i++) {
        sx += xs[i];
        sy += ys[i];
        sxx += xs[i] * xs[i];
        sxy += xs[i] * ys[i];
    }
    double d = (double)n * sxx - sx * sx;
    return d != 0 ? ((double)n * sxy - sx * sy) / d : 0;
}

/* Decay rate of the velocity (half that of the kinetic energy) from a stats CSV. */
bool lx_decay_rate(lx *x, const char *stats, double *rate, plot_table *keep)
{
    plot_table t;
    if (!lx_table(x, &t, stats)) return false;
    const double *tt = lx_col(x, &t, "t"), *ek = lx_col(x, &t, "ekin");
    if (!tt || !ek || t.nrows < 3) {
        plot_table_free(&t);
        return false;
    }
    double *le = malloc(t.nrows * sizeof *le);
    for (size_t i = 0; i < t.nrows; i++) le[i] = log(ek[i] > 0 ? ek[i] : 1e-300);
    *rate = -0.5 * lx_slope(tt, le, t.nrows);
    free(le);
    if (keep) *keep = t;
    else plot_table_free(&t);
    return true;
}

/* The 2D scenes' lattice: the particle of a block at (column, row). */
uint32_t lx_lattice_id(const sph_scene_def *d, int col, int row)
{
    return (uint32_t)(row * sph_block_nodes(d, 0, 0) + col);
}

bool lx_read_dump(lx *x, const char *path, lx_dump *d)
{
    memset(d, 0, sizeof *d);
    if (!lx_table(x, &d->t, path)) return false;
    d->id = lx_col(x, &d->t, "id");
    d->x = lx_col(x, &d->t, "x");
    d->y = lx_col(x, &d->t, "y");
    d->vx = lx_col(x, &d->t, "vx");
    d->vy = lx_col(x, &d->t, "vy");
    d->rho = lx_col(x, &d->t, "rho");
    d->p = lx_col(x, &d->t, "p");
    d->n = d->t.nrows;
    if (!d->id || !d->x || !d->y || !d->vx || !d->vy || !d->rho || !d->p) {
        plot_table_free(&d->t);
        return false;
    }
    return true;
}

double lx_at_id(const lx_dump *d, const double *col, uint32_t id)
{
    return id < d->n ? col[id] : NAN;
}

/* Moves every file of DIR/.work/SUB into DIR/SUB (made afresh). */
int lx_take_all(lx *x, const char *sub)
{
    char dst[1200];
    snprintf(dst, sizeof dst, "%s/%s", x->dir, sub);
    char cmd[2600];
    /* the destination holds only frames from this export */
    snprintf(cmd, sizeof cmd, "%s/%s", x->scratch, sub);
    struct stat st;
    if (stat(cmd, &st) != 0) return 0;
    if (stat(dst, &st) == 0) {
        /* remove old frames one by one: the folder is ours (frames/) */
        for (int i = 0; i < 100000; i++) {
            char f[1300];
            snprintf(f, sizeof f, "%s/frame_%05d.png", dst, i);
            if (unlink(f) != 0 && i > 0) break;
        }
        rmdir(dst);
    }
    if (rename(cmd, dst) != 0) return 0;
    int n = 0;
    for (int i = 0; i < 100000; i++) {
        char f[1300];
        snprintf(f, sizeof f, "%s/frame_%05d.png", dst, i);
        if (stat(f, &st) != 0) break;
        n++;
    }
    return n;
}

int lx_split_csv(char *line, char **f, int cap)
{
    int n = 0;
    for (char *p = line; n < cap;) {
        f[n++] = p;
        p = strchr(p, ',');
        if (!p) break;
        *p++ = '\0';
    }
    return n;
}
