/* Choices that are each valid but do not work together: refused at load,
 * naming the keys and where they were set, rather than run into nonsense.
 * Each rule says why it exists; lift it when the combination is built. */
#include <stdio.h>
#include <string.h>

#include "sph_fields.h"
#include "sph_pass.h"
#include "sph_scene.h"

/* "file:line", "--set", or the file, for a top-level key. */
const char *sph_scene_key_where(const sph_scene_def *def, const char *section, const char *name, char *buf, size_t n)
{
    int line = 0;
    for (int i = 0; i < sph_scene_key_count; i++)
        if (strcmp(sph_scene_keys[i].section, section) == 0 && strcmp(sph_scene_keys[i].name, name) == 0)
            line = i < SPH_MAX_KEYS ? def->origin[i].line : 0;
    if (line > 0)
        snprintf(buf, n, "%s:%d", def->file, line);
    else if (line < 0)
        snprintf(buf, n, "--set");
    else
        snprintf(buf, n, "%s", def->file);
    return buf;
}

/* The same for a key of a [fluid NAME] block: its slot is its rank among the
 * section's keys (as the parser stores it). */
static const char *block_key_where(const sph_scene_def *def, int b, const char *name, char *buf, size_t n)
{
    const sph_block_def *blk = &def->blocks[b];
    int slot = 0, line = blk->line;
    for (int i = 0; i < sph_scene_key_count; i++) {
        if (strcmp(sph_scene_keys[i].section, "fluid") != 0) continue;
        if (strcmp(sph_scene_keys[i].name, name) == 0) {
            if (slot < (int)(sizeof blk->origin / sizeof blk->origin[0]) && blk->origin[slot].line)
                line = blk->origin[slot].line;
            break;
        }
        slot++;
    }
    if (line > 0)
        snprintf(buf, n, "%s:%d", def->file, line);
    else
        snprintf(buf, n, "--set");
    return buf;
}

/* The share of the domain the fluid blocks cover (overlaps counted twice,
 * which only errs towards "filled"). */
static double fluid_share(const sph_scene_def *def)
{
    double domain = 1, fluid = 0;
    for (int d = 0; d < def->dim; d++) domain *= (double)def->domain_max[d] - def->domain_min[d];
    for (int b = 0; b < def->n_blocks; b++) {
        double v = 1;
        for (int d = 0; d < def->dim; d++) v *= def->blocks[b].max[d] - def->blocks[b].min[d];
        fluid += v;
    }
    return domain > 0 ? fluid / domain : 0;
}

