/* The I/O layer (src/io/io.h): the atomic writer's refusals, unique
 * temporaries, abort and failed writes that leave the target as it was,
 * mkdir -p, the signal handler, PNG on a full disk, and the JSON layout. */
#define _DEFAULT_SOURCE /* mkdtemp, hard links */
#include <criterion/criterion.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io.h"
#include "io_json.h"
#include "test_util.h"

static char g_dir[64];

static void make_dir(void)
{
    snprintf(g_dir, sizeof g_dir, "/tmp/sphlab-io-XXXXXX");
    cr_assert(mkdtemp(g_dir), "mkdtemp: %s", strerror(errno));
}

static const char *in_dir(const char *name)
{
    static char p[4][256];
    static int k;
    k = (k + 1) % 4;
    snprintf(p[k], sizeof p[k], "%s/%s", g_dir, name);
    return p[k];
}

static void put_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    cr_assert(f, "%s: %s", path, strerror(errno));
    fputs(text, f);
    fclose(f);
}

/* The whole file (static buffer), or "(missing)". */
static const char *slurp(const char *path)
{
    static char buf[65536];
    FILE *f = fopen(path, "r");
    if (!f) return "(missing)";
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return buf;
}

/* Entries of g_dir that are temporaries (.NAME.XXXXXX.tmp), and all entries. */
static int count_entries(bool tmp_only)
{
    DIR *d = opendir(g_dir);
    cr_assert(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        size_t len = strlen(e->d_name);
        bool tmp = e->d_name[0] == '.' && len > 4 && strcmp(e->d_name + len - 4, ".tmp") == 0;
        n += !tmp_only || tmp;
    }
    closedir(d);
    return n;
}

static void remove_tree(const char *dir)
{
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_assert_eq(system(cmd), 0);
}

/* ---- refusals --------------------------------------------------------------------- */

Test(io, refuses_a_directory)
{
    make_dir();
    sph_out o;
    char err[512];
    cr_assert(!sph_out_open(&o, g_dir, err, sizeof err));
    cr_assert(strstr(err, g_dir) && strstr(err, "is a directory"), "%s", err);
    cr_assert_eq(count_entries(false), 0, "a refusal left a file");
    remove_tree(g_dir);
}

Test(io, refuses_a_fifo_and_a_device_leaving_them_as_they_were)
{
    make_dir();
    const char *fifo = in_dir("fifo");
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    sph_out o;
    char err[512];
    cr_assert(!sph_out_open(&o, fifo, err, sizeof err));
    cr_assert(strstr(err, fifo) && strstr(err, "not a regular file (a FIFO)"), "%s", err);
    struct stat st;
    cr_assert(stat(fifo, &st) == 0 && S_ISFIFO(st.st_mode), "the FIFO was replaced");
    /* /dev/null: only looked at (the refusal comes before anything is made) */
    cr_assert(!sph_out_open(&o, "/dev/null", err, sizeof err));
    cr_assert(strstr(err, "/dev/null") && strstr(err, "a character device"), "%s", err);
    cr_assert(stat("/dev/null", &st) == 0 && S_ISCHR(st.st_mode));
    cr_assert_eq(count_entries(true), 0, "a refusal left a temporary");
    remove_tree(g_dir);
}

/* Something not a regular file appears at the target while it is written: commit refuses too. */
Test(io, commit_checks_the_target_again)
{
    make_dir();
    const char *path = in_dir("out.csv");
    sph_out o;
    char err[512];
    cr_assert(sph_out_open(&o, path, err, sizeof err), "%s", err);
    fputs("a,b\n", o.f);
    cr_assert_eq(mkfifo(path, 0600), 0);
    cr_assert(!sph_out_commit(&o, err, sizeof err));
    cr_assert(strstr(err, "not a regular file"), "%s", err);
    struct stat st;
    cr_assert(stat(path, &st) == 0 && S_ISFIFO(st.st_mode), "the FIFO was replaced");
    cr_assert_eq(count_entries(true), 0, "the temporary was left");
    remove_tree(g_dir);
}

