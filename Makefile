# plc_cell: two commands on a fresh Debian 12 machine.
#   make demo   install and build what the demo runs, launch the simulated demo cell
#               (LINE=1: the example line of three cells with one monitor)
#   make test   install, build, run every test; ends with "N passed, N failed"
#   make build  install and build only;  make bench  run the benchmarks
SHELL := /bin/bash
.SHELLFLAGS := -eo pipefail -c

BUILD   ?= .build
WS      := $(BUILD)/ws
JOBS    ?= 2
# The tests wait on masters, browsers and processes most of their time: four at a time keep
# two cores busy (docs/testing.md, "How the suite runs").
TEST_JOBS ?= 4
PY      := /usr/bin/python3
CMAKE_ARGS := -DPYTHON_EXECUTABLE=$(PY) -DCMAKE_BUILD_TYPE=Release

# The Debian packages behind every key of package.xml, through rosdep/bookworm.yaml
# (test/packaging/test_dependencies.py fails when they disagree). Written out here because a
# fresh machine has no Python to resolve them before this list is installed. DEMO_PACKAGES
# are the package's build and run keys, all `make demo` installs; PLOT_PACKAGES the run key
# of the plot scripts (scripts/plot_*.py: matplotlib brings scipy and a compiler of its own,
# a minute of apt the demo does without); TEST_PACKAGES the test keys (compilers for the
# sanitizer and fuzz builds, a browser, test servers). `make test`, `make build`,
# `make bench` and `make fuzz` install all three.
DEMO_PACKAGES := build-essential cmake pkg-config python3 catkin python3-catkin-pkg \
  ros-message-generation ros-message-runtime \
  libroscpp-dev python3-rospy ros-std-msgs libstd-msgs-dev python3-std-msgs \
  ros-std-srvs libstd-srvs-dev python3-std-srvs ros-sensor-msgs libsensor-msgs-dev python3-sensor-msgs \
  ros-diagnostic-msgs libdiagnostic-msgs-dev python3-diagnostic-msgs libdiagnostic-updater-dev \
  libnodeletlib-dev libnodeletlib-tools python3-nodelet pluginlib-dev \
  libactionlib-dev python3-actionlib ros-actionlib-msgs libactionlib-msgs-dev python3-actionlib-msgs \
  ros-rosgraph-msgs libros-rosgraph-msgs-dev python3-rosgraph-msgs \
  python3-rosmaster rosout python3-roslaunch python3-rosbag \
  python3-rostopic python3-rosservice python3-rosnode python3-rosmsg rosbash \
  libyaml-cpp-dev libmodbus-dev zlib1g-dev libasmjit-dev libboost-dev nlohmann-json3-dev libjs-dygraphs libjs-codemirror curl
PLOT_PACKAGES := python3-matplotlib
TEST_PACKAGES := librostest-dev python3-rostest \
  googletest libgtest-dev libgmock-dev libbenchmark-dev clang libclang-rt-14-dev llvm \
  socat mbpoll python3-pymodbus python3-serial python3-serial-asyncio python3-pytest git \
  chromium-headless-shell chromium-driver python3-selenium universal-ctags
DEB_PACKAGES := $(DEMO_PACKAGES) $(PLOT_PACKAGES) $(TEST_PACKAGES)

# ROS 1 from Debian runs on Debian's python3; a pyenv python3 earlier on PATH lacks rospy.
export PATH := /usr/bin:$(PATH)

SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: all deps deps-demo ws-src build demo-build test test-fresh demo-fresh demo bench clean fuzz soak

all: build

# One dpkg-query for the whole list: on a built machine this check takes well under a second.
# The phases of make test say how long they took (scripts/phase.sh: "== phase NAME: N s, N CPU s").
PHASE := scripts/phase.sh
define install_missing
@missing=$$( { dpkg-query -W -f='$${Package} $${Status}\n' $(1) 2>/dev/null || true; } \
  | awk '$$NF == "installed" {ok[$$1] = 1} END {n = split("$(1)", p, " "); \
         for (i = 1; i <= n; i++) if (!(p[i] in ok)) printf " %s", p[i]}'); \
if [ -n "$$missing" ]; then \
  echo "== installing Debian packages:$$missing"; \
  $(PHASE) apt "$(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get update -qq && \
    $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing < /dev/null"; \
fi
endef

