# tools/dynamic-demo/dynamic-demo.mk — make demo-dynamic (docs/dynamic.md):
# the Cornell box of cornell_dynamic.txt (a spot light moving across it, a
# sphere moving through it) baked, served by lumo-server --dynamic (the
# photon-streaming engine in its own thread), streamed by lumo-client
# --updates (frames over time and a strip of them), the latency from a
# change to settled lighting printed by the server, and dyn-error: the IVG
# from the VSLs against a path-traced bake of the same moment.
HOST_TOOLS += $(BIN)/dyn-error
$(BIN)/dyn-error: $(BUILD)/host/tools/dynamic-demo/dyn_error.o $(BUILD)/host/libserver.a $(BUILD)/host/libhost.a \
                  $(BUILD)/rel/liblumo_net.a \
                  $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -pthread -o $@ $^ $(SERVER_LIBS)

DEMO_DYNAMIC_DIR := $(BUILD)/demo-dynamic
.PHONY: demo-dynamic
demo-dynamic: $(BIN)/lumo-bake $(BIN)/lumo-server $(BIN)/lumo-client $(BIN)/lumo-compare $(BIN)/dyn-error
	@sh tools/dynamic-demo/demo-dynamic.sh $(BIN) $(DEMO_DYNAMIC_DIR) tools/dynamic-demo/cornell_dynamic.txt
