# bench/prt.mk — `make bench-prt` (issue 19, seed 003 Tables 5.2-5.17): PRT
# transfer, CPCA vs geometry coherence vs super-clusters vs both on the
# dragon at 48k triangles and the bunny, and the client's relight cost per
# vertex. Writes build/bench/sections/70-prt.md (pasted into
# docs/benchmarks.md) and build/bench/prt-overdraw.svg (docs/prt-overdraw.svg).
PRT_BENCH := $(BIN)/prt-bench
HOST_TOOLS += $(PRT_BENCH)

$(PRT_BENCH): $(BUILD)/host/bench/prt_bench.o $(BUILD)/host/tools/lib/options.o $(BUILD)/host/libserver.a \
              $(BUILD)/rel/liblumo_raster.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ $(SERVER_LIBS)

PRT_BENCH_MODELS := $(BUILD)/data/models/dragon_48k.ply $(BUILD)/data/models/bunny.obj
PRT_BENCH_ARGS   ?= --order 6 --strata 32 --bounces 1 --components 8 --alpha 0.05 --alpha2 8 --alpha-sweep 0,0.05,0.5,2,8,32 \
                    --clusters 64,128,192,256

BENCH_STEPS += bench-prt
.PHONY: bench-prt
bench-prt: $(PRT_BENCH)
	@mkdir -p $(BUILD)/bench/sections
	$(PRT_BENCH) --out $(BUILD)/bench/sections/70-prt.md --plot $(BUILD)/bench/prt-overdraw.svg \
	    --cmd "make bench-prt ($(PRT_BENCH) $(PRT_BENCH_ARGS) $(PRT_BENCH_MODELS))" $(PRT_BENCH_ARGS) $(PRT_BENCH_MODELS)
	@cat $(BUILD)/bench/sections/70-prt.md
