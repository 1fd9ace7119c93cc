# tools/lib/hostlib.mk — the desktop helper library build/host/libhost.a:
# PNG files, tone mapping, image Delta E / PSNR, whole-file reads, the
# one-line reason a package is refused and the strict command-line value
# parser of every tool (options.h), shared by the server (server/) and the
# host board tools (boards/host/) so that neither depends on the other.
# Headers: tools/lib/include/lumo_host/ (on HOST_CFLAGS and TEST_CFLAGS via
# -Itools/lib/include).
#
# This fragment is included after the server/, boards/ and bench/ fragments,
# so they name the archive literally, $(BUILD)/host/libhost.a, and link it
# after their own objects and libraries, followed by -lpng -lm.
HOST_LIB_MODULES := file_io png_io tonemap image_diff package_msg version_line options
HOST_LIB_OBJS    := $(patsubst %,$(BUILD)/host/tools/lib/%.o,$(HOST_LIB_MODULES))
HOST_LIB         := $(BUILD)/host/libhost.a

ALL_TARGETS += $(HOST_LIB)

$(HOST_LIB): $(HOST_LIB_OBJS)
	rm -f $@ && ar rcs $@ $^
