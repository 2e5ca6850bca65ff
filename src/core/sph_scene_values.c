/* Scene files: one key's value from its text (range and choice checks, their
 * messages) and the defaults from the key table (sph_scene_keys.c); the table of
 * named-section groups. The parser that reads the files is sph_scene.c. */
#include "sph_scene_values.h"
#include "sph_names.h"
#include "sph_obstacles.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the named-section groups ------------------------------------------ */

#define GROUP(T, field, n, max, name_max)                                                                      \
    sizeof(T), offsetof(T, name), offsetof(T, line), offsetof(T, origin), offsetof(sph_scene_def, field),      \
        offsetof(sph_scene_def, n), max, name_max
const sph_scene_group sph_scene_groups[] = {
    {"fluid", "fluid block", "[fluid pool]", GROUP(sph_block_def, blocks, n_blocks, SPH_MAX_BLOCKS, SPH_BLOCK_NAME_MAX)},
    {"obstacle", "obstacle", "[obstacle rock]",
     GROUP(sph_obstacle_def, obstacles, n_obstacles, SPH_MAX_OBSTACLES, SPH_OBSTACLE_NAME_MAX)},
};
#undef GROUP
#define N_GROUPS (int)(sizeof sph_scene_groups / sizeof sph_scene_groups[0])

const sph_scene_group *sph_scene_section_group(const char *section)
{
    for (int g = 0; g < N_GROUPS; g++) {
        size_t n = strlen(sph_scene_groups[g].kind);
        /* before reading section[n]: it may be shorter */
        if (strncmp(section, sph_scene_groups[g].kind, n) != 0) continue;
        char c = section[n];
        if (c == '\0' || c == ' ' || c == '.' || c == '\t') return &sph_scene_groups[g];
    }
    return NULL;
}

/* ---- values ------------------------------------------------------------- */

static void range_text(const sph_key *k, char *out, size_t n)
{
    if (k->type == SPH_KEY_CHOICE || k->type == SPH_KEY_KERNEL || k->type == SPH_KEY_FLAGS) {
        size_t used = (size_t)snprintf(out, n, "%s", k->type == SPH_KEY_FLAGS ? "a list of (or none): " : "one of: ");
        for (int i = 0; i < k->n_choices && used < n; i++)
            used += (size_t)snprintf(out + used, n - used, "%s%s", i ? ", " : "", k->choices[i]);
        return;
    }
    if (k->type == SPH_KEY_STRING) {
        snprintf(out, n, "text up to 63 characters, no control characters");
        return;
    }
    const char *unit = k->unit && *k->unit ? k->unit : "";
    const char *what = k->type == SPH_KEY_VEC || k->type == SPH_KEY_POINT ? "2 or 3 numbers, each " : "";
    snprintf(out, n, "%s%s %g and %s %g%s%s", what, k->min_open ? "above" : "from", k->min,
             k->max_open ? "below" : "up to", k->max, *unit ? " " : "", unit);
}

void sph_scene_where_text(const sph_scene_where *w, char *out, size_t n)
{
    if (w->line > 0)
        snprintf(out, n, "%s:%d", w->file, w->line);
    else
        snprintf(out, n, "--set");
}

static sph_error_code bad_value(sph_error *err, sph_error_code code, const sph_scene_where *w, const sph_key *k,
                                const char *value, const char *why)
{
    char loc[320], range[256];
    sph_scene_where_text(w, loc, sizeof loc);
    range_text(k, range, sizeof range);
    return sph_fail(err, code, "%s: [%s] %s = '%.80s': %s (accepted: %s)", loc, w->section, k->name, value, why,
                    range);
}

static bool parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s) return false;
    while (isspace((unsigned char)*end)) end++;
    if (*end != '\0') return false;
    *out = v;
    return true;
}

static bool in_range(const sph_key *k, double v)
{
    if (!isfinite(v)) return false;
    if (k->min_open ? !(v > k->min) : !(v >= k->min)) return false;
    if (k->max_open ? !(v < k->max) : !(v <= k->max)) return false;
    return true;
}

/* A stored float is compared with the bounds rounded to float as well, so a
 * bound such as 1e-4, which a float cannot hold exactly, is itself accepted. */
static bool stored_in_range(const sph_key *k, float f)
{
    float lo = (float)k->min, hi = (float)k->max;
    if (!isfinite(f)) return false;
    if (k->min_open ? !(f > lo) : !(f >= lo)) return false;
    if (k->max_open ? !(f < hi) : !(f <= hi)) return false;
    return true;
}

