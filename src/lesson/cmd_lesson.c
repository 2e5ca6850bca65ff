/* sphlab lesson: the course. Lists the lessons, opens one in the window (by
 * running this binary's `view` with the lesson's scene and overlays), or
 * exports its figures and report headless. */
#define _DEFAULT_SOURCE /* realpath */
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "../io/io.h"
#include "app.h"
#include "commands.h"
#include "lesson_steps.h"
#include "sph_names.h"


/* The window's options: the starting state (paused at step 0: space runs,
 * `.` steps one pass) and the overlays the lesson is about. */
const lesson sph_lessons[] = {
    {1, "01-kernel-estimation", "Kernel estimation", "beginner",
     "the SPH sum as a kernel estimate; what h does: noise against smoothing; W, grad W, lap W",
     "Estimation par noyau",
     "la somme SPH comme estimation par noyau ; ce que fait h : bruit contre lissage ; W, grad W, lap W",
     "--paused --color density --range 600:1400 --overlay neighbours,hud,legend --select 625", lx_lesson1},
    {2, "02-density-summation", "Density summation", "beginner",
     "rho_i = sum_j m_j W_ij on a lattice; the deficiency at the free surface; walls that count",
     "Sommation de la densité",
     "rho_i = somme_j m_j W_ij sur un réseau ; le déficit à la surface libre ; des parois qui comptent",
     "--paused --color density --overlay grid,neighbours,hud,legend --select 585", lx_lesson2},
    {3, "03-pressure-gradient", "The pressure gradient", "intermediate",
     "equation of state; symmetric against the seed's shared form; momentum and energy",
     "Le gradient de pression",
     "équation d'état ; la forme symétrique contre la forme partagée de la source ; quantité de mouvement et énergie",
     "--paused --color pressure --overlay forces,hud,legend", lx_lesson3},
    {4, "04-viscosity", "The viscosity Laplacian", "intermediate",
     "velocity diffusion; the 2D viscosity kernel; Taylor-Green decay against exp(-2 nu k^2 t)",
     "Le laplacien de la viscosité",
     "diffusion de la vitesse ; le noyau de viscosité 2D ; décroissance de Taylor-Green contre exp(-2 nu k^2 t)",
     "--paused --color speed --overlay forces,hud,legend", lx_lesson4},
    {5, "05-spatial-hash", "The spatial hash", "intermediate",
     "cells, hash, keys, collisions; the seed's worked example: particle 7, cell (4,1)",
     "Le hachage spatial",
     "cellules, hachage, clés, collisions ; l'exemple de la source : particule 7, cellule (4,1)",
     "--paused --color key --overlay grid,keys,collisions,neighbours,index,hud,legend --select 7 --size 1100x760",
     lx_lesson5},
    {6, "06-sorting-offsets", "Sorting and offsets", "intermediate",
     "the bitonic network step by step, the counting sort, the start-offset table",
     "Le tri et la liste des départs",
     "le réseau bitonique pas à pas, le tri par comptage, la table des départs",
     "--paused --color key --overlay grid,keys,index,hud,legend --select 7 --size 1100x760", lx_lesson6},
    {7, "07-full-simulation", "The full simulation", "beginner",
     "a dam break, stepped pass by pass; where the time goes",
     "La simulation complète",
     "une rupture de barrage, passe par passe ; où va le temps",
     "--paused --color speed --overlay hud,timings,legend", lx_lesson7},
    {8, "08-optimisation-ladder", "The optimisation ladder", "advanced",
     "switch each optimisation, read the speedup, rebuild the seed's table (350, 5,000, 20,000, 60,000)",
     "L'échelle des optimisations",
     "activer chaque optimisation, lire le gain, refaire le tableau de la source (350, 5 000, 20 000, 60 000)",
     "--paused --color neighbours --overlay grid,hud,timings,legend", lx_lesson8},
    {9, "09-accuracy", "What accuracy costs", "advanced",
     "error against time: resolution, h, kernel; the cheapest run for a given error",
     "Ce que coûte la précision",
     "l'erreur contre le temps : résolution, h, noyau ; le calcul le moins cher pour une erreur donnée",
     "--paused --color speed --overlay hud,timings,legend", lx_lesson9},
    {10, "10-boundaries", "Boundary handling", "intermediate",
     "the truncated support at a wall; reflect, volume and wall particles: the wall row, a tank, a dam break",
     "Les conditions aux parois",
     "le support tronqué contre une paroi ; reflect, volume et particules de paroi : la rangée du bord, une cuve, "
     "une rupture de barrage",
     "--paused --color density --overlay neighbours,hud,legend --select 15", lx_lesson10},
    {11, "11-incompressible", "How incompressible, at what cost?", "advanced",
     "the equation of state at three stiffnesses against PCISPH and DFSPH: density error and time per simulated second",
     "Incompressible à quel point, et à quel prix ?",
     "l'équation d'état à trois raideurs contre PCISPH et DFSPH : erreur de densité et temps par seconde simulée",
     "--paused --color density --overlay hud,timings,legend", lx_lesson11},
};
const int sph_lesson_count = (int)(sizeof sph_lessons / sizeof sph_lessons[0]);

