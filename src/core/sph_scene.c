/* Scene files: the INI parser (libinih) and --set; the key table is in sph_scene_keys.c, one value's parsing
 * and the defaults in sph_scene_values.c, the checks of a scene as a whole in sph_scene_validate.c. */
#include "sph_scene.h"
#include "sph_scene_values.h"
#include "sph_obstacles.h"
#include "sph_memory.h"
#include "sph_names.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <ini.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *const known_sections[] = {"scene", "domain", "physics", "kernels", "time", "search", "interaction", "compute"};

/* ---- the named-section groups' records (the table: sph_scene_values.c) ----- */

#define is_fluid_section(section) (sph_scene_section_group(section) != NULL)

/* "fluid pool", "fluid.pool" and "fluid   pool" all name the block "pool". */
static const char *fluid_block_name(const char *section)
{
    const char *p = section + strlen(sph_scene_section_group(section)->kind);
    while (*p == ' ' || *p == '.' || *p == '\t') p++;
    return p;
}

/* Record r of the group's list, its count, and the parts every record has. */
static char *group_item(const sph_scene_group *g, sph_scene_def *def, int r)
{
    return (char *)def + g->items_off + (size_t)r * g->size;
}
#define group_count(g, def) ((int *)((char *)(def) + (g)->count_off))
#define item_name(g, rec) ((char *)(rec) + (g)->name_off)
#define item_line(g, rec) ((int *)((char *)(rec) + (g)->line_off))
#define item_origin(g, rec) ((sph_origin *)((char *)(rec) + (g)->origin_off))

/* ---- parsing ------------------------------------------------------------ */

#define MAX_SECTIONS 64

typedef struct parse_ctx {
    sph_scene_def *def;
    const char *file;
    const char *text; /* whole file, NUL-terminated */
    size_t len, pos;
    int line;         /* line the reader handed out last */
    int header_line;  /* line of the latest section header */
    char sections[MAX_SECTIONS][64]; /* headers seen, to refuse a section given twice */
    int section_lines[MAX_SECTIONS];
    int n_sections;
    sph_error *err;
    sph_error_code code;
} parse_ctx;

static const sph_key *find_key(const char *section, const char *name, int *index)
{
    const sph_scene_group *g = sph_scene_section_group(section);
    for (int i = 0; i < sph_scene_key_count; i++) {
        const sph_key *k = &sph_scene_keys[i];
        bool match = strcmp(k->section, g ? g->kind : section) == 0;
        if (match && strcmp(k->name, name) == 0) {
            *index = i;
            return k;
        }
    }
    return NULL;
}

static bool known_section(const char *section)
{
    if (is_fluid_section(section)) return true;
    for (size_t i = 0; i < sizeof known_sections / sizeof known_sections[0]; i++)
        if (strcmp(section, known_sections[i]) == 0) return true;
    return false;
}

static const char *section_list(void)
{
    return "scene, domain, physics, kernels, time, search, interaction, compute, fluid NAME, obstacle NAME";
}

/* " (did you mean [search]?)" for a misspelt section (its first word), or "". */
static const char *section_hint(const char *section, char *buf, size_t n)
{
    char word[64];
    snprintf(word, sizeof word, "%.*s", (int)strcspn(section, " \t"), section);
    const char *all[] = {"scene", "domain", "physics", "kernels", "time", "search", "interaction", "compute", "fluid",
                         "obstacle"};
    const char *near = NULL;
    int near_d = 1 << 30;
    for (size_t i = 0; i < sizeof all / sizeof *all; i++) {
        int d = sph_edit_distance(word, all[i]);
        if (sph_name_near(word, all[i]) && d < near_d) {
            near = all[i];
            near_d = d;
        }
    }
    if (!near) return "";
    snprintf(buf, n, " (did you mean [%s%s]?)", near,
             strcmp(near, "fluid") == 0 || strcmp(near, "obstacle") == 0 ? " NAME" : "");
    return buf;
}

