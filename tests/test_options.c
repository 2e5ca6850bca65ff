/* The option table (src/app/app_options.c): its rows are consistent, the
 * parser stores what they say, every command's --help lists every option the
 * table gives it, docs/commands.md is the table's current Markdown, and the docs
 * name no option the table does not know. */
#include <criterion/criterion.h>
#include <criterion/redirect.h>
#include <ctype.h>
#include <glob.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../src/overlay/sph_overlay.h"
#include "app_options.h"
#include "test_util.h"

static const char *const cmd_names[] = {
#define NAME(name, args, about) #name,
    SPH_COMMANDS(NAME)
#undef NAME
};

static char g_out[1 << 16];

Test(options, rows_are_well_formed)
{
    for (int k = 0; k < app_option_count; k++) {
        const app_opt *r = &app_options[k];
        cr_assert(r->name && strncmp(r->name, "--", 2) == 0 && strlen(r->name) > 2, "row %d: name '%s'", k, r->name);
        cr_assert(r->help && *r->help, "%s: no help", r->name);
        cr_assert(r->cmds != 0 && r->cmds < (1u << APP_CMD_COUNT), "%s: commands 0x%x", r->name, r->cmds);
        bool takes_value = r->kind != APP_OPT_FLAG && r->kind != APP_OPT_HELP;
        cr_assert(takes_value == (r->arg != NULL), "%s: a value placeholder iff it takes a value", r->name);
        cr_assert(r->kind == APP_OPT_HELP || r->at < sizeof(app_opts), "%s: stored outside app_opts", r->name);
        if (r->kind == APP_OPT_INT || r->kind == APP_OPT_DOUBLE || r->kind == APP_OPT_SIZE)
            cr_assert(r->lo <= r->hi, "%s: empty range", r->name);
        if (r->kind == APP_OPT_CHOICE) cr_assert(r->choices && strchr(r->choices, '|'), "%s: choices", r->name);
    }
}

/* Two rows may share a spelling only if no command takes both: the parser
 * would silently use the first. */
Test(options, no_command_has_one_spelling_twice)
{
    for (int a = 0; a < app_option_count; a++)
        for (int b = a + 1; b < app_option_count; b++) {
            const app_opt *x = &app_options[a], *y = &app_options[b];
            const char *xs[2] = {x->name, x->alias}, *ys[2] = {y->name, y->alias};
            for (int i = 0; i < 2; i++)
                for (int j = 0; j < 2; j++)
                    if (xs[i] && ys[j] && strcmp(xs[i], ys[j]) == 0)
                        cr_assert((x->cmds & y->cmds) == 0, "%s is declared twice for a command (rows %d and %d)",
                                  xs[i], a, b);
        }
}

static const app_cmd_spec run_spec = {.name = "run", .cmd = APP_CMD(run), .synopsis = "", .max_pos = 1,
                                      .extra_pos = "more than one scene file"};

static int parse(const app_cmd_spec *spec, app_opts *o, int argc, const char **argv)
{
    app_opts_init(o);
    return app_opts_parse(spec, argc, (char **)argv, o);
}

Test(options, parser_stores_what_the_rows_say)
{
    app_opts o;
    const char *argv[] = {"run", "s.ini", "--steps", "12", "--time=0.5", "--set", "a.b=1", "--set=c.d=2", "-q",
                          "--backend=gl", "--threads", "3", "--vtk", "-weird-dir"};
    cr_assert_eq(parse(&run_spec, &o, 14, argv), -1);
    cr_assert_eq(o.n_pos, 1);
    cr_assert_str_eq(o.pos[0], "s.ini");
    cr_assert_eq(o.steps, 12);
    cr_assert_float_eq(o.time, 0.5, 1e-12);
    cr_assert_eq(o.sets.n, 2);
    cr_assert_str_eq(o.sets.v[0], "a.b=1");
    cr_assert_str_eq(o.sets.v[1], "c.d=2"); /* only the first '=' splits */
    cr_assert(o.quiet);
    cr_assert_str_eq(o.backend, "gl");
    cr_assert_eq(o.threads, 3);
    cr_assert_str_eq(o.vtk, "-weird-dir"); /* a value is the next argument, whatever it looks like */
    cr_assert_eq(o.frames, -1, "an option of another command was set");
}

Test(options, parser_refuses_bad_command_lines, .init = cr_redirect_stderr)
{
    app_opts o;
    const char *cases[][3] = {
        {"run", "--bogus", NULL},       /* unknown */
        {"run", "--frames", "3"},       /* view's, not run's */
        {"run", "--steps", NULL},       /* no value */
        {"run", "--steps", "-1"},       /* out of range */
        {"run", "--steps", "1.5"},      /* not whole */
        {"run", "--time", "nan"},       /* not finite */
        {"run", "--quiet=1", NULL},     /* a flag with a value */
        {"run", "--backend", "vulkan"}, /* not a choice */
        {"run", "a.ini", "b.ini"},      /* one scene only */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int argc = cases[i][2] ? 3 : 2;
        cr_expect_eq(parse(&run_spec, &o, argc, cases[i]), 2, "'%s %s' accepted", cases[i][1],
                     cases[i][2] ? cases[i][2] : "");
    }
}