/* A level's name in French, for report.fr.md. */
static const char *lx_level_fr(const char *level)
{
    if (strcmp(level, "beginner") == 0) return "débutant";
    if (strcmp(level, "intermediate") == 0) return "intermédiaire";
    if (strcmp(level, "advanced") == 0) return "avancé";
    return level;
}

/* The commands of this build, from the one list in commands.h. */
static bool have_command(const char *name)
{
#define LX_CMD_NAME(name, args, about) #name,
    static const char *const names[] = {SPH_COMMANDS(LX_CMD_NAME)};
#undef LX_CMD_NAME
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (strcmp(names[i], name) == 0) return true;
    return false;
}

bool lx_has_command(lx *x, const char *cmd)
{
    (void)x;
    return have_command(cmd);
}

static const app_cmd_spec spec = {
    .name = "lesson",
    .cmd = APP_CMD(lesson),
    .synopsis = "usage: sphlab lesson --list\n"
                "       sphlab lesson N [VIEW OPTIONS ...]   open lesson N in the window\n"
                "       sphlab lesson N --export DIR [--quick] [--quiet]\n"
                "       sphlab lesson N --dry-run            print the window's command instead of running it\n"
                "The course: one lesson per folder in lessons/ (README.md, README.fr.md, lesson.ini).\n"
                "  N                    opens the lesson's scene with `sphlab view` at its starting state, with\n"
                "                       its overlays on; further options go to `sphlab view` (see its --help)\n",
    .footer = "The lessons are found in ./lessons, in $SPHLAB_LESSONS, or beside this binary.\n"
              "exit status: 0 done; 1 a command of the lesson failed, or no display; 2 bad command line\n",
    .max_pos = 1,
    .flags = APP_SPEC_PASS_ON,
};

static bool is_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

static bool self_exe(char *out, size_t cap)
{
    ssize_t n = readlink("/proc/self/exe", out, cap - 1);
    if (n <= 0) return false;
    out[n] = '\0';
    return true;
}