/* Index of the key among its group's keys (origin slot of a record). */
static int fluid_slot(int key_index)
{
    int slot = 0;
    for (int i = 0; i < key_index; i++)
        if (strcmp(sph_scene_keys[i].section, sph_scene_keys[key_index].section) == 0) slot++;
    return slot;
}

static char *find_block(const sph_scene_group *g, sph_scene_def *def, const char *name)
{
    for (int b = 0; b < *group_count(g, def); b++)
        if (strcmp(item_name(g, group_item(g, def, b)), name) == 0) return group_item(g, def, b);
    return NULL;
}

/* Applies one key = value; line > 0 for a file line, -1 for --set. */
static sph_error_code apply_key(sph_scene_def *def, const char *file, int line, int header_line,
                                const char *section, const char *name, const char *value, sph_error *err)
{
    sph_scene_where w = {file, line, section};
    char loc[320];
    sph_scene_where_text(&w, loc, sizeof loc);
    char hint[96];
    if (!*section) { /* a key above every header: name the sections that have it */
        char homes[160] = "";
        size_t used = 0;
        for (int i = 0; i < sph_scene_key_count && used < sizeof homes; i++)
            if (strcmp(sph_scene_keys[i].name, name) == 0) {
                const char *sec = sph_scene_keys[i].section;
                bool group_sec = strcmp(sec, "fluid") == 0 || strcmp(sec, "obstacle") == 0;
                used += (size_t)snprintf(homes + used, sizeof homes - used, "%s[%s%s]", used ? " or " : "", sec,
                                         group_sec ? " NAME" : "");
            }
        return sph_fail(err, SPH_ERR_UNKNOWN_SECTION, "%s: key '%.60s' comes before any [section] header (accepted: %s)",
                        loc, name, *homes ? homes : "keys under a section header, e.g. [kernels]");
    }
    if (!known_section(section))
        return sph_fail(err, SPH_ERR_UNKNOWN_SECTION, "%s: unknown section [%.60s]%s (accepted: %s)", loc, section,
                        section_hint(section, hint, sizeof hint), section_list());
    int index;
    const sph_key *k = find_key(section, name, &index);
    if (!k) {
        char keys[512];
        size_t used = 0;
        keys[0] = '\0';
        const sph_scene_group *g = sph_scene_section_group(section);
        for (int i = 0; i < sph_scene_key_count && used < sizeof keys; i++) {
            const sph_key *c = &sph_scene_keys[i];
            if (strcmp(c->section, g ? g->kind : section) == 0)
                used += (size_t)snprintf(keys + used, sizeof keys - used, "%s%s", used ? ", " : "", c->name);
        }
        /* the nearest key of the section, for a typo */
        const char *near = NULL;
        int near_d = 1 << 30;
        for (int i = 0; i < sph_scene_key_count; i++) {
            const sph_key *c = &sph_scene_keys[i];
            /* keys are lower case: STIFFNESS is stiffness, however far apart the letters' codes */
            const bool caseless = strcasecmp(name, c->name) == 0;
            int d = caseless ? 0 : sph_edit_distance(name, c->name);
            if (strcmp(c->section, g ? g->kind : section) == 0 && (caseless || sph_name_near(name, c->name)) &&
                d < near_d) {
                near = c->name;
                near_d = d;
            }
        }
        /* the key of another section, put under the wrong header (a student's [time] solver_tolerance) */
        const char *home = NULL;
        for (int i = 0; i < sph_scene_key_count && !near && !home; i++)
            if (strcmp(sph_scene_keys[i].name, name) == 0) home = sph_scene_keys[i].section;
        char moved[120] = "";
        if (home) /* a block kind ([fluid NAME], [obstacle NAME]) takes a name */
            snprintf(moved, sizeof moved, " (it is a key of [%s%s])", home,
                     strcmp(home, "fluid") == 0 || strcmp(home, "obstacle") == 0 ? " NAME" : "");
        return sph_fail(err, SPH_ERR_UNKNOWN_KEY, "%s: unknown key '%.60s' in [%.60s]%s%s%s%s (accepted: %s)", loc,
                        name, section, near ? " (did you mean '" : "", near ? near : "", near ? "'?)" : "", moved,
                        keys);
    }
    int ncomp;
    const sph_scene_group *g = sph_scene_section_group(section);
    if (g) {
        const char *bname = fluid_block_name(section);
        int slot = fluid_slot(index), *count = group_count(g, def);
        if (slot >= SPH_GROUP_KEYS_MAX) /* a key added to the table beyond the origin slots: a build defect */
            return sph_fail(err, SPH_ERR_SCENE, "%s: [%.60s] %s: key %d of its section, past the %d origin slots "
                            "(raise SPH_GROUP_KEYS_MAX)", loc, section, name, slot + 1, SPH_GROUP_KEYS_MAX);
        char *targets[SPH_MAX_BLOCKS > SPH_MAX_OBSTACLES ? SPH_MAX_BLOCKS : SPH_MAX_OBSTACLES];
        int nt = 0;
        if (line < 0 && *bname == '\0') { /* --set fluid.key=v: every block */
            for (int b = 0; b < *count; b++) targets[nt++] = group_item(g, def, b);
            if (nt == 0)
                return sph_fail(err, SPH_ERR_SCENE, "--set [%s] %s: the scene has no %s", section, name, g->noun);
        } else {
            char *b = find_block(g, def, bname);
            if (!b) {
                if (line < 0) {
                    char names[256];
                    size_t used = 0;
                    names[0] = '\0';
                    for (int k2 = 0; k2 < *count && used < sizeof names; k2++) {
                        const char *nm = item_name(g, group_item(g, def, k2));
                        used += (size_t)snprintf(names + used, sizeof names - used, "%s%s", k2 ? ", " : "",
                                                 *nm ? nm : "(unnamed)");
                    }
                    return sph_fail(err, SPH_ERR_SCENE,
                                    "--set %s.%.40s.%.40s: no %s named '%.40s' (the scene has: %s)", g->kind, bname,
                                    name, g->noun, bname, *count ? names : "none");
                }
                if (*count == g->max)
                    return sph_fail(err, SPH_ERR_RANGE, "%s: [%.60s]: more than %d %ss", loc, section, g->max,
                                    g->noun);
                if (strlen(bname) > (size_t)g->name_max)
                    return sph_fail(err, SPH_ERR_RANGE, "%s: [%.60s]: %s name longer than %d characters", loc,
                                    section, g->noun, g->name_max);
                b = group_item(g, def, (*count)++);
                memset(b, 0, g->size);
                sph_scene_block_defaults(b, g->kind);
                snprintf(item_name(g, b), 48, "%s", bname);
                *item_line(g, b) = header_line > 0 ? header_line : line;
            }
            targets[nt++] = b;
        }
        for (int t = 0; t < nt; t++) {
            sph_origin *origin = item_origin(g, targets[t]);
            /* set under this same header: a plain duplicate; under an earlier header of the same name: two
             * blocks that were meant to be two */
            if (line > 0 && origin[slot].line > 0 && header_line > 0 && origin[slot].line > header_line)
                return sph_fail(err, SPH_ERR_DUPLICATE_KEY, "%s: duplicate key '%s' in [%.60s] (first set on line %d)",
                                loc, name, section, origin[slot].line);
            if (line > 0 && origin[slot].line > 0)
                return sph_fail(err, SPH_ERR_DUPLICATE_KEY,
                                "%s: duplicate key '%s' in [%.60s] (first set on line %d); give each %s its own "
                                "name, e.g. %s",
                                loc, name, section, origin[slot].line, g->noun, g->example);
            sph_error_code c = sph_scene_value_set(k, targets[t], value, &w, &ncomp, err);
            if (c) return c;
            origin[slot].line = line;
            origin[slot].ncomp = ncomp;
        }
        return SPH_ERR_OK;
    }
    if (line > 0 && def->origin[index].line > 0)
        return sph_fail(err, SPH_ERR_DUPLICATE_KEY, "%s: duplicate key '%s' in [%s] (first set on line %d)", loc,
                        name, section, def->origin[index].line);
    sph_error_code c = sph_scene_value_set(k, def, value, &w, &ncomp, err);
    if (c) return c;
    def->origin[index].line = line;
    def->origin[index].ncomp = ncomp;
    return SPH_ERR_OK;
}

