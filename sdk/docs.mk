# sdk/docs.mk — the API reference (Doxygen, Debian's `doxygen`) of the
# headers `make install` installs (sdk/docs/Doxyfile):
#
#   make docs         build/docs/api/html/index.html; fails on any warning,
#                     an undocumented public function, type, field, enum
#                     value or macro among them
#   make docs-check   the same as a make test step, plus a check that the
#                     check fails (tests/sdk/docs_check.sh)
#
# The headers keep plain C comments; sdk/docs/doxy_filter.awk (Doxygen's
# INPUT_FILTER) says which comments document what.
DOCS_DIR := $(BUILD)/docs/api

.PHONY: docs docs-check
docs:
	@mkdir -p $(DOCS_DIR)
	LUMO_DOC_VERSION=$(LUMO_VERSION) LUMO_DOC_OUT=$(DOCS_DIR) doxygen sdk/docs/Doxyfile
	@echo "docs: $(DOCS_DIR)/html/index.html"

TEST_STEPS += docs-check
docs-check:
	@sh tests/sdk/docs_check.sh $(BUILD)/tests/docs $(LUMO_VERSION)
