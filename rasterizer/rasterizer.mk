# rasterizer/rasterizer.mk — the soft rasterizer (client rules: C99, no heap,
# no float), built into liblumo_raster.a by the top Makefile (clients that
# draw link it before liblumo.a). The GL backends are a desktop library of
# their own (rasterizer/gl/gl.mk).
CLIENT_SRCS += $(sort $(wildcard rasterizer/soft/*.c))

# The sRGB and sine tables are data generated once by a committed script.
.PHONY: raster-tables
raster-tables:
	python3 rasterizer/soft/gen_tables.py > rasterizer/soft/raster_tables.c

# Unit tests of the soft rasterizer (tests/unit/test_raster*.c) build their
# scenes with lumo-render's scene builder and read camera and light strings
# through its scene conversion, in their test build (floats are fine in
# tests: tools/lumo-render/lumo-render.mk). The conversion parses with the
# server's scene room and test_raster_ivg encodes its bundles with the
# server's IVG encoder: both come from the server library. A test that
# builds server scenes from files (assimp) adds $(SERVER_LIBS) through
# RASTER_UNIT_LDLIBS_<test>. Libraries are named literally: fragments are
# included in any order.
RASTER_UNIT_TESTS := $(patsubst tests/unit/%.c,$(BUILD)/tests/bin/%,$(wildcard tests/unit/test_raster*.c))
RASTER_UNIT_LIBS  := $(BUILD)/tests/libmesh_build.a $(BUILD)/host/libserver.a $(BUILD)/san/liblumo_raster.a \
                     $(BUILD)/san/liblumo.a
# The server library here is its desktop build (-O2, no sanitizers), as in
# tests/server: the scene parsers and the IVG encoder these tests call run
# unsanitized (only the client code they drive is under ASan/UBSan).

# test_raster_scene builds the server's default scene and imports an OBJ.
RASTER_UNIT_LDLIBS_test_raster_scene = $(SERVER_LIBS)
# test_raster_shadow traces its reference shadows with the server's Embree tracer.
RASTER_UNIT_LDLIBS_test_raster_shadow = $(SERVER_LIBS)
RASTER_UNIT_LDLIBS_test_raster_camera = $(SERVER_LIBS)

$(RASTER_UNIT_TESTS): $(BUILD)/tests/bin/%: $(BUILD)/tests/tests/unit/%.o $(RASTER_UNIT_LIBS)
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -pthread -o $@ $< $(RASTER_UNIT_LIBS) $(RASTER_UNIT_LDLIBS_$*) $(TEST_LDLIBS)
