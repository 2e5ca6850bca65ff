/* Validation of a scene as a whole (sph_scene_validate): what no single
 * key's range can say: the domain and the blocks in it, the keys that must
 * go together, the particle count; then the limits of sph_scene_limits.c.
 * Each error names the file and line of the value it refuses. The parser
 * is sph_scene.c; each value on its own is checked in sph_scene_values.c. */
#include "sph_scene.h"
#include "sph_obstacles.h"
#include "sph_memory.h"
#include "sph_names.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* Index of a key of a plain section ([domain], [physics]) in sph_scene_keys. */
static int key_index(const char *section, const char *name)
{
    for (int i = 0; i < sph_scene_key_count; i++)
        if (strcmp(sph_scene_keys[i].section, section) == 0 && strcmp(sph_scene_keys[i].name, name) == 0)
            return i;
    return -1;
}

int64_t sph_block_nodes(const sph_scene_def *def, int b, int axis)
{
    const sph_block_def *blk = &def->blocks[b];
    if (axis >= def->dim) return 1;
    double extent = (double)blk->max[axis] - (double)blk->min[axis];
    if (!(extent > 0) || !(blk->spacing > 0)) return 0;
    double n = floor(extent / blk->spacing + 1e-3); /* tolerate float rounding of the corners (up to 0.1% of a spacing) */
    return n > 9e15 ? (int64_t)9e15 : (int64_t)n;
}

double sph_scene_neighbour_estimate(const sph_scene_def *def)
{
    double s = INFINITY;
    for (int b = 0; b < def->n_blocks; b++) s = fmin(s, def->blocks[b].spacing);
    if (!isfinite(s) || !(s > 0)) return 0;
    double q = def->h / s, pi = 3.14159265358979323846;
    return def->dim == 3 ? 4.0 / 3.0 * pi * q * q * q : pi * q * q;
}

/* Two fluid blocks whose boxes share a volume: their particles start on top
 * of each other, far above rest density, and the fluid bursts apart. Said,
 * not refused: the hard cases start blocks overlapped on purpose. */
static const char *blocks_overlap(const sph_scene_def *def, char *buf, size_t n)
{
    for (int b = 1; b < def->n_blocks; b++)
        for (int a = 0; a < b; a++) {
            const sph_block_def *A = &def->blocks[a], *B = &def->blocks[b];
            double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}, tol = 1e-3 * fmin(A->spacing, B->spacing);
            bool shared = true;
            for (int d = 0; d < def->dim; d++) {
                lo[d] = fmax(A->min[d], B->min[d]);
                hi[d] = fmin(A->max[d], B->max[d]);
                shared &= hi[d] - lo[d] > tol; /* touching faces are not an overlap */
            }
            if (!shared) continue;
            char loc[300], box[160];
            if (B->line > 0)
                snprintf(loc, sizeof loc, "%s:%d", def->file, B->line);
            else
                snprintf(loc, sizeof loc, "%s", def->file);
            if (def->dim == 3)
                snprintf(box, sizeof box, "x %g to %g, y %g to %g, z %g to %g m", lo[0], hi[0], lo[1], hi[1], lo[2],
                         hi[2]);
            else
                snprintf(box, sizeof box, "x %g to %g, y %g to %g m", lo[0], hi[0], lo[1], hi[1]);
            snprintf(buf, n,
                     "%s: [fluid %s] overlaps [fluid %s] (line %d) over %s: particles there start on top of each "
                     "other, above rest density, and burst apart; move the blocks apart",
                     loc, B->name, A->name, A->line, box);
            return buf;
        }
    return NULL;
}

static const char *origin_text(const sph_scene_def *def, int line, char *buf, size_t n);

/* Appends a warning to buf, the warnings one per line. */
static void add_warning(char *buf, size_t n, const char *line)
{
    const size_t used = strlen(buf);
    if (used + 1 < n) snprintf(buf + used, n - used, "%s%s", used ? "\n" : "", line);
}

/* Every key the file (or --set) gives that the scene's choices leave unread,
 * each said (appended to buf), since the run is then not the one written (a
 * csf drop given surface_tension_coefficient ran at the default sigma; a slip
 * given to volume walls changed nothing). All of them: a user who fixes one
 * warning must not find the next only on the following run. */
