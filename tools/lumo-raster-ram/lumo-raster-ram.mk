# tools/lumo-raster-ram/lumo-raster-ram.mk — lumo-raster-ram: the memory the
# soft rasterizer needs per resolution, pixel format and band height, as a
# markdown table (docs/rasterizer.md, bench/raster.sh).
HOST_TOOLS += $(BIN)/lumo-raster-ram

$(BIN)/lumo-raster-ram: $(BUILD)/host/tools/lumo-raster-ram/raster_ram.o $(BUILD)/rel/liblumo_raster.a \
                        $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^