/* lessons/NN-slug of the lesson: ./lessons, $SPHLAB_LESSONS, or beside the binary. */
static bool find_folder(const lesson *L, char *out, size_t cap)
{
    char bases[3][1024];
    int nb = 0;
    const char *env = getenv("SPHLAB_LESSONS");
    if (env && *env) snprintf(bases[nb++], sizeof bases[0], "%s", env);
    snprintf(bases[nb++], sizeof bases[0], "lessons");
    char exe[1024];
    if (self_exe(exe, sizeof exe)) {
        char *slash = strrchr(exe, '/');
        if (slash) {
            *slash = '\0';
            snprintf(bases[nb++], sizeof bases[0], "%.1000s/lessons", exe);
        }
    }
    for (int b = 0; b < nb; b++) {
        char dir[1200], ini[1300];
        snprintf(dir, sizeof dir, "%.1000s/%.100s", bases[b], L->slug);
        snprintf(ini, sizeof ini, "%.1200s/lesson.ini", dir);
        if (is_file(ini)) {
            snprintf(out, cap, "%s", dir);
            return true;
        }
    }
    fprintf(stderr, "sphlab lesson: cannot find lessons/%s/lesson.ini (looked in", L->slug);
    for (int b = 0; b < nb; b++) fprintf(stderr, "%s %s", b ? "," : "", bases[b]);
    fprintf(stderr, "); run sphlab from the repository's root or set SPHLAB_LESSONS\n");
    return false;
}

static int list(void)
{
    int w = (int)strlen("lesson"); /* the title column fits the longest title */
    for (int i = 0; i < sph_lesson_count; i++)
        if ((int)strlen(sph_lessons[i].title) > w) w = (int)strlen(sph_lessons[i].title);
    printf("%-3s %-*s %-13s %s\n", "N", w, "lesson", "level", "about");
    for (int i = 0; i < sph_lesson_count; i++) {
        const lesson *L = &sph_lessons[i];
        printf("%-3d %-*s %-13s %s\n", L->num, w, L->title, L->level, L->about);
    }
    printf("\nsphlab lesson N opens one in the window; sphlab lesson N --export DIR writes its figures\n"
           "and report; the texts are lessons/NN-NAME/README.md (English) and README.fr.md (French).\n");
    return 0;
}

/* ---- the window ---------------------------------------------------------------- */

static int open_window(const lesson *L, int argc, char **argv, bool dry_run)
{
    char folder[1200], scene[1300], exe[1024];
    if (!find_folder(L, folder, sizeof folder)) return 1;
    snprintf(scene, sizeof scene, "%s/lesson.ini", folder);
    if (!self_exe(exe, sizeof exe)) {
        fprintf(stderr, "sphlab lesson: cannot find this program (/proc/self/exe): %s\n", strerror(errno));
        return 1;
    }
    const char *args[128];
    int n = 0;
    char opts[512];
    snprintf(opts, sizeof opts, "%s", L->view_args);
    args[n++] = "sphlab";
    args[n++] = "view";
    args[n++] = scene;
    /* the lesson's own view options, less the single-valued ones the user gives again (theirs win; both given,
     * the window said "--color is given twice" to a student who had only asked for another colour); a repeatable
     * one (--overlay adds) stays, or the lesson's overlays went */
    const char *mine[100];
    int n_mine = 0;
    for (char *tok = strtok(opts, " "); tok && n_mine < 100; tok = strtok(NULL, " ")) mine[n_mine++] = tok;
    for (int k = 0; k < n_mine && n < 100; k++) {
        const app_opt *o = mine[k][0] == '-' ? app_opts_find(APP_CMD(view), mine[k]) : NULL;
        if (o && o->kind == APP_OPT_LIST) o = NULL; /* repeatable: kept, and its value with it */
        bool again = false;
        for (int i = 0; o && i < argc && !again; i++)
            again = argv[i][0] == '-' && app_opts_find(APP_CMD(view), argv[i]) == o;
        const bool valued = o && o->kind != APP_OPT_FLAG && o->kind != APP_OPT_HELP && !strchr(mine[k], '=');
        if (again) {
            k += valued; /* and its value */
            continue;
        }
        args[n++] = mine[k];
    }
    for (int i = 0; i < argc && n < 126; i++) args[n++] = argv[i];
    args[n] = NULL;
    if (dry_run) {
        for (int i = 0; args[i]; i++) printf("%s%s", i ? " " : "", i == 0 ? exe : args[i]);
        printf("\n");
        return 0;
    }
    if (!have_command("view")) {
        fprintf(stderr, "sphlab lesson %d: this build has no `view` command (the window), so the lesson cannot\n"
                        "open; export its figures instead: sphlab lesson %d --export DIR\n",
                L->num, L->num);
        return 1;
    }
    const char *display = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY"), *drv = getenv("SDL_VIDEODRIVER");
    if ((!display || !*display) && (!wayland || !*wayland) && (!drv || !*drv)) {
        fprintf(stderr,
                "sphlab lesson %d: no display: DISPLAY and WAYLAND_DISPLAY are not set, so the window cannot open.\n"
                "Export the lesson's figures and report instead:  sphlab lesson %d --export DIR\n"
                "(or run the window's scripted mode headless: SDL_VIDEODRIVER=offscreen sphlab lesson %d --frames N "
                "--screenshot FILE)\n",
                L->num, L->num, L->num);
        return 1;
    }
    printf("sphlab lesson %d: %s (%s); the text is %s/README.md\n", L->num, L->title, L->level, folder);
    fflush(stdout);
    execv(exe, (char *const *)args);
    fprintf(stderr, "sphlab lesson: cannot run %s view: %s\n", exe, strerror(errno));
    return 1;
}

