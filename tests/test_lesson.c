/* sphlab lesson: every lesson exports its figures headless (--quick), and each
 * figure is checked for its content, not only its existence: a PNG decodes at
 * its size and is not a uniform image, a PDF is a PDF, a CSV has its header
 * and its rows (and the numbers the lesson is about: particle 7's cell, hash
 * and key; the start table of the seed's keys; density lower at the free
 * surface than inside; ...), and report.md names the lesson and holds
 * numbers. Also: --list, bad numbers, the window without a display, the
 * window through SDL's offscreen driver, an unwritable output directory. */
#define _DEFAULT_SOURCE /* mkdtemp, setenv */
#include <criterion/criterion.h>
#include <ctype.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "stb_image.h"
#include "sph_levels.h"
#include "test_util.h"

static char out[65536];

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    cr_assert(buf && fread(buf, 1, (size_t)n, f) == (size_t)n);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* Whether this build has a command (`sphlab --help` lists it). */
static bool has_command(const char *name)
{
    static char help[8192];
    if (!help[0]) test_sphlab("--help", help, sizeof help);
    char pat[64];
    snprintf(pat, sizeof pat, "\n  %s ", name);
    return strstr(help, pat) != NULL;
}

/* ---- content checks ------------------------------------------------------------ */

/* A PNG that decodes (at w x h if given) and is not one colour: at least 2%
 * of its pixels differ clearly from its most common corner colour. */
static void check_png(const char *dir, const char *file, int w, int h)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    int iw, ih, n;
    unsigned char *px = stbi_load(path, &iw, &ih, &n, 3);
    cr_assert(px, "%s does not decode as a PNG: %s", file, stbi_failure_reason());
    if (w) cr_expect(iw == w && ih == h, "%s is %dx%d, expected %dx%d", file, iw, ih, w, h);
    cr_expect(iw >= 64 && ih >= 64, "%s is only %dx%d", file, iw, ih);
    const unsigned char *c = px; /* top-left corner: the background */
    long differ = 0, total = (long)iw * ih;
    for (long i = 0; i < total; i++) {
        const unsigned char *p = px + 3 * i;
        if (abs(p[0] - c[0]) + abs(p[1] - c[1]) + abs(p[2] - c[2]) > 60) differ++;
    }
    cr_expect(differ > total / 50, "%s is (nearly) uniform: %ld of %ld pixels differ from the background", file,
              differ, total);
    stbi_image_free(px);
}

static void check_pdf(const char *dir, const char *file)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    char *text = read_all(path);
    cr_assert(text, "%s is missing", file);
    cr_expect(strncmp(text, "%PDF-", 5) == 0, "%s is not a PDF", file);
    free(text);
}

typedef struct csv {
    char *text;
    char *line[4096];
    int nlines;
} csv;

/* A CSV whose header starts with `header` and that has at least min_rows rows,
 * each with as many fields as the header. */
static void check_csv(const char *dir, const char *file, const char *header, int min_rows, csv *keep)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    csv c = {0};
    c.text = read_all(path);
    cr_assert(c.text, "%s is missing", file);
    for (char *l = strtok(c.text, "\n"); l && c.nlines < 4096; l = strtok(NULL, "\n")) c.line[c.nlines++] = l;
    cr_assert(c.nlines > 0, "%s is empty", file);
    cr_expect(strncmp(c.line[0], header, strlen(header)) == 0, "%s: header '%s', expected it to start with '%s'",
              file, c.line[0], header);
    cr_expect(c.nlines - 1 >= min_rows, "%s has %d rows, expected at least %d", file, c.nlines - 1, min_rows);
    int fields = 1;
    for (const char *p = c.line[0]; *p; p++) fields += *p == ',';
    for (int i = 1; i < c.nlines; i++) {
        int f = 1;
        for (const char *p = c.line[i]; *p; p++) f += *p == ',';
        cr_expect(f == fields, "%s line %d has %d fields, the header %d", file, i + 1, f, fields);
    }
    if (keep) *keep = c;
    else free(c.text);
}

/* Field k of a CSV line, as a number. */
static double field(const char *line, int k)
{
    const char *p = line;
    for (int i = 0; i < k && p; i++) {
        p = strchr(p, ',');
        if (p) p++;
    }
    cr_assert(p, "no field %d in '%s'", k, line);
    return strtod(p, NULL);
}

/* report.md names the lesson and holds measured numbers (a decimal with digits
 * on both sides of the point, in a table row). */
