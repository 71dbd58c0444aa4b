# Set-up front door. `make demo` and `make test` install missing Debian packages, build and run.
PRESET   ?= release
BUILDDIR := build/$(PRESET)
JOBS     ?= $(shell nproc)
SUDO     := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
export XDG_RUNTIME_DIR ?= /tmp/penumbra-xdg-$(shell id -u)

# Debian 12 packages the build, the tests and the tools need (Debian 12 packages only: no vendored source, no downloads).
PACKAGES := cmake g++ make pkg-config glslc libvulkan-dev mesa-vulkan-drivers \
    vulkan-validationlayers libglm-dev libstb-dev libcli11-dev nlohmann-json3-dev libfmt-dev \
    libgtest-dev libbenchmark-dev libembree-dev libtbb-dev libtinygltf-dev chromium \
    clang libclang-rt-14-dev python3 libglfw3-dev libimgui-dev xvfb xauth \
    libdraco-dev libmeshoptimizer-dev libopenexr-dev pybind11-dev python3-dev python3-numpy \
    python3-pytest libtomlplusplus-dev slurm-wlm munge python3-yaml
# What `make python`'s example plots with, beyond the module's own needs.
PYTHON_PACKAGES := python3-matplotlib

# The glTF loader's libFuzzer target (clang, ASan + UBSan: the asan preset). `make fuzz` runs it
# for FUZZ_SECONDS (0: until interrupted); `make test` runs it for 60 s. New inputs accumulate in
# fuzz-work; findings (crash, leak, timeout, out-of-memory, sanitizer report) go to fuzz-crashes
# and fail the run. Replay one: build/asan/fuzz/penumbra_fuzz_gltf build/asan/fuzz-crashes/FILE
FUZZ_SECONDS ?= 600
FUZZ_DIR     := build/asan
FUZZ_ENV     := ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1 \
                UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
FUZZ_FLAGS   := -timeout=30 -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len=65536 \
                -dict=fuzz/gltf.dict -print_final_stats=1 -artifact_prefix=$(FUZZ_DIR)/fuzz-crashes/

.PHONY: regenerate baselines coupling quality deps build test demo bench clean format fuzz fuzz-smoke fuzz-build mutation-test soak renderdiff renderdiff-store faults faults-asan fuzz-cli cli-docs python slurm-test