static void unread_keys(const sph_scene_def *def, char *buf, size_t n)
{
    const bool pressure = (def->effects & SPH_EFFECT(PRESSURE)) != 0, walls = (def->effects & SPH_EFFECT(WALLS)) != 0;
    const bool solver = def->pressure_solver != SPH_PSOLVER_EOS && pressure;
    const bool particles = walls && pressure && def->wall_model == SPH_WALL_PARTICLES; /* sph_scene_wall_particles */
    const char *by_solver = "only pressure_solver = pcisph or dfsph reads it, with the effect pressure";
    const char *by_particles = "only wall_model = particles reads it, with the effects walls and pressure";
    /* the top wall's slip as its particles take it: its own key, or wall_slip */
    const sph_side_slip top = def->wall_slip_side[3];
    const bool top_free = top == SPH_SIDE_SLIP_FREE || (top == SPH_SIDE_SLIP_SAME && def->wall_slip == SPH_SLIP_FREE);
    const bool viscous = (def->effects & SPH_EFFECT(VISCOSITY)) != 0;
    const char *by_periodic = "a periodic axis has no walls";
    /* the solvers hold rho_rest with no equation of state; only a velocity field's initial pressure
     * (field_pressure = on, sph_sim.c) reads it under one. stiffness stays read: the artificial
     * viscosity's speed of sound */
    bool eos_read = !solver;
    for (int k = 0; k < def->n_blocks; k++) eos_read |= def->blocks[k].field_pressure == SPH_ON;
    const char *by_eos = "only pressure_solver = eos reads it (pcisph and dfsph hold the lattice's rho_rest, with no "
                         "equation of state)";
    const struct {
        const char *section, *key;
        bool unread;
        const char *reader;
    } keys[] = {
        {"physics", "surface_tension_coefficient", def->surface_tension != SPH_STENSION_AKINCI,
         "only surface_tension = akinci reads it (its gamma; csf's coefficient is [physics] sigma)"},
        {"physics", "sigma", def->surface_tension != SPH_STENSION_CSF && def->surface_tension != SPH_STENSION_STRESS,
         "only surface_tension = csf or stress reads it"},
        {"physics", "delta", def->density_method != SPH_DMETHOD_CONTINUITY, "only density_method = continuity reads it"},
        {"physics", "delta_form", def->density_method != SPH_DMETHOD_CONTINUITY,
         "only density_method = continuity reads it"},
        /* the solvers' keys: a tolerance given to the equation of state changed nothing, unsaid; and the
         * choice itself without the effect (a fluid without pressure ran, its --stats error 0) */
        {"physics", "pressure_solver", !pressure, "only the effect pressure reads it: no pressure acts"},
        {"physics", "solver_tolerance", !solver, by_solver},
        {"physics", "solver_max_iterations", !solver, by_solver},
        {"physics", "solver_warm_start", !solver, by_solver},
        {"physics", "divergence_tolerance", !solver || def->pressure_solver != SPH_PSOLVER_DFSPH,
         "only pressure_solver = dfsph reads it, with the effect pressure"},
        {"physics", "pcisph_local_delta", !solver || def->pressure_solver != SPH_PSOLVER_PCISPH,
         "only pressure_solver = pcisph reads it, with the effect pressure"},
        /* the acceleration starts at a solve's 10th correction: with fewer the key changed nothing, unsaid (a
         * user's review: the run's --stats equal to the plain one's) */
        {"physics", "solver_chebyshev",
         !solver || (def->solver_chebyshev > 0 && def->solver_max_iterations <= SPH_CHEBYSHEV_FIRST),
         !solver ? by_solver
                 : "the acceleration starts at a solve's 10th correction, and solver_max_iterations <= 10 allows at "
                   "most 9 (N iterations make N - 1 corrections)"},
        {"physics", "solver_wall_pressure", !solver || !particles,
         "only pressure_solver = pcisph or dfsph with wall_model = particles reads it"},
        /* the walls' keys: each model reads its own */
        {"domain", "wall_model", !walls, "only the effect walls reads it"},
        {"domain", "wall_force", !walls || def->wall_model != SPH_WALL_VOLUME,
         "only wall_model = volume reads it, with the effect walls"},
        {"domain", "wall_slip", !particles, by_particles},
        {"domain", "wall_slip_xmin", !particles || (def->periodic & 1u), particles ? by_periodic : by_particles},
        {"domain", "wall_slip_xmax", !particles || (def->periodic & 1u), particles ? by_periodic : by_particles},
        {"domain", "wall_slip_ymin", !particles || (def->periodic & 2u), particles ? by_periodic : by_particles},
        {"domain", "wall_slip_ymax", !particles || (def->periodic & 2u), particles ? by_periodic : by_particles},
        {"domain", "wall_slip_zmin", !particles || def->dim == 2 || (def->periodic & 4u),
         def->dim == 2 ? "a 2D scene has no z sides" : particles ? by_periodic : by_particles},
        {"domain", "wall_slip_zmax", !particles || def->dim == 2 || (def->periodic & 4u),
         def->dim == 2 ? "a 2D scene has no z sides" : particles ? by_periodic : by_particles},
        /* a moving top wall drags the fluid only through the viscous term, and only when no-slip (a review's
         * Couette flow with a free-slip lid stood still, unsaid) */
        {"domain", "wall_velocity", particles && (top_free || !viscous),
         !viscous ? "only the viscous term reads it (the effect viscosity): without it the wall drags nothing"
                  : "a free-slip top wall drags nothing: only a no-slip one reads it (wall_slip_ymax = no)"},
        /* the effects' own keys, and the choices' (a user's review: each ran unsaid) */
        {"physics", "gravity", !(def->effects & SPH_EFFECT(GRAVITY)), "only the effect gravity reads it"},
        {"physics", "gravity_ramp", !(def->effects & SPH_EFFECT(GRAVITY)), "only the effect gravity reads it"},
        {"physics", "cohesion", !(def->effects & SPH_EFFECT(COHESION)) || def->surface_tension == SPH_STENSION_AKINCI,
         def->surface_tension == SPH_STENSION_AKINCI
             ? "surface_tension = akinci reads surface_tension_coefficient instead"
             : "only the effect cohesion reads it"},
        {"physics", "alpha",
         !(def->effects & SPH_EFFECT(VISCOSITY)) ||
             (def->viscosity_form != SPH_VFORM_ARTIFICIAL && def->viscosity_form != SPH_VFORM_MORRIS_ARTIFICIAL),
         "only viscosity_form = artificial or morris-artificial reads it, with the effect viscosity"},
        /* Monaghan's term reads alpha and the pressure kernel; a nu left there changed nothing, unsaid (a user's
         * review of the scene format) */
        {"physics", "viscosity",
         !(def->effects & SPH_EFFECT(VISCOSITY)) || def->viscosity_form == SPH_VFORM_ARTIFICIAL,
         !(def->effects & SPH_EFFECT(VISCOSITY))
             ? "only the effect viscosity reads it"
             : "viscosity_form = artificial reads alpha instead (morris-artificial reads both)"},
        {"physics", "viscosity_form", !(def->effects & SPH_EFFECT(VISCOSITY)), "only the effect viscosity reads it"},
        {"kernels", "viscosity",
         !(def->effects & SPH_EFFECT(VISCOSITY)) || def->viscosity_form == SPH_VFORM_ARTIFICIAL,
         !(def->effects & SPH_EFFECT(VISCOSITY)) ? "only the effect viscosity reads it"
                                                   : "viscosity_form = artificial takes the pressure kernel's gradient"},
        {"physics", "shifting_coefficient", def->shifting == SPH_SHIFT_NONE, "only shifting = lind or tvf reads it"},
        {"domain", "wall_damping", !walls, "only the effect walls reads it"},
        {"interaction", "radius", !(def->effects & SPH_EFFECT(INTERACTION)), "only the effect interaction reads it"},
        {"interaction", "strength", !(def->effects & SPH_EFFECT(INTERACTION)), "only the effect interaction reads it"},
        {"search", "table_size", def->search != SPH_SEARCH_HASH, "only method = hash reads it"},
        {"time", "dt_min", def->cfl <= 0, "only the adaptive step (cfl > 0) reads it"},
        /* last: a scene written for the equation of state and run with --set pressure_solver says the
         * solver's keys first */
        {"physics", "tait_gamma", def->eos != SPH_EOS_TAIT || !eos_read,
         def->eos != SPH_EOS_TAIT ? "only eos = tait reads it" : by_eos},
        {"physics", "eos", !eos_read, by_eos},
        {"physics", "eos_rest", !eos_read, by_eos},
    };
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
        int i = key_index(keys[k].section, keys[k].key);
        if (i < 0 || def->origin[i].line == 0 || !keys[k].unread) continue;
        const char *reader = keys[k].reader;
        if (strncmp(keys[k].key, "wall_slip_z", 11) == 0 && !particles) reader = by_particles;
        char loc[300], line[700];
        snprintf(line, sizeof line, "%s: [%s] %s is set but this scene does not use it: %s",
                 origin_text(def, def->origin[i].line, loc, sizeof loc), keys[k].section, keys[k].key, reader);
        add_warning(buf, n, line);
    }
}

