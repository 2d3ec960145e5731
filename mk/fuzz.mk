# mk/fuzz.mk - libFuzzer targets and the sanitized unit build (docs/HARDENING.md).
# SPDX-License-Identifier: MIT
#
# Included by the top Makefile (uses its BUILD, CC, CLANG, WARN, FPFLAGS, INC, FW_SRC,
# TEST_SRC, Q). Build trees:
#   $(BUILD)/fuzz/      firmware + tests/hal_mem.c with -fsanitize=fuzzer-no-link,address,undefined,
#                       one binary per tests/fuzz_<t>.c: fuzz_cmd fuzz_num fuzz_frame fuzz_run
#   $(BUILD)/asan/      the unit tests (float build) with -fsanitize=address,undefined
# Seeds: tests/corpus/<t>/ (read only: libFuzzer writes new inputs to $(BUILD)/fuzz/corpus/<t>).

FUZZ_TARGETS := cmd num frame run
FUZZ_SECONDS ?= 60
FUZZ_RUNS    ?= 20000
# fuzz_run drives a whole FRAMES session per input (~600 exec/s): fewer runs keep
# fuzz-check under a minute.
FUZZ_RUNS_RUN ?= 8000
FUZZ_JOBS    ?= 1
FUZZ_SAN     := -fsanitize=address,undefined -fno-sanitize-recover=all
FUZZ_CFLAGS  := -std=c99 -O1 -g -fno-omit-frame-pointer $(FPFLAGS) $(INC) $(FUZZ_SAN)
# FUZZ_STRICT=1 (default): fail on every finding, F1 and F2 included (fixed;
# docs/HARDENING.md). FUZZ_STRICT= tolerates those two, for bisecting old trees.
FUZZ_STRICT  ?= 1
FUZZ_DIR     := $(BUILD)/fuzz$(if $(FUZZ_STRICT),,-lenient)
FUZZ_CFLAGS  += $(if $(FUZZ_STRICT),-DFUZZ_STRICT=1)
FUZZ_FW_OBJ  := $(patsubst firmware/%.c,$(FUZZ_DIR)/fw/%.o,$(FW_SRC)) $(FUZZ_DIR)/tests/hal_mem.o
FUZZ_BINS    := $(patsubst %,$(FUZZ_DIR)/fuzz_%,$(FUZZ_TARGETS))
# libFuzzer options of every run: no leak check (no allocation in the firmware),
# a hang of one input > 10 s is a failure (-timeout), crashes go to $(FUZZ_DIR)/artifacts.
FUZZ_OPTS    := -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -detect_leaks=0

ASAN_CC     ?= $(CLANG)
ASAN_DIR    := $(BUILD)/asan
ASAN_CFLAGS := $(WARN) $(FPFLAGS) -O1 -g -fno-omit-frame-pointer $(INC) \
               -fsanitize=address,undefined -fno-sanitize-recover=all
ASAN_OBJ    := $(patsubst firmware/%.c,$(ASAN_DIR)/fw/%.o,$(FW_SRC)) \
               $(patsubst tests/%.c,$(ASAN_DIR)/tests/%.o,$(TEST_SRC))

.PHONY: fuzz fuzz-build fuzz-check unit-asan
.SECONDARY: $(FUZZ_FW_OBJ)

##
## fuzz: every libFuzzer target for FUZZ_SECONDS (default 60) each; new inputs in build/fuzz/corpus
fuzz: $(FUZZ_BINS)
	$(Q)fail=0; for t in $(FUZZ_TARGETS); do \
	    mkdir -p $(FUZZ_DIR)/corpus/$$t $(FUZZ_DIR)/artifacts; \
	    echo "== fuzz_$$t ($(FUZZ_SECONDS) s)"; \
	    $(FUZZ_DIR)/fuzz_$$t $(FUZZ_OPTS) -max_total_time=$(FUZZ_SECONDS) -jobs=$(FUZZ_JOBS) \
	        -workers=$(FUZZ_JOBS) -artifact_prefix=$(FUZZ_DIR)/artifacts/$$t- \
	        $(FUZZ_DIR)/corpus/$$t tests/corpus/$$t > $(FUZZ_DIR)/fuzz_$$t.log 2>&1 \
	        || { fail=1; echo "fuzz_$$t: FAILED (log $(FUZZ_DIR)/fuzz_$$t.log)"; tail -40 $(FUZZ_DIR)/fuzz_$$t.log; }; \
	    grep -E '^stat::(number_of_executed_units|average_exec_per_sec|new_units_added)|cov: ' \
	        $(FUZZ_DIR)/fuzz_$$t.log | tail -4; \
	done; exit $$fail