Test(io, refuses_an_input_by_device_and_inode)
{
    make_dir();
    const char *scene = in_dir("scene.ini"), *link_path = in_dir("other-name.ini");
    put_file(scene, "[domain]\n");
    cr_assert_eq(link(scene, link_path), 0);
    cr_assert(sph_io_add_input(scene));
    cr_assert(!sph_io_add_input(in_dir("missing.ini")), "a missing input cannot be registered");
    sph_out o;
    char err[512];
    /* another spelling, a hard link, and a relative path from the scene's folder */
    cr_assert(!sph_out_open(&o, in_dir("./scene.ini"), err, sizeof err));
    cr_assert(strstr(err, "is an input of this command") && strstr(err, scene), "%s", err);
    cr_assert(!sph_out_open(&o, link_path, err, sizeof err));
    cr_assert_eq(chdir(g_dir), 0);
    cr_assert(!sph_out_open(&o, "scene.ini", err, sizeof err));
    cr_assert_str_eq(slurp(scene), "[domain]\n");
    /* a file of another inode is written */
    cr_assert(sph_out_open(&o, "stats.csv", err, sizeof err), "%s", err);
    cr_assert(sph_out_commit(&o, err, sizeof err), "%s", err);
    cr_assert_eq(count_entries(true), 0);
    remove_tree(g_dir);
}

/* ---- temporaries ------------------------------------------------------------------ */

Test(io, two_writers_of_one_path_have_their_own_temporaries)
{
    make_dir();
    const char *path = in_dir("same.csv");
    sph_out a, b;
    char err[512];
    cr_assert(sph_out_open(&a, path, err, sizeof err), "%s", err);
    cr_assert(sph_out_open(&b, path, err, sizeof err), "%s", err);
    cr_assert_str_neq(a.tmp, b.tmp, "both write %s", a.tmp);
    cr_assert_eq(count_entries(true), 2);
    for (int i = 0; i < 2000; i++) {
        fprintf(a.f, "a,%d\n", i);
        fprintf(b.f, "b,%d\n", i);
    }
    cr_assert(sph_out_commit(&a, err, sizeof err), "%s", err);
    cr_assert(sph_out_commit(&b, err, sizeof err), "%s", err);
    /* the last commit wins, whole: no line of the other writer in it */
    const char *got = slurp(path);
    cr_assert(strncmp(got, "b,0\nb,1\n", 8) == 0 && !strstr(got, "a,"), "mixed: %.40s", got);
    cr_assert_eq(count_entries(false), 1);
    remove_tree(g_dir);
}

Test(io, abort_leaves_nothing_and_the_target_untouched)
{
    make_dir();
    const char *fresh = in_dir("fresh.csv"), *old = in_dir("old.csv");
    put_file(old, "old\n");
    sph_out o1, o2;
    char err[512];
    cr_assert(sph_out_open(&o1, fresh, err, sizeof err), "%s", err);
    cr_assert(sph_out_open(&o2, old, err, sizeof err), "%s", err);
    fputs("new\n", o1.f);
    fputs("new\n", o2.f);
    sph_out_abort(&o1);
    sph_out_abort(&o2);
    sph_out_abort(&o2); /* twice is harmless */
    cr_assert_eq(count_entries(false), 1, "an abort left a file");
    cr_assert_str_eq(slurp(old), "old\n");
    cr_assert(sph_out_commit(&o1, err, sizeof err), "committing an aborted output does nothing");
    cr_assert_eq(count_entries(false), 1);
    /* a zeroed sph_out (never opened) commits and aborts as nothing */
    sph_out zero = {0};
    cr_assert(sph_out_commit(&zero, err, sizeof err));
    sph_out_abort(&zero);
    remove_tree(g_dir);
}

Test(io, output_gets_the_mode_fopen_would_give)
{
    make_dir();
    mode_t old = umask(027);
    sph_out o;
    char err[512];
    cr_assert(sph_out_open(&o, in_dir("m.csv"), err, sizeof err), "%s", err);
    cr_assert(sph_out_commit(&o, err, sizeof err), "%s", err);
    umask(old);
    struct stat st;
    cr_assert_eq(stat(in_dir("m.csv"), &st), 0);
    cr_assert_eq(st.st_mode & 0777, 0640, "mode %o", st.st_mode & 0777);
    remove_tree(g_dir);
}

