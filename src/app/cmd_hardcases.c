/* sphlab hardcases: scenes that break naive SPH codes, each with a verdict.
 *
 * A case passes when the run is stable (no non-finite value, no runaway, no
 * particle outside the walls, total energy not growing beyond a tolerance) and
 * its own figures hold; or, for the cases that are meant to break, when the
 * watchdog stops the run with a report instead of letting NaNs through.
 * Energy is kinetic + gravitational + the internal energy the equation of
 * state stores in compression; a pressure force that is the gradient of that
 * internal energy conserves their sum, and viscosity and wall damping only
 * take energy out. Mueller's pair (poly6 density, spiky gradient) is not such
 * a gradient: without viscosity it gains energy (it doubled in 0.3 s of a 2D
 * dam break), which is why the zero-viscosity case uses one kernel for both.
 *
 * Density error is max (rho_max - rho0) / rho0 over the run. Its floor is
 * the summation's own error on a lattice: at h = 2 spacings poly6 reads 1.5%
 * high inside the fluid and 3% in the row next to a wall. The bounds include it.
 *
 * Other verdicts a case may ask for: a largest speed over the run, the particle
 * count its blocks make, a refusal by `sphlab check` naming a key, the farthest
 * a particle may move in one step (in h: an explicit step that carries it past
 * its neighbours' support skips their forces), and a warning the scene must
 * give before its first step. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "sph_walls.h"

typedef struct hardcase {
    const char *name;
    const char *about;
    const char *ini;
    int steps;             /* steps to run (--quick: a quarter, but at least 1500) */
    bool expect_stop;      /* meant to break: passes if the watchdog stops it with a report */
    double max_rho_err;    /* bound on max (rho_max - rho0) / rho0 over the run; < 0: not checked */
    double max_gain;       /* bound on (E_end - E_start) / energy scale */
    double max_vrms_end;   /* bound on the final rms speed sqrt(2 E_kin / M) [m/s]; < 0: not checked */
    const char *compare;   /* if set, an override ("search.method=brute"): positions must agree */
    double max_speed;      /* [m/s] bound on the largest speed over the run (its reason in `about`); 0: none */
    uint32_t expect_n;     /* particles the scene must make (the same blocks at the origin); 0: not checked */
    const char *refuse;    /* if set, validation (sphlab check) must refuse the scene, the message naming this */
    double max_move;       /* [h] bound on the farthest a particle moves in one step, in support radii; 0: none */
    const char *warn;      /* if set, a warning the scene must give before its first step, containing this */
} hardcase;

#define BOX2 "[domain]\nmin = 0 0\nmax = 1 1\nwall_damping = 0.5\n"
#define BOX3 "[scene]\ndimension = 3\n[domain]\nmin = 0 0 0\nmax = 1 1 1\nwall_damping = 0.5\n"
/* The lattice starts out of hydrostatic balance; nu = 0.01 lets the pool settle in a second. */
#define CALM "[physics]\nstiffness = 400\nviscosity = 0.01\nnegative_pressure = clamp\n[time]\ncfl = 0.4\ndt = 0.002\n"
#define WATER "[physics]\nstiffness = 400\nviscosity = 0.002\nnegative_pressure = clamp\n[time]\ncfl = 0.4\ndt = 0.002\n"

