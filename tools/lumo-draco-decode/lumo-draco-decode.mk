# tools/lumo-draco-decode/lumo-draco-decode.mk — lumo-draco-decode (desktop
# tool around the client decoder). Archives are named literally.
HOST_TOOLS += $(BIN)/lumo-draco-decode

$(BIN)/lumo-draco-decode: $(BUILD)/host/tools/lumo-draco-decode/main.o $(BUILD)/rel/liblumo.a $(BUILD)/host/libhost.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lm
