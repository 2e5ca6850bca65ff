/* The field registry and the pass table: storage by number and by name are
 * the same arrays, what a pass reads is there whenever it runs, every field
 * of kind ACCELERATION is integrated, and the table's names resolve. */
#include <criterion/criterion.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "sph_overlay.h"
#include "test_util.h"

/* A scene with every effect (sph_effect_names), so every pass runs and every field exists. */
static const char *full_scene(void)
{
    static char ini[1024];
    char effects[512] = "";
    for (int e = 0; e < SPH_EFFECT_COUNT; e++) {
        strcat(effects, sph_effect_names[e]);
        strcat(effects, " ");
    }
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=%s\n"
             "[domain]\nmax=1 1\n[fluid a]\nmin=0 0\nmax=0.3 0.3\nspacing=0.02\n[kernels]\nh=0.04\n",
             effects);
    return ini;
}
#define FULL full_scene()

/* Every effect but cohesion, with surface_tension = akinci (which refuses the
 * effect cohesion and runs its pass itself) and xsph: every force field. */
static const char *full_surface_scene(void)
{
    static char ini[1024];
    char effects[512] = "";
    for (int e = 0; e < SPH_EFFECT_COUNT; e++) {
        if (e == SPH_EFFECT_BIT_COHESION) continue;
        strcat(effects, sph_effect_names[e]);
        strcat(effects, " ");
    }
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=%s\n"
             "[domain]\nmax=1 1\n[fluid a]\nmin=0 0\nmax=0.3 0.3\nspacing=0.02\n[kernels]\nh=0.04\n"
             "[physics]\nsurface_tension=akinci\nxsph=0.1\n",
             effects);
    return ini;
}

