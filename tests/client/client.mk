# tests/client/client.mk — lumo-client end to end (tests/client/client_test.sh):
# record and replay (the same PNG frames and progress byte for byte; a
# damaged recording refused after its last good frame). Every server and
# client runs under `timeout` and is killed by the script's trap.
TEST_STEPS += test-client
.PHONY: test-client
test-client: $(BIN)/lumo-client $(BIN)/lumo-server $(BIN)/lumo-bake
	@sh tests/client/client_test.sh $(BIN) $(BUILD)/tests/bin $(BUILD)/tests/client $(BUILD)/data/models
