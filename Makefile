# ksmcmc build and test entry points. GNU make.
#
#   make demo    build the WebAssembly package and serve the demo on http://127.0.0.1:8080
#   make test    every check CI runs: fmt, clippy, native tests, wasm tests in headless
#                Chromium, the browser end-to-end tests, and 20 s of each fuzz target when a
#                nightly toolchain is installed
#   make fuzz    each fuzz target for FUZZ_SECONDS (default 600) in turn, one process
#
# Both install what is missing first (wasm32 target, the wasm-bindgen CLI at the version
# Cargo.toml pins, Debian's chromium and chromium-driver, the e2e test's npm packages), so they
# work on a fresh machine that has only rustup, Node, npm, Python 3 and apt.

SHELL := bash
comma := ,
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := help
MAKEFLAGS += --no-builtin-rules

export PATH := $(HOME)/.cargo/bin:$(PATH)
CARGO ?= cargo
WASM_TARGET := wasm32-unknown-unknown
# The wasm-bindgen CLI must match the wasm-bindgen crate to the patch version.
WASM_BINDGEN_VERSION := $(shell sed -n 's/^wasm-bindgen *= *"=\([0-9][0-9.]*\)".*/\1/p' Cargo.toml)
HOST ?= 127.0.0.1
PORT ?= 8080
CHROMIUM ?= /usr/bin/chromium
CHROMEDRIVER ?= /usr/bin/chromedriver
# Browser tests: wasm-bindgen-test-runner drives headless Chromium through chromedriver with
# the capabilities in webdriver.json.
WASM_TEST_ENV := CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUNNER=wasm-bindgen-test-runner \
	CHROMEDRIVER=$(CHROMEDRIVER) WASM_BINDGEN_TEST_TIMEOUT=180 \
	WASM_BINDGEN_TEST_WEBDRIVER_JSON=$(CURDIR)/webdriver.json
# The package's modules, NAME:FEATURE (see src/wasm/mod.rs): the mapper module ksmcmc.js (maps,
# pictures, the live chain), which the live mapper loads first, and the modules pages load
# when they need them: a best world's plan (rooms, exports, routes), synthetic maps, the rules
# (inference, learning) and the table-top analysis. Each is the crate built with its feature
# alone in the wasm-release profile of Cargo.toml (no debug names, fat LTO), with simd128
# (.cargo/config.toml), then wasm-opt.
WASM_MODULES := ksmcmc:wasm-mapper ksmcmc_plan:wasm-plan ksmcmc_synth:wasm-synth ksmcmc_rules:wasm-rules \
	ksmcmc_tabletop:wasm-tabletop ksmcmc_explore:wasm-explore
WASM_FEATURES := $(subst $(eval) ,$(comma),$(foreach m,$(WASM_MODULES),$(lastword $(subst :, ,$(m)))))
WASM_NAMES := $(foreach m,$(WASM_MODULES),$(firstword $(subst :, ,$(m))))
WASM_DIR := target/$(WASM_TARGET)/wasm-release
WASM_SOURCES := Cargo.toml Cargo.lock .cargo/config.toml $(shell find src -name '*.rs' -not -path 'src/bin/*')
# wasm-opt (binaryen) shrinks rustc's output before wasm-bindgen reads it: Debian's binaryen
# 108 cannot parse the externref-table code wasm-bindgen adds (table.fill). It is told the
# features rustc's wasm32 target uses, and drops the name section. --converge runs -O3's passes
# until they change nothing more (the mapper module 767 bytes smaller gzipped than one round).
WASM_OPT_FLAGS := -O3 --converge --enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext \
	--enable-mutable-globals --enable-reference-types --enable-multivalue --enable-simd
# The most the mapper module may weigh gzipped (issue 12): what the live mapper page loads
# before its first frame. `make pkg` warns above it; tests/e2e/size.test.mjs fails.
MAPPER_GZIP_MAX := 500000

.PHONY: help demo serve pkg www-pkg www-samples www-vendor test lint fmt fmt-check clippy doc-check test-native test-wasm \
	test-e2e cli release-cli bench-wasm tools rust-tools wasm-tools wasm-opt-tool browser-tools e2e-deps vendor-deps clean-pkg \
	fuzz fuzz-ci fuzz-tools fuzz-cpu soak python python-tools test-python demo-plan

