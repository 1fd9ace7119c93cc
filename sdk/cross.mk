# sdk/cross.mk — the client libraries for a firmware, in one command:
#
#   make sdk CROSS=arm-none-eabi- CPU=cortex-m4
#       -> build/sdk/cortex-m4/liblumo.a, liblumo_raster.a, liblumo_net.a
#   make sdk CROSS=arm-none-eabi- CPU=cortex-m4 FLOAT_ABI=hard FPU=fpv4-sp-d16
#       -> build/sdk/cortex-m4-hard/... (links with a hard-float firmware;
#          lumo itself has no float either way)
#   make sdk-check CROSS=... CPU=...   the same, then nm over every object
#       (boards/armv7m/check-embedded.sh: no heap, no soft-float helper, no
#       symbol outside string.h and libgcc's integer helpers)
#   make sdk                           without CROSS: the host's build/rel libs
#
# Flags (docs/sdk.md states them for a firmware's own build): C99, the
# warnings of every client build, -Os -g -ffunction-sections -fdata-sections
# (a firmware linking with --gc-sections keeps only what it calls), and
# SDK_ARCH, by default -mcpu=$(CPU) -mthumb -mfloat-abi=$(FLOAT_ABI)
# [-mfpu=$(FPU)]; another architecture sets SDK_ARCH itself (e.g.
# CROSS=riscv64-unknown-elf- SDK_ARCH="-march=rv32imac -mabi=ilp32").
# SDK_DEFS passes limit overrides (-DLUMO_MAX_MESHES=4, lumo/config.h): the
# application must be compiled with the same ones.
#
# `make test` builds and checks the Cortex-M0+, M3, M4 and M4F (hard float)
# libraries (sdk-cross).
CROSS     ?=
CPU       ?= cortex-m3
FLOAT_ABI ?= soft
FPU       ?=
SDK_DEFS  ?=
SDK_ARCH  ?= -mcpu=$(CPU) -mthumb -mfloat-abi=$(FLOAT_ABI) $(if $(FPU),-mfpu=$(FPU))
SDK_TARGET        = $(CPU)$(if $(filter-out soft,$(FLOAT_ABI)),-$(FLOAT_ABI))
SDK_CROSS_DIR     = $(BUILD)/sdk/$(SDK_TARGET)
SDK_CROSS_CFLAGS  = $(CLIENT_STD) $(WARN) $(CLIENT_INC) $(SDK_ARCH) $(SDK_DEFS) -Os -g \
                    -ffunction-sections -fdata-sections
SDK_PARTS         = liblumo.a liblumo_raster.a liblumo_net.a
# Where the libraries of this invocation are: the cross build, else the host's.
SDK_LIB_DIR       = $(if $(CROSS),$(SDK_CROSS_DIR),$(BUILD)/rel)

.PHONY: sdk sdk-check sdk-cross
sdk: $(addprefix $(SDK_LIB_DIR)/,$(SDK_PARTS))
	@echo "sdk: $(SDK_LIB_DIR)/{$(subst $(eval) ,$(comma),$(SDK_PARTS))}$(if $(CROSS), for $(SDK_TARGET): $(SDK_ARCH))"
comma := ,

ifneq ($(CROSS),)
$(SDK_CROSS_DIR)/%.o: %.c
	@mkdir -p $(@D)
	$(CROSS)gcc $(SDK_CROSS_CFLAGS) -MMD -MP -c $< -o $@
$(SDK_CROSS_DIR)/liblumo.a: $(patsubst %.c,$(SDK_CROSS_DIR)/%.o,$(filter sdk/%,$(CLIENT_SRCS)))
	rm -f $@ && $(CROSS)ar rcs $@ $^
$(SDK_CROSS_DIR)/liblumo_raster.a: $(patsubst %.c,$(SDK_CROSS_DIR)/%.o,$(filter rasterizer/soft/%,$(CLIENT_SRCS)))
	rm -f $@ && $(CROSS)ar rcs $@ $^
$(SDK_CROSS_DIR)/liblumo_net.a: $(patsubst %.c,$(SDK_CROSS_DIR)/%.o,$(filter net/src/%,$(CLIENT_SRCS)))
	rm -f $@ && $(CROSS)ar rcs $@ $^

sdk-check: sdk
	@sh boards/armv7m/check-embedded.sh $(CROSS)nm \
	    "$(patsubst %.c,$(SDK_CROSS_DIR)/%.o,$(CLIENT_SRCS))" ""
else
sdk-check:
	@echo "sdk-check: needs CROSS= (and CPU=): the rules are proven on a bare-metal build" >&2; exit 2
endif

# The libraries for the cores a lumo client is likely to meet, each proven
# by nm. One RESULT line per build, summed by tests/run.sh.
SDK_CROSS_TARGETS := "CPU=cortex-m0plus" "CPU=cortex-m3" "CPU=cortex-m4" \
                     "CPU=cortex-m4 FLOAT_ABI=hard FPU=fpv4-sp-d16"
TEST_STEPS += sdk-cross
sdk-cross:
	+@for t in $(SDK_CROSS_TARGETS); do \
	    echo "== sdk-check CROSS=arm-none-eabi- $$t"; \
	    $(MAKE) --no-print-directory -s sdk-check CROSS=arm-none-eabi- $$t || status=1; \
	done; exit $${status:-0}
