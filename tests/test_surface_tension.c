/* Surface tension (surface_tension = akinci: src/passes/normals.c,
 * curvature.c and the cohesion pass) and XSPH (src/passes/xsph.c): the
 * normals inside and at a flat surface, the cohesion pair force's sign
 * against distance, XSPH's invariances and momentum, a drop's momentum, the
 * refusals, and the quick `validate drop` and `validate drop-3d`. */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_util.h"

/* A 20 x 20 block at rest, spacing 0.01 m, h = 3 spacings; no gravity. */
static const char *const BLOCK =
    "[scene]\ndimension=2\neffects=density\n[domain]\nmin=0 0\nmax=1 1\n"
    "[fluid b]\nmin=0.4 0.4\nmax=0.6 0.6\nspacing=0.01\n"
    "[physics]\nsurface_tension=akinci\n[kernels]\nh=0.03\ndensity=cubic\n[time]\ndt=0.0005\ncfl=0\n";

/* The particle nearest (x, y). */
static uint32_t nearest(const sph_sim *sim, double x, double y)
{
    uint32_t best = 0;
    double bd = 1e30;
    for (uint32_t i = 0; i < sim->n; i++) {
        double d = pow(sph_sim_abs(sim, 0, sim->P.pos[0][i]) - x, 2) + pow(sph_sim_abs(sim, 1, sim->P.pos[1][i]) - y, 2);
        if (d < bd) bd = d, best = i;
    }
    return best;
}

/* Akinci's eq. 3 scaled by h: ~0 in a full neighbourhood; at the middle of
 * a flat side it points into the fluid, across the side, of order 1. */
Test(surface_tension, normal_is_zero_inside_and_of_order_one_at_a_flat_surface)
{
    sph_sim *sim = test_sim(BLOCK, 1);
    sph_sim_step(sim);
    const sph_particles *P = &sim->P;
    cr_assert_not_null(P->normal[0], "surface_tension = akinci allocates the normals");
    uint32_t in = nearest(sim, 0.5, 0.5), top = nearest(sim, 0.5, 0.6);
    double n_in = hypot(P->normal[0][in], P->normal[1][in]);
    double nx = P->normal[0][top], ny = P->normal[1][top], n_top = hypot(nx, ny);
    cr_log_info("|n| inside %.3g, at the top side (%.4f, %.4f): %.4f", n_in, nx, ny, n_top);
    cr_assert_lt(n_in, 0.02, "inside: |n| = %g", n_in);
    cr_assert(ny < 0 && fabs(nx) < 0.02 * n_top, "top side: n = (%g, %g) should point down, into the fluid", nx, ny);
    cr_assert(n_top > 0.3 && n_top < 1.5, "top side: |n| = %g, of order 1 (h scales it)", n_top);
    sph_sim_destroy(sim);
}

/* Two particles alone: the cohesion term pulls them together at 0.75 h
 * (C > 0 for h/2 < r < h) and pushes them apart at 0.2 h (C < 0 where
 * 2 (1-q)^3 q^3 < 1/64, q = r/h below 0.27; between 0.27 h and h/2 it
 * still attracts, more weakly). */
static double pair_acc(double r_over_h)
{
    const double s = 0.01, h = 0.04, d = r_over_h * h;
    char ini[1024];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=density\n[domain]\nmin=0 0\nmax=1 1\n"
             "[fluid a]\nmin=0.4 0.4\nmax=%.6f %.6f\nspacing=%g\n[fluid b]\nmin=%.6f 0.4\nmax=%.6f %.6f\nspacing=%g\n"
             "[physics]\nsurface_tension=akinci\n[kernels]\nh=%g\n[time]\ndt=0.0005\ncfl=0\n",
             0.4 + s, 0.4 + s, s, 0.4 + d, 0.4 + d + s, 0.4 + s, s, h);
    sph_sim *sim = test_sim(ini, 1);
    cr_assert_eq(sim->n, 2u);
    sph_sim_step(sim);
    uint32_t left = sim->P.pos[0][0] < sim->P.pos[0][1] ? 0 : 1;
    double a = sim->P.acc_c[0][left], ay = sim->P.acc_c[1][left];
    cr_assert(fabs(ay) < 1e-6 * fabs(a) + 1e-12, "along the pair only: a_y %g", ay);
    sph_sim_destroy(sim);
    return a; /* > 0: towards the right-hand particle */
}

