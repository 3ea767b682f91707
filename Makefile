# plc_cell: two commands on a fresh Debian 12 machine.
#   make demo   install what is missing, build, launch the simulated demo cell
#   make test   install, build, run every test; ends with "N passed, N failed"
#   make build  install and build only;  make bench  run the benchmarks
SHELL := /bin/bash
.SHELLFLAGS := -eo pipefail -c

BUILD   ?= .build
WS      := $(BUILD)/ws
JOBS    ?= 2
PY      := /usr/bin/python3
CMAKE_ARGS := -DPYTHON_EXECUTABLE=$(PY) -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON

DEB_PACKAGES := build-essential cmake pkg-config python3 \
  ros-core-dev libroscpp-dev libstd-msgs-dev libsensor-msgs-dev libstd-srvs-dev \
  libdiagnostic-updater-dev libdiagnostic-msgs-dev libactionlib-dev ros-message-generation \
  catkin python3-catkin-pkg python3-rostest python3-rosbag python3-rospy python3-rostopic \
  python3-rosservice python3-roslaunch python3-rosnode python3-rosmsg \
  libyaml-cpp-dev googletest libgtest-dev libgmock-dev libbenchmark-dev \
  libmodbus-dev socat mbpoll python3-pymodbus python3-matplotlib \
  clang libclang-rt-14-dev zlib1g-dev \
  python3-std-msgs python3-sensor-msgs python3-std-srvs python3-diagnostic-msgs python3-actionlib-msgs python3-actionlib python3-serial rosbash

# ROS 1 from Debian runs on Debian's python3; a pyenv python3 earlier on PATH lacks rospy.
export PATH := /usr/bin:$(PATH)

SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: all deps build test demo bench clean fuzz soak

all: build

deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "== installing Debian packages:$$missing"; \
	  $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get update -qq; \
	  $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing < /dev/null; \
	fi

# The workspace lives inside the package, in a hidden folder: roslaunch and rosrun
# skip hidden folders when they search the package, so they find each file once.
$(WS)/src/plc_cell:
	mkdir -p $(WS)/src
	ln -sfn ../../.. $(WS)/src/plc_cell

build: deps $(WS)/src/plc_cell
	cd $(WS) && catkin_make -j$(JOBS) $(CMAKE_ARGS) all tests 2>&1 | grep -v -E '^-- (Using|Found|Looking|Detecting|Check|Performing|Configuring done|Generating done)' ; exit $${PIPESTATUS[0]}

test: build
	$(PY) scripts/run_tests.py --workspace $(WS) --jobs $(JOBS)

demo: build
	@echo "== starting the demo cell. In another shell:"
	@echo "     source $(WS)/devel/setup.bash"
	@echo "     rostopic list"
	@echo "     rostopic echo /plc_node/signals/conveyor_run"
	@echo "     rostopic echo /plc_node/io"
	@echo "     rosservice call /plc_node/read R0 1"
	@echo "   Ctrl-C stops it."
	source $(WS)/devel/setup.bash && roslaunch plc_cell cell_sim.launch

bench: build
	$(PY) scripts/run_bench.py --workspace $(WS)

# Longer fuzzing (FUZZ_TIME seconds per target, default 60); new inputs land in $(BUILD)/fuzz-corpus.
FUZZ_TIME ?= 60
fuzz: build
	@for t in fatek_decoder:fatek il_parser:il address:address config:config motion_table:motion cell:cell; do \
	  n=$${t%%:*}; c=$${t##*:}; mkdir -p $(BUILD)/fuzz-corpus/$$c; \
	  echo "== fuzz_$$n for $(FUZZ_TIME) s"; \
	  $(WS)/build/plc_cell/fuzz/fuzz_$$n -max_total_time=$(FUZZ_TIME) -max_len=512 -timeout=20 \
	    -artifact_prefix=$(BUILD)/fuzz-corpus/ $(BUILD)/fuzz-corpus/$$c test/fuzz/corpus/$$c || exit 1; \
	done

# Soak: plc_cell run hammered by FATEK and Modbus clients with faults for SOAK_TIME s (default 60).
SOAK_TIME ?= 60
soak: build
	$(WS)/devel/lib/plc_cell/plc_cell_soak $(SOAK_TIME)

clean:
	rm -rf $(BUILD)