static const hardcase cases[] = {
    {"rest-2d", "a fluid at rest stays at rest (2D)",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid pool]\nmin = 0 0\nmax = 1 0.3\nspacing = 0.02\n[kernels]\nh = 0.04\n" CALM,
     3000, false, 0.08, 0.02, 0.05, NULL, 0, 0, NULL, 0, NULL},
    {"rest-3d", "a fluid at rest stays at rest (3D)",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX3
     "[fluid pool]\nmin = 0 0 0\nmax = 1 0.2 1\nspacing = 0.05\n[kernels]\nh = 0.1\n" CALM,
     1500, false, 0.08, 0.02, 0.05, NULL, 0, 0, NULL, 0, NULL},
    {"coincident-2d", "two blocks on the same lattice: every particle has a twin at distance 0",
     "[scene]\neffects = pressure viscosity walls\n" BOX2
     "[fluid a]\nmin = 0.3 0.3\nmax = 0.5 0.5\nspacing = 0.02\n[fluid b]\nmin = 0.3 0.3\nmax = 0.5 0.5\nspacing = "
     "0.02\n[kernels]\nh = 0.04\n" WATER,
     1000, false, 1.5, 0.02, -1, NULL, 0, 0, NULL, 0, NULL},
    {"coincident-3d", "two blocks on the same lattice (3D)",
     "[scene]\neffects = pressure viscosity walls\n" BOX3
     "[fluid a]\nmin = 0.4 0.4 0.4\nmax = 0.6 0.6 0.6\nspacing = 0.04\n[fluid b]\nmin = 0.4 0.4 0.4\nmax = 0.6 0.6 "
     "0.6\nspacing = 0.04\n[kernels]\nh = 0.08\n" WATER,
     600, false, 1.5, 0.02, -1, NULL, 0, 0, NULL, 0, NULL},
    {"single-particle", "one particle: no neighbours, falls and bounces",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid one]\nmin = 0.5 0.5\nmax = 0.52 0.52\nspacing = 0.02\n[kernels]\nh = 0.04\n" WATER,
     2000, false, -1, 0.02, -1, NULL, 0, 0, NULL, 0, NULL},
    {"isolated-particle", "a block and one particle far away from it",
     "[scene]\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0\nmax = 100 1\n"
     "[fluid block]\nmin = 0 0\nmax = 0.3 0.3\nspacing = 0.02\n[fluid far]\nmin = 99.9 0.9\nmax = 99.92 "
     "0.92\nspacing = 0.02\n[kernels]\nh = 0.04\n" WATER,
     1000, false, 0.2, 0.05, -1, NULL, 0, 0, NULL, 0, NULL},
    {"one-cell", "400 particles inside one cell of the search grid (O(N^2) pairs)",
     "[scene]\neffects = pressure viscosity walls\n" BOX2
     "[fluid clump]\nmin = 0.5 0.5\nmax = 0.54 0.54\nspacing = 0.002\n[kernels]\nh = 0.05\n" WATER,
     600, false, -1, 0.05, -1, NULL, 0, 0, NULL, 0, NULL},
    {"table-size-1", "a hash table of one key: every entry collides; must flow as with brute force",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n[search]\ntable_size = 1\n" WATER,
     300, false, 0.2, 0.05, -1, "search.method=brute", 0, 0, NULL, 0, NULL},
    {"negative-borders", "negative coordinates, particles exactly on cell borders; must flow as with brute force",
     "[scene]\neffects = gravity pressure viscosity walls\n[domain]\nmin = -3 -3\nmax = -1 -1\n"
     "[fluid a]\nmin = -2.0625 -3\nmax = -1.5 -2.5\nspacing = 0.125\n[kernels]\nh = 0.25\n" WATER,
     300, false, 0.3, 0.05, -1, "search.method=brute", 0, 0, NULL, 0, NULL},
    {"negative-borders-3d", "the same in 3D, against brute force",
     "[scene]\ndimension = 3\neffects = gravity pressure viscosity walls\n[domain]\nmin = -3 -3 -3\nmax = -1 -1 -1\n"
     "[fluid a]\nmin = -2.0625 -3 -2.0625\nmax = -1.5 -2.5 -1.5\nspacing = 0.125\n[kernels]\nh = 0.25\n" WATER,
     200, false, 0.3, 0.05, -1, "search.method=brute", 0, 0, NULL, 0, NULL},
    {"impact-2d", "a block hits a wall at 50 m/s",
     "[scene]\neffects = pressure viscosity walls\n" BOX2
     "[fluid bullet]\nmin = 0.5 0.4\nmax = 0.7 0.6\nspacing = 0.02\nvelocity = 50 0\n[kernels]\nh = 0.04\n" WATER,
     1500, false, -1, 0.02, -1, NULL, 0, 0, NULL, 0, NULL},
    {"impact-3d", "a block hits a wall at 50 m/s (3D)",
     "[scene]\neffects = pressure viscosity walls\n" BOX3
     "[fluid bullet]\nmin = 0.5 0.4 0.4\nmax = 0.7 0.6 0.6\nspacing = 0.04\nvelocity = 50 0 0\n[kernels]\nh = 0.08\n" WATER,
     800, false, -1, 0.02, -1, NULL, 0, 0, NULL, 0, NULL},
    {"dt-above-cfl-adaptive", "dt bound 0.05 s, far above the CFL limit, with the adaptive step on",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n"
     "[physics]\nstiffness = 400\nviscosity = 0.002\nnegative_pressure = clamp\n[time]\ncfl = 0.4\ndt = 0.05\n",
     1500, false, 0.2, 0.05, -1, NULL, 0, 0, NULL, 0, NULL},
    {"dt-above-cfl-fixed", "a fixed dt 100x the CFL limit: must stop with a report, not run on NaNs",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n"
     "[physics]\nstiffness = 400\n[time]\ncfl = 0\ndt = 0.02\n",
     500, true, -1, 0, -1, NULL, 0, 0, NULL, 0, NULL},
    {"very-stiff", "stiffness 1e6 m^2/s^2 (c = 1000 m/s), a column at rest: speed <= the watchdog's bound, 4 x "
                   "the fall across the 1 m box + 1 m/s = 18.7 m/s. With the lattice walls the first row no longer "
                   "reads 1.5-3% high, but particles still reach 17.8 m/s (with the integral walls: 24 m/s, stopped)",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.2 0.3\nspacing = 0.02\n[kernels]\nh = 0.04\n"
     "[physics]\nstiffness = 1e6\nviscosity = 0.002\nnegative_pressure = clamp\n[time]\ncfl = 0.4\n",
     2000, false, -1, 0.05, -1, NULL, 18.7, 0, NULL, 0, NULL},
    {"tait-stiff", "Tait equation, gamma 7",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n"
     "[physics]\neos = tait\nstiffness = 400\nviscosity = 0.002\nnegative_pressure = clamp\n[time]\ncfl = 0.4\n",
     1500, false, 0.2, 0.05, -1, NULL, 0, 0, NULL, 0, NULL},
    {"zero-viscosity",
     "no viscosity (nu = 0), one kernel for density and pressure: energy must not grow (bound +5 % of its scale; "
     "the walls and the pressure's clamp take some away)",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\ndensity = cubic\npressure = cubic\n"
     "[physics]\nstiffness = 400\nviscosity = 0\nnegative_pressure = clamp\n[time]\ncfl = 0.4\n",
     1500, false, 0.2, 0.05, -1, NULL, 0, 0, NULL, 0, NULL},
    {"high-viscosity", "nu = 1 m^2/s, a million times water's: the viscous CFL condition binds",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n"
     "[physics]\nstiffness = 400\nviscosity = 1\nnegative_pressure = clamp\n[time]\ncfl = 0.4\n",
     1000, false, 0.2, 0.02, -1, NULL, 0, 0, NULL, 0, NULL},
    {"smoothing-viscosity", "the seed's velocity-smoothing viscosity and shared-pressure form",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n"
     "[physics]\nstiffness = 400\nviscosity = 0.01\nviscosity_form = smoothing\npressure_form = shared\n"
     "negative_pressure = clamp\n[time]\ncfl = 0.4\n",
     1500, false, 0.2, 0.05, -1, NULL, 0, 0, NULL, 0, NULL},
    {"dam-break-long", "a 2D dam break over 20,000 steps: bounded energy, no particle lost; density error <= 1.5 "
                       "x the water-hammer estimate v/c = sqrt(2 g 0.8 m) / 20 m/s = 0.198 (the margin for the "
                       "corner, where the surge meets two walls; measured 0.200)",
     "[scene]\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0\nmax = 2 1\nwall_damping = 0.5\n"
     "[fluid column]\nmin = 0 0\nmax = 0.5 0.8\nspacing = 0.04\n[kernels]\nh = 0.08\n"
     "[physics]\nstiffness = 400\nviscosity = 0.005\nnegative_pressure = clamp\n[time]\ncfl = 0.4\n",
     20000, false, 0.3, 0.05, -1, NULL, 0, 0, NULL, 0, NULL},
    {"dam-break-3d", "a 3D dam break",
     "[scene]\ndimension = 3\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0 0\nmax = 1.2 1 0.4\n"
     "[fluid column]\nmin = 0 0 0\nmax = 0.4 0.6 0.4\nspacing = 0.05\n[kernels]\nh = 0.1\n" WATER,
     1500, false, 0.2, 0.05, -1, NULL, 0, 0, NULL, 0, NULL},
    {"coincident-pair-2d", "two particles alone at one point, at rest, keep: speed <= 0.1 c = 2 m/s (was 23 m/s)",
     "[scene]\neffects = pressure viscosity walls\n" BOX2
     "[fluid a]\nmin = 0.5 0.5\nmax = 0.52 0.52\nspacing = 0.02\n[fluid b]\nmin = 0.5 0.5\nmax = 0.52 0.52\n"
     "spacing = 0.02\n[kernels]\nh = 0.04\n[physics]\nstiffness = 400\nnegative_pressure = keep\n[time]\ncfl = 0.4\n",
     2000, false, -1, 0.02, -1, NULL, 2.0, 0, NULL, 0, NULL},
    {"coincident-pair-3d", "the same in 3D: speed <= 0.1 c = 2 m/s (was 50 m/s)",
     "[scene]\neffects = pressure viscosity walls\n" BOX3
     "[fluid a]\nmin = 0.5 0.5 0.5\nmax = 0.52 0.52 0.52\nspacing = 0.02\n[fluid b]\nmin = 0.5 0.5 0.5\n"
     "max = 0.52 0.52 0.52\nspacing = 0.02\n[kernels]\nh = 0.04\n[physics]\nstiffness = 400\n"
     "negative_pressure = keep\n[time]\ncfl = 0.4\n",
     2000, false, -1, 0.02, -1, NULL, 2.0, 0, NULL, 0, NULL},
    {"defaults", "one block, every default: speed <= 2 x a fall across the 1 m box (a wall's run-up jet), 8.9 m/s "
     "(was 220 m/s)",
     "[fluid a]\nmin = 0 0\nmax = 0.3 0.5\n", 2000, false, -1, 0.05, -1, NULL, 8.9, 0, NULL, 0, NULL},
    {"tiny-h", "h = 0.1 mm (the smallest accepted), a 2 x 1 mm pool, c = 2 m/s (10 x its fall speed): speed "
               "<= 1.5 x a fall across the 2 mm box, 0.30 m/s",
     "[scene]\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0\nmax = 0.002 0.002\n"
     "[fluid pool]\nmin = 0 0\nmax = 0.002 0.001\nspacing = 0.00005\n[kernels]\nh = 0.0001\n"
     "[physics]\nstiffness = 4\nviscosity = 0.000001\nnegative_pressure = clamp\n[time]\ncfl = 0.4\n",
     1500, false, 0.08, 0.05, -1, NULL, 0.30, 800, NULL, 0, NULL},
    {"defaults-3d", "one 3D block, every other default: speed <= 2 x a fall across the 1 m box, 8.9 m/s",
     "[scene]\ndimension = 3\n[fluid a]\nmin = 0 0 0\nmax = 0.3 0.5 0.3\n", 1500, false, -1, 0.05, -1, NULL,
     8.9, 5625, NULL, 0, NULL},
    /* Issue 17's defects, each case failing on the code before its fix (docs/robustness.md has the table). */
    {"first-step-1000", "a block launched at 1000 m/s: the first dt is the CFL one, a particle moves <= 1 h a step "
                        "(was 10 h)",
     "[scene]\neffects = pressure viscosity walls\n[domain]\nmin = 0 0\nmax = 4 1\nwall_damping = 0.5\n"
     "[fluid bullet]\nmin = 0.2 0.4\nmax = 0.4 0.6\nspacing = 0.02\nvelocity = 1000 0\n[kernels]\nh = 0.04\n" WATER,
     100, false, -1, 0.02, -1, NULL, 0, 100, NULL, 1.0, NULL},
    {"first-step-1000-3d", "the same in 3D: a particle moves <= 1 h a step (was 10 h)",
     "[scene]\ndimension = 3\neffects = pressure viscosity walls\n[domain]\nmin = 0 0 0\nmax = 4 1 1\n"
     "wall_damping = 0.5\n[fluid bullet]\nmin = 0.2 0.4 0.4\nmax = 0.4 0.6 0.6\nspacing = 0.04\nvelocity = 1000 0 0\n"
     "[kernels]\nh = 0.08\n" WATER,
     100, false, -1, 0.02, -1, NULL, 0, 125, NULL, 1.0, NULL},
    {"impact-1000", "a block into a wall at 1000 m/s: no energy gained, none through the wall, <= 1 h a step "
                    "(was 10 h)",
     "[scene]\neffects = pressure viscosity walls\n" BOX2
     "[fluid bullet]\nmin = 0.5 0.4\nmax = 0.7 0.6\nspacing = 0.02\nvelocity = 1000 0\n[kernels]\nh = 0.04\n" WATER,
     1500, false, -1, 0.02, -1, NULL, 0, 100, NULL, 1.0, NULL},
    {"impact-1000-3d", "the same in 3D: <= 1 h a step (was 6 h)",
     "[scene]\neffects = pressure viscosity walls\n" BOX3
     "[fluid bullet]\nmin = 0.5 0.4 0.4\nmax = 0.7 0.6 0.6\nspacing = 0.04\nvelocity = 1000 0 0\n[kernels]\nh = 0.08\n"
     WATER,
     800, false, -1, 0.02, -1, NULL, 0, 125, NULL, 1.0, NULL},
    {"rest-stiff-1e6", "a pool at rest, k = 1e6 m^2/s^2 (c = 1000 m/s): the lattice's 3% excess density at the "
                       "walls, p = 0.03 k rho0, throws particles past 4 x the fall speed (4.4 m/s); must stop with "
                       "a report (ran on at 29 m/s)",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid pool]\nmin = 0 0\nmax = 1 0.3\nspacing = 0.02\n[kernels]\nh = 0.04\n"
     "[physics]\nstiffness = 1e6\nviscosity = 0.01\nnegative_pressure = clamp\n[time]\ncfl = 0.4\n",
     1500, true, -1, 0, -1, NULL, 0, 0, NULL, 0, NULL},
    {"rest-stiff-1e9", "the pool at k = 1e9 m^2/s^2 (c = 31.6 km/s): must stop with a report (ran on at 1287 m/s)",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid pool]\nmin = 0 0\nmax = 1 0.3\nspacing = 0.02\n[kernels]\nh = 0.04\n"
     "[physics]\nstiffness = 1e9\nviscosity = 0.01\nnegative_pressure = clamp\n[time]\ncfl = 0.4\n",
     1500, true, -1, 0, -1, NULL, 0, 0, NULL, 0, NULL},
    {"rest-stiff-1e6-3d", "a 3D pool at rest, k = 1e6 m^2/s^2: speed <= the watchdog's bound, 18.7 m/s (measured "
                          "11.4 m/s with the lattice walls; on the first version it ran on at 43 m/s)",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX3
     "[fluid pool]\nmin = 0 0 0\nmax = 1 0.2 1\nspacing = 0.05\n[kernels]\nh = 0.1\n"
     "[physics]\nstiffness = 1e6\nviscosity = 0.01\nnegative_pressure = clamp\n[time]\ncfl = 0.4\n",
     1500, false, -1, 0.05, -1, NULL, 18.7, 0, NULL, 0, NULL},
    {"rest-density-tiny", "rest_density = 1e-30 kg/m^2 (a float loses rho^2 below 1e-19): refused naming "
                          "rest_density (was accepted)",
     "[physics]\nrest_density = 1e-30\n[fluid a]\nmin = 0 0\nmax = 0.3 0.5\n",
     10, false, -1, 0.05, -1, NULL, 0, 0, "rest_density", 0, NULL},
    {"h-tiny", "h = 1e-30 m (poly6's 1/h^9 overflows a float): refused naming [kernels] h (was accepted)",
     "[kernels]\nh = 1e-30\n[fluid a]\nmin = 0 0\nmax = 0.3 0.5\n",
     10, false, -1, 0.05, -1, NULL, 0, 0, "[kernels] h", 0, NULL},
    {"long-names", "blocks named with 44 to 47 characters, alike in the first 43 (inih keeps 43): refused naming "
                   "the whole first name, not merged",
     "[fluid abcdefghijabcdefghijabcdefghijabcdefghij1234]\nmin = 0 0\nmax = 0.2 0.2\n"
     "[fluid abcdefghijabcdefghijabcdefghijabcdefghij12345]\nvelocity = 1 0\n"
     "[fluid abcdefghijabcdefghijabcdefghijabcdefghij123456]\nmin = 0.5 0\n"
     "max = 0.7 0.2\n[fluid abcdefghijabcdefghijabcdefghijabcdefghij1234567]\nspacing = 0.01\n",
     10, false, -1, 0.05, -1, NULL, 0, 0, "abcdefghijabcdefghijabcdefghijabcdefghij1234", 0, NULL},
    {"dotted-twin", "[fluid a] then [fluid.a] with other keys: refused as one block opened twice, naming [fluid a] "
                    "(was merged)",
     "[fluid a]\nmin = 0 0\nmax = 0.2 0.2\n[fluid.a]\nvelocity = 1 0\n",
     10, false, -1, 0.05, -1, NULL, 0, 0, "[fluid a]", 0, NULL},
    {"bom", "a scene file opening with a UTF-8 byte order mark: read as without it, 10 x 10 = 100 particles (was a "
            "syntax error)",
     "\xef\xbb\xbf[scene]\nname = bom\n[fluid a]\nmin = 0 0\nmax = 0.2 0.2\n",
     10, false, -1, 0.05, -1, NULL, 0, 100, NULL, 0, NULL},
    {"run-1e33-steps", "duration 1000 s at a fixed dt of 1e-30 s: said before the first step, 1e+33 steps (was not)",
     "[scene]\nduration = 1000\n[fluid a]\nmin = 0 0\nmax = 0.3 0.5\n[time]\ncfl = 0\ndt = 1e-30\n",
     10, false, -1, 0.05, -1, NULL, 0, 375, NULL, 0, "1e+33 steps"},
    {"fixed-dt-1000-warn", "a block at 1000 m/s, fixed dt 0.5 ms: warned before step 1 with the limit the launch "
                           "speed sets, 0.4 (h/2) / (c + 1000 m/s) = 7.84e-6 s (was 4e-4 s)",
     "[scene]\neffects = pressure viscosity\n[domain]\nmin = 0 0\nmax = 4 1\n"
     "[fluid bullet]\nmin = 0.2 0.4\nmax = 0.4 0.6\nspacing = 0.02\nvelocity = 1000 0\n[kernels]\nh = 0.04\n"
     "[physics]\nstiffness = 400\n[time]\ncfl = 0\ndt = 0.0005\n",
     1, false, -1, 0.02, -1, NULL, 0, 100, NULL, 0, "largest stable dt is about 7.84e-06"},
    {"fast-1e6-dt-min", "a block at 1e6 m/s: its CFL step, 8e-9 s, is below dt_min = 1e-7 s, so it moves 2.5 h a "
                        "step: said before step 1 (was not)",
     "[scene]\neffects = pressure viscosity\n[domain]\nmin = 0 0\nmax = 4 1\n"
     "[fluid bullet]\nmin = 0.2 0.4\nmax = 0.4 0.6\nspacing = 0.02\nvelocity = 1000000 0\n[kernels]\nh = 0.04\n" WATER,
     100, false, -1, 0.02, -1, NULL, 0, 100, NULL, 0, "held at dt_min"},
    {"dt-min-above-cfl", "dt_min = 10 ms, 25 x the CFL step of a column at rest: said before step 1, then stopped "
                         "with a report (ran 500 steps, energy +88%)",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n[physics]\nstiffness = 400\n"
     "viscosity = 0.002\nnegative_pressure = clamp\n[time]\ncfl = 0.4\ndt = 0.02\ndt_min = 0.01\n",
     500, true, -1, 0, -1, NULL, 0, 0, NULL, 0, "held at dt_min"},
    {"tiny-dt-fixed", "a column at rest, 1500 fixed steps of 0.1 us (0.15 ms): speed <= 2 (g + 0.03 k / h) t = "
                      "0.093 m/s, a fall plus the push of the lattice's 3% excess density at a wall (was 1.9 m/s)",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n"
     "[physics]\nstiffness = 400\n[time]\ncfl = 0\ndt = 1e-7\n",
     1500, false, -1, 0.02, -1, NULL, 0.093, 375, NULL, 0, NULL},
    {"rest-particles", "rest-2d with wall_model = particles (the wall particles are not fluid): rms speed at the end "
                       "<= 0.05 m/s, 3% of sqrt(g H)",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2 "wall_model = particles\n"
     "[fluid pool]\nmin = 0 0\nmax = 1 0.3\nspacing = 0.02\n[kernels]\nh = 0.04\n" CALM,
     3000, false, 0.08, 0.02, 0.05, NULL, 0, 750, NULL, 0, NULL},
    /* Guards: these pass on the code before issue 17 too. */
    {"rest-reflect", "rest-2d with wall_model = reflect: rms speed at the end <= 0.05 m/s, 3% of sqrt(g H)",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2 "wall_model = reflect\n"
     "[fluid pool]\nmin = 0 0\nmax = 1 0.3\nspacing = 0.02\n[kernels]\nh = 0.04\n" CALM,
     3000, false, 0.08, 0.02, 0.05, NULL, 0, 750, NULL, 0, NULL},
    {"periodic-x-brute", "periodic along x with L/h = 22.2 (cells not whole), blocks across the seam: the hash "
                         "must flow as brute force does",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2 "periodic = x\n"
     "[fluid column]\nmin = 0.8 0\nmax = 1 0.5\nspacing = 0.025\n[fluid b]\nmin = 0 0\nmax = 0.1 0.3\n"
     "spacing = 0.025\n[kernels]\nh = 0.045\n" WATER,
     300, false, 0.2, 0.05, -1, "search.method=brute", 0, 208, NULL, 0, NULL},
    {"one-particle-3d", "one particle in 3D: falls and bounces, speed <= a fall across the 1 m box, 4.43 m/s",
     BOX3 "[fluid one]\nmin = 0.5 0.5 0.5\nmax = 0.52 0.52 0.52\nspacing = 0.02\n[kernels]\nh = 0.04\n" WATER,
     2000, false, -1, 0.02, -1, NULL, 4.43, 1, NULL, 0, NULL},
    {"dt-1-adaptive", "dt bound 1 s with the adaptive step, a column at rest: <= 1 h a step from the first",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n"
     "[physics]\nstiffness = 400\nviscosity = 0.002\nnegative_pressure = clamp\n[time]\ncfl = 0.4\ndt = 1\n",
     1500, false, 0.2, 0.05, -1, NULL, 0, 375, NULL, 1.0, NULL},
    {"gravity-1e4", "g = 1e4 m/s^2 (the largest accepted) on a column: speed <= a fall across the 1 m box, 141 m/s; "
                    "<= 1 h a step",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n[physics]\ngravity = 0 -10000\n"
     "stiffness = 400\nviscosity = 0.002\nnegative_pressure = clamp\n[time]\ncfl = 0.4\n",
     1500, false, -1, 0.05, -1, NULL, 141, 375, NULL, 1.0, NULL},
    {"tiny-domain", "a 3 h x 3 h box full of fluid: speed <= a fall across the 0.12 m box, 1.53 m/s",
     "[scene]\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0\nmax = 0.12 0.12\n"
     "[fluid a]\nmin = 0 0\nmax = 0.12 0.12\nspacing = 0.02\n[kernels]\nh = 0.04\n" WATER,
     1500, false, 0.2, 0.05, -1, NULL, 1.53, 36, NULL, 0, NULL},
    {"far-x-1e4", "a 0.3 x 0.5 m column moved to x = 1e4 m: its 15 x 25 = 375 particles, as at the origin",
     "[scene]\neffects = gravity pressure viscosity walls\n[domain]\nmin = 9999.5 0\nmax = 10000.5 1\n"
     "[fluid column]\nmin = 10000 0\nmax = 10000.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n" WATER,
     300, false, -1, 0.05, -1, NULL, 0, 375, NULL, 0, NULL},
    {"far-x-1e5-speed", "the column at x = 1e5 m: speed <= 1.5 x a fall across the 1 m box, 6.6 m/s",
     "[scene]\neffects = gravity pressure viscosity walls\n[domain]\nmin = 99999.5 0\nmax = 100000.5 1\n"
     "[fluid column]\nmin = 100000 0\nmax = 100000.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n" WATER,
     1500, false, -1, 0.05, -1, NULL, 6.6, 375, NULL, 0, NULL},
    {"zero-viscosity-mueller", "nu = 0 with the default kernels (poly6 density, spiky pressure), which do not "
                               "conserve energy (check and run warn): energy from step 0 stays under the "
                               "watchdog's bound, half its scale (it peaks at +27%)",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid column]\nmin = 0 0\nmax = 0.3 0.5\nspacing = 0.02\n[kernels]\nh = 0.04\n"
     "[physics]\nstiffness = 400\nviscosity = 0\nnegative_pressure = clamp\n[time]\ncfl = 0.4\n",
     5000, false, -1, 0.5, -1, NULL, 0, 375, NULL, 0, NULL},
    {"huge-table", "table_size = 2^31 on a 100-particle scene (16 GiB of keys): refused by check, naming "
                   "table_size",
     "[scene]\neffects = gravity pressure viscosity walls\n" BOX2
     "[fluid a]\nmin = 0 0\nmax = 0.2 0.2\nspacing = 0.02\n[kernels]\nh = 0.04\n[search]\n"
     "table_size = 2147483648\n" WATER,
     10, false, -1, 0.05, -1, NULL, 0, 0, "table_size", 0, NULL},
};
#define N_CASES (int)(sizeof cases / sizeof cases[0])