deps:
	$(call install_missing,$(DEB_PACKAGES))

deps-demo:
	$(call install_missing,$(DEMO_PACKAGES))

# The workspace lives inside the package, in a hidden folder. Its src/plc_cell is a folder
# of links to the package's visible entries, not one link to the package: a link back to
# the package would put the workspace inside itself, a loop that rosrun's `find -L` walks
# into and warns about. Entries the package gains or loses are linked or unlinked at each
# build; `build` is the workspace copy's own (the tool's link for PATH, cmake/env-hooks).
ws-src:
	@mkdir -p $(WS)/src
	@if [ -L $(WS)/src/plc_cell ]; then rm $(WS)/src/plc_cell; fi
	@mkdir -p $(WS)/src/plc_cell
	@for f in *; do case $$f in build|devel|install|logs) continue;; esac; \
	  [ -e $(WS)/src/plc_cell/$$f ] || ln -sfn "$$(realpath -s --relative-to=$(WS)/src/plc_cell $$f)" $(WS)/src/plc_cell/$$f; \
	done
	@find $(WS)/src/plc_cell -maxdepth 1 -xtype l -delete

# Everything a catkin pass reads. make demo runs catkin only when one of these is newer
# than the last build, so a built tree starts the demo in seconds.
SOURCES := $(shell find CMakeLists.txt package.xml src include msg srv action cmake test bench scripts \
  -type f -not -name '*.pyc' 2>/dev/null)
BUILT      := $(WS)/.built
DEMO_BUILT := $(WS)/.built-demo
CATKIN_FILTER := { grep -v -E "^-- (Using|Found|Looking|Detecting|Check|Performing|Configuring done|Generating done)" || true; }

# In three phases, each timed: the product (the libraries, nodes and tool, in unity batches),
# the clang fuzz builds (ASan+UBSan and TSan sub-builds of the library sources, test/fuzz)
# and the test executables.
CATKIN := cd $(WS) && catkin_make -j$(JOBS) $(CMAKE_ARGS) -DCATKIN_ENABLE_TESTING=ON
build: deps ws-src
	@$(PHASE) "build: product" '$(CATKIN) all 2>&1 | $(CATKIN_FILTER)'
	@$(PHASE) "build: fuzzers" '$(CATKIN) plc_cell_fuzzers 2>&1 | $(CATKIN_FILTER)'
	@$(PHASE) "build: tests" '$(CATKIN) tests 2>&1 | $(CATKIN_FILTER)'
	touch $(BUILT) $(DEMO_BUILT)

$(BUILT): $(SOURCES)
	$(MAKE) --no-print-directory build

# What the demo runs and what a user types at it, nothing more: the messages in C++ (for the
# nodes) and Python (for rostopic; not Lisp, EusLisp or JavaScript, a Python start-up per
# message each), plc_node and the plc_cell tool. The tests, benchmarks and the
# sanitizer and fuzz builds wait for `make test`, `make bench` and `make fuzz`. A tree never
# configured is configured without the tests (their packages are not installed yet); one
# configured with them keeps them, so switching between demo and test runs no second cmake.
DEMO_TARGETS := plc_cell_generate_messages_cpp plc_cell_generate_messages_py plc_node plc_cell_tool
demo-build: deps-demo ws-src
	cd $(WS) && testing=OFF && if grep -qs '^CATKIN_ENABLE_TESTING:BOOL=ON' build/CMakeCache.txt; then testing=ON; fi && \
	catkin_make -j$(JOBS) $(CMAKE_ARGS) -DCATKIN_ENABLE_TESTING=$$testing $(DEMO_TARGETS) 2>&1 | $(CATKIN_FILTER) ; exit $${PIPESTATUS[0]}
	touch $(DEMO_BUILT)

$(DEMO_BUILT): $(SOURCES)
	$(MAKE) --no-print-directory demo-build

test: build
	@$(PHASE) "tests" '$(PY) scripts/run_tests.py --workspace $(WS) --jobs $(TEST_JOBS)'


