# lamina — one build for everything.
#   make            the `lamina` executable and liblamina.a (in build/)
#   make run        install missing packages, build, run the default job
#   make test       install missing packages, build, run every test (TAP via prove)
#   make SAN=1 test the same under AddressSanitizer + UndefinedBehaviorSanitizer
#   make bench      optimised build and benchmarks against peer tools
#   make install PREFIX=/usr/local [DESTDIR=...]: executable, liblamina.a, lamina.h and
#                   the headers it names, lamina.pc, profiles, plugins, Lua modules and
#                   the C module, man pages, bash completion, docs; `make uninstall`
#                   (same variables) removes them again
#   make man        the man pages in $(BUILD)/man and the bash completion in
#                   $(BUILD)/completion (generated from the commands' --help)

CC      ?= cc
PREFIX  ?= /usr/local
OPT     ?= -O2 -g
BUILD   ?= build

PLUGIN_OUT := plugins

ifeq ($(SAN),1)
BUILD    := build-san
PLUGIN_OUT := build-san/plugins
OPT      := -O1 -g
SANFLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
endif

# Debian packages the build, the tests and `make run` need; `make deps`
# installs only the missing ones.
DEPS_PKGS := gcc make perl liblua5.4-dev lua5.4 libyaml-dev libembree-dev libgeos-dev libreadline8 \
             jq python3 python3-jsonschema time librsvg2-bin tmux pkg-config parallel \
             luarocks man-db mandoc bash-completion admesh
# Packages a test can do without: installed the same way when missing, but
# a failure only means the test that needs one skips (and says so).
DEPS_OPTIONAL := chromium

LUA_CFLAGS := -I/usr/include/lua5.4
LUA_LIBS   := -llua5.4

# core/ by stage (docs/architecture.md): base (errors, files, buffers,
# threads), mesh (readers, repair, shells), layer (sections, contours,
# nesting, offsets), plan (planners, hatching, recording), out (dialects,
# JSON, SVG, HTML, plugins), check (validation, DRC, program readers),
# profile (machine profiles and their key table).
CORE_DIRS := base mesh layer plan out check profile build
CORE_INC := -Icore $(addprefix -Icore/,$(CORE_DIRS))
CPPFLAGS += $(CORE_INC) -D_POSIX_C_SOURCE=200809L
# -fPIC everywhere: the same objects also make the Lua C module lamina.so
CFLAGS   += -std=c11 -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -fPIC -pthread $(OPT) $(SANFLAGS)
LDFLAGS  += $(SANFLAGS)
LDLIBS   += -lyaml -ldl -lm -pthread
# Embree and GEOS are opened on first use (core/base/lazylib.h: a plain slice
# needs neither, and loading them costs every start ~7 ms and 5 MB);
# LAZY=0 links them as usual.
LAZY ?= 1
ifeq ($(LAZY),0)
CPPFLAGS += -DLAM_LAZY=0
LDLIBS   += -lembree3 -lgeos_c
endif

