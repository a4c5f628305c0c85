# Entry points. Each target installs what is missing (toolchain/install-deps) first.
#   make demo        build and run the simulated station with a live view of every State
#   make test        the default suite: ASan+UBSan build, all tests; TSan build, threaded tests
#   make bench       benchmarks, results into docs/benchmarks.md (slow; not in the default suite)
#   make soak        the station under reconnects, floods and faults for SOAK_MINUTES (60), sampled
#                    into build/host-release/soak/soak.csv and soak.png (docs/soak.md; not in CI)
#   make fuzz        every libFuzzer harness for FUZZ_SECONDS (60) each, clang build (fuzz/README.md)
#   make kernel-test the Linux backends and a whole hub against vcan and gpio-sim in a VM
#                    (tests/kernel/README.md; KERNEL_PRESET=host-asan reuses the ASan build)
#   make cross-test  arm64 cross build, unit tests under qemu-user (ARCH=armhf for the other)
#   make net-test    the station over 5 network namespaces, unicast peers from hubctl net-config,
#                    link faults (tests/net/run; root; reuses build/host-asan, builds what is missing)
#   make netem-test  a hub and hubctl across a link with 10 % loss / 50 ms delay (sch_netem) in the
#                    kernel tier's VM: heartbeat and echo figures (tests/net/netem-in-vm)
#   make ros1-test   hubbridge between Debian's ROS 1 and the station, on the ASan build (docs/ros1-bridge.md)
#   make ui-test     the operator screen (hubctl serve) in headless Chromium, reusing build/host-asan
#                    (docs/operator-screen.md; screenshot in build/host-asan/ui-test/)
#   make ecosystem-test  the MCAP files hubctl record and hubd's black box write, read by the
#                    ecosystem's JavaScript readers (@mcap/core, rosmsg2-serialization; tests/js/README.md),
#                    and hubctl foxglove driven by the protocol's own client (@foxglove/ws-protocol)
#   make board BOARD=rpi4-tool-ecu   the board's Debian package in build/packages (docs/deploy.md)
#   make deploy-test the Tool ECU package installed over ssh on an arm64 VM under systemd
#                    (tests/deploy/README.md; slow the first time: builds the VM image)
#   make deploy-docs regenerate the wiring tables of docs/deploy.md from boards/
#   make safety-table run the tests that measure time to safe (and the net tier: root), then
#                    regenerate docs/safety.md's table from what they wrote (build/host-asan)
#   make format      clang-format every source file;  make lint  clang-format check + clang-tidy
JOBS ?= 2
CMAKE_BUILD = cmake --build --preset

help:
	@sed -n '1,26p' Makefile | sed 's/^# \{0,1\}//'

.PHONY: help deps demo build test test-asan test-tsan test-debug bench soak fuzz kernel-test cross-test net-test netem-test ros1-test ui-test ecosystem-test board deploy-test deploy-docs safety-table format format-check lint

deps:
	@toolchain/install-deps

build: deps
	@cmake --preset host-release >/dev/null
	@$(CMAKE_BUILD) host-release -j$(JOBS) --target hubd hubctl hubsim

demo: build
	@toolchain/demo

# The TSan build runs beside the ASan tests at idle priority (toolchain/default-suite says why);
# test-asan and test-tsan run each half alone.
test: deps
	@toolchain/default-suite $(JOBS)

test-asan: deps
	@cmake --preset host-asan >/dev/null
	@$(CMAKE_BUILD) host-asan -j$(JOBS)
	@ctest --preset host-asan -j$(JOBS)

test-tsan: deps
	@cmake --preset host-tsan >/dev/null
	@$(CMAKE_BUILD) host-tsan -j$(JOBS) --target threaded-tests
	@ctest --preset host-tsan -j$(JOBS)

test-debug: deps
	@cmake --preset host-debug >/dev/null
	@$(CMAKE_BUILD) host-debug -j$(JOBS)
	@ctest --preset host-debug -j$(JOBS)

bench:
	@toolchain/install-deps --bench
	@cmake --preset host-release >/dev/null
	@$(CMAKE_BUILD) host-release -j$(JOBS) --target bench-programs
	@bench/run --build-dir build/host-release

# The soak tier (docs/soak.md): release build, SOAK_MINUTES of load, non-zero on a crash, growth
# beyond the stated slopes or a heartbeat beyond its jitter budget. python3-matplotlib draws soak.png.
SOAK_MINUTES ?= 60
soak:
	@toolchain/install-deps --bench
	@cmake --preset host-release >/dev/null
	@$(CMAKE_BUILD) host-release -j$(JOBS) --target hubd hubctl hubsim
	@tests/soak/soak --minutes $(SOAK_MINUTES) --build-dir build/host-release