/* ---- the export ------------------------------------------------------------------ */

static void remove_tree(const char *path, int depth)
{
    DIR *d = depth < 4 ? opendir(path) : NULL;
    if (d) {
        for (struct dirent *e; (e = readdir(d));) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
            char sub[2400];
            snprintf(sub, sizeof sub, "%s/%s", path, e->d_name);
            struct stat st;
            if (lstat(sub, &st) == 0 && S_ISDIR(st.st_mode)) remove_tree(sub, depth + 1);
            else unlink(sub);
        }
        closedir(d);
    }
    rmdir(path);
}

static void loadavg(char *out, size_t cap)
{
    snprintf(out, cap, "unknown");
    /* SPHLAB_LOADAVG_FILE: another file of the same form (the tests' busy and idle machines) */
    const char *path = getenv("SPHLAB_LOADAVG_FILE");
    FILE *f = fopen(path && *path ? path : "/proc/loadavg", "r");
    if (!f) return;
    double a, b, c;
    if (fscanf(f, "%lf %lf %lf", &a, &b, &c) == 3) snprintf(out, cap, "%.2f %.2f %.2f", a, b, c);
    fclose(f);
}

/* The files in dir written since `since` (the export's own, not an earlier
 * export's left in the same folder), but the reports: what "N files" says. */
static int files_written(const char *dir, const struct timespec *since)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (strncmp(e->d_name, "report.", 7) == 0 || e->d_name[0] == '.') continue;
        char path[2400];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        struct stat st;
        if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) continue;
        if (st.st_mtim.tv_sec > since->tv_sec ||
            (st.st_mtim.tv_sec == since->tv_sec && st.st_mtim.tv_nsec >= since->tv_nsec))
            n++;
    }
    closedir(d);
    return n;
}

