# rasterizer/rasterizer.mk — the soft rasterizer (client rules: C99, no heap,
# no float), built into liblumo_raster.a by the top Makefile (clients that
# draw link it before liblumo.a). The GL backends are desktop objects linked by
# tools/lumo-render/lumo-render.mk.
CLIENT_SRCS += $(sort $(wildcard rasterizer/soft/*.c))

# The sRGB and sine tables are data generated once by a committed script.
.PHONY: raster-tables
raster-tables:
	python3 rasterizer/soft/gen_tables.py > rasterizer/soft/raster_tables.c

# Unit tests of the soft rasterizer (tests/unit/test_raster*.c) build their
# scenes with lumo-render's scene builder, in its test build (floats are fine
# in tests: tools/lumo-render/lumo-render.mk); test_raster_ivg encodes its
# bundles with the server's IVG encoder (server library). Libraries are named
# literally: fragments are included in any order.
RASTER_UNIT_TESTS := $(patsubst tests/unit/%.c,$(BUILD)/tests/bin/%,$(wildcard tests/unit/test_raster*.c))
RASTER_UNIT_LIBS   = $(RASTER_UNIT_LIBS_$*) $(BUILD)/tests/libmesh_build.a $(BUILD)/san/liblumo_raster.a \
                     $(BUILD)/san/liblumo.a
# TODO(merge): the server library is its desktop build (-O2, no sanitizers);
# a test build of it (server/ fragment, server branch) would put the encoder
# back under ASan/UBSan here, as the single test-flag object did. Wherever
# the server branch moves ivg_encode.c, this archive link stays as it is.
RASTER_UNIT_LIBS_test_raster_ivg := $(BUILD)/host/libserver.a

$(RASTER_UNIT_TESTS): $(BUILD)/tests/bin/%: $(BUILD)/tests/tests/unit/%.o $(BUILD)/tests/libmesh_build.a \
                      $(BUILD)/san/liblumo_raster.a $(BUILD)/san/liblumo.a
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $< $(RASTER_UNIT_LIBS) $(TEST_LDLIBS)
$(BUILD)/tests/bin/test_raster_ivg: $(BUILD)/host/libserver.a
