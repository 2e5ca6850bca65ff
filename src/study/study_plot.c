/* The study's log-log charts are sphlab plot's log-log chart type
 * (src/plot/plot_draw.c), so they share its look and its PNG + PDF output:
 * this file only hands the study's chart over in the plot module's terms. */
#include <stdio.h>
#include <string.h>

#include "plot.h"
#include "study_plot.h"

bool study_chart_loglog(const study_chart *c, const char *dir, const char *base, int width, int height)
{
    static plot_loglog L; /* about 3 kB: kept off the stack */
    memset(&L, 0, sizeof L);
    snprintf(L.title, sizeof L.title, "%s", c->title);
    snprintf(L.subtitle, sizeof L.subtitle, "%s", c->subtitle);
    snprintf(L.xlabel, sizeof L.xlabel, "%s", c->xlabel);
    snprintf(L.ylabel, sizeof L.ylabel, "%s", c->ylabel);
    for (int k = 0; k < c->nc && k < PLOT_MAX_CURVES; k++, L.nc++) {
        const study_curve *s = &c->c[k];
        L.c[k] = (plot_curve){.x = s->x, .y = s->y, .n = s->n, .style = s->style, .line = s->line, .solid = s->solid,
                              .markers = s->markers, .filled = s->filled, .numbers = s->numbers};
        snprintf(L.c[k].label, sizeof L.c[k].label, "%s", s->label);
    }
    for (int i = 0; i < c->nn && i < PLOT_MAX_NOTES; i++, L.nn++) snprintf(L.note[i], sizeof L.note[i], "%s", c->note[i]);
    return plot_chart(PLOT_LOGLOG, &L, dir, base, width, height);
}
