# Spiral bevel gear contact analysis toolkit.
# `make validate` and `make test` each work on a fresh machine: both call `make setup` first.

SCENE   ?= reference/scenes/default.toml
OUT     ?= out
CARGO   ?= cargo
RELEASE := --release
BIN     := target/release
# The reference FE LTCA solves every REF_STRIDE-th position of the scene's
# sweep (REF_STRIDE_LW for the lightweight wheel), reduced-level meshes:
# by default all of them (0.5 deg steps, as the white paper); solved
# positions are cached, so a later run reuses them whatever its stride.
# REFERENCE=0 leaves it out of `make validate`.
REFERENCE     ?= 1
REF_STRIDE    ?= 1
REF_STRIDE_LW ?= $(REF_STRIDE)
# The fine reference at the white paper's mesh density (35 x 75 elements per
# flank, `--level reference`), which judges the reduced model in the report:
# every FINE_STRIDE-th position (FINE_STRIDE_LW for the lightweight wheel),
# by default all of them (about 25 min and 16 GB on 2 cores, 5 s per position;
# positions are cached and a killed run resumes). FINE=0 leaves it out.
FINE           ?= 1
FINE_STRIDE    ?= 1
FINE_STRIDE_LW ?= $(FINE_STRIDE)
# The contact formulation's share of the reference's uncertainty: the fine
# reference once more with only the pinion's nodes against the wheel's faces
# (`--contact pinion-slave`, into out/<scene>/reference_reference_pinion_slave),
# every FORMULATION_STRIDE-th position; the report's uncertainty table
# compares it with the two-pass sweep at the same positions. Cached like the
# two-pass sweep; measured cold 2026-11-28 at stride 4 on 2 cores with
# nothing else heavy running: see the README's cost table. FORMULATION=0
# leaves it out (FINE=0 does too).
FORMULATION        ?= 1
FORMULATION_STRIDE ?= 4

