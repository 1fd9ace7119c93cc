# tests/client/client.mk — lumo-client end to end (tests/client/client_test.sh):
# record and replay (the same PNG frames and progress byte for byte; a
# damaged recording refused after its last good frame); resume after cuts
# made by a proxy (tests/client/cut_proxy.c: the same frames as an uncut
# run, and only the frames cut mid-way and the WELCOMEs of the new
# connections received twice); --serial against lumo-server --serial-listen
# --loss 0.05 (the full scene whatever the loss); --http from Debian's nginx
# on loopback (the TCP run's frames and received bytes, byte for byte). Every server, proxy and
# client runs under
# `timeout` and is killed by the script's trap.
CUT_PROXY := $(BUILD)/tests/bin/cut_proxy
$(CUT_PROXY): $(BUILD)/tests/tests/client/cut_proxy.o
	@mkdir -p $(@D)
	$(CC) $(SAN_FLAGS) -o $@ $^

TEST_STEPS += test-client
.PHONY: test-client
test-client: $(BIN)/lumo-client $(BIN)/lumo-server $(BIN)/lumo-bake $(CUT_PROXY)
	@sh tests/client/client_test.sh $(BIN) $(BUILD)/tests/bin $(BUILD)/tests/client $(BUILD)/data/models