typedef struct outcome {
    uint64_t steps;
    bool stopped;         /* the watchdog stopped it */
    double rho_err;       /* max over the run of (rho_max - rho0) / rho0 */
    double gain;          /* (E_end - E_start) / scale */
    uint32_t lost;        /* particles outside the walls (or not finite) at the end */
    double vrms_end;      /* [m/s] sqrt(2 E_kin / M) at the end */
    double compare_diff;  /* [m] largest position difference against the comparison run */
    double vmax;          /* [m/s] largest speed seen over the run */
    uint32_t n;           /* particles the scene made */
    bool refused;         /* validation refused the scene (o->report holds why) */
    double move_max;      /* [h] farthest a particle moved in one step, in support radii */
    double vmax_end;      /* [m/s] largest speed at the end */
    char report[1024];
    char warning[1024];   /* what the scene warned of before its first step, "" if nothing */
} outcome;

static double total_energy(const sph_stats *s)
{
    return s->ekin + s->epot + s->eint;
}

static bool make_sim(const hardcase *c, const char *override, sph_sim **sim, char *why, size_t n)
{
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    if (sph_scene_load_string(c->ini, c->name, &def, &err) || (override && sph_scene_set(&def, override, &err)) ||
        sph_sim_create(&def, 0, sim, &err)) {
        snprintf(why, n, "%s", err.msg);
        return false;
    }
    return true;
}