# The medium mesh level's sweep (the geometric mean of the reduced and the
# reference level's elements, 20 x 39 on the default scene), so that the
# report gives the reference's own uncertainty from three levels
# (Richardson where monotone): measured 2026-11-27 on 2 cores shared with
# builds, meshing 172 s, the sweep of both blanks 1,321 s (73 + 181
# positions), peak 6.5 GB. MEDIUM=0 leaves it out.
MEDIUM         ?= 1
# The contact laws: seeds 001 and 002's load runs with the Hertz
# impact law and with the FE-analytical contact element, the four scenes
# reference/scenes/seed00{1,2}_{impact,element}.toml (flanks, reduced
# meshes, stiffness files, `solver dynamic`), for the report's "Contact
# laws" section: about 5 min cold on 2 cores shared with other jobs
# (measured: 303 s for the four, of it 181 s meshing, 40 s stiffness files,
# 82 s `solver dynamic`; seed001 element/impact 102/62 s, seed002 57/83 s);
# a later run reuses the meshes and stiffness files and redoes the dynamic
# runs (about 1.5 min). Each scene has its meshes and stiffness files
# under its own name; a scene whose mesh or stiffness file has the same
# inputs as another scene folder's copies that one
# (preprocess/src/sibling_reuse.rs): the element scene of a seed copies its
# impact scene's (same inputs hashes).
# CONTACT_LAWS=0 leaves them out.
CONTACT_LAWS       ?= 1
CONTACT_LAW_SCENES := seed001_impact seed001_element seed001_impact_haversine seed002_impact seed002_element
# The 8-DOF lumped model on seed 004's 23/86 pair and seed 003's 16/27 pair
# (reference/scenes/seed004_lumped.toml, seed003_lumped.toml): flanks,
# reduced meshes (6 x 10 flank elements), stiffness, then `solver lumped`;
# the report's section "Lumped 8-DOF model" reads
# out/<scene>/lumped/summary.json. Measured cold (fresh meshes directory,
# binaries built) on 2 shared cores: seed 004 about 80 s (mesh 61 s,
# stiffness 14 s, lumped 4 s for the design and its 6 ease-off variants of
# the TE-slope and contact-ratio studies, which reuse the design's meshes);
# seed 003 about 30 s (flanks, mesh and stiffness 24 s, lumped 3.5-5.7 s
# for 4 flank grades x 2 loads). The white-paper pair's order map
# (white_paper_lightweight_lumped.toml: the default scene's pair,
# meshes and stiffness files, 6 speeds x 2 wheels): lumped 7 s warm (LTCA
# 0.4 s, 12 runs 0.3-0.8 s each); cold it copies the default scene's
# meshes and stiffness files (same inputs; 4.9 s measured 2026-11-24,
# where meshing and solving them again took about 2 min 45 s).
# LUMPED=0 leaves them out.
LUMPED        ?= 1
LUMPED_SCENES := seed004_lumped seed003_lumped white_paper_lightweight_lumped
# The misalignment sensitivity study on $(SCENE): E, P, G, ΔΣ
# each over the scene's [sensitivity] range (default 9 values, ±0.05 mm,
# ±0.02°) at the scene's loads, from the stiffness files `solve` made; the
# report's section "Misalignment sensitivity" reads
# $(OUT)/<scene>/sensitivity/summary.json. Measured on the default scene
# (2 cores shared with other jobs): 104 s. SENSITIVITY=0 leaves it out.
SENSITIVITY   ?= 1
# The multibody with compliant bearings:
# reference/scenes/white_paper_bearings.toml, the default scene's pair on
# compliant bearings (flanks, reduced meshes, stiffness files, `solver ltca`
# with the bearings' deflection, `solver dynamic` with the compliant runs);
# the report's section "Compliant bearings (multibody)" reads
# out/white_paper_bearings/{ltca,multibody}. Measured warm (meshes and
# stiffness files made; 2 cores shared with other jobs, 2026-11-24, after
# the posed contact path): about 66 s (flanks, mesh and stiffness 0.8 s,
# ltca 47 s, dynamic 18 s, of it 2.7 + 5.2 s the lag shift's contact
# searches). Cold it copies the default scene's meshes and stiffness files
# (same inputs, preprocess/src/sibling_reuse.rs; measured 1.0 s mesh stage +
# 0.5 s stiffness stage, 2026-11-24), which `solve` has made. BEARINGS=0
# leaves it out.
BEARINGS      ?= 1
BEARINGS_SCENE := reference/scenes/white_paper_bearings.toml
# The flexible gearbox: reference/scenes/white_paper_gearbox.toml, the
# pair on compliant bearings with both shafts as Timoshenko beam elements
# with their mass and an FE housing (`preprocess housing`: laid out around
# the gears, meshed, reduced by Craig-Bampton onto the bearing seats;
# `solver dynamic`: the compliant runs on the condensed shafts, then the
# gearbox's loaded modes, order crossings and run-ups of both wheel
# blanks, 0 -> 1,100 rpm in 1.1 s as white_paper_lightweight_runup's, so
# that the order analysis resolves the lightweight wheel's side bands);
# the report's section "Flexible gearbox (multibody)" reads
# out/white_paper_gearbox/multibody. Measured 2026-11-29 with the meshes
# and stiffness files made (copied from the default scene's), nothing
# else running: the housing 75-82 s (0.9 GB; reused afterwards), `solver
# dynamic` 4 min 6 s wall, 3.9 GB; the gearbox run-ups 224,900 and
# 192,437 steps at 79-87 us on 235 coordinates. GEARBOX=0 leaves it out.
GEARBOX       ?= 1
GEARBOX_SCENE := reference/scenes/white_paper_gearbox.toml
# The calibrated variant of the white-paper design
# (reference/scenes/white_paper_calibrated.toml, written with its design
# and record by `make calibrate`): reduced meshes, stiffness files and
# `solver ltca`, for the report's subsection "A calibrated variant".
# Measured 2026-11-27 after `make calibrate` (2 shared cores): mesh 63 s,
# stiffness 32 s, ltca 0.9 s; the pinion and the lightweight wheel are
# copied from the calibration's last web trial (same inputs), the standard
# wheel is meshed and solved. On a fresh machine (no web trials in
# meshes/) all three bodies are meshed and solved: about as long as the
# default scene's reduced meshes and stiffness files (77 + 131 s measured
# 2026-11-27). CALIBRATED=0 leaves it out.
CALIBRATED       ?= 1
CALIBRATED_SCENE := reference/scenes/white_paper_calibrated.toml
# The reduced model at its grid limit: the default design's standard blanks
# on the grid family 12 x 20, 18 x 30 and 24 x 40 (reduced meshes refined
# to the grid, stiffness files), then `validate grid-convergence` runs the
# LTCA on them and on the scene's own files (12 x 40 on its 12 x 20 mesh)
# and extrapolates the family's TE per load to the grid's limit, for the
# report's section "The reduced model at its grid limit". Measured cold on
# 2 cores, 2026-11-28: meshes about 40 + 68 + 58 s, stiffness files about
# 39 + 69 + 148 s, the study 1 s. GRIDS=0 leaves it out.
GRIDS                   ?= 1
GRID_CONVERGENCE_SCENES := reference/scenes/grids/grid12x20.toml reference/scenes/grids/grid18x30.toml reference/scenes/grids/grid24x40.toml

