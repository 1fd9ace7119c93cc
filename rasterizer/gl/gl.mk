# rasterizer/gl/gl.mk — the GL backends as one desktop library,
# build/host/libraster_gl.a: the shared GL renderer (raster_gl.c) and its
# add-ons in their own files (shadow maps, the PRT multipass, seed 004's
# deferred VSL renderer), with the two context makers (rasterizer/osmesa,
# rasterizer/egl). Not client code: floats and the heap are fine here. They
# reach GL through get-proc-address, so no libGL is linked; a tool that
# links the library adds -lOSMesa and/or -lEGL for the contexts it makes.
# A static library: each tool takes only the objects it calls.
RASTER_GL_SRCS := $(sort $(wildcard rasterizer/gl/*.c)) rasterizer/osmesa/raster_osmesa.c rasterizer/egl/raster_egl.c
RASTER_GL_OBJS := $(patsubst %.c,$(BUILD)/host/%.o,$(RASTER_GL_SRCS))

$(filter $(BUILD)/host/rasterizer/gl/%,$(RASTER_GL_OBJS)): HOST_CFLAGS += -Irasterizer/gl

$(BUILD)/host/libraster_gl.a: $(RASTER_GL_OBJS)
	rm -f $@ && ar rcs $@ $^
