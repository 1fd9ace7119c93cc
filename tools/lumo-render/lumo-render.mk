# tools/lumo-render/lumo-render.mk — lumo-render, the client's renderer on
# Linux (soft, osmesa and egl backends; packages or the server's default
# scene). PNG files and file reads come from the desktop library
# build/host/libhost.a (tools/lib/hostlib.mk), scenes from the server
# library build/host/libserver.a (server/server.mk). Fragments are included
# in any order, so other fragments' outputs are named literally here.
#
# The GL backends (rasterizer/gl, osmesa, egl) are desktop objects built
# here; they reach GL through get-proc-address, so no libGL is linked.
RASTER_GL_OBJS := $(BUILD)/host/rasterizer/gl/raster_gl.o \
                  $(BUILD)/host/rasterizer/osmesa/raster_osmesa.o \
                  $(BUILD)/host/rasterizer/egl/raster_egl.o
# the GL backends' shadow maps (rasterizer/gl/raster_gl_shadow.c)
RASTER_GL_OBJS += $(BUILD)/host/rasterizer/gl/raster_gl_shadow.o
RASTER_GL_LIBS := -lOSMesa -lEGL
RENDER_OBJS    := $(patsubst %,$(BUILD)/host/tools/lumo-render/%.o,lumo_render package_load session_scene render_backend \
                  prt_render)

$(BUILD)/host/rasterizer/gl/raster_gl.o: HOST_CFLAGS += -Irasterizer/gl

# The scene builder (mesh_build.h: the mesh container, generated quads and
# spheres) and the scene conversion (scene_convert.h: the server's scene
# model, cameras and lights to the rasterizer's fixed point, strings through
# the server's parsers) are a library of their own, linked by lumo-render
# (desktop build) and by the soft rasterizer's unit tests (test build,
# ASan/UBSan: rasterizer/rasterizer.mk). Both builds take the scene room
# from the server library (server/server.mk): lumo-render builds its scenes
# there (default scene, assimp import), as lumo-bake does.
MESH_BUILD_SRCS := mesh_build scene_convert
$(BUILD)/host/libmesh_build.a: $(patsubst %,$(BUILD)/host/tools/lumo-render/%.o,$(MESH_BUILD_SRCS))
	rm -f $@ && ar rcs $@ $^
$(BUILD)/tests/libmesh_build.a: $(patsubst %,$(BUILD)/tests/tools/lumo-render/%.o,$(MESH_BUILD_SRCS))
	rm -f $@ && ar rcs $@ $^

HOST_TOOLS += $(BIN)/lumo-render

$(BIN)/lumo-render: $(RENDER_OBJS) $(RASTER_GL_OBJS) $(BUILD)/host/libmesh_build.a $(BUILD)/host/libserver.a \
                    $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo_raster.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ $(RASTER_GL_LIBS) $(SERVER_LIBS)
