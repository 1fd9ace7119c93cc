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