static char *check_report(const char *dir, int num, const char *title, const char *title_fr)
{
    char path[512], want[128];
    snprintf(path, sizeof path, "%s/report.md", dir);
    char *text = read_all(path);
    cr_assert(text, "report.md is missing");
    snprintf(want, sizeof want, "# Lesson %d: %s", num, title);
    cr_expect(strstr(text, want), "report.md does not start with '%s'", want);
    cr_expect(strstr(text, "## Figures"), "report.md has no list of figures");
    int numbers = 0;
    for (const char *p = text; *p; p++)
        if (*p == '.' && p > text && isdigit((unsigned char)p[-1]) && isdigit((unsigned char)p[1])) numbers++;
    cr_expect(numbers >= 5, "report.md holds %d decimal numbers", numbers);
    cr_expect(strstr(text, "| ") != NULL, "report.md has no table");
    cr_expect(!strstr(text, "A command failed") && !strstr(text, "A run failed") &&
                  !strstr(text, "command(s) or file(s) failed"),
              "report.md says something failed");
    /* every placeholder of the templates filled, in both languages */
    cr_expect(!strstr(text, "{{") && !strstr(text, "not measured)"), "report.md has an unfilled placeholder");
    snprintf(path, sizeof path, "%s/report.fr.md", dir);
    char *fr = read_all(path);
    cr_assert(fr, "report.fr.md is missing");
    snprintf(want, sizeof want, "# Leçon %d : %s", num, title_fr);
    cr_expect(strstr(fr, want), "report.fr.md does not start with '%s'", want);
    cr_expect(!strstr(fr, "{{") && !strstr(fr, "not measured)"), "report.fr.md has an unfilled placeholder");
    /* the generated tables speak the report's language: no English level or header word in French */
    cr_expect(!strstr(fr, "Niveau : beginner") && !strstr(fr, "Niveau : intermediate") &&
                  !strstr(fr, "Niveau : advanced"),
              "report.fr.md names its level in English");
    cr_expect(!strstr(fr, "| wall model |") && !strstr(fr, "| particle |") && !strstr(fr, "| level |") &&
                  !strstr(fr, "| pass |") && !strstr(fr, "Pareto front"),
              "report.fr.md has an English table header");
    /* nor an English row name (lesson 2's places in the block: "interior", "floor (wall)", ...) */
    cr_expect(!strstr(fr, "| interior |") && !strstr(fr, "| floor (wall) |") && !strstr(fr, "(free surface) |"),
              "report.fr.md has an English row name");
    /* the list of figures and the busy-machine note are French too: no caption with an English article */
    cr_expect(!strstr(fr, "The machine was busy"), "report.fr.md has the busy-machine note in English");
    for (const char *l = strstr(fr, "\n- `"); l; l = strstr(l + 1, "\n- `")) {
        const char *e = strchr(l + 1, '\n');
        int len = e ? (int)(e - l - 1) : (int)strlen(l + 1);
        char line[1024];
        snprintf(line, sizeof line, "%.*s ", len, l + 1);
        cr_expect(!strstr(line, " the ") && !strstr(line, " of ") && !strstr(line, " and ") &&
                      !strstr(line, "beside it"),
                  "report.fr.md: a figure's caption in English: %s", line);
    }
    free(fr);
    return text;
}

static const char *export_lesson(int num)
{
    const char *dir = test_temp_dir("lesson");
    char args[256];
    snprintf(args, sizeof args, "lesson %d --export %s --quick --quiet", num, dir);
    int rc = test_sphlab(args, out, sizeof out);
    cr_assert(rc == 0, "sphlab %s exited %d:\n%s", args, rc, out);
    return dir;
}

/* ---- the report templates ------------------------------------------------------------ */

/* The placeholders of a template, "{{name}}" each, in order, into out (one per line). */
static int placeholders(const char *text, char *list, size_t cap)
{
    int n = 0;
    size_t len = 0;
    list[0] = '\0';
    for (const char *p = strstr(text, "{{"); p; p = strstr(p + 2, "{{")) {
        const char *e = strstr(p, "}}");
        cr_assert(e, "'{{' without '}}'");
        len += (size_t)snprintf(list + len, cap - len, "%.*s\n", (int)(e + 2 - p), p);
        cr_assert(len < cap);
        n++;
    }
    return n;
}

/* Each lesson has an English and a French report template, and they ask for
 * the same values in the same order: a value the export provides is then used
 * by both (the export itself fails on a value a template leaves unused). */
Test(lesson, templates_agree)
{
    static const char *const slugs[] = {"01-kernel-estimation", "02-density-summation", "03-pressure-gradient",
                                        "04-viscosity",         "05-spatial-hash",      "06-sorting-offsets",
                                        "07-full-simulation",   "08-optimisation-ladder", "09-accuracy",
                                        "10-boundaries",        "11-incompressible"};
    for (int i = 0; i < 11; i++) {
        char path[256];
        snprintf(path, sizeof path, "lessons/%s/report.md", slugs[i]);
        char *en = read_all(path);
        cr_assert(en, "%s is missing", path);
        snprintf(path, sizeof path, "lessons/%s/report.fr.md", slugs[i]);
        char *fr = read_all(path);
        cr_assert(fr, "%s is missing", path);
        static char pe[16384], pf[16384];
        int ne = placeholders(en, pe, sizeof pe), nf = placeholders(fr, pf, sizeof pf);
        cr_expect(ne > 10, "%s: only %d placeholders", slugs[i], ne);
        cr_expect(ne == nf && strcmp(pe, pf) == 0, "%s: the English and French templates differ:\n%s\n---\n%s",
                  slugs[i], pe, pf);
        free(en);
        free(fr);
    }
}