Test(io, stream_api_commits_or_discards)
{
    make_dir();
    char err[512];
    FILE *keep = sph_out_fopen(in_dir("keep.csv"), err, sizeof err), *drop = sph_out_fopen(in_dir("drop.csv"), err, sizeof err);
    cr_assert(keep && drop, "%s", err);
    fputs("x\n", keep);
    fputs("y\n", drop);
    cr_assert(sph_out_fclose(keep, true, err, sizeof err), "%s", err);
    cr_assert(sph_out_fclose(drop, false, err, sizeof err));
    cr_assert_str_eq(slurp(in_dir("keep.csv")), "x\n");
    cr_assert_eq(count_entries(false), 1);
    cr_assert(!sph_out_fopen(g_dir, err, sizeof err), "a directory was opened");
    remove_tree(g_dir);
}

/* ---- a failing write (a full disk) ------------------------------------------------------ */

/* In a child: files may grow to `limit` bytes; past it write() fails with
 * EFBIG (SIGXFSZ ignored), as on a full disk. Returns the child's exit status. */
static int in_child_with_size_limit(rlim_t limit, int (*body)(void))
{
    fflush(NULL);
    pid_t pid = fork();
    cr_assert(pid >= 0);
    if (pid == 0) {
        signal(SIGXFSZ, SIG_IGN);
        struct rlimit rl = {limit, limit};
        if (setrlimit(RLIMIT_FSIZE, &rl) != 0) _exit(90);
        _exit(body());
    }
    int st;
    cr_assert_eq(waitpid(pid, &st, 0), pid);
    cr_assert(WIFEXITED(st), "the child died (signal %d)", WIFSIGNALED(st) ? WTERMSIG(st) : 0);
    return WEXITSTATUS(st);
}

static int write_too_much(void)
{
    sph_out o;
    char err[512];
    if (!sph_out_open(&o, in_dir("big.csv"), err, sizeof err)) return 10;
    for (int i = 0; i < 10000; i++) fprintf(o.f, "%d,%d\n", i, i * i);
    if (sph_out_commit(&o, err, sizeof err)) return 11; /* the failure went unseen */
    if (!strstr(err, "big.csv") || !strstr(err, "write failed") || !strstr(err, strerror(EFBIG))) return 12;
    return 0;
}

Test(io, failed_write_fails_commit_and_leaves_the_target)
{
    make_dir();
    put_file(in_dir("big.csv"), "old\n");
    int rc = in_child_with_size_limit(100, write_too_much);
    cr_assert_eq(rc, 0, "child status %d (11: commit succeeded; 12: the message lacks the path or reason)", rc);
    cr_assert_str_eq(slurp(in_dir("big.csv")), "old\n", "the target changed");
    cr_assert_eq(count_entries(false), 1, "the temporary was left");
    remove_tree(g_dir);
}

static int png_too_big(void)
{
    enum { W = 64, H = 64 };
    static uint8_t rgb[W * H * 3];
    for (size_t i = 0; i < sizeof rgb; i++) rgb[i] = (uint8_t)(i * 7919u >> 3); /* barely compressible */
    char err[512];
    if (sph_io_write_png(in_dir("frame.png"), rgb, W, H, err, sizeof err)) return 11;
    return strstr(err, "frame.png") ? 0 : 12;
}

Test(io, png_on_a_full_disk_is_an_error)
{
    make_dir();
    int rc = in_child_with_size_limit(512, png_too_big);
    cr_assert_eq(rc, 0, "child status %d (11: the PNG was reported written)", rc);
    cr_assert_eq(count_entries(false), 0, "a PNG or its temporary was left");
    /* without the limit the same image is written, and is a PNG */
    static uint8_t rgb[16 * 8 * 3];
    char err[512];
    cr_assert(sph_io_write_png(in_dir("ok.png"), rgb, 16, 8, err, sizeof err), "%s", err);
    cr_assert(memcmp(slurp(in_dir("ok.png")), "\x89PNG", 4) == 0);
    remove_tree(g_dir);
}