# The white paper's first use case, static against dynamic TE
# (reference/scenes/white_paper_ste_dte.toml): both wheel blanks run up
# from rest to 10 and to 1,000 rpm at 300 N·m, the accelerations ending at
# 30° of pinion rotation, 0.15 s at 1,000 rpm; the report's section
# "Static against dynamic TE" reads out/white_paper_ste_dte/multibody/.
# The lightweight wheel's every tooth is meshed and solved (the run turns
# it 1.12 revolutions). USE_CASES=0 leaves it out.
USE_CASES     ?= 1
STE_DTE_SCENE := reference/scenes/white_paper_ste_dte.toml
# The rattle run (reference/scenes/rattle.toml: both flank pairs across
# the backlash, no load, a 5 % pinion speed ripple, the wheel free): its
# impacts, largest contact forces and wedging (both flank pairs in contact
# at once) for the report's section "Rattle and wedging". Measured cold
# 2026-11-28 with `make test` and `make validate` beside it: meshes 3 min 9 s,
# stiffness files 4 min 18 s (coast flanks too; 2.6 GB), `solver dynamic`
# 5 s. RATTLE=0 leaves it out.
RATTLE       ?= 1
RATTLE_SCENE := reference/scenes/rattle.toml

# The lightweight wheel over its whole revolution:
# reference/scenes/white_paper_lightweight_runup.toml meshes and solves
# every wheel tooth of the lightweight blank (reduced level), runs the
# multibody run-up of both wheel blanks (0 -> 1100 rpm in 1.1 s, 4.7 wheel
# revolutions; `runup_orders.json`) and the 8-DOF order map on the solved
# revolution, then checks the results (the ignored tests of
# validate/tests/lightweight_revolution_data.rs). The report's subsection
# "lightweight wheel over its whole revolution" reads them. Costs: see
# docs/performance.md. Not part of `make validate`. The scene has the
# compliant bearings of white_paper_bearings.toml, so `solver dynamic` also
# runs both wheels' run-ups on them (bearings_runup_orders.json; the cost
# of those runs was not measured on the whole revolution: the run-up's
# 110,000 steps at the 54-85 µs per step measured on white_paper_bearings
# are about 6-10 s per wheel, plus the lag shift over one mesh cycle).
LW_SCENE := reference/scenes/white_paper_lightweight_runup.toml

# A study (docs/studies.md): STUDY's cases and jobs, run on this machine
# (EXECUTOR=local) or submitted to Slurm (EXECUTOR=slurm; then `make
# study-collect` once `study status` shows every job done).
STUDY    ?= reference/studies/small_misalignment.toml
EXECUTOR ?= local
STUDY_WORK ?= $(OUT)/studies

.PHONY: setup build test test-long bench preprocess solve validate calibrate convergence fe-stiffness stress lightweight calculix study study-collect clean

setup:
	@bash scripts/setup.sh

build: setup
	$(CARGO) build $(RELEASE) --workspace --bins

test: setup
	$(CARGO) test $(RELEASE) --workspace
	bash scripts/check_env.sh