static int export_lesson(const lesson *L, const char *dir, bool quick, bool quiet, bool html)
{
    struct timespec started;
    clock_gettime(CLOCK_REALTIME, &started);
    started.tv_nsec = 0; /* some file systems keep whole seconds */
    static lx x; /* large: the figure list */
    memset(&x, 0, sizeof x);
    x.L = L;
    x.quick = quick;
    x.quiet = quiet;
    char folder[1000];
    if (!find_folder(L, folder, sizeof folder)) return 1;
    if (!self_exe(x.exe, sizeof x.exe)) {
        fprintf(stderr, "sphlab lesson: cannot find this program (/proc/self/exe): %s\n", strerror(errno));
        return 1;
    }
    plot_out_command("lesson");
    char dir_err[1200];
    if (!sph_mkdir_p(dir, dir_err, sizeof dir_err)) { /* named as the option the user gave */
        fprintf(stderr, "sphlab lesson: --export %s: %s\n", dir, dir_err);
        return 1;
    }
    /* paths as given (they show in the commands and the logs); absolute
     * ones only where a command runs in another directory (lx_abs) */
    snprintf(x.dir, sizeof x.dir, "%s", dir);
    for (size_t n = strlen(x.dir); n > 1 && x.dir[n - 1] == '/';) x.dir[--n] = '\0';
    snprintf(x.folder, sizeof x.folder, "%s", folder);
    char logs[1100];
    snprintf(logs, sizeof logs, "%s/logs", x.dir);
    snprintf(x.scratch, sizeof x.scratch, "%s/.work", x.dir);
    remove_tree(x.scratch, 0);
    if (!plot_out_dir(logs) || !plot_out_dir(x.scratch)) return 1;
    /* an earlier export's logs go (NN-name.txt, the names this command gives them): a --quick export into a full
     * one's folder left the full runs' logs beside its own, where the report says logs/ holds what ran */
    DIR *old_logs = opendir(logs);
    for (struct dirent *e; old_logs && (e = readdir(old_logs));) {
        const char *nm = e->d_name;
        const size_t len = strlen(nm);
        if (len > 7 && isdigit((unsigned char)nm[0]) && isdigit((unsigned char)nm[1]) && nm[2] == '-' &&
            strcmp(nm + len - 4, ".txt") == 0) {
            char path[1400];
            snprintf(path, sizeof path, "%s/%s", logs, nm);
            unlink(path);
        }
    }
    if (old_logs) closedir(old_logs);
    /* a report from an earlier export must not survive a failed one */
    char report[1200];
    snprintf(report, sizeof report, "%s/report.fr.md", x.dir);
    unlink(report);
    snprintf(report, sizeof report, "%s/report.md", x.dir);
    unlink(report);
    unlink(lx_out(&x, "report.html"));
    unlink(lx_out(&x, "report.fr.html"));

    x.sink = x.mdf = open_memstream(&x.md, &x.md_len);
    if (!x.mdf) {
        fprintf(stderr, "sphlab lesson: out of memory\n");
        return 1;
    }
    char load0[64], load1[64];
    loadavg(load0, sizeof load0);
    double t0 = sph_now_ms();
    int rc = L->export_fn(&x);
    double secs = (sph_now_ms() - t0) / 1e3;
    loadavg(load1, sizeof load1);
    lx_block_end(&x);
    fclose(x.sink);
    x.sink = x.mdf = NULL;
    if (rc != 0 && !x.failed) x.failed = 1;

    /* the values every lesson's template has */
    lx_val(&x, "num", "%d", L->num);
    lx_val(&x, "title", "{{@%s|%s}}", L->title, L->title_fr);
    lx_val(&x, "level", "{{@%s|%s}}", L->level, lx_level_fr(L->level));
    lx_val(&x, "about", "{{@%s|%s}}", L->about, L->about_fr);
    lx_val(&x, "slug", "%s", L->slug);
    lx_val(&x, "seconds", "%.1f", secs);
    lx_val(&x, "cores", "%ld", sysconf(_SC_NPROCESSORS_ONLN));
    lx_val(&x, "load_before", "%s", load0);
    lx_val(&x, "load_after", "%s", load1);
    lx_val(&x, "quick", "%s", quick ? " --quick" : "");
    lx_val(&x, "notes", "%.*s", (int)x.md_len, x.md ? x.md : "");
    free(x.md);
    x.md = NULL;
    lx_block(&x, "figures");
    /* timings measured while others loaded the machine: the report says so
     * beside the figures, not only the log; "in this report", since the
     * tables it speaks of stand above the figures (the 1-minute load average
     * before the export: the export's own threads are not in it) */
    double others = strtod(load0, NULL);
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    if (strcmp(load0, "unknown") != 0 && cores > 0 && others > 0.25 * (double)cores)
        lx_md(&x, "> {{@**The machine was busy**: load average %.2f on %ld cores before this export. Every timing "
                  "in this report (milliseconds per pass, steps per second, speed-ups) ran beside that load and is slower and "
                  "noisier than on an idle machine; export again when it is idle to compare.|**La machine était "
                  "occupée** : charge moyenne %.2f sur %ld cœurs avant cet export. Chaque temps de ce rapport "
                  "(millisecondes par passe, pas par seconde, accélérations) a tourné à côté de cette charge et est "
                  "plus lent et plus bruité que sur une machine au repos ; exportez de nouveau quand elle est au "
                  "repos pour comparer.}}\n\n",
              others, cores, others, cores);
    for (int i = 0; i < x.nfig; i++) {
        lx_md(&x, "- %s\n", x.figs[i]);
        /* a single PNG that exists is shown, with its caption as alt text */
        char file[256];
        const char *a = strchr(x.figs[i], '`'), *b = a ? strchr(a + 1, '`') : NULL;
        if (!b) continue;
        snprintf(file, sizeof file, "%.*s", (int)(b - a - 1), a + 1);
        size_t fl = strlen(file);
        const char *what = b[1] == ':' ? b + 3 : "";
        if (fl > 4 && strcmp(file + fl - 4, ".png") == 0 && !strpbrk(file, ", ") &&
            access(lx_out(&x, file), R_OK) == 0)
            lx_md(&x, "\n  ![%s](%s)\n\n", what, file);
    }
    lx_block(&x, "missing");
    for (int i = 0; i < x.nmissing; i++) lx_md(&x, "- %s\n", x.missing[i]);
    lx_block_end(&x);
    lx_val(&x, "failed", "%s", x.failed ? lx_fmt("%d", x.failed) : "");

    /* the report in each language the lesson's folder has a template for */
    static const char *const langs[2][2] = {{"report.md", "report.md"}, {"report.fr.md", "report.fr.md"}};
    bool ok = true;
    int made = 0;
    for (int k = 0; k < 2 && ok; k++) {
        char tmpl[1100], path[1200];
        snprintf(tmpl, sizeof tmpl, "%s/%s", folder, langs[k][0]);
        snprintf(path, sizeof path, "%s/%s", x.dir, langs[k][1]);
        if (k > 0 && access(tmpl, R_OK) != 0) continue; /* English is required, French optional */
        app_out out;
        if (!app_out_open(&out, path)) {
            ok = false;
            break;
        }
        lx_values_reset_use(&x);
        x.lang = k;
        if (!lx_report_write(&x, tmpl, out.f)) x.failed++;
        if (lx_values_unused(&x, tmpl)) x.failed++;
        ok = app_out_commit(&out);
        made++;
        if (ok && html) { /* the same text as a page beside it: report.html, report.fr.html */
            char *md = lx_read_file(path), hpath[1210];
            snprintf(hpath, sizeof hpath, "%.*s.html", (int)(strlen(path) - 3), path);
            app_out h;
            ok = md && app_out_open(&h, hpath);
            if (ok) {
                lx_html_write(md, k == 1 ? L->title_fr : L->title, k == 1 ? "fr" : "en", h.f);
                ok = app_out_commit(&h);
            }
            free(md);
        }
    }
    lx_values_free(&x);
    remove_tree(x.scratch, 0);
    if (!ok) return 1;
    if (x.failed) {
        fprintf(stderr, "sphlab lesson %d: %d command(s) or file(s) failed; see %s and %s/logs/\n", L->num, x.failed,
                report, x.dir);
        return 1;
    }
    printf("lesson %d (%s): %d files and %s%s in %s (%.1f s)\n", L->num, L->title, files_written(x.dir, &started),
           made > 1 ? "report.md, report.fr.md" : "report.md",
           !html ? "" : made > 1 ? ", report.html, report.fr.html" : ", report.html", dir, secs);
    for (int i = 0; i < x.nmissing; i++) printf("missing: %s\n", x.missing[i]);
    return 0;
}

