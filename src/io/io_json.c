/* JSON outputs (io_json.h): cJSON builds, escapes and formats the values;
 * this file lays the tree out. */
#include "io_json.h"

#include <math.h>
#include <stdlib.h>

#include "io.h"

static bool is_container(const cJSON *v)
{
    return cJSON_IsObject(v) || cJSON_IsArray(v);
}

static void indent(FILE *f, int depth)
{
    for (int i = 0; i < depth; i++) fputs("  ", f);
}

/* A scalar as cJSON prints it. */
static bool put_leaf(FILE *f, const cJSON *v)
{
    char *s = cJSON_PrintUnformatted(v);
    if (!s) return false;
    fputs(s, f);
    cJSON_free(s);
    return true;
}

static bool put_key(FILE *f, const char *key)
{
    cJSON *k = cJSON_CreateString(key);
    if (!k) return false;
    bool ok = put_leaf(f, k);
    cJSON_Delete(k);
    fputs(": ", f);
    return ok;
}

bool sph_json_fput(FILE *f, const cJSON *v, int depth)
{
    if (!is_container(v)) return put_leaf(f, v) && !ferror(f);
    bool obj = cJSON_IsObject(v), flat = !obj;
    for (const cJSON *c = v->child; c; c = c->next) flat &= !is_container(c);
    fputc(obj ? '{' : '[', f);
    bool ok = true;
    for (const cJSON *c = v->child; c && ok; c = c->next) {
        if (flat) {
            if (c != v->child) fputs(", ", f);
        } else {
            fputs(c != v->child ? ",\n" : "\n", f);
            indent(f, depth + 1);
        }
        if (obj) ok = put_key(f, c->string ? c->string : "");
        ok = ok && sph_json_fput(f, c, depth + 1);
    }
    if (!flat && v->child) {
        fputc('\n', f);
        indent(f, depth);
    }
    fputc(obj ? '}' : ']', f);
    return ok && !ferror(f);
}

bool sph_json_save(const char *path, const cJSON *root, char *err, size_t n)
{
    sph_out o;
    if (!sph_out_open(&o, path, err, n)) return false;
    if (!sph_json_fput(o.f, root, 0)) {
        if (err && n) snprintf(err, n, "%s: cannot write the JSON (out of memory or a write error)", path);
        sph_out_abort(&o);
        return false;
    }
    fputc('\n', o.f);
    return sph_out_commit(&o, err, n);
}

double sph_json_round(double v, int digits)
{
    if (!isfinite(v)) return v;
    char s[64];
    snprintf(s, sizeof s, "%.*g", digits, v);
    return strtod(s, NULL);
}

bool sph_json_add_num(cJSON *obj, const char *key, double v, int digits)
{
    return cJSON_AddNumberToObject(obj, key, sph_json_round(v, digits)) != NULL;
}