# The long tier (CI runs it after `make test`): the test binaries that need
# the `long-tests` feature of preprocess and validate (see their
# Cargo.toml): fresh meshes of every seed pair and the whole chain on them,
# the default pinion at the medium and reference levels, the coast-side FE
# fixture, the reference sweep's shards and cache, runs stopped by
# signals at each phase, the study's local executor (against the
# stages run by hand, a failing job, two studies sharing a design) and
# the same study on a one-node Slurm cluster.
LONG_TESTS_PREPROCESS := seed_pairs mesh_levels signals
LONG_TESTS_VALIDATE   := seed_pairs_chain solver_coast reference_sweep signals
# The study tests run first: they run the programs `make test` built
# (their own build of them is then a no-op; after the other packages'
# `long-tests` builds it would rebuild them).
test-long: setup
	$(CARGO) test $(RELEASE) -p study --features long-tests --test local_study --test slurm_study
	$(CARGO) test $(RELEASE) -p preprocess --features long-tests $(addprefix --test ,$(LONG_TESTS_PREPROCESS))
	$(CARGO) test $(RELEASE) -p validate --features long-tests $(addprefix --test ,$(LONG_TESTS_VALIDATE))

bench: setup build preprocess
	$(CARGO) bench -p preprocess --bench flanks
	$(CARGO) bench -p preprocess --bench mesh
	$(CARGO) bench -p preprocess --bench stiffness
	$(CARGO) bench -p preprocess --bench influence_convergence
	$(CARGO) bench -p solver --bench ltca
	$(CARGO) bench -p solver --bench multibody
	$(CARGO) bench -p solver --bench compliant_multibody
	$(CARGO) bench -p solver --bench lumped
	$(CARGO) bench -p solver --bench sensitivity
	$(CARGO) bench -p validate --bench reference
	$(CARGO) bench -p study --bench job_overhead

# The reference against an independent FE code: example 03's first position
# exported as a CalculiX deck (`validate export-inp`) and solved by CalculiX
# (Debian's calculix-ccx, installed by `make setup`), its loaded TE against
# `validate reference --contact pinion-slave` at 100 and 300 N m (the test
# `calculix_loaded_te_of_example_03_agrees_with_the_pinion_slave_reference`,
# left out of `make test` for its run time: see the README's cost table),
# with CalculiX's surface-to-surface contact; CALCULIX_CONTACT=node-to-surface
# takes its node-to-surface contact (within 1 % plus its facet offset).
calculix: setup
	$(CARGO) test $(RELEASE) -p validate --test calculix_deck -- --ignored --nocapture

preprocess: build
	$(BIN)/preprocess flanks $(SCENE) --out $(OUT)/$(notdir $(basename $(SCENE)))/flanks
	$(BIN)/preprocess mesh $(SCENE) --level reduced --out meshes
	$(BIN)/preprocess stiffness $(SCENE) --meshes meshes

solve: preprocess
	$(BIN)/solver plan $(SCENE) --out $(OUT)/$(notdir $(basename $(SCENE)))/plan
	$(BIN)/solver ltca $(SCENE) --meshes meshes --out $(OUT)
	$(BIN)/solver dynamic $(SCENE) --meshes meshes --out $(OUT)

