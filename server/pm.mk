# server/pm.mk — progressive meshes (issue 5): the server build (half-edge
# collapse, stream writer, libdraco shim), the lumo-pm tool, the pm tests
# and the pm benchmark. Included before server/server.mk, whose tools link
# LUMO_SERVER_EXTRA_OBJS/LIBS (lumo-inspect gets server/inspect_pm.c).
PM_SERVER_SRCS := server/pm_clean.c server/pm_simplify.c server/pm_build.c server/pm_stream.c \
                  server/pm_client.c server/pm_load.c server/pm_pack.c
PM_OBJS        := $(patsubst %.c,$(BUILD)/host/%.o,$(PM_SERVER_SRCS)) $(BUILD)/host/server/draco_shim.o
PM_LIBS        := -ldraco -lstdc++ -lm

LUMO_SERVER_EXTRA_OBJS += $(PM_OBJS)
LUMO_SERVER_EXTRA_LIBS += $(PM_LIBS)

HOST_TOOLS += $(BIN)/lumo-pm
PM_TOOL_OBJS := $(BUILD)/host/server/pm_tool.o $(BUILD)/host/server/pm_bench.o

$(BIN)/lumo-pm: $(PM_TOOL_OBJS) $(PM_OBJS) $(BUILD)/host/libserver.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $(PM_TOOL_OBJS) $(PM_OBJS) $(BUILD)/host/libserver.a $(BUILD)/rel/liblumo.a \
	    -lembree3 -lassimp -lpng $(PM_LIBS)

# ---- tests: tests/pm/pm_check drives server build + stream + the sanitizer
# build of the client over generated meshes and the dragon (TEST_STEPS).
PM_CHECK := $(BUILD)/tests/bin/pm_check
PM_CHECK_OBJS := $(BUILD)/tests/tests/pm/pm_check.o $(BUILD)/tests/tests/pm/pm_meshes.o
PM_MODELS := $(BUILD)/data/models

$(PM_CHECK): $(PM_CHECK_OBJS) $(PM_OBJS) $(BUILD)/host/libserver.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -pthread -o $@ $(PM_CHECK_OBJS) $(PM_OBJS) $(BUILD)/host/libserver.a \
	    $(BUILD)/san/liblumo.a -lembree3 -lassimp -lpng $(PM_LIBS)

TEST_STEPS += test-pm
.PHONY: test-pm
test-pm: $(PM_CHECK)
	@for g in "tiny --batch 1" "sphere --batch 1" "grid --batch 1" "cornell --batch 7" \
	          "scan --batch 3" "sphere --batch 250 --bits 16" "cornell --batch 5 --absolute"; do \
	    $(PM_CHECK) --gen $$g || true; done
	@for m in "dragon_11k.ply --batch 1" "dragon_11k.ply --batch 250" "dragon_48k.ply --batch 250"; do \
	    set -- $$m; f=$(PM_MODELS)/$$1; shift; \
	    if [ -f $$f ]; then $(PM_CHECK) $$f "$$@" || true; \
	    else echo "RESULT: 0 passed, 1 failed ($$f missing: run tools/setup.sh)"; fi; done