int cmd_lesson(int argc, char **argv)
{
    /* lesson's own options; the others (and their values) go to `sphlab view` */
    app_opts opt;
    app_opts_init(&opt);
    int rc = app_opts_parse(&spec, argc, argv, &opt);
    if (rc >= 0) return rc;
    if (opt.list) {
        if (opt.n_pos || opt.n_rest) {
            fprintf(stderr, "sphlab lesson: --list takes no argument ('%s')\n", opt.n_pos ? opt.pos[0] : opt.rest[0]);
            return 2;
        }
        return list();
    }
    if (!opt.n_pos && opt.n_rest && opt.rest[0][0] == '-' && isdigit((unsigned char)opt.rest[0][1])) {
        /* a negative number reads as an option for the window: name it as the lesson number it meant */
        fprintf(stderr, "sphlab: lesson %s: out of range (accepted: 1 to %d)\n  (sphlab lesson --list names them)\n",
                opt.rest[0], sph_lesson_count);
        return 2;
    }
    if (argc <= 1) return list(); /* `sphlab lesson` alone: the course's list, as the commands' help says */
    if (!opt.n_pos) {
        app_opts_usage_error(&spec, "name a lesson (sphlab lesson --list names them)");
        return 2;
    }
    long num;
    if (!app_parse_int("lesson", opt.pos[0], 1, sph_lesson_count, &num)) {
        fprintf(stderr, "  (sphlab lesson --list names them)\n"); /* app_parse_int said what and why */
        return 2;
    }
    const lesson *L = &sph_lessons[num - 1];
    const char *dir = opt.export_dir;
    bool quick = opt.quick, quiet = opt.quiet, dry = opt.dry_run;
    if (dir && opt.n_rest) {
        fprintf(stderr,
                "sphlab lesson: unknown option '%s' with --export (an export reads --quick, --quiet and --format; "
                "the lesson's runs set the rest, as its figures were measured)\n",
                opt.rest[0]);
        return 2;
    }
    if (opt.format && !dir) {
        fprintf(stderr, "sphlab lesson: --format goes with --export DIR\n");
        return 2;
    }
    if (dir) return export_lesson(L, dir, quick, quiet, opt.format && strcmp(opt.format, "html") == 0);
    if (quick || quiet) {
        fprintf(stderr, "sphlab lesson: --quick and --quiet go with --export DIR\n");
        return 2;
    }
    /* the options passed on to the window are checked here, before the display is: `--exprot DIR` was answered
     * "no display" where it meant --export */
    for (int i = 0; i < opt.n_rest; i++) {
        const char *a = opt.rest[i];
        if (a[0] != '-' || !a[1] || isdigit((unsigned char)a[1]) || a[1] == '.') continue; /* a value: -0.5:0 */
        const app_opt *known = app_opts_find(APP_CMD(view), a); /* names and aliases (--colour) */
        if (known) {
            if (known->arg && !strchr(a, '=')) i++; /* its value follows */
            continue;
        }
        const char *own = app_opts_closest(APP_CMD(lesson), a), *as_view = app_opts_closest(APP_CMD(view), a);
        if (own && as_view) /* the closer of the two */
            own = sph_edit_distance(a, own) <= sph_edit_distance(a, as_view) ? own : NULL;
        fprintf(stderr, "sphlab lesson: unknown option '%s'", a);
        if (own || as_view) fprintf(stderr, " (did you mean %s?)", own ? own : as_view);
        fprintf(stderr, "\n  (the lesson's options: sphlab lesson --help; the window's: sphlab view --help)\n");
        return 2;
    }
    return open_window(L, opt.n_rest, opt.rest, dry);
}