validate: solve
	@if [ "$(REFERENCE)" = 1 ]; then \
	  $(BIN)/validate reference $(SCENE) --meshes meshes --out $(OUT) \
	    --stride $(REF_STRIDE) --stride-lightweight $(REF_STRIDE_LW) && \
	  $(BIN)/validate tradeoff $(SCENE) --meshes meshes --out $(OUT); fi
	@if [ "$(MEDIUM)" = 1 ]; then \
	  $(BIN)/preprocess mesh $(SCENE) --level medium --out meshes && \
	  $(BIN)/validate reference $(SCENE) --meshes meshes --out $(OUT) --level medium \
	    --stride $(FINE_STRIDE) --stride-lightweight $(FINE_STRIDE_LW); fi
	@if [ "$(FINE)" = 1 ]; then \
	  $(BIN)/preprocess mesh $(SCENE) --level reference --out meshes && \
	  $(BIN)/validate reference $(SCENE) --meshes meshes --out $(OUT) --level reference \
	    --stride $(FINE_STRIDE) --stride-lightweight $(FINE_STRIDE_LW) && \
	  if [ "$(FORMULATION)" = 1 ]; then \
	    $(BIN)/validate reference $(SCENE) --meshes meshes --out $(OUT) --level reference \
	      --contact pinion-slave --stride $(FORMULATION_STRIDE); fi; fi
	@if [ "$(CONTACT_LAWS)" = 1 ]; then \
	  for s in $(CONTACT_LAW_SCENES); do \
	    f=reference/scenes/$$s.toml; \
	    $(BIN)/preprocess flanks $$f --out $(OUT)/$$s/flanks && \
	    $(BIN)/preprocess mesh $$f --level reduced --out meshes && \
	    $(BIN)/preprocess stiffness $$f --meshes meshes && \
	    $(BIN)/solver dynamic $$f --meshes meshes --out $(OUT) || exit 1; \
	  done; fi
	@if [ "$(SENSITIVITY)" = 1 ]; then \
	  $(BIN)/solver sensitivity $(SCENE) --meshes meshes --out $(OUT); fi
	@if [ "$(LUMPED)" = 1 ]; then \
	  for s in $(LUMPED_SCENES); do f=reference/scenes/$$s.toml; \
	    $(BIN)/preprocess flanks $$f --out $(OUT)/$$s/flanks && \
	    $(BIN)/preprocess mesh $$f --level reduced --out meshes && \
	    $(BIN)/preprocess stiffness $$f --meshes meshes && \
	    $(BIN)/solver lumped $$f --meshes meshes --out $(OUT) || exit 1; \
	  done; fi
	@if [ "$(BEARINGS)" = 1 ]; then f=$(BEARINGS_SCENE); s=$(OUT)/white_paper_bearings; \
	  $(BIN)/preprocess flanks $$f --out $$s/flanks && \
	  $(BIN)/preprocess mesh $$f --level reduced --out meshes && \
	  $(BIN)/preprocess stiffness $$f --meshes meshes && \
	  $(BIN)/solver ltca $$f --meshes meshes --out $(OUT) && \
	  $(BIN)/solver dynamic $$f --meshes meshes --out $(OUT) || exit 1; fi
	@if [ "$(GEARBOX)" = 1 ]; then f=$(GEARBOX_SCENE); s=$(OUT)/white_paper_gearbox; \
	  $(BIN)/preprocess flanks $$f --out $$s/flanks && \
	  $(BIN)/preprocess mesh $$f --level reduced --out meshes && \
	  $(BIN)/preprocess stiffness $$f --meshes meshes && \
	  $(BIN)/preprocess housing $$f --meshes meshes && \
	  $(BIN)/solver dynamic $$f --meshes meshes --out $(OUT) || exit 1; fi
	@if [ "$(USE_CASES)" = 1 ]; then f=$(STE_DTE_SCENE); s=$(OUT)/white_paper_ste_dte; \
	  $(BIN)/preprocess flanks $$f --out $$s/flanks && \
	  $(BIN)/preprocess mesh $$f --level reduced --out meshes && \
	  $(BIN)/preprocess stiffness $$f --meshes meshes && \
	  $(BIN)/solver dynamic $$f --meshes meshes --out $(OUT) || exit 1; fi
	@if [ "$(RATTLE)" = 1 ]; then f=$(RATTLE_SCENE); s=$(OUT)/rattle; \
	  $(BIN)/preprocess flanks $$f --out $$s/flanks && \
	  $(BIN)/preprocess mesh $$f --level reduced --out meshes && \
	  $(BIN)/preprocess stiffness $$f --meshes meshes && \
	  $(BIN)/solver dynamic $$f --meshes meshes --out $(OUT) || exit 1; fi
	@if [ "$(GRIDS)" = 1 ]; then \
	  for f in $(GRID_CONVERGENCE_SCENES); do \
	    $(BIN)/preprocess mesh $$f --level reduced --out meshes && \
	    $(BIN)/preprocess stiffness $$f --meshes meshes || exit 1; \
	  done; \
	  $(BIN)/validate grid-convergence $(SCENE) --meshes meshes --out $(OUT) \
	    $(addprefix --grid-scene ,$(GRID_CONVERGENCE_SCENES)) || exit 1; fi
	@if [ "$(CALIBRATED)" = 1 ] && [ -f $(CALIBRATED_SCENE) ]; then f=$(CALIBRATED_SCENE); \
	  $(BIN)/preprocess mesh $$f --level reduced --out meshes && \
	  $(BIN)/preprocess stiffness $$f --meshes meshes && \
	  $(BIN)/solver ltca $$f --meshes meshes --out $(OUT) || exit 1; fi
	$(BIN)/validate report $(SCENE) --flanks $(OUT)/$(notdir $(basename $(SCENE)))/flanks --reports reports --out $(OUT)