CORE_SRC  := $(sort $(wildcard $(CORE_DIRS:%=core/%/*.c)))
# The viewer's page (core/out/viewer.html) is compiled in as a C string.
VIEWER_C  := $(BUILD)/gen/viewer_html.c
CORE_OBJ  := $(CORE_SRC:%.c=$(BUILD)/%.o) $(VIEWER_C:.c=.o)
# Sources by folder: lua/*.c is the binding (also built as the C module
# lamina.so for a stock lua5.4); lua/cli/*.c is the executable on top of it.
BIND_SRC  := $(sort $(wildcard lua/*.c))
BIND_OBJ  := $(BIND_SRC:%.c=$(BUILD)/%.o)
CLI_SRC   := $(sort $(wildcard lua/cli/*.c))
# help(x) in the REPL: lua/API.md's entries as a C table, made at build
# time (lua/cli/help.awk), so help and the document cannot drift apart
HELP_C    := $(BUILD)/lua/cli/help_text.c
CLI_OBJ   := $(CLI_SRC:%.c=$(BUILD)/%.o) $(HELP_C:.c=.o) $(BIND_OBJ)
LUAMOD    := $(BUILD)/lamina.so
UNIT_SRC  := $(sort $(wildcard tests/unit/test_*.c))
UNIT_BIN  := $(UNIT_SRC:tests/unit/%.c=$(BUILD)/tests/%.t)
# Plugins that only tests load (bad ABI, missing symbol, ...).
TEST_PLUGIN_SO := $(patsubst tests/plugins/%.c,$(BUILD)/tests/plugins/%.so,$(wildcard tests/plugins/*.c))

LIB     := $(BUILD)/liblamina.a
# The installed API: core/lamina.h, the headers it names, and the plugin ABI.
# The other headers of core/ are internal (nest.h, enclose.h, test_hooks.h, ...).
PUBLIC_H := core/lamina.h $(foreach h,$(shell grep -o '^.include "[a-z_]*\.h"' core/lamina.h | cut -d'"' -f2),$(wildcard $(CORE_DIRS:%=core/%/$(h)))) \
            core/lamina_plugin.h
# The front ends (lua/, lua/cli/) see the installed headers only: PUBLIC_H
# copied flat into INC_DIR, as `make install` lays them out, and no -Icore,
# so a front end that includes an internal header fails to build.
INC_DIR   := $(BUILD)/include/lamina
INC_STAMP := $(INC_DIR)/.stamp
FRONT_CPPFLAGS = $(filter-out $(CORE_INC),$(CPPFLAGS)) -I$(INC_DIR)
VERSION  := $(shell sed -n 's/.*LAMINA_VERSION "\(.*\)"/\1/p' core/base/version.h)
LAMINA  := $(BUILD)/lamina

# Plugins: plugins/NAME/*.c -> plugins/NAME.so (build-san/plugins/NAME.so
# under SAN=1, found first by a sanitized lamina).
PLUGIN_NAMES := $(patsubst plugins/%/,%,$(sort $(dir $(wildcard plugins/*/*.c))))
PLUGIN_SO    := $(PLUGIN_NAMES:%=$(PLUGIN_OUT)/%.so)

.PHONY: all deps run test check clean install bench fuzz
.DEFAULT_GOAL := all
.SECONDEXPANSION:

all: $(LAMINA) $(LIB) $(PLUGIN_SO) $(if $(BIND_SRC),$(LUAMOD))

# Each staged header is a target of its own (cp -p keeps its time), so a
# changed header rebuilds the objects that include it: their .d files name
# the staged copies, which make brings up to date before it compares them
# (a stamp alone was looked at too late: an object's header times were read
# before the stamp copied anything, and it stayed as it was). A header no
# longer public is removed from the staging.
STAGED_H := $(addprefix $(INC_DIR)/,$(notdir $(PUBLIC_H)))
staged_source = $(filter %/$(1).h,$(PUBLIC_H))
$(INC_DIR)/%.h: $$(call staged_source,$$*)
	@mkdir -p $(dir $@)
	cp -p $< $@
$(INC_STAMP): $(STAGED_H)
	@find $(INC_DIR) -name '*.h' $(foreach h,$(notdir $(PUBLIC_H)),! -name $(h)) -delete
	@touch $@

$(BUILD)/lua/%.o: lua/%.c | $(INC_STAMP)
	@mkdir -p $(dir $@)
	$(CC) $(FRONT_CPPFLAGS) -Ilua $(LUA_CFLAGS) $(CFLAGS) -MMD -MP -c $< -o $@

$(HELP_C): lua/API.md lua/cli/help.awk
	@mkdir -p $(dir $@)
	awk -f lua/cli/help.awk lua/API.md > $@.tmp && mv $@.tmp $@

$(HELP_C:.c=.o): $(HELP_C) lua/cli/help.h | $(INC_STAMP)
	$(CC) $(FRONT_CPPFLAGS) -Ilua/cli $(LUA_CFLAGS) $(CFLAGS) -c $< -o $@

$(LUAMOD): $(BIND_OBJ) $(LIB)
	$(CC) $(LDFLAGS) -shared -o $@ $(BIND_OBJ) $(LIB) $(filter-out -llua5.4,$(LDLIBS))

