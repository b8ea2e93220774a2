# The two commands a new user needs: `make run` and `make test`. Everything else is CMake.
PRESET ?= default
BUILD  := build/$(PRESET)
RANKS  ?= 2
SCENE  ?=
PREFIX ?= $(HOME)/regolith
MPIRUN := OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpiexec --oversubscribe

.PHONY: all deps configure build install run test bench format clean

all: build

deps:
	@bash scripts/install-deps.sh

$(BUILD)/CMakeCache.txt:
	cmake --preset $(PRESET)

configure: deps $(BUILD)/CMakeCache.txt

build: configure
	cmake --build --preset $(PRESET)

# Configured with the prefix, so that programs built against the install find its shared
# modules (PETSc, HDF5, VTK) there.
install: configure
	cmake --preset $(PRESET) -DCMAKE_INSTALL_PREFIX=$(PREFIX)
	cmake --build --preset $(PRESET)
	cmake --install $(BUILD)

run: build
	mkdir -p out
	$(MPIRUN) -n $(RANKS) $(BUILD)/bin/regolith $(SCENE) --output out

test: build
	ctest --preset $(PRESET)

bench: build
	@bash scripts/install-deps.sh --bench
	bash bench/run-all.sh $(BUILD)

format:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	rm -rf build out
