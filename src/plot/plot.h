/* sphlab plot: charts for a report, drawn with PLplot (cairo driver) as PNG
 * and PDF, each beside the CSV that holds the data it shows.
 *
 * Five files:
 *   plot_csv.c   reads a CSV with a header line into columns of doubles;
 *   plot_out.c   stages output files (through the I/O layer's atomic writer, and
 *                renamed only when every file of the command is complete);
 *   plot_draw.c  the chart types (stacked line panels, horizontal bars,
 *                stacked areas, log-log), their black-and-white-safe styles,
 *                and the pieces a chart drawn elsewhere (the bench ladder)
 *                builds on, so every chart of sphlab has one look;
 *   plot_page.c  the pages: PLplot's cairo devices drawing a chart into the
 *                PNG, PDF (fixed date) and SVG files;
 *   cmd_plot.c   the subcommands: passes, series, kernel, kernels. */
#ifndef SPH_PLOT_H
#define SPH_PLOT_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* ---- CSV tables ---------------------------------------------------------- */

typedef struct plot_table {
    char path[1024];
    int ncols;
    char **names;   /* ncols column names, from the header */
    double **col;   /* ncols arrays of nrows values */
    size_t nrows;
} plot_table;

/* Reads a comma-separated file whose first line names the columns and whose
 * other lines are numbers. Prints a message naming the file (and line and
 * column for a bad value) and returns false on failure. */
bool plot_table_read(plot_table *t, const char *path);
void plot_table_free(plot_table *t);
/* Index of the named column, or -1. */
int plot_table_find(const plot_table *t, const char *name);
/* Like plot_table_find, but prints "FILE: no column 'NAME' (what)" when missing. */
int plot_table_need(const plot_table *t, const char *name, const char *what);

/* ---- output files ---------------------------------------------------------- */

/* Makes DIR (and its parents) if it does not exist; message and false if it
 * cannot be made or is not a directory. */
bool plot_out_dir(const char *dir);
/* The command that --out errors name (default "plot"). */
void plot_out_command(const char *name);
/* That name ("plot" unless a command set its own), for the messages of the charts and tables. */
const char *plot_out_command_name(void);
/* Stages DIR/FILE: creates its temporary (so an unwritable DIR fails here,
 * before anything is drawn) and returns the temporary's path, or NULL with a
 * message. The path stays valid until plot_out_commit/abort. */
const char *plot_out_stage(const char *dir, const char *file);
/* Opens a staged CSV for writing; NULL with a message on failure. */
FILE *plot_out_stage_csv(const char *dir, const char *file);
/* Closes a CSV opened by plot_out_stage_csv; false (and message) on a write error. */
bool plot_out_close_csv(FILE *f, const char *dir, const char *file);
/* Renames every staged temporary to its final name, printing "wrote PATH"
 * unless quiet. Returns false (and removes what is left) on failure. */
bool plot_out_commit(bool quiet);
/* Whether the chart the library wrote to TMP (for FINAL, whose extension says
 * the format) ends as a whole file does; if not, false and why in err. */
bool plot_out_chart_whole(const char *tmp, const char *final, char *err, size_t n);
/* Removes every staged temporary. Also run if PLplot exits on an error. */
void plot_out_abort(void);

/* ---- charts ---------------------------------------------------------------- */

enum { PLOT_MAX_SERIES = 8, PLOT_MAX_PANELS = 4, PLOT_MAX_BARS = 32, PLOT_MAX_LAYERS = 32 };

typedef struct plot_series {
    char label[64];     /* legend text (PLplot escapes allowed) */
    const double *x, *y;
    size_t n;
    int style;          /* index into the style table: colour, line style, marker */
    bool reference;     /* an exact or published curve: its style's colour, solid and thin, no markers */
} plot_series;

typedef struct plot_panel {
    char ylabel[128];   /* quantity [unit] */
    plot_series s[PLOT_MAX_SERIES];
    int n;
    bool zero_line;     /* draw y = 0 */
    bool clip_singular; /* keep values near x = xlo that blow up off the scale */
} plot_panel;

/* Line chart: panels stacked top to bottom over one x axis. */
typedef struct plot_lines {
    char title[160], subtitle[200], xlabel[64];
    double xlo, xhi;    /* xlo == xhi: from the data */
    plot_panel p[PLOT_MAX_PANELS];
    int np;
} plot_lines;

/* Horizontal bars, one per category, top to bottom, value written at the end. */
typedef struct plot_bars {
    char title[160], subtitle[200], xlabel[64];
    char name[PLOT_MAX_BARS][40];
    char note[PLOT_MAX_BARS][48];
    double value[PLOT_MAX_BARS];
    int n;
} plot_bars;

/* Stacked areas over x, first layer at the bottom. */
typedef struct plot_stack {
    char title[160], subtitle[200], xlabel[64], ylabel[64];
    const double *x;
    size_t n;
    char name[PLOT_MAX_LAYERS][40];
    const double *y[PLOT_MAX_LAYERS];
    int nl;
} plot_stack;

enum { PLOT_MAX_CURVES = 32, PLOT_MAX_GUIDES = 4, PLOT_MAX_NOTES = 16 };

/* Points on a log-log chart; non-positive or non-finite ones are left out. */
typedef struct plot_curve {
    char label[96];       /* legend text (PLplot escapes allowed) */
    const double *x, *y;
    int n;
    int style;            /* colour, dashes and marker */
    bool line;            /* join the points */
    bool solid;           /* a solid line whatever the style's dashes */
    bool markers;         /* a marker at every point */
    bool filled;          /* filled markers, for emphasis */
    const int *numbers;   /* if set, written beside each point */
} plot_curve;

