/* Log-log charts of the study (error against time with the Pareto front;
 * estimation error against h), drawn with PLplot's cairo driver as PNG and
 * PDF, in the style of sphlab plot (docs/figures.md), staged through
 * src/plot/plot_out.c so a failure leaves no half-written file. */
#ifndef SPH_STUDY_PLOT_H
#define SPH_STUDY_PLOT_H

#include <stdbool.h>

#define STUDY_MAX_CURVES 10
#define STUDY_MAX_NOTES 16

typedef struct study_curve {
    char label[96];       /* legend text (PLplot escapes allowed) */
    const double *x, *y;  /* points; non-positive or non-finite ones are left out */
    int n;
    int style;            /* colour, line style and marker, as in sphlab plot */
    bool line;            /* join the points */
    bool solid;           /* a solid line whatever the style's dashes */
    bool markers;         /* a marker at every point */
    bool filled;          /* filled markers (the Pareto front) */
    const int *numbers;   /* if set, written beside each point (the combination's row) */
} study_curve;

typedef struct study_chart {
    char title[160], subtitle[200], xlabel[96], ylabel[96];
    study_curve c[STUDY_MAX_CURVES];
    int nc;
    char note[STUDY_MAX_NOTES][120]; /* lines of text under the legend */
    int nn;
} study_chart;

/* Draws DIR/BASE.png (width x height) and DIR/BASE.pdf (half the pixel count
 * in points), both staged; commit with plot_out_commit. Deterministic (the
 * PDF's date is SOURCE_DATE_EPOCH or 1970-01-01). False with a message. */
bool study_chart_loglog(const study_chart *c, const char *dir, const char *base, int width, int height);

#endif