/* The largest distance a particle moved since `prev` (positions by id, 3 a
 * particle), in support radii, a periodic axis counted the short way round;
 * then prev takes the new positions. */
static double step_move(const sph_sim *sim, float *prev)
{
    double worst = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        float *p = prev + 3 * (size_t)sim->P.id[i];
        double r2 = 0;
        for (int d = 0; d < sim->dim; d++) {
            double dx = (double)sim->P.pos[d][i] - p[d];
            if (sim->period[d] > 0) dx -= sim->period[d] * nearbyint(dx / sim->period[d]);
            r2 += dx * dx;
            p[d] = sim->P.pos[d][i];
        }
        worst = fmax(worst, sqrt(r2));
    }
    return worst / sim->def.h;
}

/* Particles of fluid: wall_model = particles adds fixed wall particles
 * outside the box, which the scene's blocks do not make. */
static uint32_t fluid_count(const sph_sim *sim)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < sim->n; i++) n += !sph_is_wall(&sim->P, i);
    return n;
}

/* What a user would be told before the first step: a fixed dt above the CFL
 * limit, a run of over 1e9 steps to the scene's duration. */
static void first_warnings(const sph_sim *sim, char *out, size_t n)
{
    char buf[512];
    out[0] = '\0';
    if (sph_sim_dt_warning(sim, buf, sizeof buf)) snprintf(out, n, "%s", buf);
    if (sph_sim_length_warning(sim, sim->def.duration > 0 ? sim->def.duration : -1, buf, sizeof buf)) {
        size_t len = strlen(out);
        snprintf(out + len, n - len, "%s%s", len ? "; " : "", buf);
    }
}

