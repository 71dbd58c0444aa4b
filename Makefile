# Set-up front door. `make demo` and `make test` install missing Debian packages, build and run.
PRESET   ?= release
BUILDDIR := build/$(PRESET)
JOBS     ?= $(shell nproc)
SUDO     := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
export XDG_RUNTIME_DIR ?= /tmp/penumbra-xdg-$(shell id -u)

# Debian 12 packages the build, the tests and the tools need (design.md §3).
PACKAGES := cmake g++ make pkg-config glslc libvulkan-dev mesa-vulkan-drivers \
    vulkan-validationlayers libglm-dev libstb-dev libcli11-dev nlohmann-json3-dev libfmt-dev \
    libgtest-dev libbenchmark-dev libembree-dev libtbb-dev libtinygltf-dev chromium

.PHONY: deps build test demo bench clean format

deps:
	@missing=$$(for p in $(PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null \
	    | grep -q 'install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	    echo "penumbra: installing missing packages:" $$missing; \
	    $(SUDO) apt-get update -qq && \
	    DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	fi

build: deps
	@mkdir -p $(XDG_RUNTIME_DIR) && chmod 700 $(XDG_RUNTIME_DIR)
	cmake --preset $(PRESET) >/dev/null
	cmake --build --preset $(PRESET) -j $(JOBS)

test: build
	ctest --preset $(PRESET) -j $(JOBS)

demo: build
	$(BUILDDIR)/apps/penumbra/penumbra compare builtin:showcase -o out/showcase

bench: build
	$(BUILDDIR)/bench/penumbra_bench_gltf

format:
	git ls-files '*.cpp' '*.h' | xargs clang-format -i

clean:
	rm -rf build
