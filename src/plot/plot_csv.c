/* Reading a numeric CSV with a header line into columns. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "plot.h"

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t') s++;
    size_t n = strlen(s);
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' || s[n - 1] == '\n')) s[--n] = '\0';
    return s;
}

/* Whole file into a NUL-terminated buffer; NULL with a message on failure. */
static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "sphlab %s: %s: cannot read: %s\n", plot_out_command_name(), path, strerror(errno));
        return NULL;
    }
    size_t cap = 1 << 16, len = 0;
    char *buf = malloc(cap);
    while (buf) {
        len += fread(buf + len, 1, cap - len - 1, f);
        if (ferror(f)) {
            fprintf(stderr, "sphlab %s: %s: cannot read: %s\n", plot_out_command_name(), path, strerror(errno));
            free(buf);
            fclose(f);
            return NULL;
        }
        if (feof(f)) break;
        if (len + 1 >= cap) {
            char *nb = realloc(buf, cap *= 2);
            if (!nb) free(buf);
            buf = nb;
        }
    }
    fclose(f);
    if (!buf) {
        fprintf(stderr, "sphlab %s: %s: out of memory\n", plot_out_command_name(), path);
        return NULL;
    }
    buf[len] = '\0';
    if (memchr(buf, '\0', len)) {
        fprintf(stderr, "sphlab %s: %s: not a text file (NUL byte)\n", plot_out_command_name(), path);
        free(buf);
        return NULL;
    }
    return buf;
}

void plot_table_free(plot_table *t)
{
    for (int c = 0; c < t->ncols; c++) {
        if (t->names) free(t->names[c]);
        if (t->col) free(t->col[c]);
    }
    free(t->names);
    free(t->col);
    memset(t, 0, sizeof *t);
}

static bool fail(plot_table *t, char *buf)
{
    free(buf);
    plot_table_free(t);
    return false;
}

bool plot_table_read(plot_table *t, const char *path)
{
    memset(t, 0, sizeof *t);
    snprintf(t->path, sizeof t->path, "%s", path);
    char *buf = slurp(path);
    if (!buf) return false;

    char *line = buf;
    char *nl = strchr(line, '\n');
    if (nl) *nl = '\0';
    char *head = trim(line);
    if (!*head) {
        fprintf(stderr, "sphlab %s: %s: empty: no header line naming the columns\n", plot_out_command_name(), path);
        return fail(t, buf);
    }
    int ncols = 1;
    for (const char *p = head; *p; p++) ncols += *p == ',';
    t->names = calloc((size_t)ncols, sizeof *t->names);
    t->col = calloc((size_t)ncols, sizeof *t->col);
    if (!t->names || !t->col) {
        fprintf(stderr, "sphlab %s: %s: out of memory\n", plot_out_command_name(), path);
        return fail(t, buf);
    }
    t->ncols = ncols;
    int c = 0;
    for (char *tok = head;; c++) {
        char *comma = strchr(tok, ',');
        if (comma) *comma = '\0';
        char *name = trim(tok);
        if (!*name) {
            fprintf(stderr, "sphlab %s: %s:1: column %d has no name\n", plot_out_command_name(), path, c + 1);
            return fail(t, buf);
        }
        t->names[c] = strdup(name);
        if (!t->names[c]) {
            fprintf(stderr, "sphlab %s: %s: out of memory\n", plot_out_command_name(), path);
            return fail(t, buf);
        }
        if (!comma) break;
        tok = comma + 1;
    }

    size_t cap = 0;
    int lineno = 1;
    char *next = nl ? nl + 1 : NULL;
    while (next) {
        line = next;
        lineno++;
        nl = strchr(line, '\n');
        if (nl) *nl = '\0';
        next = nl ? nl + 1 : NULL;
        char *row = trim(line);
        if (!*row) continue;
        if (t->nrows == cap) {
            cap = cap ? 2 * cap : 1024;
            for (c = 0; c < ncols; c++) {
                double *nc = realloc(t->col[c], cap * sizeof *nc);
                if (!nc) {
                    fprintf(stderr, "sphlab %s: %s: out of memory\n", plot_out_command_name(), path);
                    return fail(t, buf);
                }
                t->col[c] = nc;
            }
        }
        c = 0;
        for (char *tok = row;; c++) {
            char *comma = strchr(tok, ',');
            if (comma) *comma = '\0';
            if (c >= ncols) {
                fprintf(stderr, "sphlab %s: %s:%d: more values than the %d columns of the header\n", plot_out_command_name(), path, lineno,
                        ncols);
                return fail(t, buf);
            }
            char *v = trim(tok), *end;
            double x = strtod(v, &end);
            if (!*v || *end) {
                fprintf(stderr, "sphlab %s: %s:%d: column '%s': '%s' is not a number\n", plot_out_command_name(), path, lineno,
                        t->names[c], v);
                return fail(t, buf);
            }
            t->col[c][t->nrows] = x;
            if (!comma) break;
            tok = comma + 1;
        }
        if (c + 1 != ncols) {
            fprintf(stderr, "sphlab %s: %s:%d: %d values, the header names %d columns\n", plot_out_command_name(), path, lineno, c + 1,
                    ncols);
            return fail(t, buf);
        }
        t->nrows++;
    }
    free(buf);
    if (t->nrows == 0) {
        fprintf(stderr, "sphlab %s: %s: no data rows under the header\n", plot_out_command_name(), path);
        plot_table_free(t);
        return false;
    }
    return true;
}

int plot_table_find(const plot_table *t, const char *name)
{
    for (int c = 0; c < t->ncols; c++)
        if (strcmp(t->names[c], name) == 0) return c;
    return -1;
}

int plot_table_need(const plot_table *t, const char *name, const char *what)
{
    int c = plot_table_find(t, name);
    if (c < 0) fprintf(stderr, "sphlab %s: %s: no column '%s' (%s)\n", plot_out_command_name(), t->path, name, what);
    return c;
}
