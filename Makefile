# The C library, built by cargo and installed where C and C++ programs find it:
#
#   make                                   build target/dist/librocking.{so,a}
#   make install PREFIX=/opt/rocking       install (DESTDIR=... for staging, e.g. packaging);
#                                          builds first only if a source changed since `make`,
#                                          so `make && sudo make install` needs no cargo as root
#   make uninstall PREFIX=/opt/rocking     remove exactly the files install put there
#   make header                            regenerate include/rocking.h and the C/Python samples
#   make check-install                     install into a temporary prefix and build, link and
#                                          run C and C++ clients from it (tests/install/run.sh)
#
# Installs lib/librocking.so.VERSION (soname librocking.so.ABI, ABI = ROCKING_ABI_VERSION) with
# the links librocking.so.ABI and librocking.so, lib/librocking.a, include/rocking.h,
# lib/pkgconfig/rocking.pc and lib/cmake/rocking/rocking{Config,ConfigVersion}.cmake
# (docs/c-api.md). Everything but the build is dist/install.sh.

PREFIX ?= /usr/local
DESTDIR ?=
LIBDIR ?= lib
INCLUDEDIR ?= include
CARGO ?= cargo
STRIP ?= strip

SHELL := /bin/bash
.SHELLFLAGS := -euo pipefail -c
BUILD := target/dist
VERSION := $(shell sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)
ABI := $(shell sed -n 's/^\#define ROCKING_ABI_VERSION \([0-9][0-9]*\).*/\1/p' include/rocking.h)

.PHONY: all build install uninstall header check-install

all: build

# The library for installation: profile `dist` (release without debug info), soname from the ABI
# version. The static library's system dependencies (rustc's native-static-libs, printed again
# by cargo when nothing had to be rebuilt) go into Libs.private and the CMake static target;
# their file is also the stamp of the last build, written only when the build succeeded.
STAMP := $(BUILD)/native-static-libs
SOURCES := $(wildcard Cargo.toml Cargo.lock build.rs cbindgen.toml) $(shell find src -name '*.rs' 2>/dev/null)

define cargo_build
	@command -v "$(CARGO)" >/dev/null 2>&1 || { \
	  echo "make: cargo not found ('$(CARGO)'): install a Rust toolchain (rustup) or pass CARGO=/path/to/cargo" >&2; exit 1; }
	@test -n "$(VERSION)" -a -n "$(ABI)" || { echo "make: no version in Cargo.toml or no ROCKING_ABI_VERSION in include/rocking.h" >&2; exit 1; }
	@mkdir -p $(BUILD)
	"$(CARGO)" rustc --profile dist -p rocking --lib -- \
	  -C link-arg=-Wl,-soname,librocking.so.$(ABI) --print native-static-libs 2>&1 | tee $(BUILD)/build.log
	@sed -n 's/.*native-static-libs: //p' $(BUILD)/build.log | tail -n 1 > $(STAMP).new
	@test -s $(STAMP).new || { rm -f $(STAMP).new; echo "make: cargo printed no native-static-libs (see $(BUILD)/build.log)" >&2; exit 1; }
	@mv -f $(STAMP).new $(STAMP)
endef

# `make` always asks cargo (which decides what is stale).
build:
	$(cargo_build)

# `make install` builds only when a source is newer than the last build: `make` then
# `sudo make install` works although root has no cargo on its PATH (sudo's secure_path), and
# leaves no root-owned files in target/.
$(STAMP): $(SOURCES)
	$(cargo_build)

install: $(STAMP)
	PREFIX="$(PREFIX)" DESTDIR="$(DESTDIR)" LIBDIR="$(LIBDIR)" INCLUDEDIR="$(INCLUDEDIR)" \
	  VERSION="$(VERSION)" ABI="$(ABI)" BUILD="$(BUILD)" STRIP="$(STRIP)" \
	  NATIVE_LIBS="$$(cat $(BUILD)/native-static-libs)" sh dist/install.sh install

uninstall:
	PREFIX="$(PREFIX)" DESTDIR="$(DESTDIR)" LIBDIR="$(LIBDIR)" INCLUDEDIR="$(INCLUDEDIR)" \
	  VERSION="$(VERSION)" ABI="$(ABI)" BUILD="$(BUILD)" sh dist/install.sh uninstall

header:
	ROCKING_BLESS=1 "$(CARGO)" test --release -p rocking --test c_abi generated

check-install:
	tests/install/run.sh
