# Thin wrapper over CMake. `make demo` and `make test` are the two commands the README promises.
BUILD_DIR ?= build
JOBS ?= 2

.PHONY: deps build demo test bench report clean sanitize-build test-sanitize fuzz

deps:
	./scripts/install-deps.sh

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD_DIR) -j$(JOBS)

demo: build
	./$(BUILD_DIR)/moreau run scenes/showcase.json --out out/showcase
	@echo
	@echo "Output written to out/showcase/"
	@echo "Play it in a browser:  ./$(BUILD_DIR)/moreau view out/showcase"
	@echo "Open it in ParaView:   paraview out/showcase/showcase.pvd"
	@echo "Probe time series:     out/showcase/probes.csv    Run summary: out/showcase/run.json"

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

bench: build
	./$(BUILD_DIR)/bench/moreau_bench

# The validation report (docs/report/index.html and report.md): every case of report/cases/ run
# whole against its reference, with plots. `make test` runs its fast subset.
report: build
	/usr/bin/python3 -B report/make_report.py --moreau ./$(BUILD_DIR)/moreau --out docs/report --readme README.md

# AddressSanitizer + UndefinedBehaviorSanitizer build (clang) of the engine, its tests and the
# libFuzzer targets, in $(SANITIZE_DIR). test-sanitize runs every test but the slow ones listed in
# tests/sanitize-skip.txt (those that take 3 s or more in the Release build), or only the tests of
# the folders in SANITIZE_TEST_DIRS (e.g. "app;run", as CI does); fuzz fuzzes each target for
# FUZZ_SECONDS (scripts/fuzz.sh). The build is a unity build (several sources per compiler run):
# a clean build, the usual case here, takes about half the time. It leaves out the PETSc plugin
# (whose MPI library keeps memory to the end of the process, which LeakSanitizer would report) and
# so the tests of the PETSc solvers.
SANITIZE_DIR ?= build-sanitize
FUZZ_SECONDS ?= 60
SANITIZE_ENV = ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
               UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

SANITIZE_TEST_DIRS ?=

sanitize-build: deps
	cmake -S . -B $(SANITIZE_DIR) -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release -DMOREAU_SANITIZE=ON \
	  -DMOREAU_BUILD_BENCHMARKS=OFF -DMOREAU_BUILD_PYTHON=OFF -DMOREAU_BUILD_VIEWER=OFF -DMOREAU_BUILD_PETSC=OFF -DMOREAU_TEST_DIRS="$(SANITIZE_TEST_DIRS)" \
	  -DCMAKE_UNITY_BUILD=ON
	cmake --build $(SANITIZE_DIR) -j$(JOBS)

test-sanitize: sanitize-build
	$(SANITIZE_ENV) ./scripts/test-sanitize.sh $(SANITIZE_DIR)

fuzz: sanitize-build
	$(SANITIZE_ENV) ./scripts/fuzz.sh $(SANITIZE_DIR) $(FUZZ_SECONDS)

clean:
	rm -rf $(BUILD_DIR)
