# bench/raster.mk — soft rasterizer vs Mesa (llvmpipe, softpipe) through OSMesa.
.PHONY: bench-raster
BENCH_STEPS += bench-raster
bench-raster: $(BIN)/lumo-render $(BIN)/lumo-bake $(BIN)/lumo-raster-ram
	sh bench/raster.sh $(BUILD)

# lumo's side of the per-vertex comparison with tgx and small3dlib (docs/benchmarks.md, "Round five"; the peers'
# sides are built outside the repository): instructions a frame of its function `frame` under callgrind.
RASTER_PEERS := $(BIN)/raster-peers
$(RASTER_PEERS): $(BUILD)/host/bench/raster_peers.o $(BUILD)/rel/liblumo_raster.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lm
.PHONY: bench-raster-peers
bench-raster-peers: $(RASTER_PEERS)
	@mkdir -p $(BUILD)/bench
	valgrind --tool=callgrind --toggle-collect='frame*' --callgrind-out-file=$(BUILD)/bench/raster_peers.cg \
	    $(RASTER_PEERS) $(BUILD)/data/models/dragon_48k.ply 2>/dev/null
	@awk '/^summary:/ {printf "raster-peers: %.2f M instructions a frame (callgrind, frame(), 3 frames)\n", $$2 / 3e6}' \
	    $(BUILD)/bench/raster_peers.cg