static const char *estimate_warning(const sph_scene_def *def, char *buf, size_t n);
static const char *origin_text(const sph_scene_def *def, int line, char *buf, size_t n);

const char *sph_scene_warning(const sph_scene_def *def, char *buf, size_t n)
{
    char one[1024];
    if (n == 0) return NULL;
    buf[0] = '\0';
    if (sph_scene_ignored_z(def, one, sizeof one)) add_warning(buf, n, one); /* first: not the scene written */
    if (blocks_overlap(def, one, sizeof one)) add_warning(buf, n, one);
    unread_keys(def, buf, n);
    if (estimate_warning(def, one, sizeof one)) add_warning(buf, n, one);
    /* the damping period removes all motion at its start: a block's initial velocity with it (a review's drop
     * thrown at 1 m/s had 3e-10 J/m of kinetic energy after its first step, unsaid) */
    for (int k = 0; k < def->n_blocks && def->damping_time > 0; k++) {
        const float *v = def->blocks[k].velocity;
        if (v[0] == 0 && v[1] == 0 && v[2] == 0) continue;
        char at[300], speed[96];
        const int ld = key_index("physics", "damping_time");
        origin_text(def, def->origin[ld].line, at, sizeof at);
        if (def->dim == 3)
            snprintf(speed, sizeof speed, "%g %g %g", v[0], v[1], v[2]);
        else
            snprintf(speed, sizeof speed, "%g %g", v[0], v[1]);
        snprintf(one, sizeof one,
                 "%s: [physics] damping_time = %g s removes all motion at the start, so [fluid %s]'s velocity "
                 "(%s m/s) is damped away with it; to keep it, set damping_time = 0",
                 at, (double)def->damping_time, def->blocks[k].name, speed);
        add_warning(buf, n, one);
        break; /* one block said is enough */
    }
    /* the damping multiplies every velocity, the moving lid's wall particles' too, and nothing restores it: a
     * Couette flow with damping_time = 0.01 ended at 3.6e-4 m/s where its lid moves at 0.025 */
    if (def->damping_time > 0 && (def->wall_velocity[0] != 0 || def->wall_velocity[2] != 0) &&
        (def->effects & SPH_EFFECT(WALLS)) && (def->effects & SPH_EFFECT(PRESSURE)) &&
        def->wall_model == SPH_WALL_PARTICLES) {
        char at[300];
        origin_text(def, def->origin[key_index("physics", "damping_time")].line, at, sizeof at);
        snprintf(one, sizeof one,
                 "%s: [physics] damping_time = %g s damps the moving top wall too ([domain] wall_velocity), and it "
                 "does not start again: the lid stands still; to keep it moving, set damping_time = 0",
                 at, (double)def->damping_time);
        add_warning(buf, n, one);
    }
    return buf[0] ? buf : NULL;
}

