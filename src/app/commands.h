/* The sphlab commands, written once: main() dispatches from this list and
 * prints its help from it. A module that adds a command adds one line here and
 * defines `int cmd_NAME(int argc, char **argv)` (argv[0] is the command name). */
#ifndef SPH_COMMANDS_H
#define SPH_COMMANDS_H

#define SPH_COMMANDS(X)                                                          \
    X(run, "SCENE.ini", "simulate a scene; print per-pass timings and a summary") \
    X(check, "SCENE.ini", "validate a scene and print the pipeline it resolves to and its hash health") \
    X(plot, "WHAT ...", "charts for a report: ms per pass, --stats series, kernels (PNG + PDF)") \
    X(keys, "[SECTION]", "list the scene keys (of the named sections) with default, unit, meaning") \
    X(render, "SCENE.ini", "simulate headless and write PNG frames (and VTK files)") \
    X(view, "SCENE.ini", "open a window and run the scene live, with overlays") \
    X(hardcases, "", "run the hard cases (odd parameters) and print a verdict for each") \
    X(study, "SCENE.ini", "error against wall time over combinations of knobs (CSV, Pareto chart)") \
    X(estimate, "", "kernel estimate of a known function: error against h and sample count") \
    X(lesson, "N", "the course: list the lessons, open one in the window, or export its figures and report") \
    X(bench, "WHAT", "the optimisation ladder: largest N at 60 steps/s per level, checks, scaling (CSV, JSON, charts)") \
    X(validate, "NAME", "reference problems against published data or exact solutions: CSV, chart, PASS/FAIL (exit 0 pass, 1 fail, 2 usage, 3 run failed)")

#define SPH_COMMAND_DECL(name, args, about) int cmd_##name(int argc, char **argv);
SPH_COMMANDS(SPH_COMMAND_DECL)
#undef SPH_COMMAND_DECL

#endif