# The calibration behind $(CALIBRATED_SCENE): the default design's
# unpublished ease-off and lightweight web fitted to the white paper's
# NLFEA rows at 1 and 100 N·m (`validate calibrate`); rewrites
# reference/white_paper_20x43_calibrated.toml, the calibrated scene and
# reference/white_paper_20x43_calibration.json, which are committed.
# Measured 2026-11-28 with the scene's 12 x 40 stiffness grid, on 2 cores
# shared with short reference-FE runs and builds: 18 min 10 s wall,
# 1,355 s CPU in the process, 2.5 GB peak (32 LTCA runs of the ease-off
# fit; then 4 web trials, each meshing the lightweight wheel and solving
# its stiffness files, 3-5 min each).
calibrate: solve
	$(BIN)/validate calibrate $(SCENE) --meshes meshes --out $(OUT)

# Mesh convergence of the reference (three mesh levels at one position and
# torque; the reference level needs ~10 GB and about half an hour), and the
# line-load check of the stiffness files' global field + Weber-Banaschek
# against the fine-mesh FE.
convergence: build
	$(BIN)/preprocess mesh $(SCENE) --level medium --out meshes
	$(BIN)/preprocess mesh $(SCENE) --level reference --out meshes
	$(BIN)/validate convergence $(SCENE) --meshes meshes --out $(OUT)
	$(BIN)/validate line-load $(SCENE) --meshes meshes --out $(OUT)