void sph_scene_warnings_print(const sph_scene_def *def, FILE *f)
{
    char buf[8192];
    if (!sph_scene_warning(def, buf, sizeof buf)) return;
    for (char *line = buf, *end; line; line = end ? end + 1 : NULL) {
        end = strchr(line, '\n');
        if (end) *end = '\0';
        fprintf(f, "sphlab: warning: %s\n", line);
    }
}

/* The neighbour count and the kernels' pairing. */
static const char *estimate_warning(const sph_scene_def *def, char *buf, size_t n)
{
    double nb = sph_scene_neighbour_estimate(def);
    double count = sph_scene_particle_count(def);
    if (def->n_blocks == 0 || !(def->effects & (SPH_EFFECT(DENSITY) | SPH_EFFECT(PRESSURE) | SPH_EFFECT(VISCOSITY))))
        return NULL;
    if (nb > 400) {
        snprintf(buf, n,
                 "h = %g m is %.3g spacings: each particle will have about %.0f neighbours (usually 20 to 60); steps "
                 "will be slow, about %.3g pair evaluations each",
                 def->h, def->h / def->blocks[0].spacing, fmin(nb, count), count * fmin(nb, count));
        return buf;
    }
    double finest = INFINITY;
    for (int b = 0; b < def->n_blocks; b++) finest = fmin(finest, def->blocks[b].spacing);
    if (def->h <= finest) { /* pi (h/s)^2 is no count there: a lattice particle has none within h */
        char loc[300];
        const int line = def->origin[key_index("kernels", "h")].line;
        snprintf(buf, n,
                 "%s: [kernels] h = %g m%s is not larger than the spacing %g m: a particle on the lattice has no "
                 "neighbour within h, only itself (use h of about 2 spacings)",
                 origin_text(def, line, loc, sizeof loc), def->h, line ? "" : " (the default)", finest);
        return buf;
    }
    if (nb < 6) {
        snprintf(buf, n,
                 "h = %g m gives about %.1f neighbours per particle: too few for a smooth estimate (use h of about 2 "
                 "spacings)",
                 def->h, nb);
        return buf;
    }
    /* A pressure force conserves energy when it is the gradient of the
     * density sum's energy, so with the same kernel (Price 2012, J. Comput.
     * Phys. 231, 759: the equations from a Lagrangian); Mueller et al.'s
     * spiky gradient with poly6 density (2003) is not: without viscosity a
     * 2D column gains up to 27% of its energy scale (hard case
     * zero-viscosity-mueller). */
    bool inviscid = !(def->effects & SPH_EFFECT(VISCOSITY)) || def->viscosity == 0;
    if ((def->effects & SPH_EFFECT(PRESSURE)) && inviscid && def->kernel_density != def->kernel_pressure) {
        snprintf(buf, n,
                 "no viscosity with [kernels] density = %s and pressure = %s: the pressure force is not the gradient "
                 "of that density's energy, so total energy is not conserved (it grew by up to 27%% in a dam break); "
                 "use one kernel for both, or some viscosity",
                 sph_kernel_names[def->kernel_density], sph_kernel_names[def->kernel_pressure]);
        return buf;
    }
    return NULL;
}

