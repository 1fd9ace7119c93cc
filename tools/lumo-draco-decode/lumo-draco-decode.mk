# tools/draco.mk — lumo-draco-decode (desktop tool around the client decoder).
HOST_TOOLS += $(BIN)/lumo-draco-decode

$(BIN)/lumo-draco-decode: $(BUILD)/host/tools/lumo_draco_decode.o $(BUILD)/rel/liblumo.a $(BUILD)/host/libhost.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -lm
