# svet - the build. `make` builds the library and every chapter program,
# `make test` runs one check suite per module, `make chNN` one chapter with
# only the modules it needs. `make REAL=double ...` builds everything with
# double in place of the book's float (include/core/real.h); each REAL has its own
# build directory, so both can coexist. `make help` lists every target.

REAL     ?= float
# Speed layers. The plain algorithm of each module is the main text of
# src/PART/M.c, compiled in every build and linked by the chapters' cc lines.
# What only makes it faster (SSE and AVX lanes, early rejections, culling
# spheres, packets) lives in src/PART/fast/M_WHAT.c, named after the module
# M it speeds up (src/core/fast/ray_simd.c, src/geometry/fast/
# parallelogram_cull.c), with no header of its own in include/. SIMD=on
# (the default) compiles every src/*/fast/*.c and defines SVET_SIMD: with it
# the plain file hands its inner steps to the fast one, and core/simd.h
# offers its vectors (SIMD_REAL). SIMD=off leaves the fast files out of the
# build (build/REAL-plain/) and the images are the same bits (make bitcheck).
SIMD     ?= on
CC       ?= cc
# -O3: faster than -O2 on the renderer, and the same bits (gcc vectorises
# only what IEEE allows without -ffast-math).
OPT      ?= -O3
# The instruction set of the machine that builds (AVX2, say), which the
# vector code (include/core/simd.h) and gcc's own loops use. The bits do not
# change with it (-ffp-contract=off keeps gcc from fusing a multiply and an
# add, and no reassociation is allowed); `make ARCH=` builds a binary for
# any x86-64 (SSE2 only) to copy to another machine.
ARCH     ?= -march=native
# Link-time optimisation (gcc): the compiler inlines across modules (the
# integrator's calls into material.c, light.c and ray.c), a little faster,
# and the same bits: without -ffast-math inlining changes no rounding.
# `make LTO=` builds without it, as `make sanitize` does; with clang it
# is off unless asked for (LTO=-flto, with llvm-ar). The build does not
# track flags: give a changed LTO (or OPT, ARCH) a fresh BUILD directory
# or `make clean` first.
ifeq ($(findstring clang,$(shell $(CC) --version 2>/dev/null)),)
LTO      ?= -flto=auto
else
LTO      ?=
endif
# an archive of LTO objects needs the compiler's own ar
ifneq ($(strip $(LTO)),)
ifeq ($(origin AR),default)
ifeq ($(findstring clang,$(shell $(CC) --version 2>/dev/null)),)
AR       := gcc-ar
else
AR       := llvm-ar
endif
endif
endif
ifeq ($(SIMD),on)
SIMDDEF  := -DSVET_SIMD
PLAIN_SUFFIX :=
else ifeq ($(SIMD),off)
SIMDDEF  :=
PLAIN_SUFFIX := -plain
else
$(error SIMD must be on or off, not '$(SIMD)')
endif
BUILD    ?= build/$(REAL)$(PLAIN_SUFFIX)
PREFIX   ?= /usr/local
PKG_CONFIG ?= pkg-config

ifeq ($(REAL),double)
REALDEF  := -DSVET_DOUBLE
else ifeq ($(REAL),float)
REALDEF  :=
else
$(error REAL must be float or double, not '$(REAL)')
endif

# -ffp-contract=off: no fused multiply-add behind our back, so float results
# are the same on every x86-64 compiler that honours it (docs: determinism).
WARN     := -Wall -Wextra -Wpedantic -Wdouble-promotion -Wshadow \
            -Wstrict-prototypes -Wmissing-prototypes -Wformat=2
CFLAGS   ?= $(OPT) $(ARCH) $(LTO) -g
ALL_CFLAGS = -std=c11 -D_POSIX_C_SOURCE=200809L -ffp-contract=off $(WARN) \
             $(REALDEF) $(SIMDDEF) -Iinclude -fopenmp $(CFLAGS) $(EXTRA_CFLAGS)

PKG_CFLAGS := $(shell $(PKG_CONFIG) --cflags OpenEXR libpng 2>/dev/null)
PKG_LIBS   := $(shell $(PKG_CONFIG) --libs OpenEXR libpng 2>/dev/null)
CHECK_CFLAGS := $(shell $(PKG_CONFIG) --cflags check 2>/dev/null)
CHECK_LIBS   := $(shell $(PKG_CONFIG) --libs check 2>/dev/null)
# Only libOpenEXRCore (the C API) is used; --as-needed drops the C++ rest
# that OpenEXR.pc lists.
LDLIBS   = -Wl,--as-needed $(PKG_LIBS) -lm -fopenmp $(EXTRA_LDFLAGS)

