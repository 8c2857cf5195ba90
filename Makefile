# Thin wrapper around CMake presets; see README.md and docs/installation.md.
BUILD_DIR ?= build
PRESET    ?= default
JOBS      ?= $(shell nproc)
ROTORD_ARGS ?= --sim g5500

.PHONY: all deps build run test bench embedded pico hil deb pi-vm format format-check clean

all: build

deps:
	@BUILD_DIR=$(BUILD_DIR) ./scripts/install-deps.sh --with-web

build: deps
	@cmake --preset $(PRESET) >/dev/null
	@cmake --build --preset $(PRESET) -j $(JOBS)

run: build
	./$(BUILD_DIR)/rotord $(ROTORD_ARGS)

test: build
	@./scripts/check-format.sh
	ctest --preset $(PRESET) -j $(JOBS)

bench: build
	@cmake --build --preset $(PRESET) --target benchmarks -j $(JOBS)
	python3 bench/run.py --build-dir $(BUILD_DIR)

embedded: deps
	@cmake --preset embedded >/dev/null
	@cmake --build --preset embedded -j $(JOBS)
	ctest --preset embedded

# The Pico W firmware (ports/pico_w): a separate pico-sdk project, built only
# when PICO_SDK_PATH points at a pico-sdk 2.x checkout (see ports/pico_w/README.md).
# picotool_DIR (optional) points at an installed picotool's CMake package.
# PICO_BOARD=pico: the plain Pico's USB-only image (rotord_pico.uf2), in a
# build directory of its own (build-pico-pico).
PICO_BOARD ?= pico_w
PICO_BUILD_DIR ?= $(if $(filter pico_w,$(PICO_BOARD)),build-pico,build-pico-$(PICO_BOARD))
pico:
ifeq ($(strip $(PICO_SDK_PATH)),)
	@echo "pico-sdk not found (PICO_SDK_PATH): skipping the Pico W firmware"
else
	@cmake -S ports/pico_w -B $(PICO_BUILD_DIR) -G Ninja -DPICO_BOARD=$(PICO_BOARD) $(if $(picotool_DIR),-Dpicotool_DIR=$(picotool_DIR)) >/dev/null
	@cmake --build $(PICO_BUILD_DIR) -j $(JOBS)
endif

# The firmware on an emulated RP2040 (ports/pico_w/README.md, "The firmware on
# an emulated RP2040"): builds each board's image (make pico), then runs the
# scenarios of tests/hil/hil.mjs in rp2040js with the simulator's plant on
# its pins. ROTORD_RP2040_BOOTROM names the RP2040 B1 bootrom (the rp2040js
# repository's demo/bootrom.ts, or a 16 KB image); it is never part of this
# repository. HIL_BOARDS: which images (pico_w, pico); HIL_ARGS: e.g.
# --only=goto-relay-pot-gs232 --verbose
HIL_BOARDS ?= pico_w pico
HIL_ARGS ?=
hil:
ifeq ($(strip $(PICO_SDK_PATH)),)
	@echo "hil: skipped: pico-sdk not found (PICO_SDK_PATH), no firmware to run"
else ifeq ($(strip $(ROTORD_RP2040_BOOTROM)),)
	@echo "hil: skipped: no RP2040 bootrom (ROTORD_RP2040_BOOTROM, e.g. rp2040js's demo/bootrom.ts)"
else
	@$(MAKE) --no-print-directory build
	@rc=0; for board in $(HIL_BOARDS); do \
	  dir=$$( [ $$board = pico_w ] && echo build-pico || echo build-pico-$$board ); \
	  $(MAKE) --no-print-directory pico PICO_BOARD=$$board PICO_BUILD_DIR=$$dir || exit 1; \
	  (cd tests/hil && ROTORD_HIL_IMAGE=$(CURDIR)/$$dir/rotord_$$board.elf \
	    ROTORD_HIL_PLANT=$(abspath $(BUILD_DIR))/tests/hil/rotord_hil_plant \
	    ROTORD_HIL_OUT=$(abspath $(BUILD_DIR))/bench/hil_$$board.json node hil.mjs $(HIL_ARGS)) || rc=1; \
	done; exit $$rc
endif

# The Debian package for this machine's architecture (arm64/armhf on a Pi),
# built from a copy of the tree in $(DEB_BUILD_DIR) so debhelper's files
# stay out of the source; the .deb lands in the top directory.
# docs/installation.md, "Install on a Raspberry Pi". ARCH=arm64 or
# ARCH=armhf cross-builds the Raspberry Pi's package on an amd64 machine
# (docs/raspberry-pi.md).
# armhf from another architecture builds in a cached Debian 12 chroot
# (scripts/deb-chroot.sh; DEB_CHROOT=0 uses this machine's multiarch
# libraries instead, DEB_CHROOT=1 the chroot for arm64 too).
ARCH ?= $(shell dpkg --print-architecture 2>/dev/null)
DEB_BUILD_DIR ?= build-deb$(if $(filter-out $(shell dpkg --print-architecture 2>/dev/null),$(ARCH)),-$(ARCH))
DEB_CHROOT ?= $(if $(and $(filter armhf,$(ARCH)),$(filter-out armhf,$(shell dpkg --print-architecture 2>/dev/null))),1,0)
deb:
	@./scripts/install-deps.sh $(if $(filter 1,$(DEB_CHROOT)),--deb-chroot,--deb) $(ARCH)
	@DEB_BUILD_DIR=$(DEB_BUILD_DIR) DEB_JOBS=$(JOBS) DEB_HOST_ARCH=$(ARCH) DEB_CHROOT=$(DEB_CHROOT) ./scripts/build-deb.sh
	@cp $(DEB_BUILD_DIR)/rotord_*_$(ARCH).deb .
	@ls rotord_*_$(ARCH).deb

# The Raspberry Pi path on a booted Debian 12 arm64 machine under
# qemu-system-aarch64 (tests/pi_vm, docs/raspberry-pi.md): the arm64 build
# and package (tests/cross), the cached machine image, then the checks.
# Part of `make test`; this runs only it and what it needs (the image is
# built beside the arm64 package's checks).
pi-vm: deps
	@cmake --preset $(PRESET) >/dev/null
	ctest --preset $(PRESET) -R '^pi_vm$$' -j $(JOBS) --output-on-failure

format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR) build-embedded $(PICO_BUILD_DIR) build-deb build-deb-arm64 build-deb-armhf
