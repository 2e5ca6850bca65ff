/* Scene files at the parser's edges: long block names, two spellings of one
 * block, a byte-order mark, messages for values from --set, and values
 * outside a physically meaningful range. Each was accepted (or mangled)
 * before: a case that fails here is the specification. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>

#include "test_util.h"


/* A valid 2D scene of 9 lines; what a test appends starts on line 10. */
#define BASE2                                                                                                   \
    "[scene]\ndimension = 2\n[domain]\nmin = 0 0\nmax = 1 1\n[fluid a]\nmin = 0 0\nmax = 0.2 0.2\n"            \
    "spacing = 0.02\n"

static sph_error_code load(const char *text, sph_scene_def *def, sph_error *err)
{
    *def = sph_default_scene_def();
    memset(err, 0, sizeof *err);
    sph_error_code c = sph_scene_load_string(text, "x.ini", def, err);
    if (c == SPH_ERR_OK) c = sph_scene_validate(def, err);
    return c;
}

/* Loads text, applies one --set, validates. */
static sph_error_code load_set(const char *text, const char *assignment, sph_error *err)
{
    sph_scene_def def = sph_default_scene_def();
    memset(err, 0, sizeof *err);
    sph_error_code c = sph_scene_load_string(text, "x.ini", &def, err);
    cr_assert_eq(c, SPH_ERR_OK, "base scene: %s", err->msg);
    c = sph_scene_set(&def, assignment, err);
    if (c == SPH_ERR_OK) c = sph_scene_validate(&def, err);
    return c;
}

static void expect_has(const char *msg, const char *needle, const char *what)
{
    cr_expect(strstr(msg, needle) != NULL, "%s: message lacks '%s':\n  %s", what, needle, msg);
}

/* ---- block names -------------------------------------------------------- */

/* Two blocks whose names differ only after the 43rd character were cut to
 * the same name and merged into one block. A name up to the limit is kept
 * whole; a longer one is refused with the file, the line, the name and the limit. */
Test(parser_edges, long_block_names_are_refused_not_merged)
{
    char name[64], text[512];
    for (int len = SPH_BLOCK_NAME_MAX + 1; len <= 47; len++) {
        memset(name, 'n', (size_t)len);
        name[len] = '\0';
        snprintf(text, sizeof text, BASE2 "[fluid %s]\nmin = 0.5 0.5\nmax = 0.7 0.7\n", name);
        sph_scene_def def;
        sph_error err;
        sph_error_code c = load(text, &def, &err);
        cr_expect_eq(c, SPH_ERR_RANGE, "a %d-character name: got %s (%s), %d blocks", len, sph_error_name(c),
                     c ? err.msg : "accepted", def.n_blocks);
        if (!c) continue;
        expect_has(err.msg, "x.ini:10:", "long name");
        expect_has(err.msg, name, "long name");
        char limit[32];
        snprintf(limit, sizeof limit, "%d characters", SPH_BLOCK_NAME_MAX);
        expect_has(err.msg, limit, "long name");
    }
    /* the same with the dot spelling */
    memset(name, 'm', 47);
    name[47] = '\0';
    snprintf(text, sizeof text, BASE2 "[fluid.%s]\nmin = 0.5 0.5\nmax = 0.7 0.7\n", name);
    sph_scene_def def;
    sph_error err;
    cr_expect_eq(load(text, &def, &err), SPH_ERR_RANGE, "[fluid.<47 characters>] accepted");
}

Test(parser_edges, two_long_names_with_a_common_prefix_never_merge)
{
    char a[64], b[64], text[768];
    memset(a, 'p', 46);
    a[46] = '\0';
    snprintf(b, sizeof b, "%s", a);
    a[45] = 'A';
    b[45] = 'B';
    snprintf(text, sizeof text,
             "[scene]\ndimension = 2\n[fluid %s]\nmin = 0 0\nmax = 0.2 0.2\n[fluid %s]\nmin = 0.5 0.5\n"
             "max = 0.7 0.7\n",
             a, b);
    sph_scene_def def;
    sph_error err;
    sph_error_code c = load(text, &def, &err);
    cr_expect_eq(c, SPH_ERR_RANGE, "two blocks of 46-character names: got %s (%s), %d block(s)", sph_error_name(c),
                 c ? err.msg : "accepted", def.n_blocks);
}

