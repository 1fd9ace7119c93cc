# bench/vsl.mk — make bench-vsl (docs/benchmarks.md "Dynamic scenes"): the
# dynamic engine's pieces (server/vsl/, docs/dynamic.md) against their
# peers in one run: Algorithm 1 vs the naive removal, k-d tree vs linear
# scan, instanced vs flat Embree scene, and the engine's photon rate.
VSL_BENCH := $(BIN)/lumo-bench-vsl
HOST_TOOLS += $(VSL_BENCH)
$(VSL_BENCH): $(BUILD)/host/bench/vsl_bench.o $(BUILD)/host/libserver.a $(BUILD)/rel/liblumo_net.a \
              $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ $(SERVER_LIBS)

BENCH_STEPS += bench-vsl
.PHONY: bench-vsl
bench-vsl: $(VSL_BENCH)
	@$(VSL_BENCH) tools/dynamic-demo/cornell_dynamic.txt
