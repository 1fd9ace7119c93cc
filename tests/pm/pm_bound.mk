# tests/pm/pm_bound.mk — the simplifier's error bound (issue 23): every
# input vertex within max_error of every level's surface (tests/pm/pm_bound.c),
# on a generated scan, the holed sphere, the bunny, the 11k dragon and the
# 106-hole elephant. The simplifier before the attached points failed it on
# the dragon (an input vertex 0.00385 from levels 504-520, limit 0.00264).
PM_BOUND := $(BUILD)/tests/bin/pm_bound
PM_BOUND_OBJS := $(BUILD)/tests/tests/pm/pm_bound.o $(BUILD)/tests/tests/pm/pm_meshes.o

$(PM_BOUND): $(PM_BOUND_OBJS) $(BUILD)/host/libserver.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -pthread -o $@ $(PM_BOUND_OBJS) $(BUILD)/host/libserver.a \
	    $(BUILD)/san/liblumo.a $(SERVER_LIBS)

TEST_STEPS += test-pm-bound
.PHONY: test-pm-bound
test-pm-bound: $(PM_BOUND) $(BUILD)/data/cgal/elephant-with-holes.off
	@st=0; for a in "--gen scan --first 100" "--gen holes" "--gen sphere --max-error 0.01" "$(PM_MODELS)/bunny.obj --first 150" \
	    "$(PM_MODELS)/dragon_11k.ply --max-error 0.01" $(BUILD)/data/cgal/elephant-with-holes.off; do \
	    $(PM_BOUND) $$a || st=1; done; exit $$st
