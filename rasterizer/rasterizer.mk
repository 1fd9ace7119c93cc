# rasterizer/rasterizer.mk — the soft rasterizer (client rules: C99, no heap,
# no float). The GL backends are desktop objects linked by boards/host/host.mk.
CLIENT_SRCS += $(sort $(wildcard rasterizer/soft/*.c))

# The sRGB and sine tables are data generated once by a committed script.
.PHONY: raster-tables
raster-tables:
	python3 rasterizer/soft/gen_tables.py > rasterizer/soft/raster_tables.c

# Unit tests of the soft rasterizer build their scenes with the host mesh
# builder (floats are fine in tests).
$(BUILD)/tests/bin/test_raster: $(BUILD)/tests/boards/host/mesh_build.o
$(BUILD)/tests/bin/test_raster_shading: $(BUILD)/tests/boards/host/mesh_build.o
$(BUILD)/tests/bin/test_raster_ivg: $(BUILD)/tests/boards/host/mesh_build.o $(BUILD)/tests/server/package/ivg_encode.o
