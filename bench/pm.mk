# bench/pm.mk — progressive-mesh benchmark (issue 5): stream size against
# single-shot Draco, seed 000 Fig. 5 (receive + apply vs batch size), client
# time and memory per batch vs mesh size. Writes build/bench/sections/60-pm.md.
PM_BENCH_MODELS := $(BUILD)/data/models/bunny.obj $(BUILD)/data/models/dragon_11k.ply \
                   $(BUILD)/data/models/dragon_48k.ply $(BUILD)/data/models/dragon_203k.ply \
                   $(BUILD)/data/models/dragon_871k.ply
PM_BENCH_FIG5   := $(BUILD)/data/models/dragon_48k.ply

BENCH_STEPS += bench-pm
.PHONY: bench-pm
bench-pm: $(BIN)/lumo-pm
	@mkdir -p $(BUILD)/bench/sections
	$(BIN)/lumo-pm bench --out $(BUILD)/bench/sections/60-pm.md --fig5 $(PM_BENCH_FIG5) \
	    --cmd "make bench-pm ($(BIN)/lumo-pm bench --fig5 $(PM_BENCH_FIG5) $(PM_BENCH_MODELS))" \
	    $(PM_BENCH_MODELS)

# The size and bit tables alone (no Fig. 5, rounds or callgrind sections):
# minutes instead of hours on a loaded machine. Writes 60-pm-sizes.md.
.PHONY: bench-pm-sizes
bench-pm-sizes: $(BIN)/lumo-pm
	@mkdir -p $(BUILD)/bench/sections
	$(BIN)/lumo-pm bench --sizes-only --out $(BUILD)/bench/sections/60-pm-sizes.md \
	    --cmd "make bench-pm-sizes ($(BIN)/lumo-pm bench --sizes-only $(PM_BENCH_MODELS))" \
	    $(PM_BENCH_MODELS)

# The range code's context priors (docs/progressive-mesh.md §2.3
# "Contexts"): each training mesh's stream coded with the current table,
# the bits per context fitted into sdk/src/pmesh_priors.c and the doc's
# table. The benchmarks' bunny and the held-out CGAL models (homer,
# elephant-with-holes) are not in the training set. A changed table changes
# every stream: run tests/pm/regen_streams.sh after it.
PM_PRIOR_MODELS := $(BUILD)/data/models/dragon_11k.ply $(BUILD)/data/models/dragon_48k.ply \
                   $(BUILD)/data/cgal/camel.off $(BUILD)/data/cgal/cow.off $(BUILD)/data/cgal/fandisk.off \
                   $(BUILD)/data/cgal/blobby_3cc.off $(BUILD)/data/cgal/mech-holes-shark.off
.PHONY: pm-priors
pm-priors: $(BIN)/lumo-pm
	@mkdir -p $(BUILD)/pm-priors
	@for m in $(PM_PRIOR_MODELS); do \
	    $(BIN)/lumo-pm build $$m -o $(BUILD)/pm-priors/stream.lumo --lattice off \
	        --context-stats $(BUILD)/pm-priors/$$(basename $$m).txt >/dev/null || exit 1; done
	python3 tools/pm-priors/pm_priors.py $(patsubst %,$(BUILD)/pm-priors/%.txt,$(notdir $(PM_PRIOR_MODELS))) \
	    --c sdk/src/pmesh_priors.c --doc docs/progressive-mesh.md
