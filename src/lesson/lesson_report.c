/* The lesson's report: its text is a template in the lesson's folder
 * (lessons/NN-name/report.md, and report.fr.md in French), Markdown with
 * placeholders {{name}} that the export fills with what it measured: values
 * (lx_val) and blocks of generated Markdown, tables mostly (lx_block). A
 * section {{?name}}...{{/name}} is kept only if the value `name` is not empty.
 * Every placeholder must have a value and every value must be used by the
 * template: either slip is a failure of the export, so the text and the code
 * cannot drift apart unnoticed. Words the code writes into a value come in
 * both languages, {{@English|Français}}; each report keeps its own. */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "lesson.h"

static lx_value *find(lx *x, const char *name, size_t len)
{
    for (int i = 0; i < x->nval; i++)
        if (strlen(x->vals[i].name) == len && strncmp(x->vals[i].name, name, len) == 0) return &x->vals[i];
    return NULL;
}

/* The value `name`, made empty (a new one if it is not there yet). */
static lx_value *slot(lx *x, const char *name)
{
    lx_value *v = find(x, name, strlen(name));
    if (!v) {
        if (x->nval == LX_MAX_VALUES) {
            fprintf(stderr, "sphlab lesson: more than %d report values\n", LX_MAX_VALUES);
            x->failed++;
            v = &x->vals[LX_MAX_VALUES - 1]; /* overwritten: the report will say something failed */
        } else {
            v = &x->vals[x->nval++];
        }
        memset(v, 0, sizeof *v);
        snprintf(v->name, sizeof v->name, "%s", name);
    }
    free(v->text);
    v->text = NULL;
    v->len = 0;
    return v;
}

void lx_block_end(lx *x)
{
    if (x->blk) fclose(x->blk);
    x->blk = NULL;
    x->mdf = x->sink;
}

void lx_block(lx *x, const char *name)
{
    lx_block_end(x);
    lx_value *v = slot(x, name);
    x->blk = open_memstream(&v->text, &v->len);
    if (x->blk) x->mdf = x->blk;
}

void lx_val(lx *x, const char *name, const char *fmt, ...)
{
    FILE *keep = x->blk;
    x->blk = NULL; /* a value set inside a block leaves the block open */
    lx_value *v = slot(x, name);
    x->blk = keep;
    va_list ap, ap2;
    va_start(ap, fmt);
    va_copy(ap2, ap);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    v->text = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (v->text) vsnprintf(v->text, (size_t)n + 1, fmt, ap2);
    va_end(ap2);
    v->len = v->text ? (size_t)n : 0;
}

void lx_values_free(lx *x)
{
    lx_block_end(x);
    for (int i = 0; i < x->nval; i++) free(x->vals[i].text);
    x->nval = 0;
}

/* Appends n bytes of s to the output. */
static void put(FILE *out, const char *s, size_t n)
{
    if (n) fwrite(s, 1, n, out);
}

/* Writes a value's text, where "{{@English|Français}}" pieces (table headers,
 * words of generated sentences) give the report's language its own words:
 * the values are measured once and written in both reports. */
static void put_localised(const lx *x, FILE *out, const char *s, size_t n)
{
    const char *end = s + n;
    while (s < end) {
        const char *open = strstr(s, "{{@");
        if (!open || open >= end) break;
        const char *bar = open + 2, *close = strstr(open + 3, "}}");
        do /* the first bar not escaped as a Markdown table's \| */
            bar = strchr(bar + 1, '|');
        while (bar && bar[-1] == '\\');
        if (!bar || !close || close >= end || bar > close) break;
        put(out, s, (size_t)(open - s));
        if (x->lang == 1)
            put(out, bar + 1, (size_t)(close - bar - 1));
        else
            put(out, open + 3, (size_t)(bar - open - 3));
        s = close + 2;
    }
    put(out, s, (size_t)(end - s));
}

/* Fills [t, end) into out; returns the count of placeholders without a value. */
static int fill(lx *x, const char *t, const char *end, FILE *out, const char *tmpl_name)
{
    int unfilled = 0;
    while (t < end) {
        const char *open = strstr(t, "{{");
        if (!open || open >= end) {
            put(out, t, (size_t)(end - t));
            break;
        }
        put(out, t, (size_t)(open - t));
        const char *close = strstr(open + 2, "}}");
        if (!close || close >= end) {
            fprintf(stderr, "sphlab lesson %d: %s: '{{' without '}}'\n", x->L->num, tmpl_name);
            put(out, open, (size_t)(end - open));
            return unfilled + 1;
        }
        const char *name = open + 2;
        size_t len = (size_t)(close - name);
        bool section = *name == '?';
        if (section) {
            name++, len--;
            /* the section runs to {{/name}} */
            char tag[80];
            snprintf(tag, sizeof tag, "{{/%.*s}}", (int)len, name);
            const char *stop = strstr(close + 2, tag);
            lx_value *v = find(x, name, len);
            if (!stop || stop >= end || !v) {
                fprintf(stderr, "sphlab lesson %d: %s: section '%.*s' %s\n", x->L->num, tmpl_name, (int)len, name,
                        !v ? "has no value" : "is not closed");
                unfilled++;
                t = stop && stop < end ? stop + strlen(tag) : close + 2;
                continue;
            }
            v->used = true;
            if (v->len) unfilled += fill(x, close + 2, stop, out, tmpl_name);
            t = stop + strlen(tag);
            continue;
        }
        lx_value *v = find(x, name, len);
        if (!v) {
            fprintf(stderr, "sphlab lesson %d: %s: no value for {{%.*s}}\n", x->L->num, tmpl_name, (int)len, name);
            fprintf(out, "(%.*s: not measured)", (int)len, name);
            unfilled++;
        } else {
            v->used = true;
            put_localised(x, out, v->text ? v->text : "", v->len);
        }
        t = close + 2;
    }
    return unfilled;
}

bool lx_report_write(lx *x, const char *tmpl_path, FILE *out)
{
    lx_block_end(x);
    char *tmpl = lx_read_file(tmpl_path);
    if (!tmpl) {
        fprintf(stderr, "sphlab lesson %d: cannot read the report's template %s\n", x->L->num, tmpl_path);
        return false;
    }
    const char *base = strrchr(tmpl_path, '/');
    int unfilled = fill(x, tmpl, tmpl + strlen(tmpl), out, base ? base + 1 : tmpl_path);
    free(tmpl);
    return unfilled == 0;
}

int lx_values_unused(lx *x, const char *what)
{
    int n = 0;
    for (int i = 0; i < x->nval; i++) {
        if (x->vals[i].used) continue;
        fprintf(stderr, "sphlab lesson %d: %s uses no {{%s}}\n", x->L->num, what, x->vals[i].name);
        n++;
    }
    return n;
}

void lx_values_reset_use(lx *x)
{
    for (int i = 0; i < x->nval; i++) x->vals[i].used = false;
}