## fuzz-build: build the libFuzzer binaries only (clang, build/fuzz/fuzz_<target>)
fuzz-build: $(FUZZ_BINS)

## fuzz-check: each libFuzzer target for FUZZ_RUNS (20000; fuzz_run 8000) fixed-seed executions (word "fuzz")
fuzz-check: $(FUZZ_BINS)
	$(Q)pass=0; fail=0; for t in $(FUZZ_TARGETS); do \
	    rm -rf $(FUZZ_DIR)/check/$$t; mkdir -p $(FUZZ_DIR)/check/$$t $(FUZZ_DIR)/artifacts; \
	    t0=$$(date +%s%N); \
	    n=$(FUZZ_RUNS); [ $$t = run ] && n=$(FUZZ_RUNS_RUN); \
	    if $(FUZZ_DIR)/fuzz_$$t $(FUZZ_OPTS) -seed=1 -runs=$$n \
	        -artifact_prefix=$(FUZZ_DIR)/artifacts/$$t- \
	        $(FUZZ_DIR)/check/$$t tests/corpus/$$t > $(FUZZ_DIR)/check_$$t.log 2>&1; then \
	        pass=$$((pass + 1)); ms=$$(( ($$(date +%s%N) - t0) / 1000000 )); \
	        runs=$$(sed -n 's/^stat::number_of_executed_units: *//p' $(FUZZ_DIR)/check_$$t.log); \
	        echo "fuzz_$$t: ok, $$runs runs in $$ms ms ($$(( runs * 1000 / (ms + 1) )) exec/s), $$(grep -o 'cov: [0-9]*' $(FUZZ_DIR)/check_$$t.log | tail -1)"; \
	    else \
	        fail=$$((fail + 1)); echo "fuzz_$$t: FAILED (log $(FUZZ_DIR)/check_$$t.log)"; \
	        grep -E 'fuzz_[a-z]+: |ERROR|SUMMARY|Test unit written' $(FUZZ_DIR)/check_$$t.log | head -8; \
	    fi; \
	done; echo "fuzz: $$pass passed, $$fail failed"; [ $$fail -eq 0 ]

$(FUZZ_DIR)/fw/%.o: firmware/%.c
	@mkdir -p $(@D)
	$(Q)$(CLANG) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link -MMD -MP -c $< -o $@

$(FUZZ_DIR)/tests/%.o: tests/%.c
	@mkdir -p $(@D)
	$(Q)$(CLANG) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link -MMD -MP -c $< -o $@

$(FUZZ_DIR)/fuzz_%: tests/fuzz_%.c $(FUZZ_FW_OBJ)
	@mkdir -p $(@D)
	$(Q)$(CLANG) $(FUZZ_CFLAGS) -fsanitize=fuzzer -o $@ $< $(FUZZ_FW_OBJ) -lm

##
## unit-asan: host unit tests (float) with ASan + UBSan, no recovery (runner word "unit-asan")
unit-asan: $(ASAN_DIR)/unit
	$(Q)ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 $(ASAN_DIR)/unit

$(ASAN_DIR)/fw/%.o: firmware/%.c
	@mkdir -p $(@D)
	$(Q)$(ASAN_CC) $(ASAN_CFLAGS) -MMD -MP -c $< -o $@

$(ASAN_DIR)/tests/%.o: tests/%.c
	@mkdir -p $(@D)
	$(Q)$(ASAN_CC) $(ASAN_CFLAGS) -Wno-double-promotion -DTEST_WORD='"unit-asan"' -MMD -MP -c $< -o $@

$(ASAN_DIR)/unit: $(ASAN_OBJ)
	$(Q)$(ASAN_CC) -fsanitize=address,undefined -o $@ $^ -lm