static int on_key(void *user, const char *section, const char *name, const char *value)
{
    parse_ctx *ctx = user;
    if (ctx->code) return 0;
    ctx->code = apply_key(ctx->def, ctx->file, ctx->line, ctx->header_line, section, name, value, ctx->err);
    return ctx->code == SPH_ERR_OK;
}

/* Checks a [fluid ...] header and hands inih its one spelling "[fluid NAME]":
 * the name must fit in what inih keeps of a section (longer ones were cut,
 * and two names with a common start merged), and a block may be opened only
 * once, whatever separator ("fluid a", "fluid.a", "fluid  a") names it. */
static bool fluid_header(parse_ctx *ctx, const char *header, char *str, int num)
{
    const sph_scene_group *g = sph_scene_section_group(header);
    const char *bname = fluid_block_name(header);
    const bool fluid = g == &sph_scene_groups[0];
    size_t len = strlen(bname);
    if (len > (size_t)g->name_max) {
        ctx->code = sph_fail(ctx->err, SPH_ERR_RANGE,
                             "%s:%d: [%.120s]: the %s name '%.120s' has %zu characters, more than the limit of %d "
                             "characters",
                             ctx->file, ctx->line, header, fluid ? "block" : g->noun, bname, len, g->name_max);
        return false;
    }
    /* an obstacle's name makes CSV columns (obstacle_NAME_fx): letters, digits, - and _ only */
    for (const char *c = bname; !fluid && (c == bname || *c); c++)
        if (!*c || !(isalnum((unsigned char)*c) || *c == '-' || *c == '_')) {
            ctx->code = sph_fail(ctx->err, SPH_ERR_PARSE,
                                 "%s:%d: [%.120s]: %s; an obstacle's name, e.g. [obstacle rock], may hold letters, "
                                 "digits, '-' and '_' only (it names --stats columns)",
                                 ctx->file, ctx->line, header, *c ? "the name holds another character"
                                                                  : "the obstacle has no name");
            return false;
        }
    if (fluid && !*bname) { /* a block is named in messages, --set fluid.NAME.key and the window */
        ctx->code = sph_fail(ctx->err, SPH_ERR_PARSE, "%s:%d: [%.120s]: the fluid block has no name; give it one, "
                             "e.g. [fluid column]", ctx->file, ctx->line, header);
        return false;
    }
    for (int k = 0; k < ctx->n_sections; k++) {
        const char *seen = ctx->sections[k];
        if (sph_scene_section_group(seen) != g || strcmp(fluid_block_name(seen), bname) != 0) continue;
        bool same = strcmp(seen, header) == 0;
        ctx->code = sph_fail(ctx->err, SPH_ERR_DUPLICATE_KEY,
                             "%s:%d: [%.60s] opens the %s '%s' again (first as [%.60s] on line %d)%s; give "
                             "each %s its own name, e.g. %s",
                             ctx->file, ctx->line, header, g->noun, bname, seen, ctx->section_lines[k],
                             same ? ": section appears twice" : "", g->noun, g->example);
        return false;
    }
    snprintf(str, (size_t)num, *bname ? "[%s %s]\n" : "[%s]\n", g->kind, bname);
    return true;
}

