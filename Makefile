# libselftalk - language-assisted evolutionary robotics (see README.md)
#
#   make            library (static + shared) and apps
#   make run        set-up, build, the main job
#   make test       set-up, build, all tests (quick)
#   make asan       tests under AddressSanitizer + UBSan, with ST_ASSERT on
#   make ASSERTS=1  ST_ASSERT on (lib/core/internal.h): the public functions' preconditions
#                   abort when broken; a debug build is `make OPT="-O0 -g" ASSERTS=1`
#   make valgrind   unit tests under valgrind memcheck
#   make bench      benchmarks
#   make compare    the dynamic world against MuJoCo 2.2.2 (Debian's libmujoco-dev) on the same
#                   model, same run (tools/compare/compare.c; COMPARE_SET, COMPARE_ARGS); a
#                   benchmark, not part of make test (its smoke test is: tests/check_compare.sh)
#   make replicate [PRESET=small] [RUNS=N] [OUT=DIR]   the whole study, resumable, priced
#                   first (tools/replicate.mk; README.md, "Replicating the study")
#   make fuzz       fuzz targets (clang's libFuzzer, ASan + UBSan) and seed corpora in build-fuzz/;
#                   make fuzz-run [FUZZ_RUNS=1000000] runs each, then tests/tools_sweep.py --full
#                   (not part of make test)
#   make golden-update [GOLDEN=NAME]   rewrite tests/golden/golden.sha256 after a change meant
#                   to move results (tests/check_golden.sh)
#   make install PREFIX=/usr/local

PREFIX ?= /usr/local
CC ?= cc
CXX ?= c++
BUILD ?= build
APPDIR ?= apps
OPT ?= -O3 -g
SAN ?=
WERROR ?=
ASSERTS ?=

PKGS_CORE := inih
PKGS_SIM := ode ccd urdfdom tinyxml assimp eigen3
PKGS_TEST := cunit
# MPI (issue 16): apps/evolve is compiled with $(MPICC) and the MPI code of apps/evolve_mpi.c
# when mpicc is found (`make deps` installs Debian's OpenMPI); MPI=0 builds it without MPI,
# exactly as before; MPI=1 fails when mpicc is missing. Nothing else uses MPI.
MPICC ?= mpicc
MPI ?= auto

WARN := -Wall -Wextra -Wpedantic $(if $(WERROR),-Werror)
# The packages' flags come from pkg-config, which only knows them once `make deps` has installed
# the packages. So they are computed when a recipe first needs them, never while the Makefile is
# parsed (pkg_flags caches the answer), and the targets that install (test, run, ...) run deps,
# then a fresh make that builds: nothing from a parse made before the packages existed is used.
pkg_flags = $(shell pkg-config $(1) 2>/dev/null)$(if $(filter 0,$(.SHELLSTATUS)),,$(error \
  pkg-config $(1) failed: a package is missing. `make deps` installs them ($(DEB_PACKAGES)); \
  `make test` and `make run` do it first))
PKG_CFLAGS = $(eval PKG_CFLAGS := $(call pkg_flags,--cflags $(PKGS_CORE) $(PKGS_SIM)))$(PKG_CFLAGS)
LIBS_CORE = $(eval LIBS_CORE := $(call pkg_flags,--libs $(PKGS_CORE)) -lm)$(LIBS_CORE)
LIBS_SIM = $(eval LIBS_SIM := $(call pkg_flags,--libs $(PKGS_SIM)) -lstdc++ -lgomp)$(LIBS_SIM)
LIBS_TEST = $(eval LIBS_TEST := $(call pkg_flags,--libs $(PKGS_TEST)))$(LIBS_TEST)
# 1 when apps/evolve is built with MPI (computed, like the packages' flags, when first needed)
HAVE_MPI = $(eval HAVE_MPI := $(call mpi_found))$(HAVE_MPI)
mpi_found = $(if $(filter 0 no,$(MPI)),,$(if $(shell command -v $(MPICC) 2>/dev/null),1,$(if \
  $(filter 1 yes,$(MPI)),$(error MPI=$(MPI) but $(MPICC) is not found: `make deps` installs OpenMPI))))