deps:
	@missing=$$(for p in $(PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null \
	    | grep -q 'install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	    echo "penumbra: installing missing packages:" $$missing; \
	    tools/timed.sh "the missing packages installed" sh -c '$(SUDO) apt-get update -qq && \
	    DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends "$$@"' \
	    sh $$missing; \
	fi

# The Python module for the current user's /usr/bin/python3: `make build` and `make demo` leave
# `import penumbra` working (docs/python.md).
define install_python_module
	@site=$$(/usr/bin/python3 -m site --user-site) && mkdir -p "$$site" && \
	    cp $(BUILDDIR)/python/penumbra.*.so $(BUILDDIR)/python/penumbra.pyi "$$site"/ && \
	    echo "penumbra: import penumbra works in /usr/bin/python3 (the module is in $$site)"
endef

build: deps
	@mkdir -p $(XDG_RUNTIME_DIR) && chmod 700 $(XDG_RUNTIME_DIR)
	cmake --preset $(PRESET) >/dev/null
	@tools/timed.sh "everything built (the CLI, the viewer, the Python module, the tests)" \
	    cmake --build --preset $(PRESET) -j $(JOBS)
	$(install_python_module)

test: build
	ctest --preset $(PRESET) -j $(JOBS)
	$(MAKE) --no-print-directory fuzz-smoke
	$(MAKE) --no-print-directory slurm-test

# The sweep on a real one-node Slurm cluster (slurm-wlm and munge, as root, a private
# configuration in a temporary directory, every daemon stopped on exit): bench/plans/smoke.toml
# as a 3-task job array against the same plan run locally, about a minute (docs/sweep.md).
slurm-test: build
	tests/cluster/slurm_test.sh $(BUILDDIR)/apps/penumbra/penumbra bench/plans/smoke.toml 3

fuzz-build: deps
	cmake --preset asan >/dev/null
	cmake --build --preset asan -j $(JOBS) --target penumbra_fuzz_gltf penumbra_make_seed_corpus
	rm -rf $(FUZZ_DIR)/fuzz-corpus
	$(FUZZ_DIR)/fuzz/penumbra_make_seed_corpus $(FUZZ_DIR)/fuzz-corpus
	mkdir -p $(FUZZ_DIR)/fuzz-work $(FUZZ_DIR)/fuzz-crashes

fuzz: fuzz-build
	$(FUZZ_ENV) $(FUZZ_DIR)/fuzz/penumbra_fuzz_gltf $(FUZZ_FLAGS) -max_total_time=$(FUZZ_SECONDS) \
	    $(FUZZ_DIR)/fuzz-work $(FUZZ_DIR)/fuzz-corpus

# The 60 s run of `make test`, quiet unless it fails (the whole log stays in fuzz-smoke.log).
fuzz-smoke:
	@mkdir -p $(FUZZ_DIR) && echo "fuzz-smoke: the glTF loader for 60 s ($(FUZZ_DIR)/fuzz-smoke.log)"
	@$(MAKE) --no-print-directory fuzz FUZZ_SECONDS=60 >$(FUZZ_DIR)/fuzz-smoke.log 2>&1 \
	    && grep -E '^#[0-9]+.*DONE|^stat::' $(FUZZ_DIR)/fuzz-smoke.log \
	    || { tail -n 100 $(FUZZ_DIR)/fuzz-smoke.log; \
	         echo "fuzz-smoke: FAILED; inputs in $(FUZZ_DIR)/fuzz-crashes/"; exit 1; }

# The soak: one SceneRenderer through SOAK_FRAMES frames with the technique, sizes, camera and
# lights changing every three; device memory and the host heap must stay flat after the first
# cycle, with the validation layer on (`make test` runs three cycles of it).
SOAK_FRAMES ?= 10000
soak: build
	PENUMBRA_SOAK_FRAMES=$(SOAK_FRAMES) build/$(PRESET)/tests/penumbra_gpu_tests \
	    --gtest_filter=FrameTest.ChangingEveryFewFramesKeepsMemoryFlat

# The fault sweep at every injection point (`make test` strides over object creations), and the
# same under AddressSanitizer's leak checker (build/asan): each failure one error line, no
# output, no leak. Each takes about half an hour on 2 cores.
faults: build
	PENUMBRA_FAULT_EVERY_POINT=1 ctest --preset $(PRESET) -j $(JOBS) -R 'CliFaults\.'

faults-asan: deps
	cmake --preset asan >/dev/null
	cmake --build --preset asan -j $(JOBS) --target penumbra penumbra_cli_tests
	cc -shared -fPIC -o build/asan/keep_libraries_loaded.so tests/keep_libraries_loaded.c
	LD_PRELOAD=$(CURDIR)/build/asan/keep_libraries_loaded.so ASAN_OPTIONS=detect_leaks=1 \
	    LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp PENUMBRA_FAULT_EVERY_POINT=1 \
	    build/asan/tests/penumbra_cli_tests --gtest_filter='CliFaults.*'

# The CLI's parameter space fuzzed (tools/fuzz_cli.py): random commands and --set values, each a
# clean refusal or a render; findings in build/fuzz-cli/findings.txt.
FUZZ_CLI_SECONDS ?= 600
fuzz-cli: build
	python3 tools/fuzz_cli.py --seconds $(FUZZ_CLI_SECONDS) --jobs $(JOBS) --out build/fuzz-cli

# The Python module (which `make build` installs for the current user) and what its example
# plots with (docs/python.md).
python: build
	@$(MAKE) --no-print-directory deps PACKAGES="$(PYTHON_PACKAGES)"

# docs/cli.md's option tables refreshed from the CLI's own definitions (the build makes the page in
# build/$(PRESET)/docs; CliDocs.UpToDate fails until it is copied here).
cli-docs: build
	cp build/$(PRESET)/docs/cli.md docs/cli.md

# What a new technique or parameter changes that is generated: docs/cli.md and the stored
# compare rows (docs/architecture.md, "Adding a technique").
regenerate: cli-docs baselines

# Cross-device image agreement (tests/test_render_diff.cpp): every comparison row against the
# images stored in tests/renderdiff/, on whichever device the suite picks. renderdiff-store
# rewrites them (on lavapipe, after a deliberate change to what a technique draws).
renderdiff: build
	build/$(PRESET)/tests/penumbra_gpu_tests --gtest_filter='RenderDiffTest.*'

renderdiff-store: build
	PENUMBRA_RENDERDIFF_STORE=1 build/$(PRESET)/tests/penumbra_gpu_tests \
	    --gtest_filter='RenderDiffTest.*'

# Stored figures afresh (docs/testing.md, "Baselines"): runs the tests that own them, prints
# every figure that moved (build/baselines/diff.md) and stores them in tests/baselines unless one
# got worse and tests/accepted_regressions.toml does not name it.
baselines: build
	/usr/bin/python3 tools/baselines.py store --tests build/$(PRESET)/tests/penumbra_gpu_tests

# The corpus gate (docs/testing.md, "The corpus gate"): every generated family at the plan's
# seeds (or SEEDS=1,2,...), every technique at its defaults, against the truth; writes
# build/quality/quality.md and .json and fails naming each figure past bench/plans/quality.toml's
# bounds. FAMILIES=a,b runs a few families.
SEEDS ?=
FAMILIES ?=
quality: build
	python3 tools/quality.py --penumbra build/$(PRESET)/apps/penumbra/penumbra --jobs 1 \
	    $(if $(SEEDS),--seeds $(SEEDS)) $(if $(FAMILIES),--families $(FAMILIES))

# Plants each mutation of tests/mutations/*.toml in a scratch copy (build/mutation/tree), rebuilds,
# runs the ctest labels that can see it and reports the survivors (docs/testing.md). Not part of
# `make test`. MUTATIONS=id,id runs a few; MUTATION_LABEL=filters those of one area.
# RANDOM=N plants N mutants nobody chose instead, drawn by tools/random_mutants.py in the lines
# changed since SINCE (default HEAD~1, the working tree against it) with seed SEED (default 1);
# the report goes to build/mutation/random-report.md; MIN_RATE=85 fails the run below that rate.
MUTATIONS ?=
MUTATION_LABEL ?=
RANDOM ?=
SINCE ?=
SEED ?=
MIN_RATE ?=
# Every line outside src/shadows that names a technique (issue 58 takes them to none).
coupling:
	python3 tools/technique_coupling.py

mutation-test: deps
	python3 tools/mutation_test.py --jobs $(JOBS) $(if $(MUTATIONS),--only $(MUTATIONS)) \
	    $(if $(MUTATION_LABEL),--label $(MUTATION_LABEL)) $(if $(RANDOM),--random $(RANDOM)) \
	    $(if $(SINCE),--since $(SINCE)) $(if $(SEED),--seed $(SEED)) \
	    $(if $(MIN_RATE),--min-rate $(MIN_RATE))

# Only what the demo needs: the CLI and the Python module, not the tests (`make test` builds those).
demo: deps
	@mkdir -p $(XDG_RUNTIME_DIR) && chmod 700 $(XDG_RUNTIME_DIR)
	cmake --preset $(PRESET) >/dev/null
	@tools/timed.sh "the CLI and the Python module built" \
	    cmake --build --preset $(PRESET) -j $(JOBS) --target penumbra penumbra_python
	$(install_python_module)
	@tools/timed.sh "the comparison written (out/demo/report.html)" \
	    $(BUILDDIR)/apps/penumbra/penumbra compare builtin:demo -o out/demo

bench: build
	$(BUILDDIR)/bench/penumbra_bench_gltf
	$(BUILDDIR)/bench/penumbra_bench_frame
	$(BUILDDIR)/bench/penumbra_bench_pages

format:
	git ls-files '*.cpp' '*.h' | xargs clang-format -i

clean:
	rm -rf build
