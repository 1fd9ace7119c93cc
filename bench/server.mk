# bench/server.mk — IVG bake and reference renderer benchmarks (issue 3).
# The server library and the desktop library (PNG, tone mapping, Delta E)
# are named literally (server/server.mk, tools/lib/hostlib.mk).
BENCH_STEPS += bench-bake
.PHONY: bench-bake
$(BUILD)/host/bench/lumo-bench-bake: $(BUILD)/host/bench/bench_bake.o $(BUILD)/host/libserver.a \
                                     $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $< $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a \
	    $(SERVER_LIBS)
bench-bake: $(BUILD)/host/bench/lumo-bench-bake
	@mkdir -p $(BUILD)/bench/sections
	$(BUILD)/host/bench/lumo-bench-bake > $(BUILD)/bench/sections/30-bake.md.tmp
	mv $(BUILD)/bench/sections/30-bake.md.tmp $(BUILD)/bench/sections/30-bake.md