# The library's modules, one folder per part of the book (src/core/vec.c,
# include/core/vec.h, tests/core/test_vec.c); a module's name is unique
# across the folders, so objects, suites and the chapters' .mk files name a
# module by its name alone (a speed layer src/PART/fast/M_WHAT.c too).
PARTS    := $(sort $(notdir $(wildcard src/*)))
PLAIN_SRCS := $(sort $(wildcard src/*/*.c))
FAST_SRCS  := $(sort $(wildcard src/*/fast/*.c))
SRCS     := $(PLAIN_SRCS) $(if $(SIMDDEF),$(FAST_SRCS))
MODULES  := $(notdir $(SRCS:.c=))
HDRS     := $(sort $(wildcard include/*/*.h))
OBJS     := $(MODULES:%=$(BUILD)/obj/%.o)
LIB      := $(BUILD)/libsvet.a
TESTSRCS := $(sort $(wildcard tests/*/test_*.c))
TESTS    := $(addprefix $(BUILD)/tests/,$(notdir $(TESTSRCS:.c=)))
BENCHSRCS := $(sort $(wildcard bench/bench_*.c))
BENCHES  := $(BENCHSRCS:bench/bench_%.c=bench-%)
VECSRCS  := $(sort $(wildcard tools/vectors_*.c))
VECTOOLS := $(VECSRCS:tools/%.c=$(BUILD)/tools/%)

.SECONDARY:

.PHONY: all lib test test-images check-tags check-links sanitize sanitize-all chapters figures \
        vectors noise-vectors check-vectors cc-lines clean install uninstall \
        help bench $(BENCHES)

all: lib chapters $(BUILD)/svet

lib: $(LIB)

define object_rule
$(BUILD)/obj/$(notdir $(1:.c=.o)): $(1)
	@mkdir -p $$(@D)
	$$(CC) $$(ALL_CFLAGS) $$(PKG_CFLAGS) -MMD -MP -c $$< -o $$@
endef
$(foreach s,$(SRCS),$(eval $(call object_rule,$(s))))

$(LIB): $(OBJS)
	@rm -f $@
	$(AR) rcs $@ $^

# --- the svet command ------------------------------------------------------
# cmd/svet.c holds main() and the table of subcommands; cmd/cmdutil.c
# what they share; each other cmd/*.c is one subcommand.
SVET_MAIN := $(wildcard cmd/svet.c)
CMD_SRCS  := $(sort $(wildcard cmd/*.c))
ifneq ($(SVET_MAIN),)
$(BUILD)/svet: $(CMD_SRCS) $(wildcard cmd/*.h) $(LIB)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(PKG_CFLAGS) -Icmd $(CMD_SRCS) -o $@ $(LIB) $(LDLIBS)
else
$(BUILD)/svet:
	@true
endif

# --- unit tests: one check suite per module --------------------------------
define test_object_rule
$(BUILD)/tests/$(notdir $(1:.c=.o)): $(1)
	@mkdir -p $$(@D)
	$$(CC) $$(ALL_CFLAGS) -Itests $$(PKG_CFLAGS) $$(CHECK_CFLAGS) -MMD -MP -c $$< -o $$@
endef
$(foreach s,$(TESTSRCS) $(wildcard tests/*.c),$(eval $(call test_object_rule,$(s))))

# Test support: every tests/*.c (testutil.c, geomcheck.c, chi2.c, ...; the
# suites are in the parts' folders) goes into one archive linked to every
# suite.
TESTSUP_SRCS := $(wildcard tests/*.c)
TESTSUP_OBJS := $(TESTSUP_SRCS:tests/%.c=$(BUILD)/tests/%.o)
TESTSUP      := $(BUILD)/tests/libtestsupport.a
$(TESTSUP): $(TESTSUP_OBJS)
	@rm -f $@
	$(AR) rcs $@ $^

# With gcc's link-time optimisation the suites link the library as one
# object, optimised across its modules once (`-r`), rather than each of
# them re-optimising the whole library in its own link; else the archive.
ifneq ($(strip $(LTO)),)
ifeq ($(findstring clang,$(shell $(CC) --version 2>/dev/null)),)
TESTLIB  := $(BUILD)/tests/libsvet-lto.o
endif
endif
TESTLIB  ?= $(LIB)
ifneq ($(TESTLIB),$(LIB))
$(TESTLIB): $(OBJS)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -r -nostdlib -flinker-output=nolto-rel $^ -o $@
endif

$(BUILD)/tests/test_%: $(BUILD)/tests/test_%.o $(TESTSUP) $(TESTLIB)
	$(CC) $(ALL_CFLAGS) $^ -o $@ $(CHECK_LIBS) $(LDLIBS)

# Every suite runs from the top directory (they read tests/vectors/ and
# scenes/). CK_FORK=no keeps sanitizer reports in the test's own process.
test: check-tags $(TESTS) $(if $(SVET_MAIN),$(BUILD)/svet) check-links
	@REAL=$(REAL) sh tools/run-tests.sh $(TESTS)
	$(if $(SVET_MAIN),sh tests/cmd/test_merge.sh $(BUILD)/svet)
	$(if $(SVET_MAIN),sh tests/cmd/test_merge_methods.sh $(BUILD)/svet)
	$(if $(SVET_MAIN),sh tests/cmd/test_render_parallel.sh $(BUILD)/svet)
	$(if $(SVET_MAIN),sh tests/cmd/test_frames.sh $(BUILD)/svet)

# `make test-images`: the suites that render or trace whole scenes (the
# renderer, the references' Z-tests, the tracers, the grids, svet render),
# e.g. `make SIMD=off test-images` for the plain build in CI.
IMAGE_TESTS := $(filter %/test_render %/test_reference %/test_tracer \
                 %/test_grid %/test_batch %/test_cmd_render,$(TESTS))
test-images: $(IMAGE_TESTS) $(if $(SVET_MAIN),$(BUILD)/svet)
	@REAL=$(REAL)$(if $(SIMDDEF),,-plain) sh tools/run-tests.sh $(IMAGE_TESTS)

# The book's equations tagged in the code as "eq. (N.M)", every one listed
# in tools/eq-tags.txt; and every path a Markdown file names exists.
# tools/test-checks.sh first tries both checkers on a small made-up tree.
check-tags:
	@sh tools/test-checks.sh
	@sh tools/check-tags.sh tools/eq-tags.txt
	@sh tools/check-paths.sh

# AddressSanitizer + UndefinedBehaviorSanitizer, any report is fatal.
SAN_FLAGS := -fsanitize=address,undefined -fno-sanitize-recover=all \
             -fno-omit-frame-pointer
sanitize:
	$(MAKE) BUILD=build/sanitize-$(REAL)$(PLAIN_SUFFIX) OPT=-O1 LTO= \
	    EXTRA_CFLAGS="$(SAN_FLAGS)" EXTRA_LDFLAGS="$(SAN_FLAGS)" \
	    SVET_SANITIZE=1 test

# All three builds a change must pass sanitized: float, double and the
# plain build without the speed layers.
sanitize-all:
	$(MAKE) sanitize
	$(MAKE) REAL=double sanitize
	$(MAKE) SIMD=off sanitize

# --- chapter programs ------------------------------------------------------
# Each chapters/chNN/chapter.mk names the chapter, its programs, and for
# each program its source and the modules it needs:
#   CHAPTERS += ch01
#   ch01_PROGS := ch01_geometry ch01_brdf
#   ch01_geometry_SRC := chapters/ch01/ch01_geometry.c
#   ch01_geometry_MODULES := vec frame ...
#   ch01_geometry_LIBS := -lm
# A program is linked from exactly those objects, not the library, so a
# missing module shows up as a link error here rather than in a student's
# single cc line. With SIMD=on each module brings its speed layers
# (fast_of): the MODULES lists name plain modules only. `make ch01` builds
# the chapter's programs into $(BUILD)/.
CHAPTERS :=
-include $(sort $(wildcard chapters/*/*.mk))
CHAPTERS := $(sort $(CHAPTERS))
CHAPTER_PROGS := $(sort $(foreach c,$(CHAPTERS),$($(c)_PROGS)))
CHAPTER_HDRS := $(wildcard chapters/*.h)

# the speed layers of modules M..., src/*/fast/M_WHAT.c, when SIMD=on
# (M_WHAT's module is its name without the last _WHAT)
fast_owner = $(patsubst %_$(lastword $(subst _, ,$(1))),%,$(1))
fast_of = $(if $(SIMDDEF),$(foreach f,$(notdir $(FAST_SRCS:.c=)),\
    $(if $(filter $(call fast_owner,$(f)),$(1)),$(f))))
# (the headers the programs share, chapters/*.h, rebuild them when changed)
define program_rule
$(BUILD)/$(1): $$($(1)_SRC) $(CHAPTER_HDRS) $$(addprefix $(BUILD)/obj/,$$(addsuffix .o,$$($(1)_MODULES) $$(call fast_of,$$($(1)_MODULES))))
	@mkdir -p $$(@D)
	$$(CC) $$(ALL_CFLAGS) $$(PKG_CFLAGS) $$(filter-out %.h,$$^) -o $$@ -Wl,--as-needed $$($(1)_LIBS) -fopenmp
endef
$(foreach p,$(CHAPTER_PROGS),$(eval $(call program_rule,$(p))))

define chapter_rule
$(1): $$($(1)_PROGS:%=$(BUILD)/%)
endef
$(foreach c,$(CHAPTERS),$(eval $(call chapter_rule,$(c))))
.PHONY: $(CHAPTERS)

chapters: $(CHAPTER_PROGS:%=$(BUILD)/%)

# tests/chapters/test_chapters.c runs the chapter programs built beside it
test: chapters

# `make figures`: every chapter program writes its CSV files and PPM
# pictures into out/figures/chNN, and the gnuplot scripts beside it
# (chapters/chNN/*.gp) draw them as PNG and SVG there; without gnuplot it
# says so and still exits 0 (tools/figures.sh). Not part of `make test`.
figures: $(CHAPTER_PROGS:%=$(BUILD)/%)
	@sh tools/figures.sh $(BUILD) $(foreach p,$(CHAPTER_PROGS),$($(p)_SRC))

# A program's .mk may name the symbol prefixes of the parts its chapter
# does not use (NAME_FORBID: ch05's grid_ mesh_ primset_ ...), and those
# only link-time optimisation drops (NAME_FORBID_LTO: functions of a module
# the program needs, such as parallelogram.c's batch, which a plain link
# keeps); `make check-links` fails when the linked program has one of
# them (tools/check-links.sh, on nm's list). Part of `make test`.
check-links: $(CHAPTER_PROGS:%=$(BUILD)/%)
	@fail=0; $(foreach p,$(CHAPTER_PROGS),sh tools/check-links.sh \
	    $(BUILD)/$(p) $($(p)_FORBID) $(if $(strip $(LTO)),$($(p)_FORBID_LTO)) \
	    || fail=1;) exit $$fail

# Each chapter program's first comment is the one cc line that builds it
# alone; this runs every such line in a scratch directory to prove it.
cc-lines:
	@sh tools/check-cc-lines.sh $(foreach p,$(CHAPTER_PROGS),$($(p)_SRC))

# --- test vectors for ports (tests/vectors/) -------------------------------
$(BUILD)/tools/%: tools/%.c $(wildcard tools/*.h) $(LIB)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(PKG_CFLAGS) $< -o $@ $(LIB) $(LDLIBS)

# Regenerate the CSV files from the code. Only for a deliberate change of
# reference: the C tests check the code against the committed files.
vectors: $(VECTOOLS)
	@for t in $(VECTOOLS); do echo "$$t"; $$t tests/vectors || exit 1; done

# tests/vectors/noise_perlin.csv comes from Perlin's algorithm in Java, not
# from svet (tools/perlin/PerlinVectors.java); it needs a JDK, which neither
# the build nor the tests do.
noise-vectors:
	@if command -v javac >/dev/null 2>&1 && command -v java >/dev/null 2>&1; then \
	    d=$$(mktemp -d) && javac -d $$d tools/perlin/PerlinVectors.java && \
	    java -cp $$d PerlinVectors > tests/vectors/noise_perlin.csv.tmp && \
	    mv tests/vectors/noise_perlin.csv.tmp tests/vectors/noise_perlin.csv && \
	    rm -rf $$d && echo "wrote tests/vectors/noise_perlin.csv"; \
	else echo "noise-vectors: needs a JDK (javac and java), which is not installed"; exit 1; fi

# --- benchmarks: bench/bench_NAME.c is `make bench-NAME` --------------------
BENCH_OPT ?= -O2
$(BUILD)/bench/bench_%: bench/bench_%.c $(LIB)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(PKG_CFLAGS) $< -o $@ $(LIB) $(LDLIBS)

# OMP_WAIT_POLICY=passive unless set: by default the idle thread of a
# two-thread run spins for a while and slows the one-thread runs after it.
BENCH_ENV = OMP_WAIT_POLICY=$${OMP_WAIT_POLICY:-passive}
$(filter-out bench-geometry,$(BENCHES)): bench-%: $(BUILD)/bench/bench_%
	$(BENCH_ENV) $(BUILD)/bench/bench_$* $(BENCH_ARGS)

bench: $(BENCHES)

# float against double: both builds measure, then one table
bench-geometry: $(BUILD)/bench/bench_geometry
	$(MAKE) REAL=double build/double/bench/bench_geometry
	@mkdir -p out/bench
	$(BENCH_ENV) build/float/bench/bench_geometry --csv out/bench/geometry-float.csv
	$(BENCH_ENV) build/double/bench/bench_geometry --csv out/bench/geometry-double.csv
	@build/float/bench/bench_geometry --report out/bench/geometry-float.csv \
	    out/bench/geometry-double.csv | tee bench/results/geometry.md

# --- fuzzing: fuzz/fuzz_NAME.c is `make fuzz-NAME` ---------------------------
# libFuzzer targets, built by clang with ASan + UBSan from the modules each
# lists in fuzz_NAME_MODULES (clang here has no OpenMP: not the library).
# `make fuzz-NAME FUZZ_TIME=3600` runs one for that many seconds from its
# seed corpus fuzz/corpus/NAME/; new inputs go to fuzz/findings/NAME/corpus
# and crashes to fuzz/findings/NAME/. fuzz/README.md records the runs.
FUZZ_CC    ?= clang
FUZZ_TIME  ?= 60
FUZZ_BUILD ?= build/fuzz
FUZZ_FLAGS := -std=c11 -D_POSIX_C_SOURCE=200809L -g -O1 -Iinclude \
              -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
fuzz_scene_MODULES := bbox box brdf cobject colour cone cylinder disk error \
    fileio frame material mesh obj parallelogram plane quadric ray rng \
    sample scene scenefile shape sphere triangle vec xform allparts objmesh \
    grid grid_build primset accel batch subsample
fuzz_scene_ARGS := -dict=fuzz/scene.dict
fuzz_obj_MODULES := accel bbox cobject error fileio frame grid grid_build \
    mesh obj primset ray rng shape triangle vec
fuzz_obj_ARGS := -dict=fuzz/obj.dict
fuzz_image_MODULES := image imageio exrio pngio netpbm fileio error colour \
    tonemap spectrum
fuzz_image_ARGS := -dict=fuzz/image.dict -max_len=65536
fuzz_image_LIBS := $(PKG_CFLAGS) $(PKG_LIBS)

# the source of module M, wherever its part's folder is
src_of = $(foreach m,$(1),$(filter %/$(m).c,$(SRCS)))
$(FUZZ_BUILD)/fuzz_%: fuzz/fuzz_%.c $(SRCS) $(HDRS) $(wildcard src/*/*.h)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_FLAGS) $(REALDEF) $(SIMDDEF) $< \
	    $(call src_of,$(fuzz_$*_MODULES) $(call fast_of,$(fuzz_$*_MODULES))) \
	    $(fuzz_$*_LIBS) -lm -o $@

# fuzz_args: the argument parsing of cmd/ (every cmd/*.c but main's), with
# the library and its image libraries beside it; -close_fd_mask=3 keeps
# the usage messages out of the fuzzer's output (its reports still show).
fuzz_args_MODULES := $(MODULES)
fuzz_args_SRCS := $(filter-out $(SVET_MAIN),$(CMD_SRCS))
fuzz_args_ARGS := -dict=fuzz/args.dict -close_fd_mask=3
$(FUZZ_BUILD)/fuzz_args: fuzz/fuzz_args.c $(SRCS) $(HDRS) $(CMD_SRCS) \
                         $(wildcard cmd/*.h)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_FLAGS) $(REALDEF) $(SIMDDEF) -Icmd $(PKG_CFLAGS) $< \
	    $(call src_of,$(fuzz_args_MODULES)) $(fuzz_args_SRCS) \
	    $(PKG_LIBS) -lm -o $@

fuzz-%: $(FUZZ_BUILD)/fuzz_%
	@mkdir -p fuzz/findings/$*/corpus
	$< -max_total_time=$(FUZZ_TIME) -timeout=5 $(fuzz_$*_ARGS) \
	    -artifact_prefix=fuzz/findings/$*/ fuzz/findings/$*/corpus \
	    fuzz/corpus/$*

# `make fuzz-all`: every target in turn, FUZZ_TIME seconds each (a minute
# by default), to rerun them after a change; it stops at the first
# finding. Not part of `make test`: it needs clang with libFuzzer.
FUZZ_TARGETS := $(patsubst fuzz/fuzz_%.c,%,$(wildcard fuzz/fuzz_*.c))
fuzz-all:
	@command -v $(FUZZ_CC) >/dev/null 2>&1 || { echo "make fuzz-all:" \
	    "$(FUZZ_CC) not found; the fuzz targets need clang with libFuzzer" \
	    "(Debian: apt-get install clang)" >&2; exit 1; }
	@mkdir -p $(FUZZ_BUILD)
	@printf 'int LLVMFuzzerTestOneInput(const char *d, unsigned long n)%s\n' \
	    '{ (void)d; (void)n; return 0; }' > $(FUZZ_BUILD)/probe.c
	@$(FUZZ_CC) -fsanitize=fuzzer $(FUZZ_BUILD)/probe.c \
	    -o $(FUZZ_BUILD)/probe 2>/dev/null || { echo "make fuzz-all:" \
	    "$(FUZZ_CC) cannot link -fsanitize=fuzzer: libFuzzer is missing" \
	    "(Debian: apt-get install clang, or FUZZ_CC=clang-NN)" >&2; exit 1; }
	@for t in $(FUZZ_TARGETS); do \
	    $(MAKE) --no-print-directory fuzz-$$t FUZZ_TIME=$(FUZZ_TIME) || \
	        { echo "make fuzz-all: fuzz-$$t found something: see" \
	          "fuzz/findings/$$t/" >&2; exit 1; }; \
	done

# --- reference output and the speed/accuracy measurements -----------------
# `make reference` renders tests/reference/ from every scenes/*.scn with the
# float build (tools/reference.sh: half resolution, 4096 spp; its README
# gives the time), then checks the new files with their regression suite;
# `make tradeoffs` measures every knob of the renderer
# against those references with both builds and writes docs/tradeoffs.md
# (tools/tradeoffs.sh, under 30 minutes on 2 cores).
.PHONY: reference tradeoffs count-render count-grid ab-grid ab-render ab-plain \
        bitcheck fuzz-all tradeoffs-photon
reference:
	$(MAKE) REAL=float BUILD=build/float build/float/svet \
	    build/float/tests/test_reference
	sh tools/reference.sh build/float/svet
	build/float/tests/test_reference

# `make tradeoffs-photon`: the photon maps' settings against the path
# tracer on scenes/caustic.scn, and exact Fresnel against Schlick's
# (tools/tradeoffs-photon.sh; writes docs/tradeoffs-photon.md). Budgets
# in CPU-seconds (CLOCK=cpu, TIMES 8,...,120: about 25 minutes on 2 idle
# cores, longer on a loaded machine); ROWS=path,photon runs a subset.
tradeoffs-photon: build/float/svet
	sh tools/tradeoffs-photon.sh

# `make tradeoffs-media`: volpath's, volsingle's and volphoton's error
# against time on the smoky Cornell box and the cloud
# (tools/tradeoffs-media.sh; writes
# docs/tradeoffs-media.md, about 15 minutes on 2 cores).
.PHONY: tradeoffs-media
tradeoffs-media: build/float/svet
	sh tools/tradeoffs-media.sh

# `make tradeoffs-irradiance`: the irradiance cache's a, M x N, gradients
# and clamping, and app. F's subsampling, against the path tracer on the
# Cornell box, on the whole image and on the indirect diffuse light alone
# (tools/tradeoffs-irradiance.sh; writes docs/tradeoffs-irradiance.md,
# about 20 minutes on 2 cores; ONLY=indirect runs the indirect section
# alone and puts it into the existing document).
.PHONY: tradeoffs-irradiance
tradeoffs-irradiance: build/float/svet
	sh tools/tradeoffs-irradiance.sh

# `make count-render`: instructions per camera sample (callgrind), the
# load-independent figure of bench/results/render.md.
count-render: $(BUILD)/svet
	sh tools/count-render.sh $(BUILD)/svet

# `make count-grid`: instructions per ray of the grid at 1e6 triangles
# (callgrind), the load-independent figures of bench/results/grid.md.
count-grid: $(BUILD)/bench/bench_grid
	sh tools/count-grid.sh $(BUILD)/bench/bench_grid

# `make ab-grid BASE=COMMIT [KINDS=incoherent,camera] [PAIRS=6]`: the
# grid's rays per second against commit BASE's, alternating runs
# (tools/ab-grid.sh; float, one thread).
ab-grid: build/float/bench/bench_grid
	$(if $(BASE),,$(error ab-grid: give BASE=COMMIT))
	sh tools/ab-grid.sh build/float/bench/bench_grid $(BASE) $(KINDS) $(PAIRS)

# `make cloud-vol`: rewrite scenes/cloud.vol, the density grid of
# scenes/cloud.scn, with tools/makecloud.c (the float build's bytes are
# the committed ones).
.PHONY: cloud-vol
cloud-vol: build/float/tools/makecloud
	build/float/tools/makecloud scenes/cloud.vol

# `make bench-media [MITSUBA_PYTHON=python3] [MEDIA_SPP=64]`: the smoky
# Cornell box and the cloud by svet's volpath and by Mitsuba 3's
# (tools/mitsuba/media.py; bench/results/media.md). Optional: without a
# Python that imports mitsuba and numpy it says so and succeeds.
.PHONY: bench-media
bench-media: build/float/svet
	@py=$${MITSUBA_PYTHON:-python3}; \
	if ! $$py -c 'import mitsuba, numpy' >/dev/null 2>&1; then \
	    echo "make bench-media: $$py has no mitsuba (optional: python3 -m" \
	        "venv V && V/bin/pip install mitsuba numpy, then" \
	        "MITSUBA_PYTHON=V/bin/python); skipped"; exit 0; fi; \
	$$py tools/mitsuba/media.py build/float/svet --spp $(or $(MEDIA_SPP),64) \
	    > out-media.md.tmp && { mkdir -p bench/results; \
	    { echo "# Media: svet's volpath against Mitsuba 3"; echo; \
	      cat out-media.md.tmp; } > bench/results/media.md; \
	    rm -f out-media.md.tmp; cat bench/results/media.md; }

# `make bitcheck [BASE=COMMIT]`: every scenes/*.scn renders to the same
# bytes with SIMD=on and SIMD=off, at 1 and 2 threads, in float and in
# double (tools/bitcheck.sh, 64 x 64 at 8 spp); with BASE, also the same
# as that commit's build. With make -j the four builds, and then the float
# and the double check, run side by side (a one-thread render leaves a
# core free); each check writes a log of its own under build/bitcheck/,
# and the two logs are printed whole, float first.
BITCHECK_BUILDS := float float-plain double double-plain
.PHONY: $(BITCHECK_BUILDS:%=bitcheck-build-%) bitcheck-float bitcheck-double
$(BITCHECK_BUILDS:%=bitcheck-build-%): bitcheck-build-%:
	$(MAKE) REAL=$(word 1,$(subst -, ,$*)) \
	    SIMD=$(if $(findstring plain,$*),off,on) build/$*/svet
bitcheck-float bitcheck-double: bitcheck-%: bitcheck-build-% \
                                            bitcheck-build-%-plain
	@mkdir -p build/bitcheck
	@REAL=$* BASE=$(BASE) sh tools/bitcheck.sh build/$*/svet \
	    build/$*-plain/svet >build/bitcheck/$*.log 2>&1; \
	    echo $$? >build/bitcheck/$*.rc
bitcheck: bitcheck-float bitcheck-double
	@r=0; for x in float double; do cat build/bitcheck/$$x.log; \
	    [ "$$(cat build/bitcheck/$$x.rc)" = 0 ] || r=1; done; exit $$r

# `make ab-render BASE=COMMIT [THREADS=1,2] [PAIRS=6] [SPP=16]`: the
# Cornell box's camera samples per second against commit BASE's,
# alternating runs, the images compared too (tools/ab-render.sh; REAL as
# given).
ab-render: $(BUILD)/svet
	$(if $(BASE),,$(error ab-render: give BASE=COMMIT))
	REAL=$(REAL) sh tools/ab-render.sh $(BUILD)/svet $(BASE) "$(THREADS)" \
	    "$(PAIRS)" "$(SPP)"

# `make bench-scale [SCALE_SPP=4096] [THREADS=2] [SCALE_SCENE=F]
# [SCALE_OPTS="--set integrator=irradiance"]`: the Cornell box (or F)
# split into 2, 4 and 8 parts by samples and merged, against one render
# (tools/bench-scale.sh; bench/results/scale.md), in wall and CPU
# seconds (/usr/bin/time): on a shared machine the CPU ratio is the one
# that measures the split.
.PHONY: bench-scale
bench-scale: $(BUILD)/svet
	sh tools/bench-scale.sh $(BUILD)/svet $(or $(SCALE_SPP),4096) \
	    $(or $(THREADS),2) $(or $(SCALE_SCENE),scenes/cbox.scn) \
	    "$(SCALE_OPTS)"

# `make bench-prepass [PREPASS_SPP=16] [THREADS=2]`: the set-up and
# sampling seconds of the three pre-pass scenes (photon maps, irradiance
# cache, volume photon map) and what N parts cost with the pre-pass
# repeated in every part or computed once (tools/bench-prepass.sh;
# bench/results/scale.md).
.PHONY: bench-prepass
bench-prepass: $(BUILD)/svet
	sh tools/bench-prepass.sh $(BUILD)/svet $(or $(PREPASS_SPP),16) \
	    $(or $(THREADS),2)

# `make slurm-check`: a one-node Slurm on this machine runs
# tools/slurm/*.sbatch and the merge is compared with a single render
# (tools/slurm-check.sh; needs slurm-wlm and munge; not in CI).
.PHONY: slurm-check
slurm-check: $(BUILD)/svet
	sh tools/slurm-check.sh $(BUILD)/svet

# `make ab-plain [THREADS=1,2] [PAIRS=6] [SPP=16]`: the same, the default
# build against the plain one (SIMD=off, build/REAL-plain/), same bits.
ab-plain: build/$(REAL)/svet
	$(MAKE) REAL=$(REAL) SIMD=off build/$(REAL)-plain/svet
	BASE_SVET=build/$(REAL)-plain/svet REAL=$(REAL) sh tools/ab-render.sh \
	    build/$(REAL)/svet plain "$(THREADS)" "$(PAIRS)" "$(SPP)"

tradeoffs:
	$(MAKE) REAL=float BUILD=build/float build/float/svet
	$(MAKE) REAL=double BUILD=build/double build/double/svet
	SVET_FLAGS="$(OPT) $(ARCH) $(LTO)" sh tools/tradeoffs.sh

# --- install ---------------------------------------------------------------
install: all
	install -d $(DESTDIR)$(PREFIX)/lib $(DESTDIR)$(PREFIX)/bin \
	    $(PARTS:%=$(DESTDIR)$(PREFIX)/include/svet/%)
	install -m 644 $(LIB) $(DESTDIR)$(PREFIX)/lib/
	for p in $(PARTS); do install -m 644 include/$$p/*.h $(DESTDIR)$(PREFIX)/include/svet/$$p/; done
	if [ -x $(BUILD)/svet ]; then install -m 755 $(BUILD)/svet $(DESTDIR)$(PREFIX)/bin/; fi

uninstall:
	rm -rf $(DESTDIR)$(PREFIX)/include/svet $(DESTDIR)$(PREFIX)/lib/libsvet.a \
	    $(DESTDIR)$(PREFIX)/bin/svet

clean:
	rm -rf build

help:
	@echo "make                 library, chapter programs and the svet command"
	@echo "make test            every unit suite (REAL=double for the double build)"
	@echo "make test-images     the suites that render whole scenes (e.g. SIMD=off)"
	@echo "make sanitize        every suite under ASan and UBSan"
	@echo "make sanitize-all    sanitize in float, REAL=double and SIMD=off"
	@echo "make chNN            one chapter program, e.g. make ch01"
	@echo "make cc-lines        build each chapter from its own one-line cc command"
	@echo "make check-tags      the book's equations tagged in src/, include/; paths in *.md"
	@echo "make figures         chapter programs' plots as PNG and SVG (gnuplot)"
	@echo "make check-links     each chapter program links none of the parts it must not"
	@echo "make vectors         regenerate tests/vectors/*.csv"
	@echo "make noise-vectors   rewrite tests/vectors/noise_perlin.csv (needs a JDK)"
	@echo "make bench-NAME      one benchmark: $(BENCHES)"
	@echo "make reference       re-render tests/reference/ (converged references)"
	@echo "make tradeoffs       measure speed against accuracy: docs/tradeoffs.md"
	@echo "make count-render    instructions per Cornell-box sample (valgrind)"
	@echo "make count-grid      instructions per ray of the grid at 1e6 (valgrind)"
	@echo "make ab-grid BASE=C  the grid's rays/s against commit C's, alternating"
	@echo "make ab-render BASE=C the Cornell box's samples/s against commit C's"
	@echo "make ab-plain         the same, the default build against SIMD=off's"
	@echo "make SIMD=off ...    any target without the speed layers (build/REAL-plain/)"
	@echo "make bitcheck        every scene the same bytes with SIMD=on and off [BASE=C]"
	@echo "make fuzz-NAME       one fuzz target (clang): $(FUZZ_TARGETS)"
	@echo "make fuzz-all        every fuzz target, FUZZ_TIME=60 seconds each"
	@echo "make install PREFIX=... DESTDIR=..."
	@echo "chapters: $(CHAPTERS)"

-include $(OBJS:.o=.d) $(TESTS:=.d) $(TESTSUP_OBJS:.o=.d)

# `make test-merge`: split renders (--samples, --crop) merged by svet merge
# to the single render's bits, float and double (tests/cmd/test_merge.sh;
# the Part II methods: tests/cmd/test_merge_methods.sh), and animations
# frame by frame (tests/cmd/test_frames.sh).
.PHONY: test-merge
test-merge:
	$(MAKE) REAL=float BUILD=build/float build/float/svet
	$(MAKE) REAL=double BUILD=build/double build/double/svet
	sh tests/cmd/test_merge.sh build/float/svet
	sh tests/cmd/test_merge.sh build/double/svet
	sh tests/cmd/test_merge_methods.sh build/float/svet
	sh tests/cmd/test_merge_methods.sh build/double/svet
	sh tests/cmd/test_render_parallel.sh build/float/svet
	sh tests/cmd/test_frames.sh build/float/svet
	sh tests/cmd/test_frames.sh build/double/svet