Test(surface_tension, cohesion_attracts_at_three_quarters_h_and_repels_at_a_fifth)
{
    double far = pair_acc(0.75), close = pair_acc(0.2);
    cr_log_info("cohesion on the left particle: %.4g m/s^2 at 0.75 h, %.4g at 0.2 h", far, close);
    cr_assert_gt(far, 0.0, "0.75 h: attractive (towards the other), got %g", far);
    cr_assert_lt(close, 0.0, "0.2 h: repulsive, got %g", close);
}

/* A periodic Taylor-Green field: velocities that vary in space. */
static const char *const TG =
    "[scene]\ndimension=2\neffects=pressure\n[domain]\nmin=0 0\nmax=1 1\nperiodic=x y\n"
    "[fluid v]\nmin=0 0\nmax=1 1\nspacing=0.04\nvelocity=1 0\nfield=taylor-green\n"
    "[physics]\nstiffness=100\nnegative_pressure=keep\nxsph=%g\n[kernels]\nh=0.12\n[time]\ndt=0.001\ncfl=0\n";

Test(surface_tension, xsph_zero_is_left_out_and_changes_nothing)
{
    char a[1024], b[1024];
    snprintf(a, sizeof a, TG, 0.0);
    snprintf(b, sizeof b, "%s", a);
    char *x = strstr(b, "xsph=0\n");
    cr_assert_not_null(x);
    memmove(x, x + 7, strlen(x + 7) + 1); /* the same scene without the key */
    sph_sim *s1 = test_sim(a, 1), *s2 = test_sim(b, 1);
    cr_assert(!s1->in_pipeline[SPH_PASS_XSPH], "xsph = 0 runs no pass");
    cr_assert_null(s1->P.acc_x[0]);
    for (int k = 0; k < 5; k++) sph_sim_step(s1), sph_sim_step(s2);
    for (uint32_t i = 0; i < s1->n; i++)
        for (int d = 0; d < 2; d++) cr_assert_eq(s1->P.vel[d][i], s2->P.vel[d][i], "particle %u axis %d", i, d);
    sph_sim_destroy(s1);
    sph_sim_destroy(s2);
}

/* m_i a_i + m_j a_j = 0 pair by pair (the symmetric rho_ij), so the sum is
 * 0; it is not 0 particle by particle, and a uniform flow gets none. */
Test(surface_tension, xsph_conserves_momentum_and_leaves_a_uniform_flow_alone)
{
    char ini[1024];
    snprintf(ini, sizeof ini, TG, 0.5);
    sph_sim *sim = test_sim(ini, 1);
    sph_sim_step(sim);
    const sph_particles *P = &sim->P;
    for (int d = 0; d < 2; d++) {
        double net = 0, scale = 0;
        for (uint32_t i = 0; i < sim->n; i++) net += P->mass[i] * P->acc_x[d][i], scale += P->mass[i] * fabs(P->acc_x[d][i]);
        cr_assert_gt(scale, 0.0, "XSPH does nothing on a vortex");
        cr_assert(fabs(net) < 1e-5 * scale, "axis %d: net %g of %g", d, net, scale);
    }
    sph_sim_destroy(sim);
    /* the same lattice moving as a whole */
    char uni[1024];
    snprintf(uni, sizeof uni, "%s", ini);
    char *f = strstr(uni, "field=taylor-green\n");
    cr_assert_not_null(f);
    memmove(f, f + 19, strlen(f + 19) + 1);
    sim = test_sim(uni, 1);
    sph_sim_step(sim);
    for (uint32_t i = 0; i < sim->n; i++)
        cr_assert(fabs(sim->P.acc_x[0][i]) < 1e-3 && fabs(sim->P.acc_x[1][i]) < 1e-3, "uniform flow: a_x %g %g",
                  sim->P.acc_x[0][i], sim->P.acc_x[1][i]);
    sph_sim_destroy(sim);
}

/* A square drop with surface_tension = akinci in zero gravity: its momentum
 * stays 0 (every force is pairwise equal and opposite) while it rounds. */