/* A template that asks for a value the export does not make, or leaves one of
 * its values unused, fails the export and names both. */
Test(lesson, template_slip_fails_the_export)
{
    const char *root = test_temp_dir("lesson");
    char cmd[512];
    snprintf(cmd, sizeof cmd, "cp -r lessons/04-viscosity '%s/' && sed -i 's/{{lap_exact}}/{{no_such_value}}/' "
                              "'%s/04-viscosity/report.md'",
             root, root);
    cr_assert(system(cmd) == 0, "%s", cmd);
    char dir[128];
    snprintf(dir, sizeof dir, "%s/out", root);
    setenv("SPHLAB_LESSONS", root, 1);
    char args[256];
    snprintf(args, sizeof args, "lesson 4 --export %s --quick --quiet", dir);
    int rc = test_sphlab(args, out, sizeof out);
    unsetenv("SPHLAB_LESSONS");
    cr_expect(rc == 1, "exit %d with a slip in the template:\n%s", rc, out);
    cr_expect(strstr(out, "no value for {{no_such_value}}"), "the unknown placeholder is not named:\n%s", out);
    cr_expect(strstr(out, "uses no {{lap_exact}}"), "the unused value is not named:\n%s", out);
    char path[256];
    snprintf(path, sizeof path, "%s/report.fr.md", dir);
    char *fr = read_all(path);
    cr_expect(fr && !strstr(fr, "{{"), "the French report (its template is intact) is not filled");
    free(fr);
    test_remove_dir(root);
}

/* ---- the command ------------------------------------------------------------------ */

Test(lesson, list)
{
    int rc = test_sphlab("lesson --list", out, sizeof out);
    cr_assert(rc == 0, "exit %d: %s", rc, out);
    const char *titles[] = {"Kernel estimation",     "Density summation", "The pressure gradient",
                            "The viscosity Laplacian", "The spatial hash",  "Sorting and offsets",
                            "The full simulation",   "The optimisation ladder", "What accuracy costs",
                            "Boundary handling",     "How incompressible, at what cost?"};
    for (int i = 0; i < 11; i++) {
        char line[64];
        snprintf(line, sizeof line, "\n%-3d %s", i + 1, titles[i]);
        cr_expect(strstr(out, line), "--list lacks '%s':\n%s", line + 1, out);
    }
}

Test(lesson, bad_arguments)
{
    cr_expect(test_sphlab("lesson 0", out, sizeof out) == 2, "lesson 0: %s", out);
    cr_expect(strstr(out, "1 to 11"), "lesson 0 does not say the range: %s", out);
    cr_expect(test_sphlab("lesson 12", out, sizeof out) == 2, "lesson 12: %s", out);
    cr_expect(test_sphlab("lesson abc", out, sizeof out) == 2, "lesson abc: %s", out);
    /* alone it lists the course, as `sphlab help` says ("list the lessons, open one ..."; it exited 2) */
    cr_expect(test_sphlab("lesson", out, sizeof out) == 0, "lesson alone: %s", out);
    cr_expect(strstr(out, "Kernel estimation") != NULL, "lesson alone does not list the lessons: %s", out);
    cr_expect(test_sphlab("lesson 3 --export", out, sizeof out) == 2, "--export without a directory: %s", out);
    cr_expect(test_sphlab("lesson 3 --quick", out, sizeof out) == 2, "--quick without --export: %s", out);
}

Test(lesson, no_display)
{
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    unsetenv("SDL_VIDEODRIVER");
    int rc = test_sphlab("lesson 5", out, sizeof out);
    cr_expect(rc == 1, "exit %d without a display: %s", rc, out);
    cr_expect(strstr(out, "no display"), "no clear message: %s", out);
    cr_expect(strstr(out, "--export"), "the message does not point to --export: %s", out);
}

Test(lesson, dry_run_names_the_view_command)
{
    int rc = test_sphlab("lesson 7 --dry-run", out, sizeof out);
    cr_assert(rc == 0, "exit %d: %s", rc, out);
    cr_expect(strstr(out, " view ") && strstr(out, "07-full-simulation/lesson.ini") && strstr(out, "--paused"),
              "dry run: %s", out);
}

/* The window, through SDL's offscreen driver: `lesson 5` runs `view` with the
 * lesson's scene and overlays; extra options go to `view`. */
Test(lesson, window_offscreen)
{
    if (!has_command("view")) cr_skip_test("no view command in this build");
    setenv("SDL_VIDEODRIVER", "offscreen", 1);
    const char *dir = test_temp_dir("lesson");
    char args[256];
    snprintf(args, sizeof args, "lesson 5 --frames 2 --keys . --threads 1 --screenshot %s/shot.png", dir);
    int rc = test_sphlab(args, out, sizeof out);
    cr_assert(rc == 0, "exit %d: %s", rc, out);
    check_png(dir, "shot.png", 1100, 760);
    test_remove_dir(dir);
}