# The mesh stiffness of seeds 003 and 004 at one position (the
# middle of the fewest-pairs stretch of the mesh cycle) from the FE
# reference (both tet10 bodies in penalty contact, smooth flanks) on the
# reduced (6 x 10), medium and reference (35 x 75) meshes, against our LTCA
# on the same levels' stiffness files: k = dF/dδ and F/δ at the lumped
# scenes' torques, the roughness the slices and meshes resolve. Writes
# $(OUT)/seed00{3,4}_fe_stiffness/mesh_stiffness/summary.json, which
# `make validate`'s report shows in its lumped section (run this first).
# Measured cold on 2 shared cores (2026-11-24, load average about 9 from
# other jobs): about 28 min and 6.9 GiB peak. Seed 003 about 7 min (meshes
# 41 + 18 + 17 s reference / reduced / medium, stiffness files 4 + 18 +
# 119 s reduced / medium / reference, the study 191 s, peak 5.3 GiB: the
# reference level's factors 2.35 + 2.65 GB); seed 004 about 21 min (meshes
# 261 + 147 + 220 s, the 86-tooth wheel's cut, stiffness files 64 + 94 +
# 210 s, the study 279 s, peak 6.9 GiB: factors 3.22 + 3.38 GB, just under
# the 7 GB cap). With everything cached both take 3 s (the study reuses
# the FE levels it solved). Not in `make validate` for its cold cost.
# FE_STIFFNESS_MEMORY_GB caps the two factors held at once (a level over it
# is skipped and reported).
FE_STIFFNESS_MEMORY_GB ?= 7
FE_STIFFNESS_SCENES    := seed003_fe_stiffness:seed003_lumped seed004_fe_stiffness:seed004_lumped
fe-stiffness: build
	@for p in $(FE_STIFFNESS_SCENES); do s=$${p%%:*}; l=$${p##*:}; f=reference/scenes/$$s.toml; \
	  for lv in reduced medium reference; do \
	    $(BIN)/preprocess mesh $$f --level $$lv --out meshes && \
	    $(BIN)/preprocess stiffness $$f --meshes meshes --level $$lv || exit 1; done; \
	  $(BIN)/validate mesh-stiffness $$f --meshes meshes --out $(OUT) \
	    --memory-gb $(FE_STIFFNESS_MEMORY_GB) --lumped-scene reference/scenes/$$l.toml || exit 1; \
	done

# The stress matrix: the scene's design and the seed pairs
# (reference/scenes/seed*_*x*.toml), standard blanks, reduced meshes and
# stiffness files made where missing or stale and reused otherwise; the
# white-paper pair also at the contact grids of reference/scenes/grids/
# (6 x 10 ... 24 x 40), and every design's coast flanks from the scenes of
# reference/scenes/coast/ (coast-flank contact: coast-refined meshes and
# coast stiffness files); a grid or coast scene whose stiffness stage fails
# is reported as skipped, with the stage's error printed here. Then run time against
# error for every stage of the scene (`validate stage-tradeoffs`).
# Writes $(OUT)/<scene>/stress/ (summary.json, outcomes.svg) and
# $(OUT)/<scene>/tradeoff/ (summary.json, <stage>.json, <stage>.svg); the
# report shows both. Measured on 2 cores shared with other builds: 7 min 39 s
# with everything cached (matrix 450 s, trade-offs 7 s); made cold, the grid
# scenes' meshes and stiffness files take about 20 min more (24 x 40: 8 min)
# and the coast scenes' about 11 min more.
SEED_SCENES := $(wildcard reference/scenes/seed[0-9][0-9][0-9]_[0-9]*x[0-9]*.toml)
GRID_SCENES := $(sort $(wildcard reference/scenes/grids/*.toml))
COAST_SCENES := $(sort $(wildcard reference/scenes/coast/*.toml))
stress: build
	$(BIN)/preprocess mesh $(SCENE) --level reduced --out meshes
	$(BIN)/preprocess stiffness $(SCENE) --meshes meshes
# The medium level's stiffness files: the stiffness stage's mesh-level point
# of the run-time-against-error study (measured with the medium meshes made:
# 2 min 20 s, of it 140 s the three bodies' stiffness files).
	$(BIN)/preprocess mesh $(SCENE) --level medium --out meshes
	$(BIN)/preprocess stiffness $(SCENE) --meshes meshes --level medium
	@for s in $(SEED_SCENES); do \
	  $(BIN)/preprocess mesh $$s --level reduced --out meshes && \
	  $(BIN)/preprocess stiffness $$s --meshes meshes || exit 1; done
	@for s in $(GRID_SCENES) $(COAST_SCENES); do \
	  $(BIN)/preprocess mesh $$s --level reduced --out meshes && \
	  $(BIN)/preprocess stiffness $$s --meshes meshes || \
	  echo "stress: stiffness files of $$s could not be made (above); its cells are skipped"; done
	$(BIN)/validate stress $(SCENE) --meshes meshes --out $(OUT) \
	  $(addprefix --grid-scene ,$(GRID_SCENES)) $(addprefix --coast-scene ,$(COAST_SCENES))
	$(BIN)/validate stage-tradeoffs $(SCENE) --meshes meshes --out $(OUT) \
	  $(addprefix --grid-scene ,$(GRID_SCENES))

lightweight: build
	$(BIN)/preprocess flanks $(LW_SCENE) --out $(OUT)/$(notdir $(basename $(LW_SCENE)))/flanks
	$(BIN)/preprocess mesh $(LW_SCENE) --level reduced --out meshes
	$(BIN)/preprocess stiffness $(LW_SCENE) --meshes meshes
	$(BIN)/solver dynamic $(LW_SCENE) --meshes meshes --out $(OUT)
	$(BIN)/solver lumped $(LW_SCENE) --meshes meshes --out $(OUT)
	LIGHTWEIGHT_OUT=$(abspath $(OUT)) $(CARGO) test $(RELEASE) -p validate \
	  --test lightweight_revolution_data -- --ignored

study: build
	$(BIN)/study submit $(STUDY) --executor $(EXECUTOR) --work $(STUDY_WORK) --meshes meshes
	@if [ "$(EXECUTOR)" = local ]; then \
	  $(BIN)/study collect $(STUDY) --work $(STUDY_WORK) --meshes meshes; fi

study-collect: build
	$(BIN)/study collect $(STUDY) --work $(STUDY_WORK) --meshes meshes

clean:
	$(CARGO) clean
	rm -rf $(OUT) reports
