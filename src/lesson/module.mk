# src/lesson: `sphlab lesson`, the course in lessons/ (list, open in the
# window, export figures and a report). Included by the Makefile
# (-include src/*/module.mk). The export calls the core, the bench module
# (src/bench/bench_cmd.h), the plot module (src/plot/plot.h) and the study
# module (src/study/study.h, study_cmd.h) in process, and runs render, view
# and hardcases as child processes
# (src/lesson/lesson.h says why), so it needs no package of its own beyond
# the plot module's. Each lesson's report text is lessons/NN-name/report.md
# and report.fr.md.

# This fragment is read before the Makefile's `all`: keep whatever default
# goal was set so far, so that a rule below never becomes it.
LESSON_SAVED_GOAL := $(.DEFAULT_GOAL)

LESSON_SRC    := cmd_lesson lesson_export lesson_lab lesson_report lesson_run lesson_util lesson_density lesson_forces lesson_search lesson_perf lesson_walls lesson_html
LESSON_CFLAGS := $(shell pkg-config --cflags plplot 2>/dev/null || echo -I/usr/include/plplot)
LESSON_STB    := $(shell pkg-config --cflags stb 2>/dev/null || echo -I/usr/include/stb)
MOD_OBJ       += $(LESSON_SRC:%=$(BUILD)/lesson/%.o)

$(BUILD)/lesson/%.o: src/lesson/%.c src/lesson/*.h src/plot/plot.h src/bench/*.h src/study/*.h src/app/*.h src/core/*.h | $(BUILD)/lesson
	$(CC) $(CFLAGS) $(CORE_CFLAGS) -Isrc/app -Isrc/plot -Isrc/bench -Isrc/study $(LESSON_CFLAGS) -c -o $@ $<

$(BUILD)/lesson:
	mkdir -p $@

# The lesson tests (tests/test_lesson*.c) decode the exported PNGs with
# stb_image (linked through the plot module's MOD_TEST_SYS_LIBS, -lstb).
$(BUILD)/tests/test_lesson.o $(BUILD)/tests/test_lesson%.o: CFLAGS += $(LESSON_STB)

# `make test` compiles the library, app and tests with clang as well; this module's objects too.
check-clang: check-clang-lesson
.PHONY: check-clang-lesson
check-clang-lesson:
	$(MAKE) CC=clang BUILD=build-clang $(LESSON_SRC:%=build-clang/lesson/%.o)

.DEFAULT_GOAL := $(LESSON_SAVED_GOAL)