# The demo runs on loopback: ROS_HOSTNAME=localhost unless ROS_HOSTNAME or ROS_IP is set,
# and a hint instead of roslaunch's stack trace when the master could not reach itself
# (scripts/ros_loopback.py).
# The browser monitor of the demo cell listens on MONITOR (loopback; `make demo MONITOR=127.0.0.1:9090`
# when 8080 is taken), its pages may write and force MONITOR_WRITABLE (docs/monitor.md): all, so
# that RUN/STOP works too, as the demo is a simulated cell on loopback.
MONITOR ?= 127.0.0.1:8080
MONITOR_WRITABLE ?= all
# Its pages may change the running program through the cell's gate (the Edit tab,
# docs/online-change.md): true with writable all; `make demo MONITOR_EDIT=false` turns it off.
MONITOR_EDIT ?= true
# `make demo LINE=1`: the example line of three cells (examples/line/) in real time instead,
# with one monitor for all of them on MONITOR (docs/lines.md, "One monitor"); no ROS.
LINE ?=
ifneq ($(LINE),)
demo: deps-demo $(DEMO_BUILT)
	@echo "== starting the example line (examples/line/line.line.yaml). Its monitor: http://$(MONITOR)/ (open it in a browser)" && \
	echo "   Ctrl-C stops it." && \
	source $(WS)/devel/setup.bash && plc_cell run --line examples/line/line.line.yaml --http-tcp $(MONITOR) --http-writable $(MONITOR_WRITABLE)
else
demo: deps-demo $(DEMO_BUILT)
	@ros_env=$$($(PY) scripts/ros_loopback.py) && eval "$$ros_env" && \
	echo "== starting the demo cell. The monitor: http://$(MONITOR)/ (open it in a browser)" && \
	echo "   In another shell:" && \
	echo "     source $(WS)/devel/setup.bash" && \
	if [ -n "$$ros_env" ]; then echo "     $$ros_env"; fi && \
	echo "     rostopic list" && \
	echo "     rostopic echo /plc_node/signals/conveyor_run" && \
	echo "     rostopic echo /plc_node/io_words" && \
	echo "     rosservice call /plc_node/read R0 1" && \
	echo "   Ctrl-C stops it." && \
	source $(WS)/devel/setup.bash && roslaunch plc_cell cell_sim.launch http_tcp:=$(MONITOR) http_writable:=$(MONITOR_WRITABLE) http_edit:=$(MONITOR_EDIT)
endif

# The whole suite in a throwaway Debian 12 root: proves `make test` on a machine with nothing
# installed by hand (scripts/test_fresh.sh; root only). CI runs this.
test-fresh:
	scripts/test_fresh.sh

# The first `make demo` there, timed until the demo's topics are up (scripts/test_fresh.sh).
demo-fresh:
	scripts/test_fresh.sh demo

bench: build
	$(PY) scripts/run_bench.py --workspace $(WS)

# Longer fuzzing (FUZZ_TIME seconds per target, default 60); new inputs land in $(BUILD)/fuzz-corpus.
# The whole-cell target runs without libFuzzer's entropic schedule: its feature bookkeeping
# cost as much as the cells themselves (docs/testing.md).
FUZZ_TIME ?= 60
fuzz: build
	@for t in fatek_decoder:fatek il_parser:il address:address config:config motion_table:motion \
	    modbus_handler:modbus fatek_slave_live:fatek modbus_handler_tsan:modbus fatek_slave_live_tsan:fatek \
	    tri_slave_live:tri tri_slave_live_tsan:tri tri_codec:tri_codec cell:cell native_lockstep:native_lockstep; do \
	  n=$${t%%:*}; c=$${t##*:}; mkdir -p $(BUILD)/fuzz-corpus/$$c; \
	  ml=512; opts=; [ $$n != cell ] || { ml=8192; opts=-entropic=0; }; [ $$n != native_lockstep ] || ml=4096; \
	  echo "== fuzz_$$n for $(FUZZ_TIME) s"; \
	  $(WS)/build/plc_cell/fuzz/fuzz_$$n -max_total_time=$(FUZZ_TIME) -max_len=$$ml $$opts -timeout=20 \
	    -artifact_prefix=$(BUILD)/fuzz-corpus/ $(BUILD)/fuzz-corpus/$$c test/fuzz/corpus/$$c || exit 1; \
	done

# Soak: plc_cell run hammered by FATEK and Modbus clients with faults for SOAK_TIME s (default 60).
SOAK_TIME ?= 60
soak: build
	$(WS)/devel/lib/plc_cell/plc_cell_soak $(SOAK_TIME)

clean:
	rm -rf $(BUILD) build