Test(fields, named_members_are_the_registry_arrays)
{
    /* the union's two views must be the same storage, member by member */
#define CHECK_MEMBER(ID, name, comps, unit, unit2, kind, made_by, check, colour, label, about)                                    \
    cr_assert_eq(offsetof(sph_particles, name), offsetof(sph_particles, field[SPH_FIELD_##ID]), #name);
    SPH_FIELDS(CHECK_MEMBER)
#undef CHECK_MEMBER
    sph_sim *sim = test_sim(FULL, 1);
    cr_assert_eq(sim->P.rho, sim->P.field[SPH_FIELD_RHO][0]);
    cr_assert_eq(sim->P.acc_v[1], sim->P.field[SPH_FIELD_ACC_V][1]);
    sph_sim_destroy(sim);
}

Test(fields, names_units_and_makers_are_consistent)
{
    for (int f = 0; f < SPH_FIELD_COUNT; f++) {
        const sph_field_info *fi = &sph_field_infos[f];
        cr_assert(fi->name && *fi->name && fi->unit && *fi->unit && fi->about && *fi->about, "field %d", f);
        cr_assert_eq(sph_field_find(fi->name), f, "%s", fi->name);
        /* a field made for a pass is written by some pass */
        if (fi->made_by != SPH_PASS_COUNT) {
            bool written = false;
            for (int p = 0; p < SPH_PASS_COUNT; p++) written |= (sph_passes[p]->writes & SPH_FIELD_BIT(f)) != 0;
            cr_assert(written, "field %s is allocated for pass %s but no pass writes it", fi->name,
                      sph_passes[fi->made_by]->name);
        }
        if (fi->kind == SPH_KIND_ACCELERATION) cr_assert(fi->vector, "%s: an acceleration is a vector", fi->name);
        if (*fi->colour) cr_assert_geq(sph_color_field_find(fi->colour), 0, "%s: colour %s", fi->name, fi->colour);
    }
    cr_assert_eq(sph_field_find("no_such_field"), -1);
}

Test(fields, pass_table_rows_are_complete)
{
    for (int p = 0; p < SPH_PASS_COUNT; p++) {
        const sph_pass *ps = sph_passes[p];
        cr_assert(ps->name && ps->summary && ps->skip_reason && ps->describe && ps->run, "pass %d", p);
        cr_assert(ps->writes != 0, "pass %s writes nothing", ps->name);
        cr_assert((int)ps->group >= 0 && ps->group < SPH_GROUP_COUNT, "%s", ps->name);
        if (ps->highlight)
            cr_assert_geq(sph_color_field_find(ps->highlight), 0, "pass %s highlights unknown colour %s", ps->name,
                          ps->highlight);
    }
}

/* Whatever a pass in the pipeline reads is allocated, in every shipped kind of scene. */
Test(fields, what_a_running_pass_reads_is_allocated)
{
    const char *scenes[] = {
        FULL,
        full_surface_scene(),
        "[scene]\ndimension=2\neffects=gravity\n[domain]\nmax=1 1\n[fluid a]\nmin=0 0\nmax=0.2 0.2\nspacing=0.02\n",
        "[scene]\ndimension=3\neffects=density\n[domain]\nmax=1 1 1\n[fluid a]\nmin=0 0 0\nmax=0.1 0.1 0.1\n"
        "spacing=0.02\n[kernels]\nh=0.04\n",
    };
    for (size_t s = 0; s < sizeof scenes / sizeof *scenes; s++) {
        sph_sim *sim = test_sim(scenes[s], 1);
        for (int p = 0; p < SPH_PASS_COUNT; p++) {
            if (!sim->in_pipeline[p]) continue;
            for (int f = 0; f < SPH_FIELD_COUNT; f++)
                if ((sph_passes[p]->reads & SPH_FIELD_BIT(f)) &&
                    !(sph_field_infos[f].kind == SPH_KIND_ACCELERATION)) /* integrate sums those present */
                    cr_assert(sim->P.field[f][0], "scene %zu: pass %s reads %s, which is not allocated", s,
                              sph_passes[p]->name, sph_field_infos[f].name);
        }
        sph_sim_destroy(sim);
    }
}

/* Integration adds dt times the sum of every acceleration field to the velocity. */
Test(fields, integration_sums_every_acceleration_field)
{
    sph_sim *sim = test_sim(full_surface_scene(), 1);
    sph_particles *P = &sim->P;
    int n_acc = 0;
    for (int f = 0; f < SPH_FIELD_COUNT; f++) {
        if (sph_field_infos[f].kind != SPH_KIND_ACCELERATION) continue;
        /* the pressure solvers' are alternatives to acc_p (pressure_solver), not in this scene */
        if (sph_field_infos[f].made_by == SPH_PASS_PCISPH || sph_field_infos[f].made_by == SPH_PASS_DFSPH) continue;
        /* csf's and stress's are alternatives to akinci's curvature term (surface_tension) */
        if (sph_field_infos[f].made_by == SPH_PASS_CSF || sph_field_infos[f].made_by == SPH_PASS_SURFACE_STRESS)
            continue;
        cr_assert(P->field[f][0], "%s not allocated in a scene with every effect", sph_field_infos[f].name);
        n_acc++;
        for (uint32_t i = 0; i < sim->n; i++)
            for (int d = 0; d < sim->dim; d++) P->field[f][d][i] = (float)(1 << n_acc) * (d ? -1.0f : 1.0f);
    }
    cr_assert_geq(n_acc, 3);
    float want = 0;
    for (int k = 1; k <= n_acc; k++) want += (float)(1 << k);
    for (uint32_t i = 0; i < sim->n; i++) P->vel[0][i] = P->vel[1][i] = 0.0f;
    sim->dt = 1e-3f;
    test_run_pass(sim, SPH_PASS_INTEGRATE);
    for (uint32_t i = 0; i < sim->n; i++) {
        cr_assert_float_eq(P->vel[0][i], 1e-3f * want, 1e-6f, "particle %u: v_x %g", i, P->vel[0][i]);
        cr_assert_float_eq(P->vel[1][i], -1e-3f * want, 1e-6f, "particle %u: v_y %g", i, P->vel[1][i]);
    }
    sph_sim_destroy(sim);
}

Test(fields, mask_names_follow_the_registry)
{
    char buf[128];
    sph_mask_names(SPH_BIT(VEL) | SPH_BIT(POS), buf, (int)sizeof buf);
    cr_assert_str_eq(buf, "pos vel");
    sph_mask_names(SPH_RES_LISTS, buf, (int)sizeof buf);
    cr_assert_str_eq(buf, "nbr_start nbr");
    sph_mask_names(SPH_BIT(ACC_P) | SPH_RES_ENTRIES, buf, 8); /* truncated, still terminated */
    cr_assert(strlen(buf) < 8);
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        cr_assert_eq((SPH_MASK_ACCELERATIONS & SPH_FIELD_BIT(f)) != 0, sph_field_infos[f].kind == SPH_KIND_ACCELERATION,
                     "%s", sph_field_infos[f].name);
    cr_assert(SPH_MASK_ACCELERATIONS & SPH_BIT(ACC_P));
}

/* The watchdog checks what a pass writes, by the registry's check column:
 * a NaN in a field the pass wrote names that pass and field. */
Test(fields, watchdog_checks_the_fields_a_pass_writes)
{
    sph_sim *sim = test_sim(FULL, 1);
    sph_sim_step(sim);
    cr_assert(!sim->alarm.raised, "%s", sim->alarm.what);
    /* poison the viscous acceleration, then run the viscosity pass' check */
    sim->P.acc_v[0][3] = NAN;
    sph_watchdog_check(sim, SPH_PASS_VISCOSITY);
    cr_assert(sim->alarm.raised);
    cr_assert_eq(sim->alarm.field, SPH_FIELD_ACC_V);
    cr_assert_eq(sim->alarm.particle, 3u);
    cr_assert(strstr(sim->alarm.what, "acc_v"), "%s", sim->alarm.what);
    sph_sim_destroy(sim);
}