static bool run_case(const hardcase *c, int steps, outcome *o)
{
    memset(o, 0, sizeof *o);
    sph_sim *sim;
    if (c->refuse) { /* `sphlab check` must refuse it: nothing is allocated (it could be gigabytes) */
        sph_scene_def def = sph_default_scene_def();
        sph_error err;
        o->refused = sph_scene_load_string(c->ini, c->name, &def, &err) || sph_scene_validate(&def, &err);
        if (o->refused) snprintf(o->report, sizeof o->report, "%s", err.msg);
        o->n = (uint32_t)fmin(sph_scene_particle_count(&def), 4e9);
        return true;
    }
    if (!make_sim(c, NULL, &sim, o->report, sizeof o->report)) return false;
    o->n = fluid_count(sim);
    first_warnings(sim, o->warning, sizeof o->warning);
    float *prev = NULL;
    if (c->max_move > 0) {
        prev = calloc(3 * (size_t)sim->n, sizeof *prev);
        if (!prev) {
            snprintf(o->report, sizeof o->report, "out of memory");
            sph_sim_destroy(sim);
            return false;
        }
        step_move(sim, prev);
    }
    sph_stats s;
    sph_sim_stats(sim, &s); /* energy from step 0: creating the sim measured density, so eint exists */
    double e0 = total_energy(&s), scale = fabs(e0);
    double rho0 = sim->def.rest_density;
    for (int k = 0; k < steps && !sim->alarm.raised; k++) {
        sph_sim_step(sim);
        o->vmax = fmax(o->vmax, sim->max_speed);
        if (prev) o->move_max = fmax(o->move_max, step_move(sim, prev));
        if (k % 10 == 0 || k == steps - 1) {
            sph_sim_stats(sim, &s);
            scale = fmax(scale, s.ekin);
            if (sim->P.rho) o->rho_err = fmax(o->rho_err, (s.rho_max - rho0) / rho0);
        }
    }
    free(prev);
    o->steps = sim->step;
    o->stopped = sim->alarm.raised;
    if (o->stopped) sph_sim_alarm_report(sim, o->report, sizeof o->report);
    sph_sim_stats(sim, &s);
    o->gain = (total_energy(&s) - e0) / (scale > 0 ? scale : 1.0);
    double mass = 0;
    for (uint32_t i = 0; i < sim->n; i++)
        if (!sph_is_wall(&sim->P, i)) mass += sim->P.mass[i];
    o->vrms_end = sqrt(2.0 * s.ekin / (mass > 0 ? mass : 1.0));
    o->vmax_end = s.max_speed;
    if (sim->def.effects & SPH_EFFECT(WALLS))
        for (uint32_t i = 0; i < sim->n; i++)
            for (int d = 0; d < sim->dim && !sph_is_wall(&sim->P, i); d++) {
                float x = sim->P.pos[d][i];
                if (!(x >= sim->def.domain_min[d] && x <= sim->def.domain_max[d])) {
                    o->lost++;
                    break;
                }
            }
    if (c->compare && !o->stopped) {
        sph_sim *ref;
        if (!make_sim(c, c->compare, &ref, o->report, sizeof o->report)) {
            sph_sim_destroy(sim);
            return false;
        }
        while (ref->step < sim->step && !ref->alarm.raised) sph_sim_step(ref);
        /* match particles by id: a reordering search stores them in cell order */
        uint32_t *at = malloc((size_t)ref->n * sizeof *at);
        if (at) {
            for (uint32_t i = 0; i < ref->n; i++) at[ref->P.id[i]] = i;
            for (int d = 0; d < sim->dim; d++)
                for (uint32_t i = 0; i < sim->n; i++)
                    o->compare_diff =
                        fmax(o->compare_diff, fabs((double)sim->P.pos[d][i] - ref->P.pos[d][at[sim->P.id[i]]]));
            free(at);
        }
        sph_sim_destroy(ref);
    }
    sph_sim_destroy(sim);
    return true;
}