/* The new lessons' first frame opens in the window without error (their
 * scenes run wall particles and the equation of state's dam break). */
Test(lesson, window_opens_lessons_10_and_11)
{
    if (!has_command("view")) cr_skip_test("no view command in this build");
    setenv("SDL_VIDEODRIVER", "offscreen", 1);
    for (int num = 10; num <= 11; num++) {
        const char *dir = test_temp_dir("lesson");
        char args[256];
        snprintf(args, sizeof args, "lesson %d --frames 1 --threads 1 --screenshot %s/shot.png", num, dir);
        int rc = test_sphlab(args, out, sizeof out);
        cr_assert(rc == 0, "lesson %d: exit %d: %s", num, rc, out);
        check_png(dir, "shot.png", 0, 0);
        test_remove_dir(dir);
    }
}

Test(lesson, unwritable_output)
{
    int rc = test_sphlab("lesson 2 --export /proc/sphlab-no/such --quick --quiet", out, sizeof out);
    cr_expect(rc != 0, "exporting into /proc succeeded: %s", out);
    cr_expect(strstr(out, "/proc/sphlab-no/such"), "the message does not name the directory: %s", out);
}

/* ---- each lesson's export -------------------------------------------------------------- */

Test(lesson, export_1_kernel_estimation)
{
    const char *dir = export_lesson(1);
    free(check_report(dir, 1, "Kernel estimation", "Estimation par noyau"));
    check_png(dir, "kernels-2d.png", 0, 0);
    check_pdf(dir, "kernels-2d.pdf");
    check_csv(dir, "kernels-2d.csv", "r_over_h,r,w_poly6", 100, NULL);
    check_png(dir, "kernels-3d.png", 0, 0);
    check_png(dir, "kernel-viscosity-2d.png", 0, 0);
    if (has_command("estimate")) {
        check_png(dir, "estimate-1d.png", 0, 0);
        check_pdf(dir, "estimate-1d.pdf");
        check_csv(dir, "estimate-1d.csv", "dim,n,", 6, NULL);
        check_png(dir, "estimate-2d.png", 0, 0);
        check_csv(dir, "estimate-2d.csv", "dim,n,", 6, NULL);
        check_png(dir, "estimate-2d-lattice.png", 0, 0);
    }
    csv c;
    check_csv(dir, "density-vs-h.csv",
              "h_over_spacing,h,neighbours,interior_mean,interior_rms_percent,surface_mean,surface_deficit_percent", 3, &c);
    /* a larger h: less noise inside, a deeper deficit at the surface */
    cr_expect(field(c.line[1], 4) > field(c.line[c.nlines - 1], 4), "interior noise does not fall with h");
    cr_expect(field(c.line[1], 6) < field(c.line[c.nlines - 1], 6), "surface deficit does not grow with h");
    free(c.text);
    check_png(dir, "density-vs-h.png", 1000, 650);
    check_pdf(dir, "density-vs-h.pdf");
    check_png(dir, "density-h1.5.png", 900, 650);
    check_png(dir, "density-h4.png", 900, 650);
    test_remove_dir(dir);
}

Test(lesson, export_2_density_summation)
{
    const char *dir = export_lesson(2);
    free(check_report(dir, 2, "Density summation", "Sommation de la densité"));
    csv c;
    check_csv(dir, "density-profile.csv", "y,rho_volume,rho_reflect", 20, &c);
    /* floor row: the volume walls make up the missing support, reflect does not */
    cr_expect(field(c.line[1], 1) > field(c.line[1], 2) + 100, "floor: %s", c.line[1]);
    /* the top row lacks neighbours with either walls */
    cr_expect(field(c.line[c.nlines - 1], 1) < 900 && field(c.line[c.nlines - 1], 2) < 900, "top: %s",
              c.line[c.nlines - 1]);
    /* the interior reads a little above rho0 on a lattice */
    double mid = field(c.line[c.nlines / 2], 1);
    cr_expect(mid > 1000 && mid < 1030, "interior density %g", mid);
    free(c.text);
    check_csv(dir, "density-points.csv", "wall_model,h_over_spacing,particle,rho,error_percent", 18, &c);
    /* the lesson's texts quote the floor and the corner with volume walls at h = 2 spacings (the same
     * at --quick: the density before any step) */
    double floor_rho = 0, corner_rho = 0;
    for (int i = 1; i < c.nlines; i++) {
        if (strncmp(c.line[i], "volume,2,floor (wall),", 22) == 0) floor_rho = field(c.line[i], 3);
        if (strncmp(c.line[i], "volume,2,corner floor / left wall,", 34) == 0) corner_rho = field(c.line[i], 3);
    }
    free(c.text);
    cr_assert(floor_rho > 0 && corner_rho > 0, "no volume floor or corner row at h = 2 spacings");
    const char *texts[2][3] = {{"lessons/02-density-summation/README.md", "At the floor, `volume` gives ",
                                "in the bottom-left corner "},
                               {"lessons/02-density-summation/README.fr.md", "Au fond, `volume` donne ",
                                "dans le coin en bas à gauche, "}};
    for (int t = 0; t < 2; t++) {
        char *text = read_all(texts[t][0]);
        cr_assert(text, "%s is missing", texts[t][0]);
        /* one line, one space between words, decimal commas as points */
        size_t m = 0;
        for (const char *q = text; *q; q++) {
            char ch = *q == '\n' ? ' ' : *q == ',' && q[1] >= '0' && q[1] <= '9' ? '.' : *q;
            if (ch != ' ' || (m > 0 && text[m - 1] != ' ')) text[m++] = ch;
        }
        text[m] = '\0';
        const double want[2] = {floor_rho, corner_rho};
        for (int k = 0; k < 2; k++) {
            const char *needle = texts[t][1 + k], *at = strstr(text, needle);
            cr_expect(at, "%s: no '%s'", texts[t][0], needle);
            if (at)
                cr_expect(fabs(strtod(at + strlen(needle), NULL) - want[k]) < 0.051, "%s: '%s%.6s...', the export: %.1f",
                          texts[t][0], needle, at + strlen(needle), want[k]);
        }
        free(text);
    }
    check_png(dir, "density-profile.png", 1000, 650);
    check_pdf(dir, "density-profile.pdf");
    check_png(dir, "pool-walls.png", 1000, 600);
    check_pdf(dir, "pool-walls.pdf");
    /* the chart's data beside it (it had none: a user found it only in the deleted work folder) */
    check_csv(dir, "pool-walls.csv", "wall_model,t,ekin,max_speed", 400, NULL);
    check_png(dir, "density.png", 1000, 640);
    check_png(dir, "density-reflect.png", 1000, 640);
    test_remove_dir(dir);
}