/* Hands inih one line at a time so that the handler knows the line number
 * (Debian's libinih is built without INI_HANDLER_LINENO), and catches here,
 * in line order, what inih would pass over or report late: overlong lines,
 * NUL bytes, lines that are neither a section, a key nor a comment, unknown
 * or repeated sections. Leading blanks are removed: inih would take an
 * indented key for the continuation of the previous value. */
static char *ini_reader_fn(char *str, int num, void *stream)
{
    parse_ctx *ctx = stream;
    if (ctx->code || ctx->pos >= ctx->len) return NULL;
    const char *start = ctx->text + ctx->pos;
    const char *nl = memchr(start, '\n', ctx->len - ctx->pos);
    size_t n = nl ? (size_t)(nl - start) + 1 : ctx->len - ctx->pos;
    ctx->line++;
    ctx->pos += n;
    if (memchr(start, '\0', n)) {
        ctx->code = sph_fail(ctx->err, SPH_ERR_SYNTAX, "%s:%d: binary data (a NUL byte): not a scene file",
                             ctx->file, ctx->line);
        return NULL;
    }
    /* a CR that does not end the line: old Mac line endings, the whole file one line (its first header's rest
     * was read as nothing, or "line longer than 198 characters") */
    const char *cr = memchr(start, '\r', n), *after_cr = cr;
    while (after_cr && after_cr < start + n && *after_cr == '\r') after_cr++; /* CR CR LF: a doubled conversion */
    if (cr && after_cr < start + n && *after_cr != '\n') {
        ctx->code = sph_fail(ctx->err, SPH_ERR_SYNTAX,
                             "%s:%d: a carriage return (CR) inside the line: the file has old Mac line endings; "
                             "save it with LF (or CRLF) line endings",
                             ctx->file, ctx->line);
        return NULL;
    }
    /* a UTF-8 byte-order mark, as some editors write, opens the first line only */
    if (ctx->line == 1 && n >= 3 && memcmp(start, "\xEF\xBB\xBF", 3) == 0) start += 3, n -= 3;
    while (n > 0 && (*start == ' ' || *start == '\t')) start++, n--;
    size_t text_len = n - (n > 0 && start[n - 1] == '\n');
    if (text_len > 0 && start[text_len - 1] == '\r') text_len--;
    if (text_len + 2 > (size_t)num) {
        ctx->code = sph_fail(ctx->err, SPH_ERR_SYNTAX, "%s:%d: line longer than %d characters", ctx->file,
                             ctx->line, num - 2);
        return NULL;
    }
    memcpy(str, start, n);
    str[n] = '\0';
    const char *p = str;
    if (*p == '\0' || *p == '\n' || *p == '\r' || *p == ';' || *p == '#') return str; /* blank or comment */
    if (*p == '[') {
        const char *close = strchr(p, ']');
        if (!close) {
            ctx->code = sph_fail(ctx->err, SPH_ERR_SYNTAX, "%s:%d: section header without its closing ']'",
                                 ctx->file, ctx->line);
            return NULL;
        }
        /* what follows the ']' is a comment or nothing: "[physics] [kernels]" was read as [physics] alone */
        const char *after = close + 1;
        while (*after == ' ' || *after == '\t') after++;
        if (*after && *after != '\n' && *after != '\r' && *after != ';' && *after != '#') {
            size_t tl = strcspn(after, "\r\n");
            ctx->code = sph_fail(ctx->err, SPH_ERR_SYNTAX,
                                 "%s:%d: text after the section header's ']': '%.*s' (a header stands alone on its "
                                 "line; a comment starts with ';' or '#')",
                                 ctx->file, ctx->line, (int)(tl > 60 ? 60 : tl), after);
            return NULL;
        }
        char name[200];
        const char *a = p + 1, *b = close;
        while (a < b && isspace((unsigned char)*a)) a++;
        while (b > a && isspace((unsigned char)b[-1])) b--;
        snprintf(name, sizeof name, "%.*s", (int)(b - a), a);
        if (!known_section(name)) {
            char hint[96];
            ctx->code = sph_fail(ctx->err, SPH_ERR_UNKNOWN_SECTION, "%s:%d: unknown section [%.60s]%s (accepted: %s)",
                                 ctx->file, ctx->line, name, section_hint(name, hint, sizeof hint), section_list());
            return NULL;
        }
        if (is_fluid_section(name) && !fluid_header(ctx, name, str, num)) return NULL;
        /* A section given again continues it (its keys still may not repeat);
         * it is listed once, so the list keeps room for every fluid block */
        bool listed = false;
        for (int k = 0; k < ctx->n_sections; k++) listed |= strcmp(ctx->sections[k], name) == 0;
        if (!listed && ctx->n_sections < MAX_SECTIONS) {
            /* a block's header as "fluid NAME", its one spelling: a raw one with many blanks was cut at 63
             * characters and its name lost */
            const sph_scene_group *g = sph_scene_section_group(name);
            if (g)
                snprintf(ctx->sections[ctx->n_sections], sizeof ctx->sections[0], "%s %.48s", g->kind,
                         fluid_block_name(name));
            else
                snprintf(ctx->sections[ctx->n_sections], sizeof ctx->sections[0], "%.63s", name);
            ctx->section_lines[ctx->n_sections++] = ctx->line;
        }
        ctx->header_line = ctx->line;
        return str;
    }
    /* key = value, '=' first: inih would also split "key: value" at the ':', a form the format does not have */
    const char *eq = strchr(p, '='), *colon = strchr(p, ':');
    if (!eq || (colon && colon < eq)) {
        size_t tl = strcspn(p, "\r\n");
        ctx->code = sph_fail(ctx->err, SPH_ERR_SYNTAX,
                             "%s:%d: syntax error: expected '[section]' or 'key = value', got '%.*s'%s", ctx->file,
                             ctx->line, (int)(tl > 60 ? 60 : tl), p, tl > 60 ? "..." : "");
        return NULL;
    }
    return str;
}