sph_error_code sph_scene_check_combinations(const sph_scene_def *def, sph_error *err)
{
    char a[300], b[300];
    const int pressure = (def->effects & SPH_EFFECT(PRESSURE)) != 0;
    /* The transport velocity pushes every particle with a background pressure
     * (Adami et al. 2013); at a free surface nothing pushes back, so the
     * surface layer is driven outward (measured: water at rest reached 5 m/s). */
    if (def->shifting == SPH_SHIFT_TVF && pressure) {
        const double share = fluid_share(def);
        if (share < 0.99)
            return sph_fail(err, SPH_ERR_SCENE,
                            "%s: [physics] shifting = tvf needs a fluid that fills its domain (no free surface): "
                            "the transport velocity's background pressure drives a free surface outward; the "
                            "[fluid] blocks fill %.0f %% of the domain (accepted here: none, lind)",
                            sph_scene_key_where(def, "physics", "shifting", a, sizeof a), 100 * share);
    }
    if (def->pressure_solver != SPH_PSOLVER_EOS && pressure) {
        /* the solvers predict positions without wrapping them around a
         * periodic axis, so pairs across the seam are lost */
        if (def->periodic)
            return sph_fail(err, SPH_ERR_SCENE,
                            "%s: [physics] pressure_solver = %s does not run on a periodic domain yet (its predicted "
                            "positions are not wrapped; [domain] periodic at %s); accepted there: eos",
                            sph_scene_key_where(def, "physics", "pressure_solver", a, sizeof a),
                            sph_pressure_solver_names[def->pressure_solver],
                            sph_scene_key_where(def, "domain", "periodic", b, sizeof b));
        /* a free surface's particles sum less than rho_rest, and each PCISPH
         * iteration lowers their pressure further: lesson 11's dam break
         * reached -2e5 Pa at its surface and the watchdog at step 32; DFSPH
         * holds kappa at -kappa_v */
        if (def->pressure_solver == SPH_PSOLVER_PCISPH && def->negative_pressure == SPH_NEGP_KEEP)
            return sph_fail(err, SPH_ERR_SCENE,
                            "%s: [physics] pressure_solver = pcisph with negative_pressure = keep (at %s): a free "
                            "surface's particles sum less than the rest density, and each iteration pulls them in "
                            "harder, without bound; accepted together: negative_pressure = clamp (dfsph runs keep)",
                            sph_scene_key_where(def, "physics", "pressure_solver", a, sizeof a),
                            sph_scene_key_where(def, "physics", "negative_pressure", b, sizeof b));
        /* the solvers hold the lattice's rest density for every particle;
         * a hydrostatic start gives the particles different masses */
        for (int k = 0; k < def->n_blocks; k++)
            if (def->blocks[k].initial_pressure == SPH_INITP_HYDROSTATIC)
                return sph_fail(err, SPH_ERR_SCENE,
                                "%s: [fluid %s] initial_pressure = hydrostatic with [physics] pressure_solver = %s (at "
                                "%s): the solver holds one rest density for all particles, the hydrostatic start "
                                "gives each its own mass; accepted together: initial_pressure = none, or "
                                "pressure_solver = eos",
                                block_key_where(def, k, "initial_pressure", a, sizeof a), def->blocks[k].name,
                                sph_pressure_solver_names[def->pressure_solver],
                                sph_scene_key_where(def, "physics", "pressure_solver", b, sizeof b));
    }
    /* a hydrostatic start is the column at rest under the full gravity */
    for (int k = 0; k < def->n_blocks; k++) {
        if (def->blocks[k].initial_pressure != SPH_INITP_HYDROSTATIC) continue;
        double g2 = 0;
        for (int d = 0; d < def->dim; d++) g2 += (double)def->gravity[d] * def->gravity[d];
        block_key_where(def, k, "initial_pressure", a, sizeof a);
        if (!(def->effects & SPH_EFFECT(GRAVITY)) || g2 == 0)
            return sph_fail(err, SPH_ERR_SCENE,
                            "%s: [fluid %s] initial_pressure = hydrostatic: the scene has no gravity (add the effect "
                            "gravity, or set initial_pressure = none)",
                            a, def->blocks[k].name);
        if (!pressure)
            return sph_fail(err, SPH_ERR_SCENE,
                            "%s: [fluid %s] initial_pressure = hydrostatic: the scene has no pressure effect (set "
                            "initial_pressure = none)",
                            a, def->blocks[k].name);
        if (def->gravity_ramp > 0)
            return sph_fail(err, SPH_ERR_SCENE,
                            "%s: [fluid %s] initial_pressure = hydrostatic with [physics] gravity_ramp = %g (at %s): "
                            "the ramp starts from no gravity, so the column would not be at rest; set one of them "
                            "(initial_pressure = none, or gravity_ramp = 0)",
                            a, def->blocks[k].name, (double)def->gravity_ramp,
                            sph_scene_key_where(def, "physics", "gravity_ramp", b, sizeof b));
    }
    /* Verlet lists hold pairs out to h (1 + skin): only the passes whose
     * kernels vanish beyond h (and whose vector loops mask r >= h) may walk
     * them; the others would count the margin's pairs */
    if (def->skin > 0)
        for (int p = 0; p < SPH_PASS_COUNT; p++) {
            if (!(sph_passes[p]->reads & SPH_RES_LISTS) || sph_passes[p]->skip_reason(def)) continue;
            if (p == SPH_PASS_DENSITY || p == SPH_PASS_PRESSURE_FORCE || p == SPH_PASS_VISCOSITY) continue;
            return sph_fail(err, SPH_ERR_SCENE,
                            "%s: [search] skin = %g: the %s pass walks the neighbour lists and does not yet skip "
                            "their pairs beyond h; Verlet lists run with density, pressure_force and viscosity only "
                            "(accepted here: skin = 0)",
                            sph_scene_key_where(def, "search", "skin", a, sizeof a), (double)def->skin, sph_passes[p]->name);
        }
    /* compact lists are read by the passes of the ladder's levels (density and the
     * forces); the others are not tried with them */
    if (def->compact_lists == SPH_ON)
        for (int p = 0; p < SPH_PASS_COUNT; p++) {
            if (!(sph_passes[p]->reads & SPH_RES_LISTS) || sph_passes[p]->skip_reason(def)) continue;
            if (p == SPH_PASS_DENSITY || p == SPH_PASS_PRESSURE_FORCE || p == SPH_PASS_VISCOSITY) continue;
            return sph_fail(err, SPH_ERR_SCENE,
                            "%s: [search] compact_lists = on: the %s pass walks the neighbour lists and is not "
                            "measured with compact ones; they run with density, pressure_force and viscosity only "
                            "(accepted here: off)",
                            sph_scene_key_where(def, "search", "compact_lists", a, sizeof a), sph_passes[p]->name);
        }
    /* field_pressure is the pressure of a velocity field: without one it would
     * do nothing, silently */
    for (int k = 0; k < def->n_blocks; k++)
        if (def->blocks[k].field_pressure == SPH_ON && def->blocks[k].field == SPH_VFIELD_UNIFORM)
            return sph_fail(err, SPH_ERR_SCENE,
                            "%s: [fluid %s] field_pressure = on needs a velocity field with a pressure (field = "
                            "taylor-green); this block's field is uniform",
                            block_key_where(def, k, "field_pressure", a, sizeof a), def->blocks[k].name);
    return SPH_ERR_OK;
}
