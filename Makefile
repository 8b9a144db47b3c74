# The two commands: `make run` and `make test`. Both install what is missing, then build Release.
PRESET  ?= release
BUILD   := build/$(PRESET)
JOBS    ?= $(shell nproc)
OUT     ?= out

.PHONY: all deps configure build tool run test bench fuzz format clean

all: build

deps:
	@scripts/install-deps

configure: deps
	@cmake --preset $(PRESET) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# Only the tool: the tests, benchmarks and fuzz targets are built by `make test` / `make bench`.
tool: configure
	@cmake --build $(BUILD) -j $(JOBS) --target radiosity_app

run: tool
	@mkdir -p $(OUT)
	@$(BUILD)/radiosity render cornell --method pathtrace --width 256 --height 256 --spp 64 \
		-o $(OUT)/cornell_pathtrace.png --stats $(OUT)/cornell_pathtrace.json
	@$(BUILD)/radiosity render cornell --method pathtrace --width 256 --height 256 --spp 64 \
		-o $(OUT)/cornell_pathtrace.exr --quiet
	@$(BUILD)/radiosity render cornell --method patch --width 256 --height 256 \
		-o $(OUT)/cornell_patch.png --stats $(OUT)/cornell_patch.json
	@$(BUILD)/radiosity render cornell --method voxel --voxels 50000 --sphere-radius 16 \
		--width 256 --height 256 -o $(OUT)/cornell_voxel.png --stats $(OUT)/cornell_voxel.json
	@$(BUILD)/radiosity render cornell-spot --method patch --width 256 --height 256 \
		-o $(OUT)/cornell_spot_patch.png --stats $(OUT)/cornell_spot_patch.json
	@echo "images: $(OUT)/cornell_pathtrace.png, $(OUT)/cornell_patch.png, $(OUT)/cornell_voxel.png,"
	@echo "        $(OUT)/cornell_spot_patch.png (a spot light, patch radiosity)"
	@echo "        (tone mapped), $(OUT)/cornell_pathtrace.exr (linear radiance)"
	@echo "stats:  $(OUT)/cornell_pathtrace.json, $(OUT)/cornell_patch.json, $(OUT)/cornell_voxel.json,"
	@echo "        $(OUT)/cornell_spot_patch.json"

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	@$(BUILD)/radiosity bench all
	@$(BUILD)/radiosity_benchmarks

# Each fuzz target for FUZZ_SECONDS (default 60) on a corpus that grows from run to run.
FUZZ_SECONDS ?= 60
fuzz: build
	@scripts/fuzz $(FUZZ_SECONDS) $(BUILD)

# The files the ctest clang_format checks (scripts/format --check).
format:
	@scripts/format

clean:
	@rm -rf build $(OUT)
