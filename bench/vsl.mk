# bench/vsl.mk — make bench-vsl (docs/benchmarks.md "Dynamic scenes"): the
# dynamic engine's pieces (server/vsl/, docs/dynamic.md) against their
# peers in one run: Algorithm 1 vs the naive removal, k-d tree vs linear
# scan, instanced vs flat Embree scene, and the engine's photon rate; then
# seed 004's Table 2 (lumo-vsl-render --bench: ms per frame at 800x600 on
# Mesa llvmpipe against the VSL count, deferred shading against its peer,
# the whole scene drawn per VSL) on the Cornell box of Figure 11 and the
# Cornell box with the 48k-triangle dragon. VSL_GL_SIZE=1280x1024 gives
# Table 3; VSL_GL_FRAMES the frames timed per cell.
VSL_BENCH := $(BIN)/lumo-bench-vsl
HOST_TOOLS += $(VSL_BENCH)
$(VSL_BENCH): $(BUILD)/host/bench/vsl_bench.o $(BUILD)/host/libserver.a $(BUILD)/rel/liblumo_net.a \
              $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ $(SERVER_LIBS)

VSL_GL_SIZE   ?= 800x600
VSL_GL_FRAMES ?= 3
VSL_GL_BENCH   = LP_NUM_THREADS=2 $(BIN)/lumo-vsl-render --bench --size $(VSL_GL_SIZE) --frames $(VSL_GL_FRAMES) \
                 --pool 50000 --batch 20000

BENCH_STEPS += bench-vsl
.PHONY: bench-vsl bench-vsl-gl
bench-vsl: $(VSL_BENCH) bench-vsl-gl
	@$(VSL_BENCH) tools/dynamic-demo/cornell_dynamic.txt

bench-vsl-gl: $(BIN)/lumo-vsl-render
	@$(VSL_GL_BENCH) tools/dynamic-demo/cornell_dynamic.txt
	@$(VSL_GL_BENCH) --default $(BUILD)/data/models/dragon_48k.ply
