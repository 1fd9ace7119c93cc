# bench/ivg_compact.mk — the packed IVG grid against two peers in one run:
# the SDK before it (entries unpacked) and round one of the packed grid
# (whole pyramid): memory per grid vertex and push-pull / sampling
# instructions (bench/ivg_compact.sh; a section of docs/benchmarks.md). The
# peer commits are the main branch before each change.
IVG_MEMORY := $(BIN)/lumo-bench-ivg-memory
IVG_COMPACT_PEER ?= f78dc12
IVG_COMPACT_ROUND1 ?= 67be7e5
HOST_TOOLS += $(IVG_MEMORY)
$(IVG_MEMORY): $(BUILD)/host/bench/ivg_memory.o $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^

BENCH_STEPS += bench-ivg-compact
.PHONY: bench-ivg-compact
bench-ivg-compact: $(IVG_BENCH) $(IVG_MEMORY)
	@sh bench/ivg_compact.sh $(BUILD) $(IVG_COMPACT_PEER) $(IVG_COMPACT_ROUND1) $(IVG_BENCH) $(IVG_MEMORY)
