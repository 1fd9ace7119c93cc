# tools/lumo-render/lumo-render.mk — lumo-render, the client's renderer on
# Linux (soft, osmesa and egl backends; packages or generated scenes). PNG
# files and file reads come from the desktop library build/host/libhost.a
# (tools/lib/hostlib.mk). Fragments are included in any order, so other
# fragments' outputs are named literally here.
#
# The GL backends (rasterizer/gl, osmesa, egl) are desktop objects built
# here; they reach GL through get-proc-address, so no libGL is linked.
RASTER_GL_OBJS := $(BUILD)/host/rasterizer/gl/raster_gl.o \
                  $(BUILD)/host/rasterizer/osmesa/raster_osmesa.o \
                  $(BUILD)/host/rasterizer/egl/raster_egl.o
RASTER_GL_LIBS := -lOSMesa -lEGL
RENDER_OBJS    := $(patsubst %,$(BUILD)/host/tools/lumo-render/%.o,lumo_render package_load session_scene render_backend)

$(BUILD)/host/rasterizer/gl/raster_gl.o: HOST_CFLAGS += -Irasterizer/gl

# The scene builder (mesh_build.h: generated meshes, the Cornell box, camera
# and light strings) is a library of its own, linked by lumo-render (desktop
# build) and by the soft rasterizer's unit tests (test build, ASan/UBSan:
# rasterizer/rasterizer.mk).
$(BUILD)/host/libmesh_build.a: $(BUILD)/host/tools/lumo-render/mesh_build.o
	rm -f $@ && ar rcs $@ $^
$(BUILD)/tests/libmesh_build.a: $(BUILD)/tests/tools/lumo-render/mesh_build.o
	rm -f $@ && ar rcs $@ $^

HOST_TOOLS += $(BIN)/lumo-render

$(BIN)/lumo-render: $(RENDER_OBJS) $(RASTER_GL_OBJS) $(BUILD)/host/libmesh_build.a $(BUILD)/host/libhost.a \
                    $(BUILD)/rel/liblumo_raster.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ $(RASTER_GL_LIBS) -lpng -lm
