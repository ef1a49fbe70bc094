# jointrom makefile, on SLEPc's makefile system (which brings PETSc's variables and rules).
#
#   make          build lib/libjointrom.a and bin/jointrom
#   make run      install missing dependencies, build, run runs/default.opts, write its plots to out/
#   make test     install missing dependencies, build, run the test suite (ends "N passed, M failed")
#   make test-long  the same for the slow end-to-end checks (CI runs it after make test)
#   make bench    build and print the benchmark figures (1 and 2 MPI ranks)
#   make install  copy bin/, lib/, include/ and share/ under PREFIX (default /usr/local)
#   make clean    remove build/, lib/, bin/
#
# Variables: PETSC_DIR, SLEPC_DIR (Debian defaults), JR_OPT (optimisation flags),
# WERROR=1 (warnings are errors, as in CI), NP (ranks for make run, default 2).

# OpenMPI refuses root unless told otherwise; users should never have to.
export OMPI_ALLOW_RUN_AS_ROOT := 1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM := 1
export OMPI_MCA_rmaps_base_oversubscribe := 1

PETSC_DIR ?= /usr/lib/petsc
SLEPC_DIR ?= /usr/lib/slepc
export PETSC_DIR SLEPC_DIR
# slepc_common is slepc_variables + slepc_rules + slepc_test; slepc_test defines a 'test' target
# (SLEPc's self-test) that would clash with ours, so we include the other two directly.
SLEPC_CONF := $(SLEPC_DIR)/lib/slepc/conf
ifneq ($(wildcard $(SLEPC_CONF)/slepc_common),)
include $(SLEPC_CONF)/slepc_variables
include $(SLEPC_CONF)/slepc_rules
HAVE_SLEPC := yes
endif
.DEFAULT_GOAL := all
.SECONDARY: # keep object files (no "rm" lines after the test summary)

JR_OPT  ?= -O3 -march=native
JR_WARN := -Wall -Wextra $(if $(filter 1,$(WERROR)),-Werror)
JR_CFLAGS = $(JR_OPT) $(JR_WARN) -std=gnu11 -fPIC -MMD -MP -Iinclude -DJR_SHARE_DIR='"$(CURDIR)/share"'
NP ?= 2
MPIRUN ?= mpiexec

LIB_SRC  := $(shell find src -name '*.c' ! -path src/jointrom.c | sort)
LIB_OBJ  := $(LIB_SRC:%.c=build/%.o)
TEST_SRC := $(wildcard tests/*.c)
TEST_BIN := $(TEST_SRC:tests/%.c=build/tests/%)
BENCH_SRC := $(wildcard tests/bench/*.c)
BENCH_BIN := $(BENCH_SRC:tests/bench/%.c=build/bench/%)

.PHONY: all deps run test test-long bench clean install jr-run jr-test jr-test-long jr-bench jr-tests-build
PREFIX ?= /usr/local

ifeq ($(HAVE_SLEPC),yes)
all: lib/libjointrom.a bin/jointrom

build/%.o: %.c
	@mkdir -p $(dir $@)
	$(PCC) -c $(JR_CFLAGS) $(SLEPC_CC_INCLUDES) -o $@ $<

lib/libjointrom.a: $(LIB_OBJ)
	@mkdir -p lib
	@rm -f $@
	ar rcs $@ $^

bin/jointrom: build/src/jointrom.o lib/libjointrom.a
	@mkdir -p bin
	$(CLINKER) -o $@ $< lib/libjointrom.a $(SLEPC_LIB) -lm

build/tests/%: build/tests/%.o lib/libjointrom.a
	$(CLINKER) -o $@ $< lib/libjointrom.a $(SLEPC_LIB) -lm

build/bench/%: build/tests/bench/%.o lib/libjointrom.a
	@mkdir -p build/bench
	$(CLINKER) -o $@ $< lib/libjointrom.a $(SLEPC_LIB) -lm

jr-tests-build: all $(TEST_BIN)

jr-test: jr-tests-build
	@bash tests/run.sh

jr-test-long: jr-tests-build
	@bash tests/run.sh long

jr-bench: all $(BENCH_BIN)
	@bash tests/bench/run.sh

jr-run: all
	@mkdir -p out
	$(MPIRUN) -n $(NP) bin/jointrom -options_file runs/default.opts
else
all jr-test jr-test-long jr-bench jr-run jr-tests-build:
	@echo "jointrom: PETSc/SLEPc not found (SLEPC_DIR=$(SLEPC_DIR)). Run 'bash share/install-deps.sh' or 'make run'/'make test', which install them." >&2
	@exit 1
endif

deps:
	@bash share/install-deps.sh

install: all
	install -d $(PREFIX)/bin $(PREFIX)/lib $(PREFIX)/include/jointrom/private $(PREFIX)/share/jointrom
	install -m 755 bin/jointrom $(PREFIX)/bin/
	install -m 644 lib/libjointrom.a $(PREFIX)/lib/
	install -m 644 include/jointrom.h $(PREFIX)/include/
	install -m 644 include/jointrom/private/*.h $(PREFIX)/include/jointrom/private/
	install -m 644 share/*.gp $(PREFIX)/share/jointrom/
	@echo "installed; set JOINTROM_SHARE=$(PREFIX)/share/jointrom so bin/jointrom finds its plot scripts" 

run: deps
	@$(MAKE) --no-print-directory jr-run

test: deps
	@$(MAKE) --no-print-directory jr-test

test-long: deps
	@$(MAKE) --no-print-directory jr-test-long

bench: deps
	@$(MAKE) --no-print-directory jr-bench

# PETSc's rules define 'clean' (it removes CLEANDIRS); without PETSc we define it ourselves.
CLEANDIRS := build lib bin
ifneq ($(HAVE_SLEPC),yes)
clean:
	rm -rf $(CLEANDIRS)
endif

-include $(shell find build -name '*.d' 2>/dev/null)