/* The verdict, and why a case failed. */
static bool judge(const hardcase *c, const outcome *o, int steps, char *why, size_t n)
{
    why[0] = '\0';
    if (c->refuse) {
        if (!o->refused)
            snprintf(why, n, "expected check to refuse the scene (naming %s); it accepted %u particles", c->refuse,
                     o->n);
        else if (!strstr(o->report, c->refuse))
            snprintf(why, n, "refused, but the message does not name %s: %.150s", c->refuse, o->report);
        return why[0] == '\0';
    }
    if (c->warn && !strstr(o->warning, c->warn)) {
        snprintf(why, n, "expected a warning naming '%s' before the first step; got: %.150s", c->warn,
                 o->warning[0] ? o->warning : "none");
        return false;
    }
    if (c->expect_n && o->n != c->expect_n) {
        snprintf(why, n, "%u particles, the scene's blocks make %u", o->n, c->expect_n);
        return false;
    }
    if (c->expect_stop) {
        if (!o->stopped) snprintf(why, n, "expected the watchdog to stop this run; it ran %llu steps",
                                  (unsigned long long)o->steps);
        return o->stopped;
    }
    if (o->stopped) snprintf(why, n, "stopped by the watchdog (see its report)");
    else if (o->steps < (uint64_t)steps) snprintf(why, n, "ran %llu of %d steps", (unsigned long long)o->steps, steps);
    else if (o->lost) snprintf(why, n, "%u particles outside the walls", o->lost);
    else if (o->gain > c->max_gain) snprintf(why, n, "energy grew by %.3g of its scale (bound %.3g)", o->gain, c->max_gain);
    else if (c->max_rho_err >= 0 && o->rho_err > c->max_rho_err)
        snprintf(why, n, "density error %.3g above %.3g", o->rho_err, c->max_rho_err);
    else if (c->max_speed > 0 && o->vmax > c->max_speed)
        snprintf(why, n, "speed %.3g m/s above %.3g m/s", o->vmax, c->max_speed);
    else if (c->max_move > 0 && o->move_max > c->max_move)
        snprintf(why, n, "a particle moved %.3g h in one step (bound %.3g h)", o->move_max, c->max_move);
    else if (c->max_vrms_end >= 0 && o->vrms_end > c->max_vrms_end)
        snprintf(why, n, "final rms speed %.3g m/s above %.3g m/s: not at rest", o->vrms_end, c->max_vrms_end);
    else if (c->compare && o->compare_diff > 1e-3)
        snprintf(why, n, "differs from the %s run by %.3g m", c->compare, o->compare_diff);
    return why[0] == '\0';
}