/* A thin straight line across a whole log-log chart, y = y0 (x / x0)^slope,
 * to read the data against. A level (slope 0) is kept inside the y axis; a
 * slope is not, as it may cross every decade. */
typedef struct plot_guide {
    double x0, y0, slope;
    int style;            /* colour and dashes, as a curve's; -1: grey dots */
    char label[72];       /* legend text ("": none) */
    bool on_line;         /* the label above the line's left end instead */
} plot_guide;

/* Log-log chart. Axes span whole decades, so every axis carries at least two
 * labelled powers of ten. */
typedef struct plot_loglog {
    char title[160], subtitle[200], xlabel[96], ylabel[96];
    plot_curve c[PLOT_MAX_CURVES];
    int nc;
    plot_guide g[PLOT_MAX_GUIDES];
    int ng;
    char note[PLOT_MAX_NOTES][120]; /* lines of text under the legend */
    int nn;
} plot_loglog;

typedef enum plot_kind { PLOT_LINES, PLOT_BARS, PLOT_STACK, PLOT_LOGLOG } plot_kind;

/* Draws a chart into DIR/BASE.png (width x height pixels) and DIR/BASE.pdf
 * (width/2 x height/2 points: the same layout, 144 dpi), both staged.
 * Deterministic: the PDF's creation date is SOURCE_DATE_EPOCH, or 1970-01-01
 * when that is not set. Returns false with a message on failure. */
bool plot_chart(plot_kind kind, const void *chart, const char *dir, const char *base, int width, int height);
/* Also write DIR/BASE.svg (the PDF's page size) for every chart from now on:
 * a vector format that web pages and most editors take. */
void plot_set_svg(bool on);

/* Escapes PLplot's text escape character '#' in s (for file names in titles). */
void plot_escape(char *dst, size_t cap, const char *s);
/* The power of ten a y-axis of values up to mag (the largest |y|) is divided by, named in its title's unit
 * ("[10^e ...]"); 0: none. Values at or above 1e4 or below 0.1 are scaled, so the tick labels stay short
 * beside the axis title. */
static inline int plot_axis_exponent(double mag)
{
    /* below 0.1 too: ticks such as -0.002 and 0.010 took six characters, and the y-axis title stood on them
     * (the hydrostatic chart's top panel) */
    if (!(isfinite(mag) && mag > 0 && (mag >= 1e4 || mag < 1e-1))) return 0;
    return (int)floor(log10(mag));
}

/* The ends of a log axis, as log10: whole decades around the points' log10 values lo..hi, and a decade more
 * where a point would sit within 0.05 of a decade (12 %) of an end: a study whose errors all read 0.000997 put
 * its markers on the top of the frame, and their row numbers outside it (a user's review). */
static inline void plot_log_axis_ends(double lo, double hi, double *end_lo, double *end_hi)
{
    double a = floor(lo + 1e-9), b = ceil(hi - 1e-9);
    if (b <= a) b = a + 1;
    if (hi > b - 0.05) b += 1;
    if (lo < a + 0.05) a -= 1;
    *end_lo = a;
    *end_hi = b;
}

/* ---- drawing kit: for a chart that none of the kinds above draws ---------- */

/* Colour map 0, as every page sets it: curve colours at PLOT_CURVE + style % 8,
 * fill greys at PLOT_FILL + style % 12. */
enum { PLOT_BG, PLOT_FG, PLOT_GRID, PLOT_REF, PLOT_CURVE, PLOT_FILL = PLOT_CURVE + 8 };

/* Draws draw(chart) on the pages of DIR/BASE.png and DIR/BASE.pdf, as
 * plot_chart does (same sizes, staging and fixed PDF date). */
typedef void plot_draw_fn(const void *chart);
bool plot_page(plot_draw_fn *draw, const void *chart, const char *dir, const char *base, int width, int height);

/* Before plinit (plot_page.c): the colour map and the scale of absolute
 * lengths (1 for the PNG, 0.5 for the PDF and SVG pages). */
void plot_style_start(double scale);

/* Within a page being drawn: */
void plot_width(double w);  /* line width, scaled with the page */
void plot_dash(int style);  /* the style's dashes; style 0 is solid */
/* The polygon in fill style `style`: its grey, then its hatching in black. */
void plot_fill(int n, const double *x, const double *y, int style);
void plot_titles(const char *title, const char *subtitle);

/* A legend entry: a fill sample, or a line and/or marker sample. */
typedef struct plot_key {
    const char *text;
    int style;      /* fill style, or curve style (-1: a guide's grey dots) */
    bool fill;
    bool line, solid, marker, filled;
} plot_key;
/* A boxed legend between x0 and x1 (page fractions) from `top` down: the
 * keys, then lines of notes. */
void plot_legend(const plot_key *k, int n, const char *const *notes, int nn, double x0, double x1, double top);

/* ---- the charts of `sphlab plot` (cmd_plot.c) ------------------------------- */

/* What `sphlab plot WHAT ...` draws: what is passes, series, kernel or kernels;
 * input the stats CSV (passes, series) or the kernel's name (kernel); 0 or
 * NULL fields take the command's defaults. */
typedef struct plot_opts {
    const char *what, *input, *out, *name, *ycols, *xcol;
    int width, height, dim, bins; /* [px], [px], 2 or 3, histogram bins */
    double h;                     /* [m] smoothing length of the kernel charts */
    bool quiet;
} plot_opts;
/* Draws and writes the chart(s) into o->out; the command's exit status. */
int plot_run(const plot_opts *o);

#endif
