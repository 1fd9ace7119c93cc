# tests/sdk/sdk.mk — the SDK as a user gets it (tests/sdk/sdk_test.sh):
# `make install` into a prefix under build/, the example client
# sdk/examples/lumo_view.c built outside the tree through pkg-config
# against it, its frames equal to lumo-render's byte for byte, hostile
# packages refused in one line, a DESTDIR install, uninstall leaving
# nothing, a bare-metal install, the CHANGELOG at the headers' version.
PPM_PNG_SAME := $(BUILD)/tests/bin/ppm_png_same
$(PPM_PNG_SAME): $(BUILD)/host/tests/sdk/ppm_png_same.o $(BUILD)/host/libhost.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lpng -lm

TEST_STEPS += test-sdk
.PHONY: test-sdk
test-sdk: $(BIN)/lumo-render $(BIN)/lumo-bake $(BIN)/lumo-server $(BIN)/lumo-client $(PPM_PNG_SAME) $(BUILD)/rel/liblumo.a \
          $(BUILD)/rel/liblumo_raster.a $(BUILD)/rel/liblumo_net.a
	+@sh tests/sdk/sdk_test.sh "$(MAKE)" $(BUILD) $(BIN) $(PPM_PNG_SAME) $(BUILD)/data/models
