# boards/host/host.mk — the Linux host tools of the rasterizer: lumo-render
# (soft, osmesa and egl backends; packages or generated scenes) and
# lumo-compare (side-by-side PNG with Delta E and PSNR). PNG files, image
# metrics and file reads come from the desktop library build/host/libhost.a
# (tools/lib/hostlib.mk, included after this file: named literally here).
#
# The GL backends (rasterizer/gl, osmesa, egl) are desktop objects built
# here; they reach GL through get-proc-address, so no libGL is linked.
RASTER_GL_OBJS := $(BUILD)/host/rasterizer/gl/raster_gl.o \
                  $(BUILD)/host/rasterizer/osmesa/raster_osmesa.o \
                  $(BUILD)/host/rasterizer/egl/raster_egl.o
RASTER_GL_LIBS := -lOSMesa -lEGL
HOST_RENDER_OBJS := $(patsubst %,$(BUILD)/host/boards/host/%.o,mesh_build package_load render_backend)

$(BUILD)/host/rasterizer/gl/raster_gl.o: HOST_CFLAGS += -Irasterizer/gl

HOST_TOOLS += $(BIN)/lumo-render $(BIN)/lumo-compare

$(BIN)/lumo-render: $(BUILD)/host/boards/host/lumo_render.o $(HOST_RENDER_OBJS) $(RASTER_GL_OBJS) \
                    $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ $(RASTER_GL_LIBS) -lpng -lm

$(BIN)/lumo-compare: $(BUILD)/host/boards/host/lumo_compare.o $(BUILD)/host/libhost.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lpng -lm

# Progressive meshes in lumo-render (issue 5): pm vs raw package (mean
# Delta E <= 1), --lod levels, a damaged stream (tests/render/lod.sh).
.PHONY: raster-lod
TEST_STEPS += raster-lod
raster-lod: $(BIN)/lumo-render $(BIN)/lumo-compare $(BIN)/lumo-bake $(BIN)/lumo-inspect
	sh tests/render/lod.sh $(BUILD)

HOST_TOOLS += $(BIN)/lumo-raster-ram
$(BIN)/lumo-raster-ram: $(BUILD)/host/boards/host/raster_ram.o $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^

# make demo (issue 6): bake the default scene, render it on the client with
# and without the IVG, path-trace the server's reference, and place the
# three side by side with the error printed; the progressive meshes at three
# levels of detail side by side (lod.png); plus an orbit of PNG frames.
DEMO_DIR  := $(BUILD)/demo
DEMO_SIZE ?= 640x480
DEMO_SPP  ?= 128