sph_error_code sph_scene_load_string(const char *text, const char *name, sph_scene_def *def, sph_error *err)
{
    parse_ctx ctx;
    memset(&ctx, 0, sizeof ctx);
    ctx.def = def;
    ctx.file = name;
    ctx.text = text;
    ctx.len = strlen(text);
    ctx.err = err;
    snprintf(def->file, sizeof def->file, "%s", name);
    int rc = ini_parse_stream(ini_reader_fn, &ctx, on_key, &ctx);
    if (ctx.code) return ctx.code;
    if (rc > 0)
        return sph_fail(err, SPH_ERR_SYNTAX, "%s:%d: syntax error: expected '[section]' or 'key = value'", name, rc);
    if (rc < 0) return sph_fail(err, SPH_ERR_MEMORY, "%s: out of memory while parsing", name);
    /* a block or obstacle is made by its first key: a header with none under it was dropped without a word */
    for (int k = 0; k < ctx.n_sections; k++) {
        const sph_scene_group *g = sph_scene_section_group(ctx.sections[k]);
        if (g && !find_block(g, def, fluid_block_name(ctx.sections[k])))
            return sph_fail(err, SPH_ERR_SCENE, "%s:%d: [%.60s] has no keys: a %s needs at least its %s", name,
                            ctx.section_lines[k], ctx.sections[k], g->noun,
                            g == &sph_scene_groups[0] ? "min and max" : "shape and place");
    }
    if (ctx.line == 0 || def->n_blocks == 0) {
        /* validate() reports missing blocks; an empty file is worth its own words */
        bool blank = true;
        for (const char *p = text; *p; p++)
            if (!isspace((unsigned char)*p)) blank = false;
        if (blank) return sph_fail(err, SPH_ERR_SCENE, "%s: the file is empty: a scene needs at least a [fluid NAME] block", name);
    }
    return SPH_ERR_OK;
}