Test(surface_tension, drop_keeps_its_momentum, .timeout = 120)
{
    sph_sim *sim = test_sim("[scene]\ndimension=2\neffects=pressure viscosity\njitter=0.1\n"
                            "[domain]\nmin=0 0\nmax=1 1\n[fluid square]\nmin=0.4 0.4\nmax=0.6 0.6\nspacing=0.01\n"
                            "[physics]\nstiffness=100\nviscosity=0.001\nsurface_tension=akinci\nxsph=0.1\n"
                            "[kernels]\nh=0.03\n[time]\ncfl=0.4\ndt=0.001\n",
                            1);
    double scale = 0;
    while (sim->t < 0.2 && !sim->alarm.raised) {
        sph_sim_step(sim);
        double p[2] = {0, 0}, s = 0;
        for (uint32_t i = 0; i < sim->n; i++)
            for (int d = 0; d < 2; d++) p[d] += sim->P.mass[i] * sim->P.vel[d][i], s += sim->P.mass[i] * fabs(sim->P.vel[d][i]);
        scale = fmax(scale, s);
        cr_assert(fabs(p[0]) < 1e-4 * s + 1e-12 && fabs(p[1]) < 1e-4 * s + 1e-12,
                  "t = %g: momentum (%g, %g) of %g", sim->t, p[0], p[1], s);
    }
    cr_assert(!sim->alarm.raised, "%s", sim->alarm.what);
    cr_assert_gt(scale, 0.0, "nothing moved: no surface tension");
    sph_sim_destroy(sim);
}

Test(surface_tension, bad_combinations_are_refused_with_the_key)
{
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    cr_assert_eq(sph_scene_load_string("[scene]\neffects=pressure cohesion\n[fluid b]\nmin=0.4 0.4\nmax=0.5 0.5\n"
                                       "[physics]\nsurface_tension=akinci\n",
                                       "both.ini", &def, &err),
                 SPH_ERR_OK);
    cr_assert_neq(sph_scene_validate(&def, &err), SPH_ERR_OK);
    cr_assert(strstr(err.msg, "both.ini:7") && strstr(err.msg, "surface_tension = akinci") &&
                  strstr(err.msg, "cohesion"),
              "%s", err.msg);
    def = sph_default_scene_def();
    cr_assert_neq(sph_scene_load_string("[physics]\nxsph=2\n", "x.ini", &def, &err), SPH_ERR_OK);
    cr_assert(strstr(err.msg, "xsph"), "%s", err.msg);
    /* the GL backend runs both (tests/test_gl_backend.c compares them with the
     * CPU): a run there may fail only for want of an OpenGL 4.3 context,
     * never by refusing them */
    char out[8192];
    const char *scene = test_write_temp("[scene]\ndimension=2\neffects=pressure\n[domain]\nmin=0 0\nmax=1 1\n"
                                        "[fluid b]\nmin=0.4 0.4\nmax=0.5 0.5\nspacing=0.02\n[kernels]\nh=0.04\n"
                                        "[physics]\nsurface_tension=akinci\n",
                                        ".ini");
    for (int k = 0; k < 2; k++) {
        char args[512];
        snprintf(args, sizeof args, "run %s --backend gl --steps 1 -q%s", scene,
                 k ? " --set physics.surface_tension=none --set physics.xsph=0.1" : "");
        int rc = test_sphlab(args, out, sizeof out);
        cr_assert(rc == 0 || strstr(out, "no OpenGL 4.3 context"), "%s: %s", args, out);
        cr_assert(!strstr(out, "not implemented by the GL backend"), "%s: %s", args, out);
    }
}

Test(surface_tension, quick_validate_drop_writes_its_outputs_and_a_verdict, .timeout = 300)
{
    char dir[] = "/tmp/sphlab-drop-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    char args[600], out[16384];
    snprintf(args, sizeof args, "validate drop --quick --quiet --threads 2 --out %s", dir);
    int rc = test_sphlab(args, out, sizeof out);
    cr_assert(rc == 0 || rc == 1, "exit %d (want 0 pass or 1 fail): %s", rc, out);
    cr_assert(strstr(out, rc == 0 ? "validate drop: PASS: " : "validate drop: FAIL: ") && strstr(out, "Rayleigh"),
              "no verdict line: %s", out);
    /* sigma with its unit: per metre of depth in 2D, N (the verdict gave it none) */
    cr_assert(strstr(out, "sigma 1 N (stated)"), "no sigma with its unit in: %s", out);
    /* the period at R/10 (surface_tension = stress), "(+1.1%)": within the band measured there, -0.7 % (3
     * periods) to +4.7 % (a kick of a quarter; docs/accuracy.md, the drop; csf read +7.1 %, with shifting = lind
     * +10.4 %) */
    const char *pc = strstr(out, "Rayleigh 2.409 s (");
    cr_assert_not_null(pc, "no period error in: %s", out);
    double err = atof(pc + strlen("Rayleigh 2.409 s ("));
    cr_assert(fabs(err) < 6.0, "period error %+.1f %% at R/10 (within 6 %% wanted): %s", err, out);
    static const char *const ext[] = {"csv", "png", "pdf"};
    for (int k = 0; k < 3; k++) {
        char path[700];
        struct stat st;
        snprintf(path, sizeof path, "%s/drop.%s", dir, ext[k]);
        cr_assert(stat(path, &st) == 0 && st.st_size > 0, "%s missing", path);
    }
}

