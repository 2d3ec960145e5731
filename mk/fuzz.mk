# mk/fuzz.mk - libFuzzer targets and the sanitized unit build (docs/HARDENING.md).
# SPDX-License-Identifier: MIT
#
# Included by the top Makefile (uses its BUILD, CC, CLANG, WARN, FPFLAGS, INC, FW_SRC,
# TEST_SRC, Q). Build trees:
#   $(BUILD)/fuzz/      firmware with -fsanitize=fuzzer-no-link,address,undefined -O2, harness
#                       (tests/fuzz_<t>.c, tests/hal_mem.c, tests/frame_h.o: a copy of frame.c)
#                       with address,undefined only; one binary per target: fuzz_cmd fuzz_num
#                       fuzz_frame fuzz_run (shipped limits)
#   $(BUILD)/fuzz-small/ the same with small compile-time limits (FUZZ_SMALL_DEFS), `make fuzz`
#   $(BUILD)/asan/      the unit tests (float build) with -fsanitize=address,undefined
# Seeds: tests/corpus/<t>/ (read only: libFuzzer writes new inputs to $(BUILD)/fuzz/corpus/<t>).

# reply_<dialect>: tests/fuzz_reply.c built once per machine dialect (machines.def)
FUZZ_DIALECTS := $(shell sed -n 's/^CP_MACHINE.\([A-Z]*\),.*/\1/p' firmware/job/machines.def | tr A-Z a-z)
FUZZ_TARGETS := cmd num frame run $(patsubst %,reply_%,$(FUZZ_DIALECTS))
FUZZ_SECONDS ?= 60
# the reply_<dialect> targets run a count, not a time: at least 10^6 executions each in
# `make fuzz` (~6000 exec/s: ~3 min each), 10^7 in a campaign (FUZZ_REPLY_RUNS=10000000)
FUZZ_REPLY_RUNS ?= 1000000
FUZZ_RUNS    ?= 20000
# fuzz_run drives a whole FRAMES session per input (~600 exec/s): fewer runs keep
# fuzz-check under a minute.
FUZZ_RUNS_RUN ?= 20000
# FUZZ_JOBS > 1: libFuzzer -jobs/-workers (forked workers write fuzz-<i>.log into the
# current directory); 1 (default) runs one plain process.
FUZZ_JOBS    ?= 1
FUZZ_SAN     := -fsanitize=address,undefined -fno-sanitize-recover=all
FUZZ_CFLAGS  := -std=c99 -g -fno-omit-frame-pointer $(FPFLAGS) $(INC) $(FUZZ_SAN)
# Firmware objects at -O2 (the image is built -O2/-Os too; -O1 only cost speed).
# Harness objects (tests/fuzz_<t>.c, tests/hal_mem.c) carry no coverage
# instrumentation: ASan/UBSan only. Their branches mirror the firmware's and only
# slowed every poll (trace-cmp hooks on each loop bound); the firmware, including
# frame.c used by the harness to decode, keeps full coverage + trace-cmp.
# Comparison tracing (trace-cmp, the fuzzer's hints for magic values) is left out of
# the pure arithmetic of canal.c and cp_math.c, where every compare is of computed
# values, never of input bytes, and the hooks cost half the run time; their edge
# coverage stays. frame_crc16 has no coverage at all (its 8 branches per byte are
# data bits, not paths). Sanitizers stay on everywhere.
# The same holds for the other geometry and number formatting: the surface models
# (drc, gsr, channel), the canal iterator (canal_path), its dispatcher (path) and the
# output number formatter (fmt) compare only values computed from parsed numbers or
# from the fixed jobs of fuzz_run; a text number's binary image never occurs in the
# input, so their compare hints never helped a mutation. In fuzz_run the hooks of
# canal_path.c were ~10 % of the time, in fuzz_cmd those of the three models ~18 %.
# Byte-level code (proto, job*, parse, frame) keeps trace-cmp.
FUZZ_FW_OPT  ?= -O2
FUZZ_H_OPT   ?= -O2
FUZZ_NOCMP   := canal cp_math drc gsr channel canal_path path fmt
# fuzz_cmd and fuzz_run decode every byte the firmware sends, and encode the host's
# frames, with frame.c. Through the firmware's object that ran its coverage and
# trace-cmp hooks on every output byte (~20 % of fuzz_run). These two harnesses get
# their own copy of frame.c built like the harness (sanitizers, no coverage), its
# functions renamed by the preprocessor; the firmware's frame.c (its encoder and
# receive path) keeps full coverage, and fuzz_frame tests that object.
FUZZ_HFRAME  := $(foreach f,crc16 encode rx_init rx_feed put_u16 put_u32 get_u16 get_u32,\
                  -Dframe_$(f)=fuzz_h_frame_$(f))
