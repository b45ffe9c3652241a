# The two commands of the README, and a few more for development.
#   make run    install what is missing, build, and run the main job
#   make test   install what is missing, build, and run every test
PRESET ?= release
BUILD := build/$(PRESET)

.PHONY: run test deps configure build package bench asan sanitize fuzz clean

deps:
	@scripts/install-deps.sh

configure: deps
	@if [ ! -f $(BUILD)/build.ninja ]; then cmake --preset $(PRESET); fi

build: configure
	cmake --build --preset $(PRESET)

run: build
	scripts/run.sh $(BUILD)

test: build
	ctest --preset $(PRESET)

# The Debian packages (umf-provider, umf-requester, umf-field) in
# $(BUILD)/packages: README.md, "Install".
package: build
	cmake --build --preset $(PRESET) --target package

# Benchmarks write their numbers to docs/BENCHMARKS.md by hand: see that file.
bench: build
	scripts/bench-generator.sh $(BUILD)

asan:
	$(MAKE) test PRESET=asan

# clang with ASan, UBSan and libFuzzer (the fuzz preset, tests/fuzz): what CI
# runs after `make test`, the sanitizer test subset and each fuzz target for
# 30 s; `make fuzz` runs each target longer (FUZZ_SECONDS a target).
FUZZ_SECONDS ?= 300
sanitize: deps
	scripts/ci-sanitizers.sh

fuzz: deps
	scripts/fuzz.sh $(FUZZ_SECONDS)

clean:
	rm -rf build
