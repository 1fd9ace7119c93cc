# bench/stream.mk — `make bench-stream`: streaming over lumo-server's emulated
# link (seed 000 §5.2, Figures 5-7) and the server's throughput, CPU and
# memory per client (bench/stream.sh). Writes build/bench/sections/70-stream.md
# and the plots docs/bench-stream-*.png.
# lumo-bench-stream (bench/stream_client.c): the measuring client, the SDK's
# driver and session without a renderer; the driver's push-pull calls are
# timed through the linker (--wrap=lumo_session_update).
STREAM_BENCH := $(BIN)/lumo-bench-stream
HOST_TOOLS   += $(STREAM_BENCH)

$(STREAM_BENCH): $(BUILD)/host/bench/stream_client.o $(BUILD)/host/net/host/net_socket.o $(BUILD)/host/tools/lib/options.o \
                 $(BUILD)/rel/liblumo_net.a $(BUILD)/rel/liblumo.a
	@mkdir -p $(@D)
	$(CC) -o $@ $^ -Wl,--wrap=lumo_session_update

BENCH_STEPS += bench-stream
.PHONY: bench-stream
bench-stream: $(STREAM_BENCH) $(BIN)/lumo-server $(BIN)/lumo-client $(BIN)/lumo-bake
	@sh bench/stream.sh $(BUILD) $(BIN)
