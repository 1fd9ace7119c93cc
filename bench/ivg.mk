# bench/ivg.mk — the IVG client core's extra build rules: its unit tests link
# the server-side encoder (they build bundles the way the server does), and
# the push-pull / sampling benchmark (BENCH_STEPS += bench-ivg).

# Unit tests: tests/unit/test_ivg*.c also link server/package/ivg_encode.c (built with
# the test flags, sanitizers on). The generic link rule of tests/tests.mk
# picks up the extra object through $^.
IVG_TEST_BINS := $(patsubst tests/unit/%.c,$(BUILD)/tests/bin/%,$(wildcard tests/unit/test_ivg*.c))
$(IVG_TEST_BINS): $(BUILD)/tests/server/package/ivg_encode.o
# Benchmark: build/bin/lumo-bench-ivg (host -O2 against the rel library).
IVG_BENCH := $(BIN)/lumo-bench-ivg
HOST_TOOLS += $(IVG_BENCH)
$(IVG_BENCH): $(BUILD)/host/bench/ivg_bench.o $(BUILD)/host/server/package/ivg_encode.o $(BUILD)/host/tools/lib/options.o \
              $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lm

BENCH_STEPS += bench-ivg
.PHONY: bench-ivg
bench-ivg: $(IVG_BENCH)
	@sh bench/ivg_run.sh $(BUILD) $(IVG_BENCH)