help:
	@echo "make demo      build pkg/ and serve www/ on http://$(HOST):$(PORT)"
	@echo "make test      fmt, clippy, native tests, the Python package, wasm tests (headless Chromium), e2e tests"
	@echo "make pkg       build the npm package in pkg/ (release wasm + wasm-bindgen + the mount embed)"
	@echo "make bench-wasm  chain speed in headless Chromium (compare: ./target/release/ksmcmc bench)"
	@echo "make lint      cargo fmt --check, clippy (native and wasm32) and the API docs without a warning"
	@echo "make test-native | test-python | test-wasm | test-e2e    one part of make test"
	@echo "make python    the Python package as a wheel in target/wheels (pip install ./python also works)"
	@echo "make tools     install what the build and tests need"
	@echo "make fuzz      run each fuzz target FUZZ_SECONDS (default 600) s, one at a time (needs nightly)"
	@echo "make fuzz-cpu  run each fuzz target until it has used FUZZ_SECONDS of CPU time, at low priority"
	@echo "make soak      drive the mapper and table-top pages SOAK_MINUTES (default 30) and watch their heaps"

# ---------------------------------------------------------------- tools

tools: rust-tools wasm-tools wasm-opt-tool browser-tools e2e-deps vendor-deps

rust-tools:
	@command -v rustup >/dev/null || { echo "rustup is needed: https://rustup.rs" >&2; exit 1; }
	@rustup component list --installed | grep -q '^rustfmt' || rustup component add rustfmt
	@rustup component list --installed | grep -q '^clippy' || rustup component add clippy

wasm-tools: rust-tools
	@test -n "$(WASM_BINDGEN_VERSION)" || { echo "no wasm-bindgen = \"=X.Y.Z\" pin in Cargo.toml" >&2; exit 1; }
	@rustup target list --installed | grep -qx '$(WASM_TARGET)' || rustup target add $(WASM_TARGET)
	@if [ "$$(wasm-bindgen --version 2>/dev/null)" != "wasm-bindgen $(WASM_BINDGEN_VERSION)" ] || \
	    [ "$$(wasm-bindgen-test-runner --version 2>/dev/null)" != "wasm-bindgen-test-runner $(WASM_BINDGEN_VERSION)" ]; then \
	  echo "installing wasm-bindgen-cli $(WASM_BINDGEN_VERSION) (a few minutes, once)"; \
	  $(CARGO) install wasm-bindgen-cli --version $(WASM_BINDGEN_VERSION); \
	fi

# binaryen's wasm-opt, which shrinks the package's .wasm (Debian's binaryen package).
wasm-opt-tool:
	@if ! command -v wasm-opt >/dev/null; then \
	  echo "installing Debian's binaryen (wasm-opt)"; \
	  sudo=; [ "$$(id -u)" = 0 ] || sudo=sudo; \
	  $$sudo apt-get update -q; \
	  DEBIAN_FRONTEND=noninteractive $$sudo apt-get install -y -q binaryen; \
	fi

browser-tools:
	@if [ ! -x $(CHROMIUM) ] || [ ! -x $(CHROMEDRIVER) ]; then \
	  echo "installing Debian's chromium and chromium-driver"; \
	  sudo=; [ "$$(id -u)" = 0 ] || sudo=sudo; \
	  $$sudo apt-get update -q; \
	  DEBIAN_FRONTEND=noninteractive $$sudo apt-get install -y -q chromium chromium-driver; \
	fi

# playwright-core (it drives the Debian Chromium and never downloads a browser) and
# @placemarkio/check-geojson (the GeoJSON export is read back with it), from package-lock.json.
e2e-deps: tests/e2e/node_modules/.package-lock.json

tests/e2e/node_modules/.package-lock.json: tests/e2e/package.json tests/e2e/package-lock.json
	cd tests/e2e && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error
	@touch $@

# three.js for the live mapper's 3D view, at the version vendor/package-lock.json pins.
vendor-deps: vendor/node_modules/.package-lock.json

vendor/node_modules/.package-lock.json: vendor/package.json vendor/package-lock.json
	@echo "installing three.js from npm into vendor/ (under a minute)"
	cd vendor && npm ci --no-audit --no-fund --loglevel=error
	@touch $@

# ---------------------------------------------------------------- build