Test(parser_edges, name_at_the_limit_is_kept_whole)
{
    char name[64], text[512];
    memset(name, 'k', SPH_BLOCK_NAME_MAX);
    name[SPH_BLOCK_NAME_MAX] = '\0';
    snprintf(text, sizeof text, BASE2 "[fluid.%s]\nmin = 0.5 0.5\nmax = 0.7 0.7\n", name);
    sph_scene_def def;
    sph_error err;
    cr_assert_eq(load(text, &def, &err), SPH_ERR_OK, "%s", err.msg);
    cr_assert_eq(def.n_blocks, 2);
    cr_expect_str_eq(def.blocks[1].name, name);
}

/* ---- one block, two spellings ------------------------------------------- */

Test(parser_edges, one_block_under_two_spellings_is_refused_with_both_lines)
{
    const char *spellings[] = {"[fluid.a]", "[fluid  a]", "[fluid\ta]", "[ fluid a ]", "[fluid. a]"};
    for (size_t i = 0; i < sizeof spellings / sizeof spellings[0]; i++) {
        char text[512];
        snprintf(text, sizeof text, BASE2 "%s\nvelocity = 1 0\n", spellings[i]);
        sph_scene_def def;
        sph_error err;
        sph_error_code c = load(text, &def, &err);
        cr_expect_eq(c, SPH_ERR_DUPLICATE_KEY, "%s after [fluid a]: got %s (%s)", spellings[i], sph_error_name(c),
                     c ? err.msg : "accepted: the two merged");
        if (!c) continue;
        expect_has(err.msg, "x.ini:10:", spellings[i]);
        expect_has(err.msg, "line 6", spellings[i]);
        expect_has(err.msg, "'a'", spellings[i]);
    }
}