sph_error_code sph_scene_load(const char *path, sph_scene_def *def, sph_error *err)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return sph_fail(err, SPH_ERR_IO, "%s: cannot open scene file: %s", path, strerror(errno));
    if (!S_ISREG(st.st_mode)) {
        const char *what = S_ISDIR(st.st_mode)                        ? "a directory"
                           : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                           : S_ISFIFO(st.st_mode)                       ? "a pipe (read once; give a file)"
                                                                        : "not a regular file";
        return sph_fail(err, SPH_ERR_IO, "%s: %s, not a scene file", path, what);
    }
    if (st.st_size > (1 << 20)) return sph_fail(err, SPH_ERR_IO, "%s: larger than 1 MiB: not a scene file", path);
    FILE *f = fopen(path, "rb");
    if (!f) return sph_fail(err, SPH_ERR_IO, "%s: cannot open scene file: %s", path, strerror(errno));
    size_t cap = (size_t)st.st_size + 1;
    char *text = malloc(cap);
    if (!text) {
        fclose(f);
        return sph_fail(err, SPH_ERR_MEMORY, "%s: out of memory", path);
    }
    size_t n = fread(text, 1, cap - 1, f);
    bool failed = ferror(f);
    fclose(f);
    if (failed) {
        free(text);
        return sph_fail(err, SPH_ERR_IO, "%s: read error", path);
    }
    text[n] = '\0';
    sph_error_code c;
    if (memchr(text, '\0', n)) { /* strlen would stop there: say where */
        int line = 1;
        for (const char *p = text; *p; p++) line += *p == '\n';
        c = sph_fail(err, SPH_ERR_SYNTAX, "%s:%d: binary data (a NUL byte): not a scene file", path, line);
    } else {
        c = sph_scene_load_string(text, path, def, err);
    }
    free(text);
    return c;
}

