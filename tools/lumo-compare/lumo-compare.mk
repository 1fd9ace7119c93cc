# tools/lumo-compare/lumo-compare.mk — lumo-compare: PNG pictures side by
# side, labelled, with the mean Delta E (CIE76) and the PSNR of every pair.
# PNG files and image metrics come from the desktop library
# build/host/libhost.a (tools/lib/hostlib.mk, named literally: fragments are
# included in any order).
HOST_TOOLS += $(BIN)/lumo-compare

$(BIN)/lumo-compare: $(BUILD)/host/tools/lumo-compare/lumo_compare.o $(BUILD)/host/libhost.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lpng -lm