Test(lesson, export_3_pressure_gradient)
{
    const char *dir = export_lesson(3);
    free(check_report(dir, 3, "The pressure gradient", "Le gradient de pression"));
    check_csv(dir, "pool-stats.csv", "step,t,dt,n,ekin", 300, NULL);
    csv c;
    check_csv(dir, "pressure-depth.csv", "y,p_sph,p_hydrostatic", 10, &c);
    cr_expect(field(c.line[2], 1) > field(c.line[c.nlines - 1], 1), "pressure does not fall with height");
    free(c.text);
    check_png(dir, "pressure-depth.png", 1000, 650);
    check_csv(dir, "eos.csv", "rho_linear,p_linear,rho_tait,p_tait", 700, NULL);
    check_png(dir, "eos.png", 1000, 650);
    check_png(dir, "pool-energy.png", 1000, 600);
    check_pdf(dir, "pool-energy.pdf");
    check_csv(dir, "energy.csv", "density_kernel,pressure_kernel,form,steps,e_start,e_end,change_percent", 4, NULL);
    check_csv(dir, "momentum.csv", "form,steps,sum_m_abs_v,abs_sum_m_v,ratio", 2, &c);
    for (int i = 1; i < c.nlines; i++) /* pair forces equal and opposite: momentum stays at round-off */
        cr_expect(field(c.line[i], 4) < 1e-5, "momentum not conserved: %s", c.line[i]);
    free(c.text);
    check_png(dir, "pressure.png", 1000, 560);
    test_remove_dir(dir);
}

/* The full export (not --quick) runs Mueller's pair in the pool for the
 * scene's 2 s without viscosity; its energy grows until the watchdog stops
 * it (t = 1.04 s). That stop is the lesson's result, not a failed export:
 * exit 0, and the report gives the energy and the time it was stopped at. */
Test(lesson, export_3_full_reports_the_watchdog_stop, .timeout = 600)
{
    const char *dir = test_temp_dir("lesson");
    char args[256];
    snprintf(args, sizeof args, "lesson 3 --export %s --quiet", dir);
    int rc = test_sphlab(args, out, sizeof out);
    cr_assert(rc == 0, "sphlab %s exited %d:\n%s", args, rc, out);
    char path[512];
    snprintf(path, sizeof path, "%s/report.md", dir);
    char *md = read_all(path);
    cr_assert(md, "no report.md");
    cr_expect(strstr(md, "J/m with poly6 / spiky (Mueller's pair)") && strstr(md, "stopped by the watchdog"),
              "the report does not give Mueller's run and its stop:\n%.2000s", md);
    cr_expect(!strstr(md, "A run failed"), "the report names a failed run");
    free(md);
    snprintf(path, sizeof path, "%s/report.fr.md", dir);
    md = read_all(path);
    cr_assert(md, "no report.fr.md");
    cr_expect(strstr(md, "arrêté par le chien de garde"), "report.fr.md does not say the run was stopped");
    free(md);
    test_remove_dir(dir);
}