double sph_scene_particle_count(const sph_scene_def *def)
{
    double total = 0;
    for (int b = 0; b < def->n_blocks; b++) {
        double n = 1;
        for (int a = 0; a < def->dim; a++) n *= (double)sph_block_nodes(def, b, a);
        total += n;
    }
    /* less the nodes that fall inside obstacles (not counted beyond 2e8, which validation refuses) */
    return def->n_obstacles && total <= 2e8 ? total - sph_obstacles_fluid_dropped(def) : total;
}

#define SPH_MAX_PARTICLES 200000000.0

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

static sph_error_code block_error(sph_error *err, const sph_scene_def *def, int b, const char *fmt, const char *what)
{
    return sph_fail(err, SPH_ERR_SCENE, fmt, def->file, def->blocks[b].line, def->blocks[b].name, what);
}

sph_error_code sph_scene_validate(const sph_scene_def *def, sph_error *err)
{
    const char *axes = "xyz";
    int dim = def->dim;
    /* A 3D scene needs every vector with 3 components (sph_scene.c: the parser counted them). */
    sph_error_code cc = sph_scene_check_components(def, err);
    if (cc) return cc;
    for (int a = 0; a < dim; a++) {
        if (!(def->domain_min[a] < def->domain_max[a])) {
            /* name the key the user wrote: max if given, else min (max is then its default) */
            int li = key_index("domain", "max"), lo = key_index("domain", "min");
            int line = def->origin[li].line ? def->origin[li].line : def->origin[lo].line;
            if (def->origin[lo].line < 0) line = -1; /* a min given by --set is what the command changed */
            char loc[300];
            return sph_fail(err, SPH_ERR_RANGE,
                            "%s: [domain] max.%c = %g%s is not above min.%c = %g (accepted: max above min on each axis)",
                            origin_text(def, line, loc, sizeof loc), axes[a], def->domain_max[a],
                            def->origin[li].line ? "" : " (the default)", axes[a], def->domain_min[a]);
        }
    }
    for (int a = 0; a < 3; a++) {
        if (!(def->periodic & (1u << a))) continue;
        int li = key_index("domain", "periodic");
        char loc[300];
        origin_text(def, def->origin[li].line, loc, sizeof loc);
        if (a >= dim)
            return sph_fail(err, SPH_ERR_RANGE, "%s: [domain] periodic lists %c but the scene is %dD", loc, axes[a],
                            dim);
        double len = (double)def->domain_max[a] - def->domain_min[a];
        if (len < 3.0 * def->h * (1.0 + 1.0 / 1024))
            return sph_fail(err, SPH_ERR_RANGE,
                            "%s: [domain] periodic %c: the domain is %g m long, less than 3 h = %g m (a particle "
                            "would meet its own image)",
                            loc, axes[a], len, 3.0 * def->h);
        /* Verlet lists: three cells of h (1 + skin) must fit, or the stencil wraps onto itself */
        const double reach = def->skin > 0 ? def->h * (1.0 + (double)def->skin) : 0.0;
        if (reach > 0 && len < 3.0 * reach * (1.0 + 1.0 / 1024))
            return sph_fail(err, SPH_ERR_RANGE,
                            "%s: [domain] periodic %c: the domain is %g m long, less than 3 h (1 + skin) = %g m, "
                            "three cells of the Verlet lists' reach ([search] skin = %g)",
                            loc, axes[a], len, 3.0 * reach, (double)def->skin);
    }
    /* a moving top wall: only wall particles carry it, and they cannot move along their normal */
    if (def->wall_velocity[0] != 0 || def->wall_velocity[1] != 0 || def->wall_velocity[2] != 0) {
        int li = key_index("domain", "wall_velocity");
        char loc[300];
        origin_text(def, def->origin[li].line, loc, sizeof loc);
        if (!(def->effects & SPH_EFFECT(WALLS)) || def->wall_model != SPH_WALL_PARTICLES ||
            !(def->effects & SPH_EFFECT(PRESSURE)))
            return sph_fail(err, SPH_ERR_RANGE,
                            "%s: [domain] wall_velocity = %g %g: a moving wall needs wall particles ([domain] "
                            "wall_model = particles, effects walls and pressure)",
                            loc, def->wall_velocity[0], def->wall_velocity[1]);
        if (def->wall_velocity[1] != 0)
            return sph_fail(err, SPH_ERR_RANGE,
                            "%s: [domain] wall_velocity y = %g: the top wall may only move along itself (accepted: "
                            "a y component of 0)",
                            loc, def->wall_velocity[1]);
        if (def->periodic & 2u)
            return sph_fail(err, SPH_ERR_RANGE, "%s: [domain] wall_velocity: y is periodic, there is no top wall",
                            loc);
    }
    /* the adaptive step lies within [dt_min, dt]: a floor above the ceiling held every step at dt_min, longer
     * than the scene's own dt allows (check said "dt <= 0.001 s", then run stepped at 1 s) */
    if (def->cfl > 0 && def->dt_min > def->dt) {
        int lm = key_index("time", "dt_min"), ld = key_index("time", "dt");
        int line = def->origin[lm].line ? def->origin[lm].line : def->origin[ld].line;
        char loc[300];
        return sph_fail(err, SPH_ERR_RANGE,
                        "%s: [time] dt_min = %g s%s is above dt = %g s%s: the adaptive step lies between them "
                        "(accepted: dt_min <= dt)",
                        origin_text(def, line, loc, sizeof loc), def->dt_min,
                        def->origin[lm].line ? "" : " (the default)", def->dt,
                        def->origin[ld].line ? "" : " (the default)");
    }
    /* Morris's form divides x_ij . grad W = r W'(r) by r^2: it needs W'(r) / r
     * bounded, that is W'(0) = 0, which the viscosity and spiky kernels lack */
    if ((def->viscosity_form == SPH_VFORM_MORRIS || def->viscosity_form == SPH_VFORM_MORRIS_ARTIFICIAL) &&
        (def->kernel_viscosity == SPH_KERNEL_VISCOSITY || def->kernel_viscosity == SPH_KERNEL_SPIKY) &&
        (def->effects & SPH_EFFECT(VISCOSITY))) {
        int li = key_index("physics", "viscosity_form");
        char loc[300];
        return sph_fail(err, SPH_ERR_RANGE,
                        "%s: [physics] viscosity_form = %s with [kernels] viscosity = %s: that kernel's slope "
                        "does not vanish at r = 0, so W'(r)/r grows without bound for close pairs; set [kernels] "
                        "viscosity = cubic, wendland or poly6",
                        origin_text(def, def->origin[li].line, loc, sizeof loc),
                        sph_viscosity_form_names[def->viscosity_form], sph_kernel_names[def->kernel_viscosity]);
    }
    if (def->n_blocks == 0)
        return sph_fail(err, SPH_ERR_SCENE, "%s: no particles: the scene has no [fluid NAME] block", def->file);
    for (int b = 0; b < def->n_blocks; b++) {
        const sph_block_def *blk = &def->blocks[b];
        for (int a = 0; a < dim; a++) {
            if (!(blk->min[a] < blk->max[a])) {
                char what[64];
                snprintf(what, sizeof what, "max.%c (%g) is not above min.%c (%g)", axes[a], blk->max[a], axes[a],
                         blk->min[a]);
                return block_error(err, def, b, "%s:%d: [fluid %s]: %s", what);
            }
            if (blk->min[a] < def->domain_min[a] || blk->max[a] > def->domain_max[a]) {
                char what[160];
                snprintf(what, sizeof what, "%c from %g to %g leaves the domain, %g to %g", axes[a], blk->min[a],
                         blk->max[a], def->domain_min[a], def->domain_max[a]);
                return block_error(err, def, b,
                                   "%s:%d: [fluid %s]: block outside the domain: %s (accepted: min and max within "
                                   "[domain])",
                                   what);
            }
            if (sph_block_nodes(def, b, a) == 0) {
                char what[128];
                snprintf(what, sizeof what, "along %c the box (%g m) is thinner than one spacing (%g m)", axes[a],
                         blk->max[a] - blk->min[a], blk->spacing);
                return block_error(err, def, b, "%s:%d: [fluid %s]: no particles: %s", what);
            }
        }
    }
    sph_error_code oc = sph_obstacles_validate(def, err); /* sph_obstacles.c */
    if (oc) return oc;
    double count = sph_scene_particle_count(def);
    if (count > SPH_MAX_PARTICLES) { /* particle indices are 32-bit, with room for wall particles */
        /* name the block that makes the most, at the line that set its spacing */
        int big = 0, slot = 0;
        double most = -1;
        for (int b = 0; b < def->n_blocks; b++) {
            double nb = 1;
            for (int a = 0; a < dim; a++) nb *= (double)sph_block_nodes(def, b, a);
            if (nb > most) most = nb, big = b;
        }
        for (int i = 0; i < sph_scene_key_count && strcmp(sph_scene_keys[i].name, "spacing") != 0; i++)
            slot += strcmp(sph_scene_keys[i].section, "fluid") == 0;
        const sph_block_def *blk = &def->blocks[big];
        char loc[300];
        origin_text(def, blk->origin[slot].line ? blk->origin[slot].line : blk->line, loc, sizeof loc);
        return sph_fail(err, SPH_ERR_MEMORY,
                        "%s: [fluid %s] spacing = %g m: the fluid blocks make %.3g particles, more than memory "
                        "allows (at most %.0f); raise the spacing or shrink the blocks",
                        loc, blk->name, blk->spacing, count, SPH_MAX_PARTICLES);
    }
    if (def->pressure_solver != SPH_PSOLVER_EOS && (def->effects & SPH_EFFECT(PRESSURE)) &&
        def->density_method == SPH_DMETHOD_CONTINUITY) {
        char loc[300];
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [physics] pressure_solver = %s needs density_method = summation (it sums the predicted "
                        "density itself)",
                        origin_text(def, def->origin[key_index("physics", "pressure_solver")].line, loc, sizeof loc),
                        sph_pressure_solver_names[def->pressure_solver]);
    }
    if (def->surface_tension == SPH_STENSION_AKINCI && (def->effects & SPH_EFFECT(COHESION))) {
        char loc[300];
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [physics] surface_tension = akinci with the effect cohesion: akinci includes the cohesion "
                        "term (with gamma = surface_tension_coefficient); list one of them",
                        origin_text(def, def->origin[key_index("physics", "surface_tension")].line, loc, sizeof loc));
    }
    sph_error_code combos = sph_scene_check_combinations(def, err); /* sph_scene_combos.c */
    if (combos != SPH_ERR_OK) return combos;
    return sph_scene_check_limits(def, err); /* precision, cells, memory (sph_scene_limits.c) */
}