Test(options, pass_on_keeps_unknown_arguments_in_order)
{
    const app_cmd_spec spec = {.name = "lesson", .cmd = APP_CMD(lesson), .synopsis = "", .max_pos = 1,
                               .flags = APP_SPEC_PASS_ON};
    app_opts o;
    const char *argv[] = {"lesson", "3", "--size", "640x480", "--dry-run", "--paused", "x"};
    cr_assert_eq(parse(&spec, &o, 7, argv), -1);
    cr_assert_str_eq(o.pos[0], "3");
    cr_assert(o.dry_run);
    cr_assert_eq(o.n_rest, 4);
    cr_assert_str_eq(o.rest[0], "--size");
    cr_assert_str_eq(o.rest[1], "640x480");
    cr_assert_str_eq(o.rest[2], "--paused");
    cr_assert_str_eq(o.rest[3], "x");
    cr_assert_eq(o.size[0], 0, "lesson does not take --size: view does");
}

Test(options, closest_option_names_the_typo)
{
    cr_assert_str_eq(app_opts_closest(APP_CMD(run), "--step"), "--steps");
    cr_assert_str_eq(app_opts_closest(APP_CMD(render), "--colr=speed"), "--color");
    cr_assert_str_eq(app_opts_closest(APP_CMD(view), "--screenshoot"), "--screenshot");
    cr_assert_str_eq(app_opts_closest(APP_CMD(bench), "--quik"), "--quick");
    cr_assert_null(app_opts_closest(APP_CMD(run), "--frobnicate"));
    cr_assert_null(app_opts_closest(APP_CMD(check), "--steps"), "check takes no --steps, nor anything like it");
}

/* The binary: every option of the table is in its command's --help, and
 * `sphlab help CMD` says the same. */
Test(options, every_option_is_in_its_commands_help, .timeout = 60)
{
    for (int c = 0; c < APP_CMD_COUNT; c++) {
        bool any = false;
        for (int k = 0; k < app_option_count; k++) any |= (app_options[k].cmds >> c) & 1;
        if (!any) continue;
        char args[64];
        snprintf(args, sizeof args, "%s --help", cmd_names[c]);
        cr_assert_eq(test_sphlab(args, g_out, sizeof g_out), 0, "%s: %s", args, g_out);
        static char help[sizeof g_out];
        memcpy(help, g_out, sizeof help);
        for (int k = 0; k < app_option_count; k++) {
            const app_opt *r = &app_options[k];
            if (!((r->cmds >> c) & 1)) continue;
            char label[96];
            snprintf(label, sizeof label, "  %s%s%s%s%s", r->name, r->alias ? ", " : "", r->alias ? r->alias : "",
                     r->arg ? " " : "", r->arg ? r->arg : "");
            cr_expect(strstr(help, label), "`sphlab %s --help` lacks '%s'", cmd_names[c], label + 2);
            char first[64];
            snprintf(first, sizeof first, "%.*s", (int)strcspn(r->help, "\n"), r->help);
            cr_expect(strstr(help, first), "`sphlab %s --help` lacks the help of %s", cmd_names[c], r->name);
        }
        snprintf(args, sizeof args, "help %s", cmd_names[c]);
        cr_assert_eq(test_sphlab(args, g_out, sizeof g_out), 0, "%s: %s", args, g_out);
        cr_expect_str_eq(g_out, help, "`sphlab help %s` differs from `sphlab %s --help`", cmd_names[c], cmd_names[c]);
    }
}

/* An unknown option: exit 2, the command and the option named, with the closest known one. */
Test(options, unknown_option_suggests_the_closest, .timeout = 30)
{
    cr_assert_eq(test_sphlab("view x.ini --frame 3", g_out, sizeof g_out), 2, "%s", g_out);
    cr_assert(strstr(g_out, "sphlab view: unknown option '--frame' (did you mean --frames?)"), "%s", g_out);
    cr_assert_eq(test_sphlab("hardcases --only", g_out, sizeof g_out), 2, "%s", g_out);
    cr_assert(strstr(g_out, "--only needs a value (NAME)"), "%s", g_out);
}

/* docs/commands.md is what `sphlab help --markdown` prints: regenerate it with
 * `./sphlab help --markdown > docs/commands.md` after changing the table. */
