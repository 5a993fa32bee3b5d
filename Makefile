# Thin wrapper over CMake. `make demo` and `make test` are the two commands the README promises.
BUILD_DIR ?= build
JOBS ?= 2

.PHONY: deps build demo test bench clean

deps:
	./scripts/install-deps.sh

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD_DIR) -j$(JOBS)

demo: build
	./$(BUILD_DIR)/moreau run scenes/showcase.json --out out/showcase
	@echo
	@echo "Output written to out/showcase/"
	@echo "Open it in ParaView:   paraview out/showcase/showcase.pvd"
	@echo "Probe time series:     out/showcase/probes.csv    Run summary: out/showcase/run.json"

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

bench: build
	./$(BUILD_DIR)/bench/moreau_bench

clean:
	rm -rf $(BUILD_DIR)
