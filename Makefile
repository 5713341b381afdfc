# demcal: the two commands a new user needs are `make demo` and `make test`.
# Both install missing Debian packages first (scripts/install-deps.sh).

BUILD      ?= build
SAN_BUILD  ?= build-sanitize
JOBS       ?= $(shell scripts/cpu_count.sh)
CMAKE_ARGS ?=

.PHONY: all deps configure build test demo bench sanitize clean study calibrate calibration-benchmark fidelity-benchmark yade-study liggghts-study liggghts-peer boundary-calibration uncertainty-benchmark

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS) > $(BUILD).configure.log 2>&1 \
	  || { cat $(BUILD).configure.log; exit 1; }

build: configure
	cmake --build $(BUILD) -j $(JOBS)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

demo: build
	@scripts/demo.sh $(BUILD)

# One study file, every stage a file target under build/studies/NAME (resumable; make -j2 works).
STUDY ?= data/studies/demo.json
study: build
	@scripts/run_study.sh $(STUDY) $(BUILD) $(JOBS)

# One scene and its targets, no study file (docs/explanation/calibration_method.md); resumable, exit 0 met, 3 unreachable, 4 budget:
#   make calibrate SCENE=data/scenes/ucs_rock_cb.json TARGETS="sigma_u_MPa=48 E_GPa=6.5 nu=0.27"
#                  [SPACE=...] [FIXED="R_min_m=0.00075 ..."] [TOLERANCE=0.05] [BUDGET=80] [NAME=...]
#                  [STRATEGY=kriging] [CHECK_RESOLUTION=2] [CHECK_TESTS="data/scenes/biaxial_rock_fj.json"]
#                  [CURVES="lab_curve.csv"] [CURVE_WINDOW=0.1:1.0]
#   with the lab's scatter: TARGETS="sigma_u_MPa=200+-22/n=5 ..." or LAB_SPECIMENS=lab.csv, and STRATEGY=bayes
#   [MODEL_DISCREPANCY=0.1]
TOLERANCE ?= 0.05
BUDGET    ?= 80
calibrate: build
	@test -n "$(SCENE)" -a -n "$(TARGETS)$(LAB_SPECIMENS)" || { echo 'make calibrate: give SCENE=... and TARGETS="NAME=VALUE ..." (or LAB_SPECIMENS=FILE.csv)' >&2; exit 2; }
	BIN=$(BUILD)/bin JOBS=$(JOBS) CACHE=$(BUILD)/cache PYTHONPATH=python /usr/bin/python3 -m demcal_study calibrate \
	  --scene $(SCENE) $(foreach t,$(TARGETS),--target $(t)) $(if $(SPACE),--space $(SPACE)) \
	  $(foreach f,$(FIXED),--fixed $(f)) --tolerance $(TOLERANCE) --budget $(BUDGET) $(if $(NAME),--name $(NAME)) \
	  $(if $(STRATEGY),--strategy $(STRATEGY)) $(if $(CHECK_RESOLUTION),--check-resolution $(CHECK_RESOLUTION)) \
	  $(foreach c,$(CHECK_TESTS),--check-test $(c)) $(if $(LAB_SPECIMENS),--lab-specimens $(LAB_SPECIMENS)) \
	  $(foreach c,$(CURVES),--curve $(c)) $(if $(CURVE_WINDOW),--curve-window $(CURVE_WINDOW)) \
	  $(if $(MODEL_DISCREPANCY),--model-discrepancy $(MODEL_DISCREPANCY)) \
	  --out-root $(BUILD)/calibrations

# Hours: every target of data/benchmarks/calibration_targets.json (resumable; ONLY=a,b runs a part; GLOBAL=1 adds
# the old global-surface strategy where marked, KRIGING=1 the kriging strategy there). Summary: $(BUILD)/calibration_benchmark/summary.md.
calibration-benchmark: build
	scripts/calibration_benchmark.py --build $(BUILD) --jobs $(JOBS) $(if $(ONLY),--only $(ONLY)) $(if $(GLOBAL),--global) $(if $(KRIGING),--kriging)

# Viscous boundary coefficients calibrated in the loop by LHS-WCA, WCA, GA, SA and harmony search at equal budgets:
# the wave strip by default (docs/explanation/wave_strip.md), SCENE=data/scenes/rockfill_slope.json for the slope
# (docs/explanation/rockfill_slope.md); BUDGET= and SEEDS= change the runs per optimiser run and the seeds.
# BUDGET given on the command line (or in the environment): calibrate's default of 80 is not this target's.
GIVEN_BUDGET = $(if $(filter-out file default undefined,$(origin BUDGET)),--budget $(BUDGET))
boundary-calibration: build
	scripts/boundary_calibration_comparison.py --build $(BUILD) --jobs $(JOBS) $(if $(SCENE),--scene $(SCENE)) \
	  $(GIVEN_BUDGET) $(if $(SEEDS),--seeds $(SEEDS)) $(if $(FIGURE),--figure $(FIGURE))

# Hours: the Bayesian search on ROCKS (20) synthetic rocks our DEM made at truths drawn from the prior
# (docs/howto/calibrate_with_scatter.md); resumable. Summary: $(BUILD)/uncertainty_benchmark/summary.md.
uncertainty-benchmark: build
	scripts/uncertainty_benchmark.py --build $(BUILD) --jobs $(JOBS) --out $(BUILD)/uncertainty_benchmark \
	  $(if $(ROCKS),--rocks $(ROCKS)) $(GIVEN_BUDGET)

# Our DEM at published PFC2D and PFC3D parameter sets (docs/explanation/fidelity.md); hours, resumable (QUICK=1: the L64 on 16 points, 1 seed).
fidelity-benchmark: build
	scripts/fidelity_benchmark.py --build $(BUILD) --jobs $(JOBS) $(if $(ONLY),--only $(ONLY)) $(if $(QUICK),--quick) $(if $(FIGURE),--figure $(FIGURE))

bench: build
	@scripts/bench.sh $(BUILD)

# The whole chain on YADE's CPM concrete as an external simulator (docs/howto/own_simulator.md); installs Debian's yade on demand.
yade-study: build
	/usr/bin/python3 -c "import sys; sys.path.insert(0, 'scripts'); import debian_package; debian_package.ensure('yade', 'yade', 'make yade-study')"
	@scripts/run_study.sh data/studies/yade_cpm.json $(BUILD) $(JOBS)

# The whole chain on LIGGGHTS' rotating drum as an external simulator (docs/explanation/liggghts_peer.md); installs
# Debian's liggghts on demand.
liggghts-study: build
	/usr/bin/python3 -c "import sys; sys.path.insert(0, 'scripts'); import debian_package; debian_package.ensure('liggghts', 'liggghts', 'make liggghts-study')"
	@scripts/run_study.sh data/studies/liggghts_drum.json $(BUILD) $(JOBS)

# Our drum against LIGGGHTS' on the same scene: angles over SEEDS (5) seeds and cost per particle-step, one thread
# each; time it on a quiet machine. Summary: $(BUILD)/liggghts_peer/summary.md.
liggghts-peer: build
	scripts/liggghts_peer.py --build $(BUILD) --out $(BUILD)/liggghts_peer $(if $(SEEDS),--seeds $(SEEDS))

sanitize: deps
	cmake -S . -B $(SAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDEMCAL_SANITIZE=ON $(CMAKE_ARGS)
	cmake --build $(SAN_BUILD) -j $(JOBS)
	cd $(SAN_BUILD) && ctest --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD) $(SAN_BUILD) $(BUILD).configure.log