Test(options, docs_commands_md_is_current)
{
    char *want = NULL;
    size_t want_len = 0;
    FILE *m = open_memstream(&want, &want_len);
    cr_assert(m);
    app_opts_markdown(m);
    fclose(m);
    FILE *f = fopen("docs/commands.md", "r");
    cr_assert(f, "docs/commands.md is missing");
    char *have = calloc(want_len + 2, 1);
    size_t n = fread(have, 1, want_len + 1, f);
    fclose(f);
    cr_expect(n == want_len && memcmp(have, want, want_len) == 0,
              "docs/commands.md is not the table's: run ./sphlab help --markdown > docs/commands.md");
    free(have);
    free(want);
}

static bool known_spelling(const char *word)
{
    if (strcmp(word, "--markdown") == 0 || strcmp(word, "--options") == 0) return true; /* sphlab help's */
    for (int k = 0; k < app_option_count; k++)
        if (strcmp(word, app_options[k].name) == 0 || (app_options[k].alias && strcmp(word, app_options[k].alias) == 0))
            return true;
    return false;
}

/* Every --option the README, docs/ and the lessons mention is one the table
 * knows: a renamed or removed option leaves no stale docs behind. */
Test(options, docs_name_only_known_options)
{
    glob_t g;
    cr_assert_eq(glob("README.md", 0, NULL, &g), 0, "run the tests from the repository root");
    glob("docs/*.md", GLOB_APPEND, NULL, &g);
    glob("lessons/*/README*.md", GLOB_APPEND, NULL, &g);
    int files = 0;
    for (size_t i = 0; i < g.gl_pathc; i++) {
        FILE *f = fopen(g.gl_pathv[i], "r");
        if (!f) continue;
        files++;
        char line[4096];
        for (int ln = 1; fgets(line, sizeof line, f); ln++)
            for (char *p = line; !strstr(line, "sphlab-tests") && (p = strstr(p, "--")); p += 2) { /* the test
                binary's options are Criterion's */
                if ((p > line && (isalnum((unsigned char)p[-1]) || p[-1] == '-')) || !islower((unsigned char)p[2]))
                    continue;
                char word[64];
                size_t n = 2;
                while (n < sizeof word - 1 && (islower((unsigned char)p[n]) || p[n] == '-')) n++;
                snprintf(word, sizeof word, "%.*s", (int)n, p);
                cr_expect(known_spelling(word), "%s:%d names %s, which no command takes", g.gl_pathv[i], ln, word);
            }
        fclose(f);
    }
    globfree(&g);
    cr_assert_gt(files, 5, "README.md and docs/*.md not found");
}

/* --color's help names every colour the renderer accepts (it named 7 of 21:
 * pcisph-pressure, the pressure of a PCISPH run, could only be guessed). */
Test(options, color_help_names_every_colour)
{
    const app_opt *color = NULL;
    for (int k = 0; k < app_option_count; k++)
        if (strcmp(app_options[k].name, "--color") == 0) color = &app_options[k];
    cr_assert(color, "no --color option");
    for (int c = 0; c < SPH_COLOR_COUNT; c++) {
        const char *name = sph_color_field_names[c];
        if (!name || !*name) continue;
        char word[64];
        snprintf(word, sizeof word, " %s ", name);
        char help[2048], expanded[2048];
        snprintf(help, sizeof help, " %s ", app_opt_help(color, expanded, sizeof expanded));
        for (char *p = help; *p; p++)
            if (*p == ',' || *p == ':' || *p == '(' || *p == ')') *p = ' ';
        cr_expect(strstr(help, word), "--color's help does not name '%s': %s", name, help);
    }
}

/* A whole number too large for a long is out of range, not "not a whole number"; a negative lesson
 * number is out of range, not a missing one (a user's review). */
Test(options, numbers_out_of_range_are_named_so, .timeout = 30)
{
    cr_assert_eq(test_sphlab("run lessons/scenes/rest-2d.ini --steps 99999999999999999999", g_out, sizeof g_out), 2,
                 "%s", g_out);
    cr_expect(strstr(g_out, "--steps 99999999999999999999: out of range (accepted: 0 to") != NULL, "%s", g_out);
    cr_assert_eq(test_sphlab("lesson -1", g_out, sizeof g_out), 2, "%s", g_out);
    cr_expect(strstr(g_out, "lesson -1: out of range (accepted: 1 to") != NULL, "%s", g_out);
}

/* `sphlab keys` given an option it lacks or a key's name says so, not "no section" alone (a user's review). */
Test(options, keys_names_an_unknown_option_and_a_key_given_for_a_section, .timeout = 30)
{
    cr_assert_eq(test_sphlab("keys --bogus", g_out, sizeof g_out), 2, "%s", g_out);
    cr_expect(strstr(g_out, "unknown option '--bogus'") != NULL, "%s", g_out);
    cr_assert_eq(test_sphlab("keys stiffness", g_out, sizeof g_out), 2, "%s", g_out);
    cr_expect(strstr(g_out, "'stiffness' is a key: physics.stiffness (sphlab keys physics lists it)") != NULL, "%s",
              g_out);
}