static int find_choice(const sph_key *k, const char *s, size_t len)
{
    for (int i = 0; i < k->n_choices; i++)
        if (strlen(k->choices[i]) == len && strncmp(k->choices[i], s, len) == 0) return i;
    return -1;
}

/* why: "unknown choice", or "unknown effect 'word'", with the nearest choice for a typo. */
static const char *unknown_choice(const sph_key *k, const char *what, const char *s, size_t len, char *why, size_t n)
{
    char word[64];
    snprintf(word, sizeof word, "%.*s", (int)(len < 60 ? len : 60), s);
    const char *near = NULL;
    int near_d = 1 << 30;
    for (int i = 0; i < k->n_choices; i++) {
        const int d = sph_edit_distance(word, k->choices[i]);
        if (sph_name_near(word, k->choices[i]) && d < near_d) near = k->choices[i], near_d = d;
    }
    /* a choice's word is the whole value, already quoted; an effect is one word of a list */
    const bool quote = strcmp(what, "choice") != 0;
    snprintf(why, n, "unknown %s%s%s%s%s%s%s", what, quote ? " '" : "", quote ? word : "", quote ? "'" : "",
             near ? " (did you mean '" : "", near ? near : "", near ? "'?)" : "");
    return why;
}

sph_error_code sph_scene_value_set(const sph_key *k, void *base, const char *value, const sph_scene_where *w,
                                   int *ncomp, sph_error *err)
{
    char *field = (char *)base + k->offset;
    *ncomp = 1;
    switch (k->type) {
    case SPH_KEY_STRING:
        if (strlen(value) > 63) return bad_value(err, SPH_ERR_RANGE, w, k, value, "too long");
        /* a name is printed on terminals, charts and files: a control character (an escape sequence) is no text */
        for (const char *c = value; *c; c++)
            if (((unsigned char)*c < 0x20 && *c != '\t') || *c == 0x7f) {
                char shown[64 * 4 + 1]; /* the value with each control character written \xNN */
                size_t m = 0;
                for (const char *q = value; *q && m + 5 < sizeof shown; q++)
                    if (((unsigned char)*q < 0x20 && *q != '\t') || *q == 0x7f)
                        m += (size_t)snprintf(shown + m, sizeof shown - m, "\\x%02x", (unsigned char)*q);
                    else
                        shown[m++] = *q;
                shown[m] = '\0';
                return bad_value(err, SPH_ERR_PARSE, w, k, shown, "holds a control character: write plain text");
            }
        snprintf(field, 64, "%s", value);
        return SPH_ERR_OK;
    case SPH_KEY_FLOAT: {
        double v;
        if (!parse_double(value, &v)) return bad_value(err, SPH_ERR_PARSE, w, k, value, "not a number");
        if (!in_range(k, v) || !stored_in_range(k, (float)v))
            return bad_value(err, SPH_ERR_RANGE, w, k, value,
                             in_range(k, v) ? "out of range once stored as a float" : "out of range");
        *(float *)field = (float)v;
        return SPH_ERR_OK;
    }
    case SPH_KEY_INT:
    case SPH_KEY_UINT: {
        double v;
        if (!parse_double(value, &v) || v != floor(v))
            return bad_value(err, SPH_ERR_PARSE, w, k, value, "not a whole number");
        if (!in_range(k, v)) return bad_value(err, SPH_ERR_RANGE, w, k, value, "out of range");
        if (k->type == SPH_KEY_INT)
            *(int *)field = (int)v;
        else
            *(uint32_t *)field = (uint32_t)v;
        return SPH_ERR_OK;
    }
    case SPH_KEY_VEC:
    case SPH_KEY_POINT: {
        double v[3] = {0, 0, 0};
        int n = 0;
        const char *p = value;
        /* Spaces and commas both separate components, so "0,5 0" read as 0, 5, 0: a French decimal comma gave a
         * vortex no speed and gravity (0, -9, 81) with no error. A comma between two digits in a value whose
         * components are also separated by spaces is refused; "1,2" and "1, 2" stay lists. */
        int tokens = 0; /* words between runs of white space, other than a lone comma */
        bool digit_comma = false;
        for (const char *q = value; *q;) {
            while (isspace((unsigned char)*q)) q++;
            if (!*q) break;
            const char *t = q;
            while (*q && !isspace((unsigned char)*q)) q++;
            if (!(q - t == 1 && *t == ',')) tokens++;
            for (const char *c = t + 1; c + 1 < q; c++)
                if (*c == ',' && isdigit((unsigned char)c[-1]) && isdigit((unsigned char)c[1])) digit_comma = true;
        }
        if (tokens > 1 && digit_comma)
            return bad_value(err, SPH_ERR_PARSE, w, k, value,
                             "a comma between digits beside components separated by spaces: a decimal comma? "
                             "write the number with a point (0.5), and separate the components with spaces or "
                             "with commas, not both");
        while (*p) {
            while (isspace((unsigned char)*p) || *p == ',') p++;
            if (!*p) break;
            if (n == 3) return bad_value(err, SPH_ERR_PARSE, w, k, value, "more than 3 numbers");
            char *end;
            double d = strtod(p, &end);
            if (end == p || (*end && !isspace((unsigned char)*end) && *end != ','))
                return bad_value(err, SPH_ERR_PARSE, w, k, value, "not a list of numbers");
            if (!in_range(k, d) || !stored_in_range(k, (float)d))
                return bad_value(err, SPH_ERR_RANGE, w, k, value, "a component is out of range");
            v[n++] = k->type == SPH_KEY_POINT ? d : (float)d;
            p = end;
        }
        if (n < 2) return bad_value(err, SPH_ERR_PARSE, w, k, value, "needs 2 (2D) or 3 (3D) numbers");
        if (k->type == SPH_KEY_POINT)
            memcpy(field, v, sizeof v);
        else
            for (int c = 0; c < 3; c++) ((float *)field)[c] = (float)v[c];
        *ncomp = n;
        return SPH_ERR_OK;
    }
    case SPH_KEY_CHOICE:
    case SPH_KEY_KERNEL: {
        int c = find_choice(k, value, strlen(value));
        char why[160];
        if (c < 0)
            return bad_value(err, SPH_ERR_PARSE, w, k, value,
                             unknown_choice(k, "choice", value, strlen(value), why, sizeof why));
        *(int *)field = c;
        return SPH_ERR_OK;
    }
    case SPH_KEY_FLAGS: {
        unsigned bits = 0;
        const char *p = value;
        int words = 0;
        bool none = false;
        while (*p) {
            while (isspace((unsigned char)*p) || *p == ',') p++;
            if (!*p) break;
            const char *q = p;
            while (*q && !isspace((unsigned char)*q) && *q != ',') q++;
            words++;
            if (q - p == 4 && strncmp(p, "none", 4) == 0) {
                none = true;
            } else {
                int c = find_choice(k, p, (size_t)(q - p));
                char why[160];
                if (c < 0)
                    return bad_value(err, SPH_ERR_PARSE, w, k, value,
                                     unknown_choice(k, strcmp(k->name, "periodic") == 0 ? "axis" : "effect", p,
                                                    (size_t)(q - p), why, sizeof why));
                bits |= 1u << c;
            }
            p = q;
        }
        /* "none pressure" ran as pressure, and an empty value as none: say which was meant */
        if (words == 0)
            return bad_value(err, SPH_ERR_PARSE, w, k, value, "empty: write none for none of them");
        if (none && words > 1)
            return bad_value(err, SPH_ERR_PARSE, w, k, value, "none with others: write none alone, or the others");
        *(unsigned *)field = bits;
        return SPH_ERR_OK;
    }
    }
    return SPH_ERR_OK;
}

/* ---- defaults ----------------------------------------------------------- */

/* kind: the group whose keys to set ("fluid", "obstacle"), NULL: the scene's own keys. */
static void apply_defaults(void *base, const char *kind)
{
    for (int i = 0; i < sph_scene_key_count; i++) {
        const sph_key *k = &sph_scene_keys[i];
        const sph_scene_group *g = sph_scene_section_group(k->section);
        if (kind ? !g || strcmp(g->kind, kind) != 0 : g != NULL) continue;
        sph_scene_where w = {"(defaults)", 0, k->section};
        int nc;
        sph_error e;
        if (sph_scene_value_set(k, base, k->def, &w, &nc, &e) != SPH_ERR_OK) abort(); /* table bug */
    }
}

void sph_scene_block_defaults(void *block, const char *kind)
{
    apply_defaults(block, kind);
}

sph_scene_def sph_default_scene_def(void)
{
    sph_scene_def def;
    memset(&def, 0, sizeof def);
    apply_defaults(&def, NULL);
    return def;
}
