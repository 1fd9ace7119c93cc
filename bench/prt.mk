# bench/prt.mk — `make bench-prt` (issue 19, seed 003 Tables 5.2-5.17): PRT
# transfer, CPCA vs geometry coherence vs super-clusters vs both on the
# dragon at 48k triangles and the bunny, and the client's relight cost per
# vertex. Writes build/bench/sections/70-prt.md (pasted into
# docs/benchmarks.md) and build/bench/prt-overdraw.svg (docs/prt-overdraw.svg).
PRT_BENCH := $(BIN)/prt-bench
HOST_TOOLS += $(PRT_BENCH)

# The fps column draws with the GL backends' PRT multipass on OSMesa
# (build/host/libraster_gl.a, rasterizer/gl/gl.mk; named literally:
# fragments are included in any order).
$(PRT_BENCH): $(BUILD)/host/bench/prt_bench.o $(BUILD)/host/tools/lib/options.o $(BUILD)/host/libraster_gl.a \
              $(BUILD)/host/libserver.a $(BUILD)/rel/liblumo_raster.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ -lOSMesa $(SERVER_LIBS)

PRT_BENCH_MODELS := $(BUILD)/data/models/dragon_48k.ply $(BUILD)/data/models/bunny.obj
PRT_BENCH_ARGS   ?= --order 6 --strata 32 --bounces 1 --components 8 --alpha 0.05 --alpha2 8 --alpha-sweep 0,0.05,0.5,2,8,32 \
                    --clusters 64,128,192,256 --fps-frames 15 --size 640x480
# llvmpipe's threads for the fps column: 0 draws in the calling thread, whose
# CPU time is then the frame's whole cost (prt_bench.c gl_fps_of)
PRT_BENCH_LP ?= 0

BENCH_STEPS += bench-prt
.PHONY: bench-prt
bench-prt: $(PRT_BENCH)
	@mkdir -p $(BUILD)/bench/sections
	LP_NUM_THREADS=$(PRT_BENCH_LP) $(PRT_BENCH) --out $(BUILD)/bench/sections/70-prt.md --plot $(BUILD)/bench/prt-overdraw.svg \
	    --cmd "make bench-prt (LP_NUM_THREADS=$(PRT_BENCH_LP) $(PRT_BENCH) $(PRT_BENCH_ARGS) $(PRT_BENCH_MODELS))" $(PRT_BENCH_ARGS) $(PRT_BENCH_MODELS)
	@cat $(BUILD)/bench/sections/70-prt.md