/* A resolution the method cannot hold gives a verdict, not "no verdict": validate drop run from a directory
 * whose scenes/validate/drop.ini states sigma = 300 N (its drop at R/10 goes past the watchdog's speed while
 * settling, at 0.83 s) FAILs naming the resolution, "unstable, stopped by the watchdog", and the time. Before,
 * the command ended with "the run or its outputs failed (above); no verdict" (exit 3). */
Test(surface_tension, validate_drop_says_which_resolution_is_unstable, .timeout = 300)
{
    char dir[] = "/tmp/sphlab-dropw-XXXXXX", path[700], cwd[512], cmd[2048], out[16384];
    cr_assert_not_null(mkdtemp(dir));
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    FILE *in = fopen("scenes/validate/drop.ini", "r");
    cr_assert_not_null(in, "scenes/validate/drop.ini");
    snprintf(path, sizeof path, "%s/scenes", dir);
    cr_assert_eq(mkdir(path, 0700), 0);
    snprintf(path, sizeof path, "%s/scenes/validate", dir);
    cr_assert_eq(mkdir(path, 0700), 0);
    snprintf(path, sizeof path, "%s/scenes/validate/drop.ini", dir);
    FILE *o = fopen(path, "w");
    cr_assert_not_null(o, "%s", path);
    char line[512];
    int set = 0;
    while (fgets(line, sizeof line, in)) {
        if (strcmp(line, "sigma = 1\n") == 0) snprintf(line, sizeof line, "sigma = 300\n"), set++;
        fputs(line, o);
    }
    fclose(in), fclose(o);
    cr_assert_eq(set, 1, "drop.ini's sigma line not found");
    const char *bin = getenv("SPHLAB") && *getenv("SPHLAB") ? getenv("SPHLAB") : "./sphlab";
    snprintf(cmd, sizeof cmd, "cd %s && %s%s%s validate drop --quick --quiet --threads 2 --out %s/out 2>&1", dir,
             bin[0] == '/' ? "" : cwd, bin[0] == '/' ? "" : "/", bin, dir);
    FILE *p = popen(cmd, "r");
    cr_assert_not_null(p);
    size_t n = fread(out, 1, sizeof out - 1, p);
    out[n] = '\0';
    int st = pclose(p), rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    cr_assert_eq(rc, 1, "exit %d (want 1, a FAIL verdict): %s", rc, out);
    cr_assert(strstr(out, "validate drop: FAIL: R/10: unstable, stopped by the watchdog"), "no such verdict: %s", out);
    cr_assert(!strstr(out, "no verdict"), "%s", out);
}

/* validate drop-3d --quick (R/6, the sphere laid on the lattice points nearest the centre): its outputs, a
 * verdict, and the Laplace pressure of the settled sphere, 2 sigma / R in 3D, within 10 % (measured 20.78 Pa
 * at R = 0.0930 m for 21.49, -3.3 %): the csf force and the sphere's layout in 3D. */
Test(surface_tension, quick_validate_drop_3d_holds_the_laplace_pressure, .timeout = 600)
{
    char dir[] = "/tmp/sphlab-drop3-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    char args[600], out[16384];
    snprintf(args, sizeof args, "validate drop-3d --quick --threads 2 --out %s", dir);
    int rc = test_sphlab(args, out, sizeof out);
    cr_assert(rc == 0 || rc == 1, "exit %d (want 0 pass or 1 fail): %s", rc, out);
    cr_assert(strstr(out, rc == 0 ? "validate drop-3d: PASS: " : "validate drop-3d: FAIL: ") &&
                  strstr(out, "Rayleigh"), "no verdict line: %s", out);
    const char *q = strstr(out, "R/6: sigma 1 N/m (inner pressure ");
    cr_assert_not_null(q, "no inner pressure in: %s", out);
    double p = 0, R = 0;
    cr_assert_eq(sscanf(q, "R/6: sigma 1 N/m (inner pressure %lf Pa at R = %lf m", &p, &R), 2, "%s", q);
    cr_assert(R > 0.08 && R < 0.11 && fabs(p / (2 / R) - 1) < 0.1, "inner pressure %g Pa at R = %g m, 2 sigma/R %g", p,
              R, 2 / R);
    char path[700];
    struct stat st;
    snprintf(path, sizeof path, "%s/drop-3d.csv", dir);
    cr_assert(stat(path, &st) == 0 && st.st_size > 0, "%s missing", path);
}
