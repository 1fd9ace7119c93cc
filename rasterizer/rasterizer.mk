# rasterizer/rasterizer.mk — the soft rasterizer (client rules) and the GL
# backends (desktop objects, linked by boards/host/host.mk).
#
# raster_ivg.c adapts lumo_ivg to the rasterizer; it joins the client library
# only once the IVG client (sdk/src/ivg.c) exists, so every client program
# (fuzz targets link all client sources) links.
RASTER_SOFT_SRCS := $(filter-out rasterizer/soft/raster_ivg.c,$(sort $(wildcard rasterizer/soft/*.c)))
ifneq ($(wildcard sdk/src/ivg.c),)
RASTER_SOFT_SRCS += rasterizer/soft/raster_ivg.c
endif
CLIENT_SRCS += $(RASTER_SOFT_SRCS)

# The sRGB and sine tables are data generated once by a committed script.
.PHONY: raster-tables
raster-tables:
	python3 rasterizer/soft/gen_tables.py > rasterizer/soft/raster_tables.c

# Unit tests of the soft rasterizer build their scenes with the host mesh
# builder (floats are fine in tests).
$(BUILD)/tests/bin/test_raster: $(BUILD)/tests/boards/host/mesh_build.o