/* Two different blocks still load, whatever the spelling. */
Test(parser_edges, distinct_blocks_in_mixed_spellings_load)
{
    sph_scene_def def;
    sph_error err;
    cr_assert_eq(load(BASE2 "[fluid.b]\nmin = 0.5 0.5\nmax = 0.7 0.7\n", &def, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_eq(def.n_blocks, 2);
    cr_expect_str_eq(def.blocks[1].name, "b");
}

/* ---- byte-order mark ------------------------------------------------------ */

Test(parser_edges, utf8_bom_is_skipped)
{
    sph_scene_def def;
    sph_error err;
    cr_assert_eq(load("\xEF\xBB\xBF" BASE2, &def, &err), SPH_ERR_OK, "a BOM is refused: %s", err.msg);
    cr_expect_eq(def.dim, 2);
    cr_expect_eq(def.n_blocks, 1);
    /* errors after it still name the right line */
    sph_error_code c = load("\xEF\xBB\xBF" BASE2 "[kernels]\nh = -1\n", &def, &err);
    cr_expect_eq(c, SPH_ERR_RANGE, "got %s", sph_error_name(c));
    expect_has(err.msg, "x.ini:11:", "after a BOM");
    /* only at the start of the file */
    c = load(BASE2 "\xEF\xBB\xBF[kernels]\nh = 0.04\n", &def, &err);
    cr_expect_neq(c, SPH_ERR_OK, "a BOM in the middle of the file is accepted");
}

Test(parser_edges, cli_accepts_a_file_with_a_bom)
{
    const char *path = test_write_temp("\xEF\xBB\xBF" BASE2, ".ini");
    char args[512], out[4096];
    snprintf(args, sizeof args, "check '%s'", path);
    int rc = test_sphlab(args, out, sizeof out);
    cr_expect_eq(rc, 0, "check of a file with a BOM: exit %d:\n%s", rc, out);
    remove(path);
}

/* ---- no line -1 ----------------------------------------------------------- */

static void expect_no_minus_one(sph_error_code c, const sph_error *err, const char *what)
{
    cr_expect_neq(c, SPH_ERR_OK, "%s: accepted", what);
    if (!c) return;
    cr_expect(strstr(err->msg, ":-1") == NULL && strstr(err->msg, ":0:") == NULL,
              "%s: the message names a line that does not exist: %s", what, err->msg);
    expect_has(err->msg, "--set", what);
}

Test(parser_edges, checks_of_set_values_name_the_option_not_line_minus_one)
{
    sph_error err;
    expect_no_minus_one(load_set(BASE2 "[kernels]\nh = 0.5\n", "domain.periodic=x", &err), &err,
                        "periodic x shorter than 3 h");
    expect_no_minus_one(load_set(BASE2, "domain.periodic=z", &err), &err, "periodic z in 2D");
    expect_no_minus_one(load_set("[scene]\ndimension = 2\n[domain]\nmin = 0 0\nmax = 100000 100000\n[fluid a]\n"
                                 "min = 0 0\nmax = 0.2 0.2\n",
                                 "search.method=grid", &err),
                        &err, "grid too large");
}

/* ---- physically meaningless values --------------------------------------- */

Test(parser_edges, tiny_rest_density_and_h_are_refused_at_load)
{
    const char *cases[][2] = {
        {"[physics]\nrest_density = 1e-30\n", "rest_density"},
        {"[kernels]\nh = 1e-30\n", "h"},
        {"[physics]\nrest_density = 1e-6\n", "rest_density"},
        {"[kernels]\nh = 1e-6\n", "h"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[512];
        snprintf(text, sizeof text, BASE2 "%s", cases[i][0]);
        sph_scene_def def;
        sph_error err;
        sph_error_code c = load(text, &def, &err);
        cr_expect_eq(c, SPH_ERR_RANGE, "%s: got %s (%s)", cases[i][0], sph_error_name(c), c ? err.msg : "accepted");
        if (!c) continue;
        expect_has(err.msg, "x.ini:11:", cases[i][0]);
        expect_has(err.msg, cases[i][1], cases[i][0]);
        expect_has(err.msg, "accepted: from", cases[i][0]);
    }
}

/* The bounds are where the run still works: a scene at each lower bound steps. */
Test(parser_edges, scenes_at_the_lower_bounds_run)
{
    const char *scenes[] = {
        BASE2 "[physics]\nrest_density = 0.001\n",
        "[scene]\ndimension = 3\n[domain]\nmin = 0 0 0\nmax = 0.001 0.001 0.001\n[fluid a]\nmin = 0 0 0\n"
        "max = 0.0004 0.0004 0.0004\nspacing = 0.00005\n[kernels]\nh = 0.0001\n[physics]\nrest_density = 0.001\n",
    };
    for (size_t i = 0; i < sizeof scenes / sizeof scenes[0]; i++) {
        const char *path = test_write_temp(scenes[i], ".ini");
        char args[512], out[8192];
        snprintf(args, sizeof args, "run '%s' --steps 20 --quiet --threads 1", path);
        int rc = test_sphlab(args, out, sizeof out);
        cr_expect_eq(rc, 0, "scene %zu at the lower bounds: exit %d:\n%s", i, rc, out);
        remove(path);
    }
}

/* docs/scene-format.md states each number's accepted range as the table has
 * it: "from MIN to MAX", or "above MIN, up to MAX" where MIN is excluded. */
Test(parser_edges, documented_ranges_match_the_key_table)
{
    FILE *f = fopen("docs/scene-format.md", "rb");
    cr_assert(f, "docs/scene-format.md: cannot read it (run the suite from the repository root)");
    static char doc[1 << 18];
    size_t n = fread(doc, 1, sizeof doc - 1, f);
    fclose(f);
    doc[n] = '\0';
    for (int i = 0; i < sph_scene_key_count; i++) {
        const sph_key *k = &sph_scene_keys[i];
        if (k->type != SPH_KEY_FLOAT && k->type != SPH_KEY_INT && k->type != SPH_KEY_UINT) continue;
        char heading[64], row[96], want[96];
        snprintf(heading, sizeof heading, "\n### [%s", k->section);
        const char *sec = strstr(doc, heading);
        cr_expect(sec, "no heading for [%s]", k->section);
        if (!sec) continue;
        snprintf(row, sizeof row, "\n| `%s` |", k->name);
        const char *r = strstr(sec, row);
        const char *next = strstr(sec + 1, "\n### ");
        cr_expect(r && (!next || r < next), "no row for [%s] %s", k->section, k->name);
        if (!r || (next && r > next)) continue;
        const char *eol = strchr(r + 1, '\n');
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)(eol ? eol - r : (long)strlen(r)), r);
        if (!k->min_open && !k->max_open)
            snprintf(want, sizeof want, "| from %.10g to %.10g |", k->min, k->max);
        else
            snprintf(want, sizeof want, "| %s %.10g, %s %.10g |", k->min_open ? "above" : "from", k->min,
                     k->max_open ? "below" : "up to", k->max);
        cr_expect(strstr(line, want), "[%s] %s: the row should state '%s':%s", k->section, k->name, want, line);
    }
}

/* ---- forms a user's review found read silently (each used to load) ------ */

/* A header with text after its ']', a "key: value" line, an unnamed or empty
 * block, "none" with other effects, an empty list, dt_min above dt: each was
 * read as something else without a word; each is now refused, naming the line
 * and what it read. */
Test(parser_edges, silently_read_forms_are_refused)
{
    static const struct {
        const char *text, *want;
    } cases[] = {
        {BASE2 "[physics] [kernels]\n", "x.ini:10: text after the section header's ']': '[kernels]'"},
        {BASE2 "[physics]x\n", "x.ini:10: text after the section header's ']': 'x'"},
        {BASE2 "[physics]\nstiffness:100\n", "x.ini:11: syntax error: expected '[section]' or 'key = value', got "
                                             "'stiffness:100'"},
        {BASE2 "[physics]\nno equals sign\n", "got 'no equals sign'"},
        {BASE2 "[fluid]\nmin = 0.5 0.5\nmax = 0.7 0.7\n", "x.ini:10: [fluid]: the fluid block has no name"},
        {BASE2 "[fluid e]\n", "x.ini:10: [fluid e] has no keys"},
        {BASE2 "[obstacle rock]\n", "x.ini:10: [obstacle rock] has no keys"},
        {BASE2 "[time]\ndt = 0.001\ndt_min = 1\n", "x.ini:12: [time] dt_min = 1 s is above dt = 0.001 s"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        sph_scene_def def;
        sph_error err;
        cr_expect_neq(load(cases[i].text, &def, &err), SPH_ERR_OK, "accepted:\n%s", cases[i].text);
        expect_has(err.msg, cases[i].want, cases[i].text);
    }
    sph_error err;
    sph_error_code c = load_set(BASE2, "scene.effects=none pressure", &err);
    cr_expect_neq(c, SPH_ERR_OK, "effects = none pressure: accepted");
    expect_has(err.msg, "none with others", "effects = none pressure");
    c = load_set(BASE2, "scene.effects=", &err);
    cr_expect_neq(c, SPH_ERR_OK, "effects = (empty): accepted");
    expect_has(err.msg, "empty: write none", "effects = (empty)");
    c = load_set(BASE2, "domain.periodic=abc", &err);
    expect_has(err.msg, "unknown axis 'abc'", "periodic = abc");
    /* an error a --set causes names --set: min = 1 1 from the command line blamed the file's max line, and an h
     * too small for the domain's floats the file's [domain] line alone */
    c = load_set(BASE2, "domain.min=1,1", &err);
    cr_expect(c != SPH_ERR_OK && strncmp(err.msg, "--set: [domain] max.x = 1 is not above min.x = 1", 48) == 0, "%s",
              err.msg);
    c = load_set("[scene]\ndimension = 2\n[domain]\nmin = 0 0\nmax = 3 1\n[fluid a]\nmin = 0 0\nmax = 0.2 0.2\n",
                 "kernels.h=0.0001", &err);
    cr_expect(c != SPH_ERR_OK, "h = 1e-4 over a 3 m domain: accepted");
    expect_has(err.msg, "x.ini:5 and --set: [domain] x from 0 to 3 m: positions are floats", "h by --set");
    /* old Mac line endings: the whole file one line, read as "[scene]" and nothing else */
    {
        sph_scene_def d;
        cr_expect_neq(load("[scene]\rdimension = 2\r[fluid a]\rmin = 0 0\rmax = 0.2 0.2\r", &d, &err), SPH_ERR_OK);
        expect_has(err.msg, "x.ini:1: a carriage return (CR) inside the line", "CR line endings");
        cr_expect_eq(load("[scene]\r\ndimension = 2\r\n[fluid a]\r\nmin = 0 0\r\nmax = 0.2 0.2\r\n", &d, &err),
                     SPH_ERR_OK, "CRLF: %s", err.msg);
        /* CR CR LF (a file converted twice) was read before the CR check and still is */
        cr_expect_eq(load("[scene]\r\r\ndimension = 2\r\r\n[fluid a]\r\r\nmin = 0 0\r\r\nmax = 0.2 0.2\r\r\n", &d, &err),
                     SPH_ERR_OK, "CRCRLF: %s", err.msg);
        /* a name at the 43-character limit behind many blanks: the list of headers cut it, and the block was
         * called empty */
        cr_expect_eq(load(BASE2 "[fluid                aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa]\nmin = 0.5 0.5\n"
                                "max = 0.7 0.7\n",
                          &d, &err),
                     SPH_ERR_OK, "a long name behind blanks: %s", err.msg);
        /* a tab is text */
        cr_expect_eq(load(BASE2 "[scene]\nname = lesson\t7\n", &d, &err), SPH_ERR_OK, "a tab in a name: %s", err.msg);
        /* dt_min's default named as such: a scene that sets dt = 5e-8 alone never wrote dt_min */
        cr_expect_neq(load(BASE2 "[time]\ndt = 5e-8\n", &d, &err), SPH_ERR_OK);
        expect_has(err.msg, "dt_min = 1e-07 s (the default) is above dt = 5e-08 s", "dt below the default dt_min");
        /* a control character in a name reached the terminal raw (an escape sequence coloured it) */
        cr_expect_neq(load(BASE2 "[scene]\nname = a\x1b[31mred\n", &d, &err), SPH_ERR_OK);
        expect_has(err.msg, "name = 'a\\x1b[31mred': holds a control character", "a control character");
        /* keys are lower case: the hint names the key however its case was typed */
        cr_expect_neq(load(BASE2 "[physics]\nSTIFFNESS = 100\n", &d, &err), SPH_ERR_OK);
        expect_has(err.msg, "(did you mean 'stiffness'?)", "STIFFNESS");
    }
    /* what is still read: a comment after a header, none alone, dt_min below dt */
    sph_scene_def def;
    cr_expect_eq(load(BASE2 "[physics] ; the fluid\nstiffness = 100\n", &def, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_eq(load_set(BASE2, "scene.effects=none", &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_eq(load(BASE2 "[time]\ndt = 0.001\ndt_min = 0.001\n", &def, &err), SPH_ERR_OK, "%s", err.msg);
}
