# Overlay draw lists (src/overlay/): what the overlays show (grid, cells,
# neighbours, keys, collisions, arrows, HUD text), built from a simulation as
# plain lines, points and labels in world space. No GL: the renderer
# (src/render/) draws the lists, and the tests check them without a context.
# Included by the top Makefile.

OVERLAY_OBJ := $(patsubst %,$(BUILD)/overlay/%.o,sph_overlay sph_colour sph_hud)

MOD_OBJ        += $(OVERLAY_OBJ)
# A base layer: linked after the module libraries that use it, before the core.
BASE_TEST_LIBS += $(BUILD)/overlay/libsphoverlay.a

$(BUILD)/sphlab-tests: $(BUILD)/overlay/libsphoverlay.a

$(BUILD)/overlay/libsphoverlay.a: $(OVERLAY_OBJ)
	rm -f $@ && ar rcs $@ $^

$(BUILD)/overlay/%.o: src/overlay/%.c src/overlay/*.h src/core/*.h | $(BUILD)/overlay
	$(CC) $(CFLAGS) $(CORE_CFLAGS) -Isrc/overlay -c -o $@ $<

$(BUILD)/overlay:
	mkdir -p $@

# Warnings are errors under clang too.
.PHONY: check-clang-overlay
check-clang: check-clang-overlay
check-clang-overlay:
	$(MAKE) CC=clang BUILD=build-clang $(patsubst $(BUILD)/%,build-clang/%,$(OVERLAY_OBJ))

# The registry's tests check that every colour name a field or pass gives exists.
$(BUILD)/tests/test_fields.o: CORE_CFLAGS += -Isrc/overlay
# The hash health tests read the HUD's rows.
$(BUILD)/tests/test_hash_health.o: CORE_CFLAGS += -Isrc/overlay
# and are rebuilt when the overlay's header changes (sph_hud_info's layout, for one)
$(BUILD)/tests/test_hash_health.o $(BUILD)/tests/test_fields.o: src/overlay/*.h
