# tools/board-demo/board-demo.mk — make demo-board: the thin client's view.
# The recording `make board-client` made (the default scene streamed from
# lumo-server) is replayed by the board client under QEMU (mps2-an385) and
# by its host build, each writing every picture (--out); the PPMs become
# PNGs side by side in build/demo-board/{board,host}/, with lumo-compare's
# sheet of each pair (equal bytes: the pictures are the same).
HOST_TOOLS += $(BIN)/lumo-ppm-to-png
$(BIN)/lumo-ppm-to-png: $(BUILD)/host/tools/board-demo/ppm_to_png.o $(BUILD)/host/libhost.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lpng -lm

DEMO_BOARD_DIR := $(BUILD)/demo-board
.PHONY: demo-board
demo-board: board-client $(BIN)/lumo-ppm-to-png
	@sh tools/board-demo/board-demo.sh $(DEMO_BOARD_DIR) $(CLIENT_DIR)/session.rec $(CLIENT_HOST) $(CLIENT_ELF) \
	    "$(MPS2_QEMU_CMD)" $(BIN)/lumo-ppm-to-png