sph_error_code sph_scene_set(sph_scene_def *def, const char *assignment, sph_error *err)
{
    const char *eq = strchr(assignment, '=');
    char left[160];
    if (!eq || (size_t)(eq - assignment) >= sizeof left)
        return sph_fail(err, SPH_ERR_USAGE, "--set '%.80s': expected section.key=value, e.g. kernels.h=0.05",
                        assignment);
    snprintf(left, sizeof left, "%.*s", (int)(eq - assignment), assignment);
    char *dot = strrchr(left, '.');
    if (!dot || dot == left || !dot[1]) {
        char hint[400];
        sph_scene_key_sections(left, eq + 1, hint, sizeof hint); /* the sections that have this key */
        return sph_fail(err, SPH_ERR_USAGE, "--set '%.80s': expected section.key=value%s%s%s", assignment,
                        *hint ? " (did you mean " : ", e.g. kernels.h=0.05", hint, *hint ? "?)" : "");
    }
    *dot = '\0';
    const char *value = eq + 1;
    while (isspace((unsigned char)*value)) value++;
    /* trim: "kernels.h = 0.05" means the same as "kernels.h=0.05" */
    char *key = dot + 1;
    while (isspace((unsigned char)*key)) key++;
    size_t kl = strlen(key);
    while (kl > 0 && isspace((unsigned char)key[kl - 1])) key[--kl] = '\0';
    size_t sl = strlen(left);
    while (sl > 0 && isspace((unsigned char)left[sl - 1])) left[--sl] = '\0';
    /* "obstacle.rock" names the block [obstacle rock]: written so in the messages */
    const sph_scene_group *g = sph_scene_section_group(left);
    if (g && left[strlen(g->kind)] == '.') left[strlen(g->kind)] = ' ';
    return apply_key(def, def->file, -1, 0, left, key, value, err);
}

/* ---- checks of what the parser recorded ------------------------------------ */