Test(lesson, export_4_viscosity)
{
    const char *dir = export_lesson(4);
    free(check_report(dir, 4, "The viscosity Laplacian", "Le laplacien de la viscosité"));
    csv c;
    check_csv(dir, "taylor-green.csv", "run,t,ekin_over_ekin0,analytic", 200, &c);
    double last = field(c.line[100], 2), an = field(c.line[100], 3); /* the first run's last row */
    cr_expect(last > 0.8 && last < 0.98, "E/E0 after 100 steps: %g", last);
    cr_expect(an > 0.8 && an < 0.9, "analytic E/E0 after 0.1 s: %g", an);
    free(c.text);
    check_png(dir, "taylor-green.png", 1000, 650);
    check_pdf(dir, "taylor-green.pdf");
    check_png(dir, "kernel-viscosity-2d.png", 0, 0);
    check_csv(dir, "kernel-viscosity-2d.csv", "r_over_h,r,w,dw_dr,lap", 100, NULL);
    check_png(dir, "kernel-viscosity-3d.png", 0, 0);
    check_png(dir, "speed.png", 800, 700);
    test_remove_dir(dir);
}

Test(lesson, export_5_spatial_hash)
{
    const char *dir = export_lesson(5);
    char *report = check_report(dir, 5, "The spatial hash", "Le hachage spatial");
    cr_expect(strstr(report, "Particle 7: cell (4, 1), hash 9800625, key 5"), "report lacks particle 7's numbers");
    free(report);
    csv c;
    check_csv(dir, "hash-example.csv", "particle,x,y,cell_x,cell_y,hash,key", 10, &c);
    /* particle 7, as on the seed's slide: cell (4, 1); the seed's primes: 4 * 15823 + 9737333 */
    cr_expect(field(c.line[8], 0) == 7 && field(c.line[8], 3) == 4 && field(c.line[8], 4) == 1, "%s", c.line[8]);
    cr_expect(field(c.line[8], 5) == 9800625 && field(c.line[8], 6) == 5, "%s", c.line[8]);
    free(c.text);
    check_png(dir, "hash.png", 1100, 760);
    check_csv(dir, "collisions.csv", "table_size,keys,occupied_cells,colliding_cells,neighbours_ms", 2, &c);
    /* 16 keys for a few hundred cells: every occupied cell shares its key */
    cr_expect(field(c.line[2], 1) == 16 && field(c.line[2], 3) == field(c.line[2], 2), "%s", c.line[2]);
    free(c.text);
    check_png(dir, "collisions.png", 1000, 640);
    test_remove_dir(dir);
}

Test(lesson, export_6_sorting_offsets)
{
    const char *dir = export_lesson(6);
    free(check_report(dir, 6, "Sorting and offsets", "Le tri et la liste des départs"));
    csv c;
    check_csv(dir, "bitonic-steps.csv", "stage,step,w,kind,swaps,k0", 10, &c);
    cr_expect(strstr(c.line[c.nlines - 1], ",0,1,1,2,2,2,4,6,7,9"), "not sorted after the last step: %s",
              c.line[c.nlines - 1]);
    free(c.text);
    check_csv(dir, "offsets-slide.csv", "key,count,start", 10, &c);
    /* the seed's keys: start of key 6 is entry 7, key 8 is empty */
    cr_expect(field(c.line[7], 0) == 6 && field(c.line[7], 2) == 7, "%s", c.line[7]);
    cr_expect(strstr(c.line[9], "8,0,inf"), "%s", c.line[9]);
    free(c.text);
    check_csv(dir, "offsets.csv", "key,count,start", 10, NULL);
    if (has_command("view")) {
        const char *shots[] = {"pass-1-external.png", "pass-2-hash.png", "pass-3-sort.png",
                               "pass-4-reorder.png",  "pass-5-offsets.png", "pass-6-neighbours.png"};
        for (int i = 0; i < 6; i++) check_png(dir, shots[i], 1100, 760);
    }
    check_csv(dir, "sort-time.csv", "particles,bitonic_ms,counting_ms,qsort_ms", 2, &c);
    /* which sort is faster is the lesson's finding, not the test's: a busy machine may reorder them */
    cr_expect(field(c.line[2], 0) > field(c.line[1], 0), "a smaller spacing gave no more particles: %s / %s",
              c.line[1], c.line[2]);
    for (int i = 1; i < c.nlines; i++)
        for (int k = 1; k <= 3; k++)
            cr_expect(field(c.line[i], k) >= 0, "sort %d: no time in %s", k, c.line[i]);
    free(c.text);
    check_png(dir, "sort-time.png", 1000, 650);
    test_remove_dir(dir);
}