# The npm package: the modules' wasm, wasm-bindgen's ES modules and .d.ts, the hand-written
# modules in npm/ (the `mount` embed, the sample recipes), the page modules mount imports
# (PKG_LIB: zoom and pan, and the wings' chains, shared with the demo pages) and package.json. Prints each module's
# size, raw and gzipped (gzip -9), and fails if the mapper module is over MAPPER_GZIP_MAX.
PKG_LIB := www/lib/viewport.js www/lib/wing-chains.js
pkg: wasm-tools wasm-opt-tool $(foreach n,$(WASM_NAMES),$(WASM_DIR)/$(n).opt.wasm)
	rm -f pkg/*.js pkg/*.d.ts pkg/*.wasm pkg/package.json
	@for n in $(WASM_NAMES); do \
	  echo "wasm-bindgen $$n"; wasm-bindgen --target web --out-dir pkg --out-name $$n $(WASM_DIR)/$$n.opt.wasm; \
	done
	cp npm/*.js npm/*.d.ts $(PKG_LIB) pkg/
	node scripts/pkg-json.mjs Cargo.toml npm $(PKG_LIB) --modules $(filter-out ksmcmc,$(WASM_NAMES)) > pkg/package.json
	@for n in $(WASM_NAMES); do \
	  echo "pkg/$${n}_bg.wasm: $$(wc -c < pkg/$${n}_bg.wasm) bytes, $$(gzip -9 -c pkg/$${n}_bg.wasm | wc -c) gzipped"; \
	done
	@echo "version $$(node -p 'require("./pkg/package.json").version')"
	@gz=$$(gzip -9 -c pkg/ksmcmc_bg.wasm | wc -c); if [ $$gz -gt $(MAPPER_GZIP_MAX) ]; then \
	  echo "warning: pkg/ksmcmc_bg.wasm is $$gz bytes gzipped, over the $(MAPPER_GZIP_MAX) the live mapper may load first (tests/e2e/size.test.mjs fails)" >&2; fi

# One module: the crate with that module's feature alone, then wasm-opt. rustc writes every
# module to the same ksmcmc.wasm, so each is copied out at once (do not build them with -j).
FEATURE_OF = $(lastword $(subst :, ,$(filter $(1):%,$(WASM_MODULES))))
$(WASM_DIR)/%.opt.wasm: $(WASM_SOURCES) | wasm-tools wasm-opt-tool
	@echo "building the WebAssembly module $* (module $$(( $$(echo ' $(WASM_NAMES) ' | sed 's/ $* .*//' | wc -w) + 1 )) of $(words $(WASM_NAMES)))"
	$(CARGO) build --lib --profile wasm-release --target $(WASM_TARGET) --no-default-features \
	  --features $(call FEATURE_OF,$*)
	wasm-opt $(WASM_OPT_FLAGS) $(WASM_DIR)/ksmcmc.wasm -o $@

