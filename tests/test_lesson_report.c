/* The exported report shows its figures (Markdown image links with their
 * captions), can be written as HTML too (--format html), and says in
 * itself when the machine was busy while its timings were taken. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test_util.h"

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f, "cannot read %s", path);
    static char buf[1 << 18];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static void export4(const char *dir, const char *load, const char *more)
{
    char loadf[300];
    snprintf(loadf, sizeof loadf, "%s.loadavg", dir); /* beside the export: tests run side by side */
    FILE *f = fopen(loadf, "w");
    cr_assert_not_null(f);
    fprintf(f, "%s 1.00 1.00 1/100 1\n", load);
    fclose(f);
    char args[1024], out[8192];
    snprintf(args, sizeof args, "lesson 4 --export %s --quick --quiet %s", dir, more);
    setenv("SPHLAB_LOADAVG_FILE", loadf, 1);
    int rc = test_sphlab(args, out, sizeof out);
    unsetenv("SPHLAB_LOADAVG_FILE");
    remove(loadf);
    cr_assert_eq(rc, 0, "%s", out);
}

Test(lesson_report, figures_are_embedded_and_html_is_written)
{
    char dir[] = "/tmp/sphlab-report-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    export4(dir, "0.00", "--format html");
    char p[256];
    snprintf(p, sizeof p, "%s/report.md", dir);
    const char *md = slurp(p);
    /* every shown image is a PNG the export wrote, with a caption */
    int shown = 0;
    for (const char *at = md; (at = strstr(at, "![")); at++) {
        const char *close = strstr(at, "](");
        cr_assert_not_null(close);
        cr_expect_gt(close - at, 2, "an image without a caption");
        char file[200], path[300];
        cr_assert_eq(sscanf(close + 2, "%199[^)]", file), 1);
        snprintf(path, sizeof path, "%s/%s", dir, file);
        cr_expect_eq(access(path, R_OK), 0, "the report shows %s, which is not there", file);
        shown++;
    }
    cr_expect_geq(shown, 2, "%d images in report.md", shown);
    cr_expect_null(strstr(md, "The machine was busy"), "an idle machine called busy");
    snprintf(p, sizeof p, "%s/report.html", dir);
    const char *html = slurp(p);
    cr_expect(strstr(html, "<!DOCTYPE html>") && strstr(html, "<img src=\"") && strstr(html, "<table>") &&
                  strstr(html, "<h2>") && strstr(html, "</html>"),
              "report.html: %.400s", html);
    cr_expect_null(strstr(html, "{{"), "a placeholder left in the page");
    cr_expect(strstr(html, "<html lang=\"en\">"), "report.html does not say it is English");
    snprintf(p, sizeof p, "%s/report.fr.html", dir);
    html = slurp(p);
    cr_expect(strstr(html, "<html lang=\"fr\">"), "report.fr.html does not say it is French: %.200s", html);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_expect_eq(system(cmd), 0);
}

Test(lesson_report, a_busy_machine_is_named_in_the_report)
{
    char dir[] = "/tmp/sphlab-report-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    export4(dir, "64.00", "");
    char p[256];
    snprintf(p, sizeof p, "%s/report.md", dir);
    const char *md = slurp(p);
    cr_expect(strstr(md, "**The machine was busy**: load average 64.00"), "no note in the report");
    snprintf(p, sizeof p, "%s/report.html", dir);
    cr_expect_neq(access(p, F_OK), 0, "report.html without --format html");
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_expect_eq(system(cmd), 0);
}

Test(lesson_report, format_is_checked)
{
    char out[4096];
    cr_expect_eq(test_sphlab("lesson 4 --format html", out, sizeof out), 2, "%s", out);
    cr_expect(strstr(out, "--format goes with --export"), "%s", out);
    cr_expect_eq(test_sphlab("lesson 4 --export /tmp/sphlab-x --format pdf", out, sizeof out), 2, "%s", out);
    cr_expect(strstr(out, "pdf"), "%s", out);
}
