# tests/pm/pm.mk — end-to-end progressive-mesh checks (issue 5): the server
# build + stream (server/pm/, in build/host/libserver.a) and the sanitizer
# build of the client, on generated meshes and the dragon. Each run prints
# "RESULT: N passed, M failed"; see tests/pm/pm_check.c for the checks.
PM_CHECK := $(BUILD)/tests/bin/pm_check
PM_CHECK_OBJS := $(BUILD)/tests/tests/pm/pm_check.o $(BUILD)/tests/tests/pm/pm_meshes.o
PM_MODELS := $(BUILD)/data/models

$(PM_CHECK): $(PM_CHECK_OBJS) $(BUILD)/host/libserver.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -pthread -o $@ $(PM_CHECK_OBJS) $(BUILD)/host/libserver.a \
	    $(BUILD)/san/liblumo.a $(SERVER_LIBS)

TEST_STEPS += test-pm
.PHONY: test-pm
# A run that crashes prints no RESULT line: the non-zero exit then fails the step.
test-pm: $(PM_CHECK)
	@st=0; for g in "tiny --batch 1" "sphere --batch 1" "grid --batch 1" "cornell --batch 7" \
	          "scan --batch 3" "scan --batch 2 --rounds 0" "sphere --batch 250 --bits 16" "cornell --batch 5 --absolute" "seam --batch 4" "seam --batch 60 --absolute" \
	          "scan --batch 3 --predicted" "sphere --batch 9 --bits 20" "grid --batch 40 --predicted" \
	          "sphere --batch 7 --rank-escape" "scan --batch 3 --rank-escape" \
	          "wall --batch 5 --base 4/2" "box --batch 5 --base 8/12" \
	          "voxel --batch 50 --expect-lattice 1" "sphere --batch 50 --expect-lattice 0" \
	          "scan --batch 3 --lattice on" "cornell --batch 7 --lattice on" "grid --batch 40 --lattice on"; do \
	    $(PM_CHECK) --gen $$g || st=1; done; \
	for m in "dragon_11k.ply --batch 1" "dragon_11k.ply --batch 250" "dragon_11k.ply --batch 250 --rounds 0" "dragon_11k.ply --batch 250 --predicted" "dragon_48k.ply --batch 250" "dragon_11k.ply --batch 250 --lattice on"; do \
	    set -- $$m; f=$(PM_MODELS)/$$1; shift; \
	    if [ -f $$f ]; then $(PM_CHECK) $$f "$$@" || st=1; \
	    else echo "RESULT: 0 passed, 1 failed ($$f missing: run tools/setup.sh)"; st=1; fi; done; exit $$st

# The tools: lumo-pm build, lumo-inspect --stream / --lod N --ply.
TEST_STEPS += test-pm-tools
.PHONY: test-pm-tools
test-pm-tools: $(BIN)/lumo-pm $(BIN)/lumo-inspect $(BIN)/lumo-bake
	@sh tests/pm/pm_tools.sh $(BIN) $(PM_MODELS)/dragon_11k.ply $(BUILD)/tests/pm-tools
