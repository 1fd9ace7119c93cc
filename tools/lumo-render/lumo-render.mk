# tools/lumo-render/lumo-render.mk — lumo-render, the client's renderer on
# Linux (soft, osmesa and egl backends; packages or the server's default
# scene). PNG files and file reads come from the desktop library
# build/host/libhost.a (tools/lib/hostlib.mk), scenes from the server
# library build/host/libserver.a (server/server.mk). Fragments are included
# in any order, so other fragments' outputs are named literally here.
#
# The GL backends (rasterizer/gl, osmesa, egl) are the desktop library
# build/host/libraster_gl.a (rasterizer/gl/gl.mk).
RENDER_OBJS    := $(patsubst %,$(BUILD)/host/tools/lumo-render/%.o,lumo_render package_load session_scene render_backend \
                  prt_render)

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

$(BIN)/lumo-render: $(RENDER_OBJS) $(BUILD)/host/libraster_gl.a $(BUILD)/host/libmesh_build.a $(BUILD)/host/libserver.a \
                    $(BUILD)/host/libhost.a $(BUILD)/rel/liblumo_raster.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ -lOSMesa -lEGL $(SERVER_LIBS)