$(PLUGIN_OUT)/%.so: $$(wildcard plugins/%/*.c) core/lamina_plugin.h
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) -fPIC -shared -o $@ $(filter %.c,$^) $(LDFLAGS)

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) -MMD -MP -c $< -o $@

# od (coreutils) turns the page into bytes: no tool beyond the build's own.
$(VIEWER_C): core/out/viewer.html
	@mkdir -p $(dir $@)
	{ echo '/* generated from core/out/viewer.html by the Makefile: do not edit */'; \
	  echo '#include "viewer_html.h"'; echo 'const char lam_viewer_html[] = {'; \
	  od -An -v -tx1 $< | sed 's/ \([0-9a-f][0-9a-f]\)/0x\1,/g'; \
	  echo '0x00};'; echo 'const size_t lam_viewer_html_len = sizeof lam_viewer_html - 1;'; } > $@.tmp
	mv $@.tmp $@

$(VIEWER_C:.c=.o): $(VIEWER_C) core/out/viewer_html.h
	$(CC) $(CPPFLAGS) $(CFLAGS) -c $< -o $@

$(LIB): $(CORE_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	ar rcs $@ $^

$(LAMINA): $(CLI_OBJ) $(LIB)
	$(CC) $(LDFLAGS) -o $@ $(CLI_OBJ) $(LIB) $(LUA_LIBS) $(LDLIBS)

$(BUILD)/tests/%.t: tests/unit/%.c $(wildcard tests/unit/*.h) $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) -Itests/unit $(CFLAGS) -o $@ $< $(LIB) $(LDFLAGS) $(LDLIBS)

deps:
	@missing=""; \
	for p in $(DEPS_PKGS); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "make deps: installing$$missing"; \
	  if [ "$$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi; \
	  $$sudo apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $$sudo apt-get install -y -qq --no-install-recommends $$missing; \
	fi
	@for p in $(DEPS_OPTIONAL); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' && continue; \
	  echo "make deps: installing $$p (optional)"; \
	  if [ "$$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi; \
	  { $$sudo apt-get update -qq && \
	    DEBIAN_FRONTEND=noninteractive $$sudo apt-get install -y -qq --no-install-recommends $$p; } || \
	    echo "make deps: $$p could not be installed; the tests that need it skip"; \
	done

RUN_PART := recipes/parts/thesis_cube_hole.ug
run: deps
	@$(MAKE) --no-print-directory all
	@mkdir -p out
	$(LAMINA) run recipes/default.lua --out out $(RUN_PART)
	@$(LAMINA) info $(RUN_PART) > out/thesis_cube_hole.info.txt
	@$(LAMINA) validate $(RUN_PART) -w 0.25 --cut floor > out/thesis_cube_hole.validate.txt
	@tail -n 1 out/thesis_cube_hole.validate.txt
	@$(LAMINA) slice $(RUN_PART) -m creol-ladrp --svg out/thesis_cube_hole.paths.svg \
	  --html out/thesis_cube_hole.html -o /dev/null
	@echo "lamina: outputs in $(CURDIR)/out/:"
	@echo "  thesis_cube_hole.ladrp         LADRP program for the thesis's CREOL cell"
	@echo "  thesis_cube_hole.sls           SLS contour program (thesis dialect)"
	@echo "  thesis_cube_hole.svg           contact sheet of the SLS layers"
	@echo "  thesis_cube_hole.info.txt      model report (lamina info)"
	@echo "  thesis_cube_hole.validate.txt  Embree check of every solid/hole label"
	@echo "  thesis_cube_hole.paths.svg     the LADRP layers with their deposits and travel"
	@echo "  thesis_cube_hole.html          viewer of the LADRP plan (one file, open it in a browser)"
	@echo "lamina: viewer: $(CURDIR)/out/thesis_cube_hole.html"

# Tests: C unit tests are compiled to TAP programs; tests/cli/*.t are shell
# scripts that drive the executable. prove runs both and prints the summary.
# The fuzz target (with the Lua binding, for recipes), as a mutation driver
# for the test suite over the corpus in tests/fuzz/corpus; `make fuzz`
# builds it for libFuzzer with clang instead and runs every target of
# FUZZ_TARGETS (a folder of the corpus each) for FUZZ_TIME seconds, each
# its full time whatever another finds (tests/fuzz/run.sh: restarted after
# a finding; working corpus in build-fuzz/corpus, so the kept corpus only
# changes by hand; from a copy of tests/models, where a recipe writes);
# it prints each target's executions and findings (build-fuzz/artifacts/
# TARGET/, logs in build-fuzz/TARGET.log, summary in build-fuzz/summary.txt)
# and fails when any target found something.
FUZZ_BIN := $(BUILD)/tests/fuzz_inputs
FUZZ_FLAGS = $(CPPFLAGS) $(LUA_CFLAGS) -DLAMINA_FUZZ_LUA
$(FUZZ_BIN): tests/fuzz/fuzz_inputs.c $(BIND_OBJ) $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(FUZZ_FLAGS) $(CFLAGS) -o $@ $< $(BIND_OBJ) $(LIB) $(LDFLAGS) $(LUA_LIBS) $(LDLIBS)

FUZZ_TIME ?= 600
FUZZ_TARGETS ?= models profiles recipes programs parts
fuzz:
	@$(MAKE) --no-print-directory BUILD=build-fuzz CC=clang OPT="-O1 -g" \
	  SANFLAGS="-fsanitize=address,undefined,fuzzer-no-link" build-fuzz/liblamina.a \
	  $(BIND_SRC:%.c=build-fuzz/%.o)
	clang $(FUZZ_FLAGS) -DLAMINA_LIBFUZZER -g -O1 -fsanitize=address,undefined,fuzzer \
	  -o build-fuzz/fuzz_inputs tests/fuzz/fuzz_inputs.c $(BIND_SRC:%.c=build-fuzz/%.o) build-fuzz/liblamina.a \
	  $(LUA_LIBS) $(LDLIBS)
	@rm -rf build-fuzz/models && cp -r tests/models build-fuzz/models
	@bash tests/fuzz/run.sh "$(CURDIR)/build-fuzz/fuzz_inputs" "$(CURDIR)/build-fuzz" $(FUZZ_TIME) $(FUZZ_TARGETS)

$(BUILD)/tests/plugins/%.so: tests/plugins/%.c core/lamina_plugin.h tests/plugins/noop_writer.h
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) -fPIC -shared -o $@ $< $(LDFLAGS)

# CHECK_TESTS: the test programs prove runs (all of them unless given).
# CHECK_JOBS=2 (CHECK_JOBS=1: one at a time): two streams side by side, each
# test after the other within its stream. One stream is long_path.t, which
# reruns every command-line test from another path, with the two tests that
# make and install in the checkout itself (install.t, rock.t; long_path.t
# runs them too, so they must never overlap it); the other is every other
# test. The two are about as long (long_path.t is the command-line tests
# once more), so the suite takes about half its serial time on two cores.
CHECK_TESTS ?= $(UNIT_BIN) $(sort $(wildcard tests/cli/*.t)) tests/fuzz/fuzz.t
CHECK_JOBS ?= 2
CHECK_RULES := --rules='seq=tests/cli/{install,long_path,rock}.t' --rules='seq=**'
check: all $(UNIT_BIN) $(TEST_PLUGIN_SO) $(FUZZ_BIN) man
	LAMINA="$(CURDIR)/$(LAMINA)" TESTS="$(CURDIR)/tests" BUILD="$(CURDIR)/$(BUILD)" LAZY=$(LAZY) \
	  prove --exec '' -j$(CHECK_JOBS) $(CHECK_RULES) $(CHECK_TESTS)

test: deps
	@$(MAKE) --no-print-directory check

bench:
	@$(MAKE) --no-print-directory OPT="-O3 -march=native -DNDEBUG" BUILD=build-bench all
	@bash tests/bench/run.sh "$(CURDIR)/build-bench/lamina"

# ---- installation ----------------------------------------------------------
# One list, INSTALL_FILES (MODE:SOURCE:DESTINATION, destinations without
# DESTDIR), drives `make install` and `make uninstall`, so uninstall removes
# exactly what install put there. The layout follows each ecosystem: Lua
# modules in share/lua/5.4, the C module in lib/lua/5.4 (a stock lua5.4
# finds both under /usr/local), man pages, bash completion, docs. The C
# module finds machines and plugins relative to its own file and the
# executable relative to itself (core/base/paths.h), so the tree may move; with
# other directories than these defaults set LAMINA_MACHINES/LAMINA_PLUGINS.
BINDIR      ?= $(PREFIX)/bin
LIBDIR      ?= $(PREFIX)/lib
INCLUDEDIR  ?= $(PREFIX)/include
DATADIR     ?= $(PREFIX)/share
LUA_CMODDIR ?= $(LIBDIR)/lua/5.4
LUA_MODDIR  ?= $(DATADIR)/lua/5.4
MACHINEDIR  ?= $(DATADIR)/lamina/machines
PLUGINDIR   ?= $(LIBDIR)/lamina/plugins
DOCDIR      ?= $(DATADIR)/doc/lamina
MANDIR      ?= $(DATADIR)/man
BASHCOMPDIR ?= $(DATADIR)/bash-completion/completions

# Man pages: lamina(1) and lamina-CMD(1) for each command of the command
# table (lua/cli/main.c: `lamina --help` lists the same; the generator
# checks that its list is this one), generated from the
# commands' --help texts and man/*.in (description, examples); the bash
# completion from the same reading of --help and completion/lamina.bash.in.
MAN_CMDS  := $(shell sed -n 's/^ *{ "\([a-z][a-z0-9-]*\)", .*/\1/p' lua/cli/main.c)
MAN_PAGES := $(BUILD)/man/lamina.1 $(MAN_CMDS:%=$(BUILD)/man/lamina-%.1)
MAN_STAMP := $(BUILD)/man/.stamp

man: $(MAN_STAMP)
$(MAN_STAMP): $(LAMINA) man/genman.py $(wildcard man/*.in) completion/lamina.bash.in $(if $(BIND_SRC),$(LUAMOD)) $(PLUGIN_SO)
	@mkdir -p $(dir $@) $(BUILD)/completion
	python3 man/genman.py --lamina $(LAMINA) --in man --out $(BUILD)/man --version $(VERSION) \
	  --binaries "$(LAMINA) $(LUAMOD) $(PLUGIN_SO)" --expect "$(MAN_CMDS)" \
	  --completion-in completion/lamina.bash.in --completion-out $(BUILD)/completion/lamina
	@touch $@
$(MAN_PAGES) $(BUILD)/completion/lamina: $(MAN_STAMP)

# Made on every install (FORCE) but replaced only when its text changes:
# it holds PREFIX and the directories, which are not files make can see.
$(BUILD)/lamina.pc: lamina.pc.in core/base/version.h FORCE
	@mkdir -p $(dir $@)
	@sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(patsubst $(PREFIX)/%,$${prefix}/%,$(LIBDIR))|' \
	  -e 's|@INCLUDEDIR@|$(patsubst $(PREFIX)/%,$${prefix}/%,$(INCLUDEDIR))|' \
	  -e 's|@VERSION@|$(VERSION)|' -e 's|@LIBS@|$(strip $(SANFLAGS) $(LDLIBS))|' $< > $@.tmp
	@if cmp -s $@.tmp $@; then rm -f $@.tmp; else mv $@.tmp $@; fi
.PHONY: FORCE
FORCE:

# What the Lua module needs (also all a LuaRocks rock installs: install-lua).
# Each entry is MODE:SOURCE:DIR/NAME with DIR the name of one of the
# directory variables above (INSTALL_DIRS): make splits a list at spaces,
# so the directories themselves, which may hold spaces (a LuaRocks tree in
# "My Projects"), are put in by the shell (install_vars), quoted.
INSTALL_DIRS := BINDIR LIBDIR INCLUDEDIR DATADIR LUA_CMODDIR LUA_MODDIR MACHINEDIR PLUGINDIR DOCDIR MANDIR BASHCOMPDIR
INSTALL_LUA := 755:$(LUAMOD):LUA_CMODDIR/lamina.so \
  $(foreach f,$(wildcard lua/lamina/*.lua),644:$(f):LUA_MODDIR/lamina/$(notdir $(f))) \
  $(foreach f,$(wildcard machines/*.yaml),644:$(f):MACHINEDIR/$(notdir $(f))) \
  $(foreach f,$(PLUGIN_SO),755:$(f):PLUGINDIR/$(notdir $(f)))
INSTALL_FILES := $(INSTALL_LUA) \
  755:$(LAMINA):BINDIR/lamina \
  644:$(LIB):LIBDIR/liblamina.a \
  $(foreach f,$(PUBLIC_H),644:$(f):INCLUDEDIR/lamina/$(notdir $(f))) \
  644:$(BUILD)/lamina.pc:LIBDIR/pkgconfig/lamina.pc \
  644:README.md:DOCDIR/README.md 644:lua/API.md:DOCDIR/lua/API.md \
  644:machines/README.md:DOCDIR/machines/README.md \
  $(foreach f,$(wildcard docs/*.md),644:$(f):DOCDIR/docs/$(notdir $(f))) \
  $(foreach f,$(wildcard schema/*.json),644:$(f):DATADIR/lamina/schema/$(notdir $(f))) \
  $(foreach f,recipes/README.md $(wildcard recipes/*.lua),644:$(f):DOCDIR/recipes/$(notdir $(f))) \
  $(foreach f,$(wildcard recipes/parts/*),644:$(f):DOCDIR/recipes/parts/$(notdir $(f))) \
  $(foreach f,$(MAN_PAGES),644:$(f):MANDIR/man1/$(notdir $(f))) \
  644:$(BUILD)/completion/lamina:BASHCOMPDIR/lamina
# Directories that are lamina's alone: removed by uninstall when empty.
INSTALL_OWN_DIRS := DATADIR/lamina/schema DOCDIR/recipes/parts DOCDIR/recipes DOCDIR/lua DOCDIR/machines DOCDIR/docs DOCDIR/. \
  INCLUDEDIR/lamina MACHINEDIR/. DATADIR/lamina PLUGINDIR/. LIBDIR/lamina LUA_MODDIR/lamina \
  LUA_MODDIR/lamina/machines LUA_CMODDIR/lamina/plugins LUA_CMODDIR/lamina

# install_vars: the directories as shell variables (with DESTDIR before
# them), and dest, which turns DIR/NAME into the path it names.
install_vars = $(foreach d,$(INSTALL_DIRS),$(d)='$(DESTDIR)$($(d))';) \
	dest() { v=$${1%%/*}; eval "b=\$$$$v"; dst="$$b/$${1\#*/}"; };
# install_files LIST: each MODE:SOURCE:DIR/NAME
install_files = $(install_vars) for e in $(1); do \
	  mode=$${e%%:*}; rest=$${e\#*:}; src=$${rest%%:*}; dest "$${rest\#*:}"; \
	  install -d "$${dst%/*}" && install -m $$mode "$$src" "$$dst" || exit 1; \
	done

.PHONY: man lua-module install-lua uninstall
install: all $(MAN_STAMP) $(BUILD)/lamina.pc
	@$(call install_files,$(INSTALL_FILES))
	@echo "lamina: installed in $(DESTDIR)$(PREFIX) ($(words $(INSTALL_FILES)) files)"

# The Lua module alone (the LuaRocks rock: lamina-scm-1.rockspec).
lua-module: $(LUAMOD) $(PLUGIN_SO)
install-lua: lua-module
	@$(call install_files,$(INSTALL_LUA))

uninstall:
	@$(install_vars) for e in $(INSTALL_FILES); do rest=$${e#*:}; dest "$${rest#*:}"; rm -f "$$dst"; done; \
	  for d in $(INSTALL_OWN_DIRS); do dest "$$d"; echo "$${dst%/.}"; done | sort -ru | \
	  while read -r d; do [ ! -d "$$d" ] || rmdir --ignore-fail-on-non-empty "$$d"; done
	@echo "lamina: uninstalled from $(DESTDIR)$(PREFIX)"

clean:
	rm -rf build build-san build-bench build-fuzz out rocks $(PLUGIN_SO)

-include $(CORE_OBJ:.o=.d) $(CLI_OBJ:.o=.d)