# FUZZ_STRICT=1 (default): fail on every finding, F1 and F2 included (fixed;
# docs/HARDENING.md). FUZZ_STRICT= tolerates those two, for bisecting old trees.
FUZZ_STRICT  ?= 1
FUZZ_CFLAGS  += $(if $(FUZZ_STRICT),-DFUZZ_STRICT=1)
# Two configurations, each its own tree:
#   full   $(BUILD)/fuzz        the shipped compile-time limits. fuzz-check uses it.
#   small  $(BUILD)/fuzz-small  CP_MAX_STEPS=64, CP_MAX_LINES=8 (CP_MAX_LINK stays 64:
#          the paper job needs 15-50 link points),
#          OUT_FRAMES_WINDOW=8: every job is at most a few hundred points, so a run ends
#          inside the poll budget and ~10x more inputs per second reach the end of a
#          run, the resume/abort paths and the $I check. Jobs beyond the limits are
#          rejected at RUN/command time with their documented codes (error:14, 17),
#          which the harness checks like any reply. Default of `make fuzz`.
FUZZ_CONF    ?= small
FUZZ_SMALL_DEFS := -DCP_MAX_STEPS=64 -DCP_MAX_LINES=8 -DOUT_FRAMES_WINDOW=8u
FUZZ_SFX     := $(if $(FUZZ_STRICT),,-lenient)
FUZZ_DIR     := $(BUILD)/fuzz$(FUZZ_SFX)
FUZZ_SDIR    := $(BUILD)/fuzz-small$(FUZZ_SFX)
FUZZ_LDIR    := $(if $(filter small,$(FUZZ_CONF)),$(FUZZ_SDIR),$(FUZZ_DIR))
FUZZ_BINS    := $(patsubst %,$(FUZZ_DIR)/fuzz_%,$(FUZZ_TARGETS))
FUZZ_SBINS   := $(patsubst %,$(FUZZ_SDIR)/fuzz_%,$(FUZZ_TARGETS))
FUZZ_LBINS   := $(patsubst %,$(FUZZ_LDIR)/fuzz_%,$(FUZZ_TARGETS))
# libFuzzer options of every run: no leak check (no allocation in the firmware),
# a hang of one input > 10 s is a failure (-timeout), crashes go to <tree>/artifacts.
# (-timeout=10 per input: every input of fuzz-check runs in under 1 s, 855-1400 exec/s
# on cmd/run, stat::slowest_unit_time_sec 0 (2026-11-26): >= 10x, the rule of mk/m4f.mk
# is >= 5x the unloaded time. -max_total_time is a duration, not a limit.)
FUZZ_OPTS    := -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -detect_leaks=0

ASAN_CC     ?= $(CLANG)
ASAN_DIR    := $(BUILD)/asan
ASAN_CFLAGS := $(WARN) $(FPFLAGS) -O1 -g -fno-omit-frame-pointer $(INC) \
               -fsanitize=address,undefined -fno-sanitize-recover=all
ASAN_OBJ    := $(patsubst firmware/%.c,$(ASAN_DIR)/fw/%.o,$(FW_SRC)) \
               $(patsubst tests/%.c,$(ASAN_DIR)/tests/%.o,$(TEST_SRC))

.PHONY: fuzz fuzz-build fuzz-check unit-asan

# One fuzz tree: $(1) directory, $(2) extra -D flags. Firmware objects: coverage
# (fuzzer-no-link) + sanitizers; harness objects: sanitizers only.
define FUZZ_TREE
$(1)/fw/%.o: firmware/%.c $(1)/cov-ignore.txt
	@mkdir -p $$(@D)
	$$(Q)$$(CLANG) $$(FUZZ_CFLAGS) $(2) $$(FUZZ_FW_OPT) -fsanitize=fuzzer-no-link \
	    -fsanitize-coverage-ignorelist=$(1)/cov-ignore.txt \
	    $$(if $$(filter $$(FUZZ_NOCMP),$$*),-fno-sanitize-coverage=trace-cmp) -MMD -MP -c $$< -o $$@

$(1)/cov-ignore.txt:
	@mkdir -p $$(@D)
	$$(Q)echo 'fun:frame_crc16' > $$@