# mpicc wraps $(CC) (OpenMPI and MPICH both honour these)
EVOLVE_CC = $(if $(HAVE_MPI),OMPI_CC="$(CC)" MPICH_CC="$(CC)" $(MPICC) -DST_WITH_MPI,$(CC))
CPPFLAGS_ALL = -Iinclude -Ilib $(PKG_CFLAGS)
# release builds (the default) leave ST_ASSERT out: it never changes a result, only stops early
ASSERT_FLAGS := $(if $(filter 1,$(ASSERTS)),-DST_ASSERTS)
# -fvisibility=hidden: the shared libraries export the public functions (ST_API, selftalk/base.h)
# and nothing else; tools/libselftalk.map keeps out what the compilers export all the same
VISIBILITY := -fvisibility=hidden
CFLAGS_ALL := -std=c99 $(WARN) $(OPT) -fPIC -fopenmp $(VISIBILITY) $(SAN) $(ASSERT_FLAGS) $(CFLAGS)
CXXFLAGS_ALL := -std=c++17 -Wall -Wextra $(OPT) -fPIC -fopenmp $(VISIBILITY) -fvisibility-inlines-hidden \
  $(SAN) $(CXXFLAGS)
SO_EXPORTS := tools/libselftalk.map

# lib/ by layer: core (network, GA, config, genomes, statistics: no simulator, so a robot
# controller can link them alone), model (URDF, kinematics), world (kinematic and ODE
# backends), task (postures, fitness, caretaker), episode (the one episode loop, its
# controllers - the network's and the scripted one - its trials and the trace CSV), run
# (evolution), posteval (the post-evaluation tests). A layer's folder may hold one level of
# subfolders (lib/episode/trials/: a file per trial kind). Objects mirror the folders under
# build/obj/. A file includes no header of a higher layer (tests/check_layers.sh).
LAYERS := core model world task episode run posteval
STRAY_SRC := $(filter-out $(LAYERS:%=lib/%/),$(sort $(dir $(wildcard lib/*.c lib/*.cpp lib/*/*.c lib/*/*.cpp))))
$(if $(STRAY_SRC),$(error sources outside the layer folders ($(STRAY_SRC)): move them into one of lib/{$(LAYERS)}/ or add a layer to LAYERS))
CORE_SRC := $(wildcard lib/core/*.c)
SIM_SRC := $(foreach l,$(filter-out core,$(LAYERS)),$(wildcard lib/$(l)/*.c lib/$(l)/*.cpp lib/$(l)/*/*.c))
CORE_OBJ := $(CORE_SRC:lib/%.c=$(BUILD)/obj/%.o)
SIM_OBJ := $(patsubst lib/%,$(BUILD)/obj/%.o,$(basename $(SIM_SRC)))

CORE_A := $(BUILD)/libselftalk-core.a
CORE_SO := $(BUILD)/libselftalk-core.so
FULL_A := $(BUILD)/libselftalk.a
FULL_SO := $(BUILD)/libselftalk.so

APP_SRC := $(wildcard apps/*.c)
APP_COMMON := apps/app_common.c
APP_MPI := apps/evolve_mpi.c
APP_PAGE := apps/trial_page.c
APP_MAINS := $(filter-out $(APP_COMMON) $(APP_MPI) $(APP_PAGE),$(APP_SRC))
APPS := $(APP_MAINS:apps/%.c=$(APPDIR)/%)
# diagnostics built from tools/*.c (not part of the protocol; see each file's header)
TOOLS := $(patsubst tools/%.c,$(BUILD)/%,$(wildcard tools/*.c))

TEST_SRC := $(wildcard tests/test_*.c)
TEST_BIN := $(BUILD)/run_tests

HEADERS := $(wildcard include/selftalk/*.h) $(wildcard lib/*/*.h lib/*/*/*.h)

DEB_PACKAGES := build-essential pkg-config libode-dev libccd-dev libeigen3-dev liburdfdom-dev \
  libassimp-dev libtinyxml-dev libcunit1-dev libinih-dev python3 python3-matplotlib valgrind \
  libopenmpi-dev openmpi-bin libjs-three chromium python3-pil ffmpeg libmujoco-dev
# Debian's interpreter, which python3-matplotlib serves (another python3 may come first in PATH)
PYTHON := /usr/bin/python3
RUN_CONFIG := configs/simple_prim.cfg
RUN_DIR := runs/simple_prim-s1

.PHONY: FORCE all deps run run-only test test-only asan asan-only valgrind valgrind-only bench \
  compare compare-only \
  replicate replicate-only \
  bench-only golden-update install uninstall clean fuzz fuzz-run
.DELETE_ON_ERROR:

all: $(CORE_A) $(CORE_SO) $(FULL_A) $(FULL_SO) $(APPS) $(TOOLS)

# installs the Debian packages the project needs; does nothing when they are present
deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "make deps: installing$$missing"; \
	  if [ "$$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $$missing; \
	fi

$(BUILD)/obj/%.o: lib/%.c $(HEADERS) | $(BUILD)/obj
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS_ALL) $(CFLAGS_ALL) -c $< -o $@

$(BUILD)/obj/%.o: lib/%.cpp $(HEADERS) | $(BUILD)/obj
	@mkdir -p $(@D)
	$(CXX) $(CPPFLAGS_ALL) $(CXXFLAGS_ALL) -c $< -o $@

$(BUILD)/obj $(BUILD)/tobj:
	mkdir -p $@

$(CORE_A): $(CORE_OBJ)
	rm -f $@ && ar rcs $@ $^

$(FULL_A): $(CORE_OBJ) $(SIM_OBJ)
	rm -f $@ && ar rcs $@ $^

$(CORE_SO): $(CORE_OBJ) $(SO_EXPORTS)
	$(CC) -shared $(SAN) -Wl,-soname,libselftalk-core.so.0 -Wl,--version-script=$(SO_EXPORTS) \
	  -o $@ $(CORE_OBJ) $(LIBS_CORE)

$(FULL_SO): $(CORE_OBJ) $(SIM_OBJ) $(SO_EXPORTS)
	$(CXX) -shared $(SAN) -fopenmp -Wl,-soname,libselftalk.so.0 -Wl,--version-script=$(SO_EXPORTS) \
	  -o $@ $(CORE_OBJ) $(SIM_OBJ) $(LIBS_SIM) $(LIBS_CORE)

# apps link the static library: they run from the source tree without LD_LIBRARY_PATH
$(APPDIR)/bench: apps/press_plan.h
$(APPDIR)/%: apps/%.c $(APP_COMMON) apps/app_common.h $(FULL_A) $(HEADERS)
	@mkdir -p $(APPDIR)
	$(CC) $(CPPFLAGS_ALL) $(CFLAGS_ALL) -o $@ $< $(APP_COMMON) $(FULL_A) $(LIBS_SIM) $(LIBS_CORE)

# evolve: with MPI when HAVE_MPI (the stamp rebuilds it when that changes)
$(APPDIR)/evolve: apps/evolve.c $(APP_MPI) apps/evolve_mpi.h $(APP_COMMON) apps/app_common.h \
  $(FULL_A) $(HEADERS) $(BUILD)/evolve-mpi.stamp
	@mkdir -p $(APPDIR)
	$(EVOLVE_CC) $(CPPFLAGS_ALL) $(CFLAGS_ALL) -o $@ $< $(APP_MPI) $(APP_COMMON) $(FULL_A) \
	  $(LIBS_SIM) $(LIBS_CORE)

# replay: with the trial page writer (--html) and its template, tools/trial_page.html, compiled in
# as bytes (od is in coreutils), so the installed app needs no file of its own
$(APPDIR)/replay: apps/replay.c $(APP_PAGE) apps/trial_page.h $(BUILD)/trial_page.inc \
  $(APP_COMMON) apps/app_common.h $(FULL_A) $(HEADERS)
	@mkdir -p $(APPDIR)
	$(CC) $(CPPFLAGS_ALL) -I$(BUILD) $(CFLAGS_ALL) -o $@ $< $(APP_PAGE) $(APP_COMMON) $(FULL_A) \
	  $(LIBS_SIM) $(LIBS_CORE)

$(BUILD)/trial_page.inc: tools/trial_page.html | $(BUILD)/obj
	od -An -v -tx1 $< | sed 's/\([0-9a-f][0-9a-f]\)/0x\1,/g' > $@.tmp && mv $@.tmp $@

$(BUILD)/evolve-mpi.stamp: FORCE | $(BUILD)/obj
	@echo 'mpi=$(HAVE_MPI)' | cmp -s - $@ || echo 'mpi=$(HAVE_MPI)' > $@

FORCE:

# the page writer's fuzz target without libFuzzer (tests/fuzz/run_inputs.c), with the default
# compiler: make test runs its property on the seeds (tests/check_html.sh)
$(BUILD)/page_check: tests/fuzz/fuzz_page.c tests/fuzz/run_inputs.c tests/fuzz/app_shim.h \
  $(APP_PAGE) apps/trial_page.h $(BUILD)/trial_page.inc $(FULL_A) $(HEADERS)
	$(CC) $(CPPFLAGS_ALL) -Iapps -I$(BUILD) $(CFLAGS_ALL) -o $@ tests/fuzz/fuzz_page.c \
	  tests/fuzz/run_inputs.c $(FULL_A) $(LIBS_SIM) $(LIBS_CORE)

$(BUILD)/%: tools/%.c $(FULL_A) $(HEADERS)
	$(CC) $(CPPFLAGS_ALL) $(CFLAGS_ALL) -o $@ $< $(FULL_A) $(LIBS_SIM) $(LIBS_CORE)

# one CUnit binary; every tests/test_NAME.c defines st_suite_NAME(), found by this list
$(BUILD)/suites.inc: $(TEST_SRC) | $(BUILD)/obj
	@for f in $(TEST_SRC); do n=$${f#tests/test_}; echo "SUITE($${n%.c})"; done > $@.tmp && mv $@.tmp $@

$(TEST_BIN): tests/main.c $(TEST_SRC) tests/test_util.h $(BUILD)/suites.inc $(FULL_A) $(HEADERS)
	$(CC) $(CPPFLAGS_ALL) -I$(BUILD) $(CFLAGS_ALL) -Wno-pedantic -D_POSIX_C_SOURCE=200809L -o $@ tests/main.c $(TEST_SRC) \
	  $(FULL_A) $(LIBS_TEST) $(LIBS_SIM) $(LIBS_CORE)

# the targets that set up first: deps, then a fresh make that computes the flags (pkg_flags)
test run asan valgrind bench replicate compare: deps
	@$(MAKE) --no-print-directory $@-only

# every step's files under OUT; a killed replication continues where it stopped. Its cost
# first (tools/replicate.mk's target cost: measured here, printed, no prompt)
replicate-only: all
	@$(MAKE) --no-print-directory -f tools/replicate.mk PYTHON=$(PYTHON) EVAL_COST=$(BUILD)/eval_cost cost
	@$(MAKE) --no-print-directory -f tools/replicate.mk PYTHON=$(PYTHON)

# the main job: the simple-prim stage, then what it gave (summary, files, PNG plot)
run-only: all
	./$(APPDIR)/evolve $(RUN_CONFIG) --out $(RUN_DIR)
	@$(PYTHON) tools/run_report.py $(RUN_DIR)

# fault injection for tests/check_faults.sh (LD_PRELOAD; no sanitizer: it runs inside the apps)
FAULT_SHIM := $(BUILD)/fault_shim.so
$(FAULT_SHIM): tests/faults/fault_shim.c | $(BUILD)/obj
	$(CC) -std=c99 $(WARN) -O2 -fPIC -shared -o $@ $< -ldl

# a host program that uses ODE itself (tests/check_link.sh): ODE alone, with the shared library,
# with the static library; the same host lines in all three
LINK_HOSTS := $(BUILD)/ode_host_plain $(BUILD)/ode_host_shared $(BUILD)/ode_host_static
$(BUILD)/ode_host_plain: tests/link/ode_host.c | $(BUILD)/obj
	$(CC) $(CFLAGS_ALL) $(PKG_CFLAGS) -o $@ $< $(LIBS_SIM)
$(BUILD)/ode_host_shared: tests/link/ode_host.c $(FULL_SO) $(HEADERS) | $(BUILD)/obj
	$(CC) -DWITH_SELFTALK $(CPPFLAGS_ALL) $(CFLAGS_ALL) -o $@ $< $(FULL_SO) $(LIBS_SIM) $(LIBS_CORE)
$(BUILD)/ode_host_static: tests/link/ode_host.c $(FULL_A) $(HEADERS) | $(BUILD)/obj
	$(CC) -DWITH_SELFTALK $(CPPFLAGS_ALL) $(CFLAGS_ALL) -o $@ $< $(FULL_A) $(LIBS_SIM) $(LIBS_CORE)

# make compare: libselftalk's dynamic world against MuJoCo (Debian's libmujoco-dev, 2.2.2) on
# the same model imported from the same URDF, free, press and held interleaved in one run
# (docs/PROTOCOL.md, "Speed"; docs/notebook/speed.md, "Against MuJoCo"); the variant
# COMPARE_SET, 10 rounds unless COMPARE_ARGS
COMPARE := $(BUILD)/compare
COMPARE_SET ?= dynamics.lcp=warm
COMPARE_ARGS ?=
$(COMPARE): tools/compare/compare.c apps/press_plan.h $(FULL_A) $(HEADERS)
	$(CC) $(CPPFLAGS_ALL) -Iapps $(CFLAGS_ALL) -o $@ $< $(FULL_A) -lmujoco $(LIBS_SIM) $(LIBS_CORE)

compare-only: all $(COMPARE)
	./$(COMPARE) --set '$(COMPARE_SET)' $(COMPARE_ARGS)

test-only: all $(TEST_BIN) $(FAULT_SHIM) $(BUILD)/page_check $(LINK_HOSTS) $(COMPARE)
	+@BUILD=$(BUILD) APPDIR=$(APPDIR) bash tests/run_all.sh

asan-only:
	$(MAKE) BUILD=build-asan APPDIR=build-asan/apps OPT="-O1 -g -fno-omit-frame-pointer" ASSERTS=1 \
	  SAN="-fsanitize=address,undefined -fno-sanitize-recover=all" test-only

valgrind-only: $(TEST_BIN)
	valgrind --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite \
	  ./$(TEST_BIN)

bench-only: all
	./$(APPDIR)/bench --mode kinematic

# golden results (tests/golden/golden.sha256, checked by make test): rewrite them after a change
# meant to move results, e.g. `make golden-update GOLDEN=dynamic` after a model change
golden-update: all
	@BUILD=$(BUILD) APPDIR=$(APPDIR) bash tests/check_golden.sh --update $(GOLDEN)

# ---- fuzzing (tests/fuzz/): libFuzzer needs clang (Debian: apt-get install clang); the
# default build and make test do not. The readers and what they call are compiled again with
# coverage and ASan + UBSan (any UB aborts) into build-fuzz/; each target gets a seed corpus
# from the shipped files, and libFuzzer adds what it finds to it.
FUZZ_CC ?= clang
FUZZ_CXX ?= clang++
FUZZ_DIR := build-fuzz
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZ_FLAGS := -g -O1 $(FUZZ_SAN) -fsanitize=fuzzer-no-link
FUZZ_TARGETS := config genome urdf checkpoint journal score stats page fitness
# the library but its two OpenMP modules (evolution, the parallel post-evaluation)
FUZZ_LIB := $(filter-out run/evolve posteval/postrun,$(patsubst lib/%,%,$(basename $(CORE_SRC) $(SIM_SRC))))
FUZZ_OBJ := $(FUZZ_LIB:%=$(FUZZ_DIR)/obj/%.o)
FUZZ_BIN := $(FUZZ_TARGETS:%=$(FUZZ_DIR)/fuzz_%)
FUZZ_RUNS ?= 1000000
FUZZ_TIME ?= 1200
FUZZ_NICE ?= 19

fuzz: $(FUZZ_BIN) $(FUZZ_TARGETS:%=$(FUZZ_DIR)/corpus/%/.seeded)
.SECONDARY: $(FUZZ_OBJ) # kept: a changed reader recompiles alone

$(FUZZ_DIR)/obj/%.o: lib/%.c $(HEADERS)
	@command -v $(FUZZ_CC) > /dev/null || { echo "make fuzz: $(FUZZ_CC) not found (apt-get install clang)"; exit 1; }
	@mkdir -p $(@D)
	$(FUZZ_CC) $(CPPFLAGS_ALL) -std=c99 $(WARN) $(FUZZ_FLAGS) -c $< -o $@

$(FUZZ_DIR)/obj/%.o: lib/%.cpp $(HEADERS)
	@mkdir -p $(@D)
	$(FUZZ_CXX) $(CPPFLAGS_ALL) -std=c++17 -Wall -Wextra $(FUZZ_FLAGS) -c $< -o $@

# the app's reader (score) and replay's page writer are fuzzed in the apps' own source, included
# by the target; stats's readers are the library's
$(FUZZ_DIR)/fuzz_score: apps/score.c tests/fuzz/app_shim.h
$(FUZZ_DIR)/fuzz_page: $(APP_PAGE) apps/trial_page.h $(BUILD)/trial_page.inc tests/fuzz/app_shim.h

$(FUZZ_DIR)/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_OBJ) $(HEADERS)
	$(FUZZ_CC) $(CPPFLAGS_ALL) -Iapps -I$(BUILD) -std=c99 $(WARN) $(FUZZ_FLAGS) -c $< -o $@.o
	$(FUZZ_CXX) -fsanitize=fuzzer $(FUZZ_SAN) -o $@ $@.o $(FUZZ_OBJ) $(LIBS_SIM) $(LIBS_CORE)

# seeds: the shipped configs, genomes and URDF, a short run's checkpoint with its files, and
# the inputs fuzzing found (tests/fuzz/regressions/TARGET/: each is a regression test too);
# each seed is named after its path (data/evolved/prims_s2/population.genome ->
# data_evolved_prims_s2_population.genome): several runs' population.genome do not collide
FUZZ_SEEDS_config := configs/*.cfg
FUZZ_SEEDS_genome := data/evolved/*.genome data/evolved/*/population.genome tests/golden/*.genome
FUZZ_SEEDS_urdf := data/*.urdf tests/fuzz/seeds/urdf/*
FUZZ_SEEDS_checkpoint := tests/fuzz/seeds/checkpoint/*
FUZZ_SEEDS_journal := tests/fuzz/seeds/journal/*
FUZZ_SEEDS_score := tests/fuzz/seeds/score/*
FUZZ_SEEDS_stats := tests/fuzz/seeds/stats/*
FUZZ_SEEDS_page := tests/fuzz/seeds/page/*
FUZZ_SEEDS_fitness := data/evolved/unchained/*/fitness.csv
$(FUZZ_DIR)/corpus/%/.seeded: tests/fuzz/fuzz_%.c
	@mkdir -p $(@D)
	@for f in $(wildcard $(FUZZ_SEEDS_$*) tests/fuzz/regressions/$*/*); do \
	  cp "$$f" "$(@D)/$$(echo "$$f" | tr / _)" || exit 1; done
	@touch $@

# each target for FUZZ_RUNS executions (or FUZZ_TIME seconds), one after the other, niced (the
# machine's evolution runs come first), with the flags of tests/fuzz/TARGET.options (a
# dictionary, a length limit); a hang is an input that takes over 10 s, a leak fails
# like a crash; what libFuzzer finds goes to build-fuzz/TARGET-crash-*, -leak-*, -timeout-*
fuzz-run: fuzz
	@bad=0; for t in $(FUZZ_TARGETS); do \
	  echo "== fuzz_$$t: -runs=$(FUZZ_RUNS) -max_total_time=$(FUZZ_TIME)"; \
	  if TMPDIR=/dev/shm nice -n $(FUZZ_NICE) ./$(FUZZ_DIR)/fuzz_$$t -runs=$(FUZZ_RUNS) \
	       -max_total_time=$(FUZZ_TIME) -timeout=10 -print_final_stats=1 \
	       $$(cat tests/fuzz/$$t.options 2> /dev/null) \
	       -artifact_prefix=$(FUZZ_DIR)/$$t- $(FUZZ_DIR)/corpus/$$t > $(FUZZ_DIR)/$$t.log 2>&1; then \
	    grep -E '^(Done|stat::number_of_executed_units|stat::average_exec_per_sec|stat::peak_rss_mb)' $(FUZZ_DIR)/$$t.log; \
	  else bad=1; tail -40 $(FUZZ_DIR)/$$t.log; fi; \
	done; \
	echo "== tools_sweep --full: every Python tool on malformed CSVs, every value in every column"; \
	nice -n $(FUZZ_NICE) $(PYTHON) tests/tools_sweep.py $(FUZZ_DIR)/tools-sweep --full \
	  > $(FUZZ_DIR)/tools-sweep.log 2>&1 || bad=1; tail -20 $(FUZZ_DIR)/tools-sweep.log; \
	exit $$bad

install: all
	install -d $(DESTDIR)$(PREFIX)/include/selftalk $(DESTDIR)$(PREFIX)/lib/pkgconfig \
	  $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/share/selftalk
	install -m 644 include/selftalk/*.h $(DESTDIR)$(PREFIX)/include/selftalk/
	install -m 644 $(CORE_A) $(FULL_A) $(DESTDIR)$(PREFIX)/lib/
	install -m 755 $(CORE_SO) $(DESTDIR)$(PREFIX)/lib/libselftalk-core.so.0
	install -m 755 $(FULL_SO) $(DESTDIR)$(PREFIX)/lib/libselftalk.so.0
	ln -sf libselftalk-core.so.0 $(DESTDIR)$(PREFIX)/lib/libselftalk-core.so
	ln -sf libselftalk.so.0 $(DESTDIR)$(PREFIX)/lib/libselftalk.so
	install -m 755 $(APPS) $(DESTDIR)$(PREFIX)/bin/
	for d in data configs; do if [ -d $$d ]; then cp -r $$d $(DESTDIR)$(PREFIX)/share/selftalk/; fi; done
	for pc in selftalk selftalk-core; do \
	  sed -e 's|@PREFIX@|$(PREFIX)|g' -e 's|@VERSION@|$(shell sed -n 's/.*ST_VERSION_STRING "\(.*\)"/\1/p' include/selftalk/base.h)|g' \
	    tools/$$pc.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/$$pc.pc; done

uninstall:
	rm -rf $(DESTDIR)$(PREFIX)/include/selftalk $(DESTDIR)$(PREFIX)/share/selftalk
	rm -f $(DESTDIR)$(PREFIX)/lib/libselftalk* $(DESTDIR)$(PREFIX)/lib/pkgconfig/selftalk*.pc
	cd $(DESTDIR)$(PREFIX)/bin && rm -f $(notdir $(APPS))

clean:
	rm -rf build build-asan $(FUZZ_DIR) $(APPS)