/* ---- signals ---------------------------------------------------------------------------- */

static int g_err_fd = -1;

Test(io, a_signal_removes_the_temporaries_and_says_so)
{
    make_dir();
    const char *log = in_dir("stderr.txt");
    fflush(NULL);
    pid_t pid = fork();
    cr_assert(pid >= 0);
    if (pid == 0) {
        g_err_fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0600);
        if (g_err_fd < 0 || dup2(g_err_fd, STDERR_FILENO) < 0) _exit(90);
        signal(SIGINT, SIG_DFL); /* whatever the test runner set */
        sph_out a, b;
        if (!sph_out_open(&a, in_dir("a.csv"), NULL, 0) || !sph_out_open(&b, in_dir("b.csv"), NULL, 0)) _exit(91);
        fputs("partial\n", a.f);
        fflush(a.f);
        raise(SIGINT);
        _exit(92); /* not reached: the handler ends the process by the signal */
    }
    int st;
    cr_assert_eq(waitpid(pid, &st, 0), pid);
    cr_assert(WIFSIGNALED(st) && WTERMSIG(st) == SIGINT, "want death by SIGINT; status %d", st);
    cr_assert_eq(count_entries(true), 0, "a temporary was left");
    cr_assert(access(in_dir("a.csv"), F_OK) != 0, "the output appeared");
    cr_assert(strstr(slurp(log), "interrupted; partial outputs removed"), "stderr: %s", slurp(log));
    remove_tree(g_dir);
}

/* Interrupted before it wrote anything, a command leaves no empty folder it made either. */
Test(io, a_signal_takes_back_the_empty_folders_made)
{
    make_dir();
    fflush(NULL);
    pid_t pid = fork();
    cr_assert(pid >= 0);
    if (pid == 0) {
        int fd = open("/dev/null", O_WRONLY);
        if (fd < 0 || dup2(fd, STDERR_FILENO) < 0) _exit(90);
        signal(SIGINT, SIG_DFL);
        sph_out a;
        if (!sph_mkdir_p(in_dir("made/frames"), NULL, 0) || !sph_out_open(&a, in_dir("made/frames/a.csv"), NULL, 0))
            _exit(91);
        raise(SIGINT);
        _exit(92);
    }
    int st;
    cr_assert_eq(waitpid(pid, &st, 0), pid);
    cr_assert(WIFSIGNALED(st) && WTERMSIG(st) == SIGINT, "want death by SIGINT; status %d", st);
    cr_expect(access(in_dir("made"), F_OK) != 0, "the empty folder made was left");
    remove_tree(g_dir);
}

/* ---- folders ---------------------------------------------------------------------------- */

Test(io, mkdir_p_makes_nested_folders)
{
    make_dir();
    char err[512];
    cr_assert(sph_mkdir_p(in_dir("a/b/c/d"), err, sizeof err), "%s", err);
    cr_assert(sph_mkdir_p(in_dir("a/b/c/d"), err, sizeof err), "an existing folder: %s", err);
    cr_assert(sph_mkdir_p(in_dir("a/x//y/"), err, sizeof err), "a trailing and a double slash: %s", err);
    struct stat st;
    cr_assert(stat(in_dir("a/b/c/d"), &st) == 0 && S_ISDIR(st.st_mode));
    cr_assert(stat(in_dir("a/x/y"), &st) == 0 && S_ISDIR(st.st_mode));
    put_file(in_dir("file"), "x");
    cr_assert(!sph_mkdir_p(in_dir("file/sub"), err, sizeof err));
    cr_assert(strstr(err, "file"), "%s", err);
    cr_assert(!sph_mkdir_p(in_dir("file"), err, sizeof err));
    cr_assert(strstr(err, "not a directory"), "%s", err);
    cr_assert(!sph_mkdir_p("", err, sizeof err));
    cr_assert(sph_output_dir(in_dir("out/frames"), err, sizeof err), "%s", err);
    cr_assert(!sph_output_dir("/proc/self", err, sizeof err), "/proc/self taken as writable");
    remove_tree(g_dir);
}