# The pages load the package from www/pkg, the live mapper its samples from www/samples and
# three.js from www/vendor (copies, not committed).
www-pkg: pkg www-samples www-vendor
	rm -rf www/pkg
	mkdir -p www/pkg
	cp pkg/*.js pkg/*_bg.wasm pkg/*.d.ts pkg/package.json www/pkg/

www-samples:
	node scripts/www-samples.mjs samples www/samples

# three.js (its ES modules and the glTF loader and orbit controls from its addons, with its
# licence) into www/vendor/three, where the live mapper's import map finds them; the page loads
# them only when its 3D view opens. No CDN: the demo works offline.
THREE := vendor/node_modules/three
www-vendor: vendor-deps
	rm -rf www/vendor
	mkdir -p www/vendor/three/build www/vendor/three/addons/loaders www/vendor/three/addons/utils \
	  www/vendor/three/addons/controls
	cp $(THREE)/LICENSE www/vendor/three/
	cp $(THREE)/build/three.module.js $(THREE)/build/three.core.js www/vendor/three/build/
	cp $(THREE)/examples/jsm/loaders/GLTFLoader.js www/vendor/three/addons/loaders/
	cp $(THREE)/examples/jsm/utils/BufferGeometryUtils.js $(THREE)/examples/jsm/utils/SkeletonUtils.js \
	  www/vendor/three/addons/utils/
	cp $(THREE)/examples/jsm/controls/OrbitControls.js www/vendor/three/addons/controls/

cli:
	$(CARGO) build --bin ksmcmc

release-cli:
	$(CARGO) build --release --bin ksmcmc

clean-pkg:
	rm -rf www/pkg www/samples www/vendor
	find pkg -mindepth 1 ! -name README.md -delete 2>/dev/null || true

# ---------------------------------------------------------------- demo

demo: demo-plan www-pkg serve

# Says up front what `make demo` will install and build, and roughly how long that takes.
demo-plan:
	@scripts/demo-plan.sh $(WASM_TARGET) $(WASM_BINDGEN_VERSION) $(WASM_DIR) $(WASM_NAMES)

# Python's http.server, sending .wasm as application/wasm and nothing cached.
serve: www-samples www-vendor
	@test -f www/pkg/ksmcmc_bg.wasm || { echo "www/pkg is missing: run make demo" >&2; exit 1; }
	python3 scripts/serve.py www $(HOST) $(PORT)

# ---------------------------------------------------------------- checks

lint: fmt-check clippy doc-check

fmt:
	$(CARGO) fmt

# The API docs build without a warning: no broken or private intra-doc links.
doc-check: rust-tools
	RUSTDOCFLAGS="-D warnings" $(CARGO) doc --no-deps --lib

fmt-check: rust-tools
	$(CARGO) fmt --check

clippy: rust-tools wasm-tools
	$(CARGO) clippy --all-targets -- -D warnings
	$(CARGO) clippy --target $(WASM_TARGET) --no-default-features --features $(WASM_FEATURES) --lib --test wasm -- -D warnings

test: tools
	@start=$$(date +%s); \
	$(MAKE) --no-print-directory lint test-native test-python test-wasm test-e2e fuzz-ci; \
	echo "make test: all checks passed in $$(( $$(date +%s) - start )) s"

test-native:
	$(CARGO) test

# ---------------------------------------------------------------- python
#
# The Python package (python/): a PyO3 extension built by maturin, its own Cargo workspace.
# `make python` builds a wheel into target/wheels. `make test-python` checks the extension's
# Rust (fmt, clippy), installs the package as a user would, `pip install ./python` (the PEP 517
# build compiles it on the spot, about 3 minutes the first time on 2 cores), into a fresh
# virtual environment, and runs its tests beside the command line of the same tree; the ROS 2
# example is only compiled (no ROS 2 here). maturin, pytest and numpy come from PyPI.
PYTHON ?= python3
PY_TOOLS := target/python-tools
PY_FRESH := target/python-fresh

python-tools:
	@test -x $(PY_TOOLS)/bin/python || $(PYTHON) -m venv $(PY_TOOLS) || \
	  { echo "make: $(PYTHON) -m venv failed: install Python 3 with venv (Debian: python3-venv)" >&2; exit 1; }
	@$(PY_TOOLS)/bin/pip install -q --disable-pip-version-check "maturin>=1.5,<2"

python: python-tools
	$(PY_TOOLS)/bin/maturin build --release -m python/Cargo.toml -o target/wheels

test-python: rust-tools cli
	cd python && $(CARGO) fmt --check && $(CARGO) clippy -- -D warnings
	rm -rf $(PY_FRESH) && $(PYTHON) -m venv $(PY_FRESH)
	$(PY_FRESH)/bin/pip install -q --disable-pip-version-check ./python "pytest>=7"
	KSMCMC_BIN=$(CURDIR)/target/debug/ksmcmc $(PY_FRESH)/bin/python -m pytest -q -p no:cacheprovider python/tests
	$(PY_FRESH)/bin/python -m py_compile python/examples/ros2_node.py

# The CLI binary is native only; --no-default-features leaves it out of the wasm build, which
# has every module's API (WASM_FEATURES).
test-wasm: wasm-tools browser-tools
	$(WASM_TEST_ENV) $(CARGO) test --target $(WASM_TARGET) --no-default-features --features $(WASM_FEATURES) --test wasm

# Serves www/ (with the release package) and drives Debian's Chromium through playwright-core;
# compares with the native CLI (target/debug/ksmcmc).
test-e2e: www-pkg cli browser-tools e2e-deps
	cd tests/e2e && CHROMIUM=$(CHROMIUM) node --test --test-concurrency=1 --test-timeout=300000

# ---------------------------------------------------------------- speed

# The chain's speed in headless Chromium: 20000 iterations on the Radish Cartesium map and on
# synthetic 556x322 and 1237x672 maps, as `ksmcmc bench` runs them natively. Prints
# iterations/s and setup time; not a test (numbers depend on the machine). Compare with
# `./target/release/ksmcmc bench` (make release-cli), run while the machine is otherwise idle.
bench-wasm: www-pkg browser-tools e2e-deps
	CHROMIUM=$(CHROMIUM) node scripts/bench-wasm.mjs $(BENCH_ARGS)

# The pages' soak test (not in CI): the mapper and the table-top page driven side by side with
# random seeded actions for SOAK_MINUTES, recording the wasm and JS heaps every minute; fails on
# any uncaught error or a wasm heap that grows over 10 % after the first five minutes. Results
# in target/soak.json.
SOAK_MINUTES ?= 30
soak: www-pkg browser-tools e2e-deps
	CHROMIUM=$(CHROMIUM) node scripts/soak.mjs --minutes $(SOAK_MINUTES) --out target/soak.json

# ---------------------------------------------------------------- fuzzing

# cargo-fuzz (libFuzzer) targets in fuzz/, one per reader; see docs/fuzzing.md.
# One fuzzer process at a time (no -jobs): the machines are shared. New corpus entries go to
# fuzz/corpus/TARGET (not committed), crashes to fuzz/artifacts/TARGET; the committed seeds
# are fuzz/seeds/TARGET, and fixed crashes are kept in fuzz/regressions/TARGET, which
# `cargo test` replays on stable (tests/it/hostile.rs).
FUZZ_TARGETS := pgm png ros_yaml mln db world_json world_arbitrary scene_json chain_config synth_config edits
FUZZ_SECONDS ?= 600
FUZZ_CI_SECONDS ?= 20
CARGO_FUZZ_VERSION := 0.13.2
FUZZ_FLAGS = -rss_limit_mb=2048 -timeout=10 -print_final_stats=1
HAVE_NIGHTLY = $(shell rustup toolchain list 2>/dev/null | grep -q '^nightly' && echo yes)

fuzz-tools:
	@test "$(HAVE_NIGHTLY)" = yes || { echo "make fuzz needs a nightly toolchain: rustup toolchain install nightly" >&2; exit 1; }
	@if [ "$$(cargo-fuzz --version 2>/dev/null)" != "cargo-fuzz $(CARGO_FUZZ_VERSION)" ]; then \
	  echo "installing cargo-fuzz $(CARGO_FUZZ_VERSION) (a few minutes, once)"; \
	  $(CARGO) install cargo-fuzz --version $(CARGO_FUZZ_VERSION) --locked; \
	fi

# Runs every target for $(1) seconds; fails on the first crash, leak or timeout.
define run-fuzz
	cd fuzz && $(CARGO) +nightly fuzz build -O
	@cd fuzz && for t in $(FUZZ_TARGETS); do \
	  mkdir -p corpus/$$t; \
	  echo "fuzz $$t: $(1) s"; \
	  $(CARGO) +nightly fuzz run -O $$t corpus/$$t seeds/$$t -- -max_total_time=$(1) $(FUZZ_FLAGS) \
	    2>&1 | grep -E '^#[0-9]+[[:space:]]+DONE|^stat::(number_of_executed_units|peak_rss_mb)|ERROR|panicked|SUMMARY|Test unit written' \
	    || { echo "fuzz $$t failed: the crashing input is in fuzz/artifacts/$$t" >&2; exit 1; }; \
	done
endef

fuzz: fuzz-tools
	$(call run-fuzz,$(FUZZ_SECONDS))

# The same, counting CPU time rather than wall time (for a machine shared with other work).
fuzz-cpu: fuzz-tools
	scripts/fuzz-cpu.sh $(FUZZ_SECONDS)

# The short run make test includes: skipped, with a message, without nightly.
fuzz-ci:
	@if [ "$(HAVE_NIGHTLY)" != yes ]; then \
	  echo "fuzz: skipped (no nightly toolchain; rustup toolchain install nightly to run the fuzz targets)"; \
	else \
	  $(MAKE) --no-print-directory fuzz FUZZ_SECONDS=$(FUZZ_CI_SECONDS); \
	fi
