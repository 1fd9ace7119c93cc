# sdk/install.mk — make install / make uninstall (docs/sdk.md).
#
#   make install [PREFIX=/usr/local] [DESTDIR=...]   the client SDK, all parts:
#     install-sdk     lumo/*.h of sdk/include, liblumo.a, lumo.pc
#     install-raster  lumo/raster.h, liblumo_raster.a, lumo-raster.pc (Requires: lumo)
#     install-net     lumo/net.h, net_client.h, liblumo_net.a, lumo-net.pc (Requires: lumo)
#   make install-tools    the desktop programs (lumo-bake, lumo-server,
#                         lumo-client, lumo-render, ...) into BINDIR: a separate
#                         part, it needs the whole desktop build
#   make uninstall        removes exactly what the above install, nothing else
#
# The libraries are the host's (build/rel), or with CROSS=... CPU=... the
# bare-metal build of sdk/cross.mk: `make install CROSS=arm-none-eabi-
# CPU=cortex-m4 PREFIX=/opt/fw-sysroot` installs what a firmware links.
# The pkg-config files say where things are after DESTDIR is taken off (a
# packager's staging directory is not where the files end up).
PREFIX       ?= /usr/local
DESTDIR      ?=
INCLUDEDIR   ?= $(PREFIX)/include
LIBDIR       ?= $(PREFIX)/lib
BINDIR       ?= $(PREFIX)/bin
PKGCONFIGDIR ?= $(LIBDIR)/pkgconfig
INSTALL      ?= install

# "MAJOR.MINOR.PATCH" from lumo/version.h, the one place it is written.
LUMO_VERSION = $(shell sed -n 's/^\#define LUMO_VERSION_\(MAJOR\|MINOR\|PATCH\) *\([0-9]*\).*/\2/p' \
                   sdk/include/lumo/version.h | paste -sd.)

INSTALL_SDK_HEADERS    = $(sort $(wildcard sdk/include/lumo/*.h))
INSTALL_RASTER_HEADERS = rasterizer/include/lumo/raster.h
INSTALL_NET_HEADERS    = $(sort $(wildcard net/include/lumo/*.h))
# The programs a user runs; benchmark and sanitizer builds stay in build/.
INSTALL_TOOLS = $(sort $(filter-out %-san $(BIN)/lumo-bench-%,$(filter $(BIN)/lumo-%,$(HOST_TOOLS))))

# A directory as the .pc file writes it: relative to ${prefix} when under it.
pc_dir = $(patsubst $(PREFIX)%,$${prefix}%,$(1))

# install_part HEADERS LIBRARY PC-NAME DESCRIPTION REQUIRES
define install_part
	$(INSTALL) -d $(DESTDIR)$(INCLUDEDIR)/lumo $(DESTDIR)$(LIBDIR) $(DESTDIR)$(PKGCONFIGDIR)
	$(INSTALL) -m 644 $(1) $(DESTDIR)$(INCLUDEDIR)/lumo/
	$(INSTALL) -m 644 $(SDK_LIB_DIR)/$(2) $(DESTDIR)$(LIBDIR)/$(2)
	printf '%s\n' 'prefix=$(PREFIX)' 'includedir=$(call pc_dir,$(INCLUDEDIR))' \
	    'libdir=$(call pc_dir,$(LIBDIR))' '' 'Name: $(3)' 'Description: $(4)' \
	    'Version: $(LUMO_VERSION)' $(if $(5),'Requires: $(5) = $(LUMO_VERSION)') 'Cflags: -I$${includedir}' \
	    'Libs: -L$${libdir} -l$(patsubst lib%.a,%,$(2))' > $(DESTDIR)$(PKGCONFIGDIR)/$(3).pc
	chmod 644 $(DESTDIR)$(PKGCONFIGDIR)/$(3).pc
endef

.PHONY: install install-sdk install-raster install-net install-tools uninstall
install: install-sdk install-raster install-net

install-sdk: $(SDK_LIB_DIR)/liblumo.a
	$(call install_part,$(INSTALL_SDK_HEADERS),liblumo.a,lumo,lumo client SDK: packages$(comma) progressive meshes$(comma) IVG lighting$(comma) the client session (C99$(comma) fixed point$(comma) no heap),)
install-raster: $(SDK_LIB_DIR)/liblumo_raster.a
	$(call install_part,$(INSTALL_RASTER_HEADERS),liblumo_raster.a,lumo-raster,lumo fixed-point software rasterizer (bit-exact$(comma) bands$(comma) no heap),lumo)
install-net: $(SDK_LIB_DIR)/liblumo_net.a
	$(call install_part,$(INSTALL_NET_HEADERS),liblumo_net.a,lumo-net,lumo stream protocol codec and client driver,lumo)

install-tools: $(INSTALL_TOOLS)
	$(INSTALL) -d $(DESTDIR)$(BINDIR)
	$(INSTALL) -m 755 $(INSTALL_TOOLS) $(DESTDIR)$(BINDIR)/

uninstall:
	rm -f $(addprefix $(DESTDIR)$(INCLUDEDIR)/lumo/,$(notdir $(INSTALL_SDK_HEADERS) $(INSTALL_RASTER_HEADERS) \
	          $(INSTALL_NET_HEADERS))) \
	      $(addprefix $(DESTDIR)$(LIBDIR)/,$(SDK_PARTS)) \
	      $(addprefix $(DESTDIR)$(PKGCONFIGDIR)/,lumo.pc lumo-raster.pc lumo-net.pc) \
	      $(addprefix $(DESTDIR)$(BINDIR)/,$(notdir $(INSTALL_TOOLS)))
	-rmdir $(DESTDIR)$(INCLUDEDIR)/lumo 2>/dev/null