# libFuzzer harnesses (fuzz/): clang with ASan+UBSan, each harness run on a scratch copy of its
# seed corpus; non-zero on any crash, whose input stays in build/fuzz/fuzz-artifacts/.
FUZZ_SECONDS ?= 60
fuzz:
	@toolchain/install-deps --fuzz
	@cmake --preset fuzz >/dev/null
	@$(CMAKE_BUILD) fuzz -j$(JOBS)
	@toolchain/fuzz --seconds $(FUZZ_SECONDS) --build-dir build/fuzz

# Which build's "kernel" tests the VM runs: host-debug, or host-asan after `make test` (then
# nothing is rebuilt).
KERNEL_PRESET ?= host-debug
kernel-test: deps
	@cmake --preset $(KERNEL_PRESET) >/dev/null
	@$(CMAKE_BUILD) $(KERNEL_PRESET) -j$(JOBS)
	@tests/kernel/run --build-dir build/$(KERNEL_PRESET)

# The operator screen in a real browser (tests/ui/README.md); builds only hubd and hubctl if the
# default suite has not.
ui-test:
	@toolchain/install-deps --ui
	@cmake --preset host-asan >/dev/null
	@$(CMAKE_BUILD) host-asan -j$(JOBS) --target hubd hubctl
	@tests/ui/run --build-dir build/host-asan

# The ecosystem tier (tests/js/README.md): reuses build/host-asan (builds only hubd and hubctl if the
# default suite has not); the JavaScript packages from tests/js's lockfile (toolchain/install-js-deps).
ecosystem-test: deps
	@cmake --preset host-asan >/dev/null
	@$(CMAKE_BUILD) host-asan -j$(JOBS) --target hubd hubctl
	@toolchain/install-js-deps --build-dir build/host-asan
	@tests/js/run --build-dir build/host-asan

cross-test: deps
	@toolchain/cross-test $(or $(ARCH),arm64)

# docs/safety.md's time-to-safe table (issue 29): the tests that measure it write their rows into
# build/host-asan/time-to-safe/, the net tier its partition rows (needs root), then the generator.
# CTest names: the two unit programs are one test each; the integration programs' tests are named
# after their suites (a program's own name matched none of them, so this ran only those two).
SAFETY_TESTS = ^(hubrt_clock_step_test|hubrt_rsp_ecu_device_vanish_test)$$|/(HubdStaleAfterStopTest|HubdHeartbeatHoldsTest|HubdPlannerGoneTest)\.
safety-table: deps
	@cmake --preset host-asan >/dev/null
	@$(CMAKE_BUILD) host-asan -j$(JOBS)
	@ctest --preset host-asan --no-tests=error -R '$(SAFETY_TESTS)'
	@tests/net/run --build-dir build/host-asan
	@toolchain/time-to-safe-table --build-dir build/host-asan

# The net tier: the programs of the ASan build (after `make test` nothing is rebuilt).
net-test: deps
	@cmake --preset host-asan >/dev/null
	@$(CMAKE_BUILD) host-asan -j$(JOBS) --target hubd hubctl hubsim
	@tests/net/run --build-dir build/host-asan

netem-test: deps
	@cmake --preset host-asan >/dev/null
	@$(CMAKE_BUILD) host-asan -j$(JOBS) --target hubd hubctl
	@tests/net/netem-in-vm --build-dir build/host-asan
# The ROS 1 tier (docs/ros1-bridge.md): a rospy Dock ECU bridged by hubbridge, its conformance and
# the station's use-case with it, rosmaster restarts, mismatching publishers. Reuses build/host-asan
# (builds only the programs it runs when they are missing or stale).
ros1-test: deps
	@cmake --preset host-asan >/dev/null
	@$(CMAKE_BUILD) host-asan -j$(JOBS) --target hubbridge hubd hubctl hubsim
	@tests/ros1/ros1_tier.py --build build/host-asan

board:
	@test -n "$(BOARD)" || { echo "make board: say which, e.g. make board BOARD=rpi4-tool-ecu" >&2; exit 2; }
	@toolchain/package-board $(BOARD)

# Reuses the package of the cross tier (build/packages) when there is one, else makes it.
deploy-test: deps
	@toolchain/install-deps --deploy
	@tests/deploy/run

deploy-docs: deps
	@cmake --preset host-release >/dev/null
	@$(CMAKE_BUILD) host-release -j$(JOBS) --target hubrt-board-info
	@build/host-release/packaging/hubrt-board-info deploy-docs --doc docs/deploy.md boards/*.yaml

format:
	@git ls-files '*.cc' '*.h' '*.cpp' | xargs clang-format -i

format-check:
	@git ls-files '*.cc' '*.h' '*.cpp' | xargs clang-format --dry-run -Werror

lint: format-check
	@cmake --preset host-debug >/dev/null
	@$(CMAKE_BUILD) host-debug -j$(JOBS)
	@# fuzz/ is built only by the fuzz preset, so host-debug's compilation database has no entry for it.
	@git ls-files '*.cc' | grep -v '/test/' | grep -v '^fuzz/' | xargs -P$(JOBS) -n8 clang-tidy -p build/host-debug --quiet