Test(io, failed_command_takes_back_only_the_empty_folders_it_made)
{
    make_dir();
    char err[512];
    sph_dirs_made_remove_empty(); /* what earlier tests made is gone or not empty */
    cr_assert(mkdir(in_dir("kept"), 0777) == 0, "%s", strerror(errno)); /* a folder the user had */
    cr_assert(sph_mkdir_p(in_dir("a/b/c"), err, sizeof err), "%s", err);
    cr_assert(sph_mkdir_p(in_dir("a/x"), err, sizeof err), "%s", err);
    cr_assert(sph_mkdir_p(in_dir("kept/y"), err, sizeof err), "%s", err);
    put_file(in_dir("a/x/file"), "x");
    sph_dirs_made_remove_empty();
    struct stat st;
    cr_expect(stat(in_dir("a/b"), &st) != 0, "a/b: empty, made here, still there");
    cr_expect(stat(in_dir("kept/y"), &st) != 0, "kept/y: empty, made here, still there");
    cr_expect(stat(in_dir("a/x/file"), &st) == 0, "a/x/file: something written was removed");
    cr_expect(stat(in_dir("kept"), &st) == 0, "kept: made before, removed");
    cr_expect(stat(g_dir, &st) == 0, "the folder that was there is gone");
    remove_tree(g_dir);
}

/* ---- JSON ------------------------------------------------------------------------------- */

Test(io, json_layout_and_escapes)
{
    make_dir();
    cJSON *root = cJSON_CreateObject();
    cJSON_AddNumberToObject(root, "n", 3);
    cr_assert(sph_json_add_num(root, "ghz", 3.14159265, 4));
    cJSON_AddStringToObject(root, "s", "a \"quote\"\nand a \\");
    cJSON_AddNumberToObject(root, "nan", NAN);
    cJSON_AddTrueToObject(root, "ok");
    cJSON *arr = cJSON_AddArrayToObject(root, "load");
    cJSON_AddItemToArray(arr, cJSON_CreateNumber(0.5));
    cJSON_AddItemToArray(arr, cJSON_CreateNumber(2));
    cJSON *rows = cJSON_AddArrayToObject(root, "rows");
    cJSON *row = cJSON_CreateObject();
    cJSON_AddStringToObject(row, "name", "L0");
    cJSON_AddItemToArray(rows, row);
    cJSON_AddObjectToObject(root, "empty");
    char err[512];
    cr_assert(sph_json_save(in_dir("x.json"), root, err, sizeof err), "%s", err);
    cJSON_Delete(root);
    cr_assert_str_eq(slurp(in_dir("x.json")), "{\n"
                                              "  \"n\": 3,\n"
                                              "  \"ghz\": 3.142,\n"
                                              "  \"s\": \"a \\\"quote\\\"\\nand a \\\\\",\n"
                                              "  \"nan\": null,\n"
                                              "  \"ok\": true,\n"
                                              "  \"load\": [0.5, 2],\n"
                                              "  \"rows\": [\n"
                                              "    {\n"
                                              "      \"name\": \"L0\"\n"
                                              "    }\n"
                                              "  ],\n"
                                              "  \"empty\": {}\n"
                                              "}\n");
    cr_assert_eq(count_entries(false), 1);
    remove_tree(g_dir);
}

/* `run` lists the files it wrote, as the other commands do, and -q leaves the list out (as its help says); it listed
 * none before 2026-11-27 (a user's report). */
Test(io, run_lists_what_it_wrote)
{
    const char *dir = test_temp_dir("runlist");
    char args[1024], out[8192];
    snprintf(args, sizeof args,
             "run lessons/11-incompressible/lesson.ini --steps 2 --stats %s/s.csv --dump %s/d.csv --vtk %s/vtk", dir,
             dir, dir);
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    char want[600];
    snprintf(want, sizeof want, "wrote %s/s.csv\nwrote %s/d.csv\nwrote %s/vtk/", dir, dir, dir);
    cr_assert(strstr(out, want), "want the list\n%s\nin\n%s", want, out);
    snprintf(args + strlen(args), sizeof args - strlen(args), " -q");
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    cr_assert_null(strstr(out, "wrote"), "-q: %s", out);
    test_remove_dir(dir);
}