static const app_cmd_spec spec = {
    .name = "hardcases",
    .cmd = APP_CMD(hardcases),
    .synopsis = "usage: sphlab hardcases [--quick] [--only NAME] [--list] [--verbose]\n"
                "Runs scenes that break naive SPH codes and prints a verdict for each: max density error\n"
                "(rho_max - rho0)/rho0, energy change relative to its scale, particles lost, whether the\n"
                "watchdog stopped it, steps run. Exit status 1 if any case fails.\n",
};

int cmd_hardcases(int argc, char **argv)
{
    app_opts opt;
    app_opts_init(&opt);
    int rc = app_opts_parse(&spec, argc, argv, &opt);
    if (rc >= 0) return rc;
    bool quick = opt.quick, verbose = opt.verbose;
    const char *only = opt.only;
    if (opt.list) {
        for (int k = 0; k < N_CASES; k++) printf("%-22s %s\n", cases[k].name, cases[k].about);
        return 0;
    }
    bool known = !only;
    for (int k = 0; k < N_CASES && !known; k++) known = strcmp(cases[k].name, only) == 0;
    if (!known) { /* refused before the table: a header with no row under it read as a run */
        fprintf(stderr, "sphlab hardcases: no case named '%s' (see --list)\n", only);
        return 2;
    }
    int passed = 0, failed = 0;
    printf("%-22s %7s %9s %9s %5s %8s  %s\n", "case", "steps", "rho err", "energy", "lost", "watchdog", "verdict");
    for (int k = 0; k < N_CASES; k++) {
        const hardcase *c = &cases[k];
        if (only && strcmp(only, c->name) != 0) continue;
        int steps = c->steps;
        if (quick && steps > 1500) steps = steps / 4 > 1500 ? steps / 4 : 1500;
        outcome o;
        char why[256];
        double t0 = sph_now_ms();
        bool ran = run_case(c, steps, &o);
        bool ok = ran && judge(c, &o, steps, why, sizeof why);
        if (!ran) snprintf(why, sizeof why, "%.200s", o.report);
        if (o.refused) /* nothing ran: no figure to show, only the refusal */
            printf("%-22s %7s %9s %9s %5s %8s  %s: refused: %s (%.1f s)\n", c->name, "-", "-", "-", "-", "-",
                   ok ? "pass" : "FAIL", ok ? o.report : why, (sph_now_ms() - t0) / 1e3);
        else
            printf("%-22s %7llu %8.2f%% %8.2f%% %5u %8s  %s%s%s (%.1f s)\n", c->name, (unsigned long long)o.steps,
                   100 * o.rho_err, 100 * o.gain, o.lost, o.stopped ? "stopped" : "-", ok ? "pass" : "FAIL",
                   why[0] ? ": " : "", why, (sph_now_ms() - t0) / 1e3);
        if (c->max_speed > 0 && ran && !o.refused) /* the figure the case is judged on */
            printf("%-22s %7s fastest %.4g m/s over the run (bound %.3g m/s)\n", "", "", o.vmax, c->max_speed);
        if (c->compare && ran && !o.stopped)
            printf("%-22s %7s same flow as %s within %.2g m\n", "", "", c->compare, o.compare_diff);
        if (c->max_move > 0 && ran)
            printf("%-22s %7s farthest move in one step %.3g h, fastest %.4g m/s\n", "", "", o.move_max, o.vmax);
        if (verbose && ran && !c->refuse)
            printf("%-22s %7s fastest %.4g m/s over the run, at the end %.3g m/s (rms %.3g m/s)\n", "", "", o.vmax,
                   o.vmax_end, o.vrms_end);
        if (c->warn && ran && o.warning[0]) printf("%-22s %7s warned: %s\n", "", "", o.warning);
        if (o.stopped && (verbose || !ok))
            printf("%s%s", o.report, o.report[0] && o.report[strlen(o.report) - 1] != '\n' ? "\n" : "");
        ok ? passed++ : failed++;
    }
    printf("hardcases: %d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