Test(lesson, export_7_full_simulation)
{
    const char *dir = export_lesson(7);
    char *report = check_report(dir, 7, "The full simulation", "La simulation complète");
    cr_expect(strstr(report, "| neighbours |") && strstr(report, "| all passes |"), "no timing table in the report");
    free(report);
    check_csv(dir, "stats.csv", "step,t,dt,n,ekin,rho_min,rho_mean,rho_max,max_speed", 200, NULL);
    check_csv(dir, "final.csv", "id,x,y,z,vx,vy,vz,rho,p", 1000, NULL);
    check_png(dir, "passes.png", 0, 0);
    check_pdf(dir, "passes.pdf");
    check_png(dir, "passes-time.png", 0, 0);
    check_png(dir, "energy-density.png", 0, 0);
    for (int i = 0; i < 3; i++) check_png(dir, i == 0 ? "frames/frame_00000.png" : i == 1 ? "frames/frame_00001.png"
                                                                                      : "frames/frame_00002.png",
                                          960, 520);
    if (has_command("view")) {
        const char *shots[] = {"pass-01-external.png", "pass-06-neighbours.png", "pass-07-density.png",
                               "pass-09-pressure_force.png", "pass-12-walls.png"};
        for (int i = 0; i < 5; i++) check_png(dir, shots[i], 960, 560);
    }
    test_remove_dir(dir);
}

Test(lesson, export_8_optimisation_ladder)
{
    const char *dir = export_lesson(8);
    free(check_report(dir, 8, "The optimisation ladder", "L'échelle des optimisations"));
    char fr_path[1100];
    snprintf(fr_path, sizeof fr_path, "%s/report.fr.md", dir);
    char *fr = read_all(fr_path);
    cr_assert(fr, "no %s", fr_path);
    /* the tables' level descriptions come from the core's table, in both
     * languages (the quoted `sphlab bench levels` output stays as printed) */
    cr_expect(!strstr(fr, "| L0 | brute force") && !strstr(fr, "| L3 | counting sort |"),
              "report.fr.md's table describes a level in English");
    cr_expect(strstr(fr, "| L0 | force brute O(N^2)") || strstr(fr, "| L3 | tri par comptage |"),
              "report.fr.md's table describes no level in French");
    free(fr);
    if (has_command("bench")) {
        csv c;
        check_csv(dir, "levels.csv", "level,threads,particles,ms_per_step,neighbours_ms,speedup,steps_per_s", 7, &c);
        /* every level runs the same scene; its speed is measured, not asserted (a busy machine may reorder
         * the levels), only that the speed-up and steps/s columns follow from the milliseconds */
        /* a row for every CPU level of the core's table, in its order (the lesson's arrays once held 16:
         * L16-L18 ran past them, which the sanitizers' build caught) */
        int cpu_levels = 0;
        for (int l = 0; l < sph_level_count; l++) cpu_levels += !sph_level_gl(&sph_levels[l]);
        cr_expect_eq(c.nlines - 1, cpu_levels, "levels.csv: %d rows for %d CPU levels", c.nlines - 1, cpu_levels);
        /* and each row ran with every key of its level: logs/NN-run-LEVEL.txt starts with the command (a
         * run of 12 keys at most once ran L13-L18 as L12 under their names) */
        DIR *logs = NULL;
        char logdir[1100];
        snprintf(logdir, sizeof logdir, "%s/logs", dir);
        for (int l = 0; l < sph_level_count; l++) {
            if (sph_level_gl(&sph_levels[l])) continue;
            char tail[32], path[1400];
            snprintf(tail, sizeof tail, "-run-%s.txt", sph_levels[l].name);
            path[0] = 0;
            logs = opendir(logdir);
            cr_assert_not_null(logs, "no %s", logdir);
            for (struct dirent *e; (e = readdir(logs));) {
                const size_t ln = strlen(e->d_name), tn = strlen(tail);
                if (ln > tn && strcmp(e->d_name + ln - tn, tail) == 0) snprintf(path, sizeof path, "%s/%s", logdir, e->d_name);
            }
            closedir(logs);
            cr_assert(path[0], "no log of %s's run in %s", sph_levels[l].name, logdir);
            char *log = read_all(path);
            cr_assert_not_null(log, "%s", path);
            char keys[600];
            snprintf(keys, sizeof keys, "%s", sph_levels[l].sets);
            char *save = NULL;
            for (char *k = strtok_r(keys, " ", &save); k; k = strtok_r(NULL, " ", &save))
                cr_expect(strstr(log, k), "%s ran without %s (%s)", sph_levels[l].name, k, path);
            free(log);
        }
        int row = 1;
        for (int l = 0; l < sph_level_count && row < c.nlines; l++) {
            if (sph_level_gl(&sph_levels[l])) continue;
            const size_t nlen = strlen(sph_levels[l].name);
            cr_expect(strncmp(c.line[row], sph_levels[l].name, nlen) == 0 && c.line[row][nlen] == ',',
                      "levels.csv row %d: %.40s, not %s", row, c.line[row], sph_levels[l].name);
            row++;
        }
        double l0 = field(c.line[1], 3);
        for (int i = 1; i < c.nlines; i++) {
            double ms = field(c.line[i], 3);
            cr_expect(field(c.line[i], 2) == field(c.line[1], 2), "%s: not the particles of L0", c.line[i]);
            cr_expect(ms > 0, "%s: no positive ms per step", c.line[i]);
            /* the CSV rounds ms to 4 decimals: allow twice what that rounding can move a ratio */
            double rel = 1e-4 / ms + 1e-4 / l0;
            cr_expect(fabs(field(c.line[i], 5) - l0 / ms) <= rel * (l0 / ms) + 1e-4, "%s: speedup is not L0's ms / ms",
                      c.line[i]);
            cr_expect(fabs(field(c.line[i], 6) - 1000 / ms) <= 1e-4 / ms * (1000 / ms) + 0.01,
                      "%s: steps/s is not 1000 / ms", c.line[i]);
        }
        free(c.text);
        check_png(dir, "levels.png", 1000, 600);
        check_pdf(dir, "levels.pdf");
    }
    check_png(dir, "block.png", 900, 700);
    test_remove_dir(dir);
}

