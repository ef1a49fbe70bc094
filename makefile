# jointrom makefile, on SLEPc's makefile system (which brings PETSc's variables and rules).
#
#   make          build lib/libjointrom.a and bin/jointrom
#   make run      install missing dependencies, build, run runs/default.opts, write its plots to out/
#   make test     install missing dependencies, build, run the test suite (ends "N passed, M failed")
#   make test-long  the same for the slow end-to-end checks (CI runs it after make test)
#   make bench    build and print the benchmark figures (1 and 2 MPI ranks)
#   make install  install under PREFIX (default /usr/local): bin/jointrom, lib/libjointrom.a,
#                 lib/pkgconfig/jointrom.pc, include/ (jointrom.h, jointrom/private/), and the plot
#                 scripts in share/jointrom/ (which the installed bin/jointrom finds by itself);
#                 DESTDIR=dir stages the files under dir$(PREFIX) (packaging), paths stay PREFIX-based
#   make uninstall  remove those files from DESTDIR$(PREFIX)
#   make clean    remove build/, lib/, bin/
#
# Variables: PETSC_DIR, SLEPC_DIR (Debian defaults), JR_OPT (optimisation flags),
# WERROR=1 (warnings are errors, as in CI), NP (ranks for make run, default 2), PREFIX and DESTDIR
# (make install, make uninstall).

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
JR_CFLAGS = $(JR_OPT) $(JR_WARN) -std=gnu11 -fopenmp-simd -fPIC -MMD -MP -Iinclude -DJR_SHARE_DIR='"$(CURDIR)/share"'
NP ?= 2
MPIRUN ?= mpiexec

LIB_SRC  := $(shell find src -name '*.c' ! -path src/jointrom.c | sort)
LIB_OBJ  := $(LIB_SRC:%.c=build/%.o) build/optnames.o
TEST_SRC := $(wildcard tests/*.c)
TEST_BIN := $(TEST_SRC:tests/%.c=build/tests/%)
BENCH_SRC := $(wildcard tests/bench/*.c)
BENCH_BIN := $(BENCH_SRC:tests/bench/%.c=build/bench/%)

.PHONY: all deps run test test-long bench clean install uninstall jr-run jr-test jr-test-long jr-bench jr-tests-build
PREFIX ?= /usr/local

ifeq ($(HAVE_SLEPC),yes)
all: lib/libjointrom.a bin/jointrom

build/%.o: %.c
	@mkdir -p $(dir $@)
	$(PCC) -c $(JR_CFLAGS) $(SLEPC_CC_INCLUDES) -o $@ $<

# the option names, for "did you mean" (src/sys/options.c), generated from the sources
build/optnames.c: $(LIB_SRC) src/jointrom.c src/sys/optnames.sh
	@mkdir -p build
	bash src/sys/optnames.sh $(LIB_SRC) src/jointrom.c > $@

build/optnames.o: build/optnames.c
	$(PCC) -c $(JR_CFLAGS) -o $@ $<

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

# The pkg-config file: the include and link flags of the PETSc/SLEPc that built the library (it calls
# HDF5 and LAPACK directly, so SLEPc.pc/PETSc.pc's Libs alone would not link it); compile with ccompiler.
JR_VERSION := $(shell sed -n 's/^.define JR_VERSION_MAJOR //p' include/jointrom/sys.h).$(shell sed -n 's/^.define JR_VERSION_MINOR //p' include/jointrom/sys.h)
JR_DEST := $(DESTDIR)$(PREFIX)
JR_PUBLIC_H := $(wildcard include/jointrom/*.h)

install: all
	install -d $(JR_DEST)/bin $(JR_DEST)/lib/pkgconfig $(JR_DEST)/include/jointrom/private $(JR_DEST)/share/jointrom
	install -m 755 bin/jointrom $(JR_DEST)/bin/
	install -m 644 lib/libjointrom.a $(JR_DEST)/lib/
	install -m 644 include/jointrom.h $(JR_DEST)/include/
	$(if $(JR_PUBLIC_H),install -m 644 $(JR_PUBLIC_H) $(JR_DEST)/include/jointrom/)
	install -m 644 include/jointrom/private/*.h $(JR_DEST)/include/jointrom/private/
	install -m 644 share/*.gp $(JR_DEST)/share/jointrom/
	printf '%s\n' 'prefix=$(PREFIX)' 'exec_prefix=$${prefix}' 'libdir=$${exec_prefix}/lib' \
	  'includedir=$${prefix}/include' 'sharedir=$${prefix}/share/jointrom' 'ccompiler=$(PCC)' '' \
	  'Name: jointrom' \
	  'Description: Reduced-order models of bolted joints by harmonic balance with friction contact elements' \
	  'Version: $(JR_VERSION)' \
	  'Cflags: -I$${includedir} $(strip $(SLEPC_CC_INCLUDES))' \
	  'Libs: -L$${libdir} -ljointrom $(strip $(SLEPC_LIB)) -lm' > $(JR_DEST)/lib/pkgconfig/jointrom.pc
	chmod 644 $(JR_DEST)/lib/pkgconfig/jointrom.pc

uninstall:
	rm -f $(JR_DEST)/bin/jointrom $(JR_DEST)/lib/libjointrom.a $(JR_DEST)/lib/pkgconfig/jointrom.pc \
	  $(JR_DEST)/include/jointrom.h $(addprefix $(JR_DEST)/,$(wildcard include/jointrom/*.h include/jointrom/private/*.h)) \
	  $(addprefix $(JR_DEST)/share/jointrom/,$(notdir $(wildcard share/*.gp)))
	rmdir $(JR_DEST)/include/jointrom/private $(JR_DEST)/include/jointrom $(JR_DEST)/share/jointrom 2>/dev/null || true

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
