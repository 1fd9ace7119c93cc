# bench/raster.mk — soft rasterizer vs Mesa (llvmpipe, softpipe) through OSMesa.
.PHONY: bench-raster
BENCH_STEPS += bench-raster
bench-raster: $(BIN)/lumo-render $(BIN)/lumo-bake $(BIN)/lumo-raster-ram
	sh bench/raster.sh $(BUILD)