Test(lesson, export_9_accuracy)
{
    const char *dir = export_lesson(9);
    free(check_report(dir, 9, "What accuracy costs", "Ce que coûte la précision"));
    csv c;
    if (has_command("study")) {
        check_csv(dir, "accuracy.csv", "combo,", 4, NULL);
        check_csv(dir, "accuracy-precision.csv", "combo,", 2, NULL);
        check_png(dir, "accuracy-precision.png", 0, 0);
    } else {
        check_csv(dir, "accuracy.csv", "spacing,h_over_spacing,accumulate,particles,steps,wall_s", 4, &c);
        free(c.text);
    }
    check_png(dir, "accuracy.png", 0, 0);
    check_pdf(dir, "accuracy.pdf");
    test_remove_dir(dir);
}

/* Lesson 10: the three wall models side by side. The wall row of a block at
 * rest reads the interior's density with volume walls and wall particles,
 * and less without (reflect: the truncated support); the tank's and the dam
 * break's CSV have a row for every model. */
Test(lesson, export_10_boundaries)
{
    const char *dir = export_lesson(10);
    char *text = check_report(dir, 10, "Boundary handling", "Les conditions aux parois");
    cr_expect(strstr(text, "| reflect |") && strstr(text, "| volume |") && strstr(text, "| particles |"),
              "the report does not compare the three models");
    free(text);
    csv c;
    check_csv(dir, "wall-row-density.csv", "wall_model,row,y,rho,rho_over_rho0", 30, &c);
    double first[3] = {NAN, NAN, NAN};
    for (int i = 1; i < c.nlines; i++)
        if (field(c.line[i], 1) == 0) {
            int m = strncmp(c.line[i], "reflect,", 8) == 0 ? 0 : strncmp(c.line[i], "volume,", 7) == 0 ? 1 : 2;
            first[m] = field(c.line[i], 4);
        }
    cr_expect(first[0] < 0.95, "reflect: the wall row reads %g rho0, not less than the interior", first[0]);
    cr_expect(fabs(first[1] - 1) < 0.02 && fabs(first[2] - 1) < 0.02, "volume %g, particles %g: not rho0", first[1],
              first[2]);
    free(c.text);
    check_png(dir, "wall-row-density.png", 1000, 650);
    check_pdf(dir, "wall-row-density.pdf");
    check_csv(dir, "hydrostatic-pressure.csv", "wall_model,rank,y,p,p_exact", 20, NULL);
    check_png(dir, "hydrostatic-pressure.png", 1000, 650);
    check_pdf(dir, "hydrostatic-pressure.pdf");
    check_csv(dir, "dam-front.csv", "wall_model,t,front_x", 6, NULL);
    check_png(dir, "dam-front.png", 1000, 650);
    check_pdf(dir, "dam-front.pdf");
    test_remove_dir(dir);
}

/* Lesson 11: one row per setting, the solvers iterate and the equation of
 * state does not, and the chart. */
Test(lesson, export_11_incompressible)
{
    if (!has_command("study")) cr_skip_test("no study command in this build");
    const char *dir = export_lesson(11);
    free(check_report(dir, 11, "How incompressible, at what cost?", "Incompressible à quel point, et à quel prix ?"));
    csv c;
    check_csv(dir, "solvers.csv", "combo,physics.pressure_solver+physics.stiffness+physics.solver_tolerance,", 3, &c);
    int it = -1, nf = 1;
    for (char *p = c.line[0]; *p; p++) nf += *p == ',';
    char head[1024];
    snprintf(head, sizeof head, "%s", c.line[0]);
    int k = 0;
    for (char *tok = strtok(head, ","); tok; tok = strtok(NULL, ","), k++)
        if (strcmp(tok, "iterations_per_step") == 0) it = k;
    cr_assert(it > 0 && it < nf, "no iterations_per_step column: %s", c.line[0]);
    for (int i = 1; i < c.nlines; i++) {
        bool eos = strstr(c.line[i], ",eos+") != NULL;
        double v = field(c.line[i], it);
        cr_expect(eos ? v == 0 : v >= 1, "%s: %g iterations per step", c.line[i], v);
    }
    free(c.text);
    check_png(dir, "solvers.png", 0, 0);
    check_pdf(dir, "solvers.pdf");
    test_remove_dir(dir);
}