$(1)/tests/%.o: tests/%.c
	@mkdir -p $$(@D)
	$$(Q)$$(CLANG) $$(FUZZ_CFLAGS) $(2) $$(FUZZ_H_OPT) $$(FUZZ_HDEFS) -MMD -MP -c $$< -o $$@

# the harnesses that decode the firmware's output call the copy (FUZZ_HFRAME)
$(1)/tests/fuzz_cmd.o $(1)/tests/fuzz_run.o: FUZZ_HDEFS = $$(FUZZ_HFRAME)

# the machine-answer target, one binary per dialect
$(patsubst %,$(1)/tests/fuzz_reply_%.o,$(FUZZ_DIALECTS)): $(1)/tests/fuzz_reply_%.o: tests/fuzz_reply.c
	@mkdir -p $$(@D)
	$$(Q)$$(CLANG) $$(FUZZ_CFLAGS) $(2) $$(FUZZ_H_OPT) -DFUZZ_DIALECT=$$* -MMD -MP -c $$< -o $$@

$(1)/tests/frame_h.o: firmware/proto/frame.c
	@mkdir -p $$(@D)
	$$(Q)$$(CLANG) $$(FUZZ_CFLAGS) $(2) $$(FUZZ_H_OPT) $$(FUZZ_HFRAME) -MMD -MP -c $$< -o $$@

$(1)/fuzz_%: $(1)/tests/fuzz_%.o $(patsubst firmware/%.c,$(1)/fw/%.o,$(FW_SRC)) $(1)/tests/hal_mem.o \
             $(1)/tests/frame_h.o
	$$(Q)$$(CLANG) $$(FUZZ_CFLAGS) -fsanitize=fuzzer -o $$@ $$^ -lm

.SECONDARY: $(patsubst firmware/%.c,$(1)/fw/%.o,$(FW_SRC)) $(1)/tests/hal_mem.o \
            $(1)/tests/frame_h.o $(patsubst %,$(1)/tests/fuzz_%.o,$(FUZZ_TARGETS))
-include $(wildcard $(1)/fw/*.d $(1)/tests/*.d)
endef
$(eval $(call FUZZ_TREE,$(FUZZ_DIR),))
$(eval $(call FUZZ_TREE,$(FUZZ_SDIR),$(FUZZ_SMALL_DEFS)))

##
## fuzz: every libFuzzer target for FUZZ_SECONDS (default 60) each (reply_<dialect>: FUZZ_REPLY_RUNS, 10^6, executions each), FUZZ_CONF=small (default) or full; new inputs in <tree>/corpus
fuzz: $(FUZZ_LBINS)
	$(Q)fail=0; for t in $(FUZZ_TARGETS); do \
	    mkdir -p $(FUZZ_LDIR)/corpus/$$t $(FUZZ_LDIR)/artifacts; \
	    case $$t in reply_*) lim="-runs=$(FUZZ_REPLY_RUNS)";; *) lim="-max_total_time=$(FUZZ_SECONDS)";; esac; \
	    echo "== fuzz_$$t ($(FUZZ_CONF), $$lim)"; \
	    $(FUZZ_LDIR)/fuzz_$$t $(FUZZ_OPTS) $$lim \
	        $(if $(filter-out 1,$(FUZZ_JOBS)),-jobs=$(FUZZ_JOBS) -workers=$(FUZZ_JOBS)) -artifact_prefix=$(FUZZ_LDIR)/artifacts/$$t- \
	        $(FUZZ_LDIR)/corpus/$$t tests/corpus/$$t > $(FUZZ_LDIR)/fuzz_$$t.log 2>&1 \
	        || { fail=1; echo "fuzz_$$t: FAILED (log $(FUZZ_LDIR)/fuzz_$$t.log)"; tail -40 $(FUZZ_LDIR)/fuzz_$$t.log; }; \
	    grep -E '^stat::(number_of_executed_units|average_exec_per_sec|new_units_added)|cov: ' \
	        $(FUZZ_LDIR)/fuzz_$$t.log | tail -4; \
	done; exit $$fail

## fuzz-build: build the libFuzzer binaries of both trees (clang, build/fuzz/ and build/fuzz-small/)
fuzz-build: $(FUZZ_BINS) $(FUZZ_SBINS)

## fuzz-check: seed corpus, then FUZZ_RUNS (20000) and FUZZ_RUNS_RUN (20000) fixed-seed executions per target, full limits (word "fuzz")
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