/* "file:line" for a value set in the file, "--set" for one set on the command line. */
static const char *origin_text(const sph_scene_def *def, int line, char *buf, size_t n)
{
    if (line > 0)
        snprintf(buf, n, "%s:%d", def->file, line);
    else if (line < 0)
        snprintf(buf, n, "--set");
    else
        snprintf(buf, n, "%s", def->file);
    return buf;
}

/* The z component of a vector or point key as stored at base. */
static double key_z(const sph_key *k, const void *base)
{
    const char *field = (const char *)base + k->offset;
    return k->type == SPH_KEY_POINT ? ((const double *)(const void *)field)[2]
                                    : (double)((const float *)(const void *)field)[2];
}

/* Said, not refused: 2D ignoring z is documented (a scene may be written for
 * both), but a non-zero z is most often a 3D scene run in 2D by mistake. */
const char *sph_scene_ignored_z(const sph_scene_def *def, char *buf, size_t n)
{
    if (def->dim == 3) return NULL;
    for (int i = 0; i < sph_scene_key_count; i++) {
        const sph_key *k = &sph_scene_keys[i];
        if (k->type != SPH_KEY_VEC && k->type != SPH_KEY_POINT) continue;
        const sph_scene_group *g = sph_scene_section_group(k->section);
        char loc[300];
        if (g) {
            int slot = fluid_slot(i);
            for (int b = 0; b < *group_count(g, def); b++) {
                char *rec = group_item(g, (sph_scene_def *)def, b);
                const sph_origin *o = &item_origin(g, rec)[slot];
                if (o->line != 0 && o->ncomp == 3 && key_z(k, rec) != 0.0) {
                    snprintf(buf, n,
                             "%s: [%s %s] %s has a z component (%g), which a 2D scene ignores; for 3D, set [scene] "
                             "dimension = 3",
                             origin_text(def, o->line, loc, sizeof loc), g->kind, item_name(g, rec), k->name,
                             key_z(k, rec));
                    return buf;
                }
            }
        } else if (def->origin[i].line != 0 && def->origin[i].ncomp == 3 && key_z(k, def) != 0.0) {
            snprintf(buf, n, "%s: [%s] %s has a z component (%g), which a 2D scene ignores; for 3D, set [scene] "
                             "dimension = 3",
                     origin_text(def, def->origin[i].line, loc, sizeof loc), k->section, k->name, key_z(k, def));
            return buf;
        }
    }
    return NULL;
}

sph_error_code sph_scene_check_components(const sph_scene_def *def, sph_error *err)
{
    if (def->dim != 3) return SPH_ERR_OK;
    for (int i = 0; i < sph_scene_key_count; i++) {
        const sph_key *k = &sph_scene_keys[i];
        if (k->type != SPH_KEY_VEC && k->type != SPH_KEY_POINT) continue;
        const sph_scene_group *g = sph_scene_section_group(k->section);
        if (g) {
            int slot = fluid_slot(i);
            for (int b = 0; b < *group_count(g, def); b++) {
                char *rec = group_item(g, (sph_scene_def *)def, b);
                const sph_origin *o = &item_origin(g, rec)[slot];
                if (o->line != 0 && o->ncomp < 3) {
                    char loc[300];
                    return sph_fail(err, SPH_ERR_RANGE,
                                    "%s: [%s %s] %s has 2 components but the scene is 3D (accepted: 3 "
                                    "numbers)",
                                    origin_text(def, o->line, loc, sizeof loc), g->kind, item_name(g, rec),
                                    k->name);
                }
            }
        } else if (def->origin[i].line != 0 && def->origin[i].ncomp < 3) {
            char loc[300];
            return sph_fail(err, SPH_ERR_RANGE, "%s: [%s] %s has 2 components but the scene is 3D (accepted: 3 numbers)",
                            origin_text(def, def->origin[i].line, loc, sizeof loc), k->section, k->name);
        }
    }
    return SPH_ERR_OK;
}
