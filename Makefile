# libggx: the two commands of the README, and helpers. Everything real is in CMake.
BUILD ?= build
PREFIX ?= /usr/local
JOBS ?= 2
MAKEFLAGS += --no-print-directory

.PHONY: all deps configure build run example test install clean

all: build

deps:
	@sh cmake/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DGGX_WERROR=ON -DCMAKE_INSTALL_PREFIX=$(PREFIX) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The main job on built-in defaults: the seeds' figures into out/ and a check of every sampler.
run: build
	@./$(BUILD)/ggx demo

# The small C example of the library (D, G1 and the BRDF for a skewed shape).
example: build
	@./$(BUILD)/ggx_example

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

install: build
	@cmake --install $(BUILD)

clean:
	rm -rf $(BUILD)
