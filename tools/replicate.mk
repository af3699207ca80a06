# The whole study (thesis §2.4-§3), one file per step, as make targets: a killed replication
# continues where it stopped (every job writes its result atomically and evolve resumes from its
# checkpoint), and every step's jobs are independent (`make -j`, or one cluster job each:
# `make -f tools/replicate.mk jobs STEP=prims` lists them; README.md, "Replicating the study").
#
#   make replicate [PRESET=small] [RUNS=N] [OUT=DIR] [THREADS=N]      (top-level Makefile)
#   make -f tools/replicate.mk [target] [the same variables]
#   make -f tools/replicate.mk cost [the same variables] [REMEASURE=1]  what it will cost
#   make -f tools/replicate.mk status [the same variables]   what is done and left, while it runs
#   make replicate SET='section.key=value ...'   settings for every evolve and posteval step
#   make -f tools/replicate.mk snapshot|restore OUT=DIR SNAPSHOT=DIR    copy it while it runs
#   make -f tools/replicate.mk interim [the same variables]  robustness of the runs done so far
#
# Steps and their files (under OUT):
#   prims       prims-s<N>/population.genome       configs/prims.cfg, seeds 1..RUNS
#   chain       chain-s<N>/population.genome       PROTOCOL=chain: the chain stage,
#                                                  configs/chain_prim.cfg from prims-s<N>
#                                                  (SPEC 12; the default; PROTOCOL=thesis: none)
#   integration posteval/integration/summary.csv   top 10 of each primitive run, caretaker words
#   integrated  int-<cond>-s<N>/population.genome  4 conditions x RUNS seeds, assembled from the
#                                                  primitive runs (integrated.populations)
#   robustness  posteval/robustness-<cond>/        the best of each integrated run
#   generalisation posteval/generalisation-<cond>/ (and -stct0, -st0: the caretaker's words)
#   stats       stats/*.txt, *.csv                 ./apps/stats: Tables 3.1-3.3, descriptions
#   figures     figures/*.png, *.svg               tools/fig_*.py
#   report      report.md                          tools/replicate_report.py: ours beside the thesis
#   cost        (printed; OUT/cost/costs.csv)      tools/replicate_cost.py: each step's core-hours
#                                                  and wall hours on THREADS, from what one
#                                                  evaluation costs here (build/eval_cost);
#                                                  `make replicate` prints it before the first job
#
# PRESET=small is a quick look (2 runs, capped generations, reduced post-evaluations): it shows
# every step working in well under an hour, not the thesis's results.

PRESET ?= full
# chain (the default): each primitive run continued by the chain stage (configs/chain_prim.cfg;
# SPEC 12, docs/PROTOCOL.md), whose primitives chain (integration test median 30 of 40 on the
# completed runs, the thesis's 25); thesis: the thesis's primitive stages alone (their
# integration test: 0 of 1200), so that its result can be reported beside
PROTOCOL ?= chain
OUT ?= runs/replicate
THREADS ?= 0
PYTHON ?= /usr/bin/python3

# Arguments of each step's commands (a key either acts in a command or is refused, so each
# post-evaluation test has its own).
ifeq ($(PRESET),full)
RUNS ?= 10
else ifeq ($(PRESET),small)
RUNS ?= 2
PRIM_ARGS ?= --generations 40
CHAIN_ARGS ?= --generations 10
INT_ARGS ?= --generations 3
INTEG_ARGS ?= --set posteval.integration_top=2 --set posteval.integration_trials=8
ROB_ARGS ?= --set posteval.robustness_trials=8
GEN_ARGS ?= --set posteval.generalisation_cells=3 --set posteval.generalisation_repetitions=1
else ifeq ($(PRESET),tiny)
# the end-to-end test (tests/check_replicate.sh): every step, seconds each, meaningless numbers
RUNS ?= 2
GA_TINY := --set ga.population=20 --set ga.elites=2 --set ga.parents=4
PRIM_ARGS ?= --generations 2 $(GA_TINY)
CHAIN_ARGS ?= --generations 2 $(GA_TINY) --set stage.chain_trials=2 --set integrated.steps=20 \
  --set stage.handover_rollin_steps=20
INT_ARGS ?= --generations 2 $(GA_TINY) --set integrated.trials=4 --set integrated.steps=20
INTEG_ARGS ?= --set posteval.integration_top=2 --set posteval.integration_trials=4
FIG3_3_ARGS ?= --bin 1
ROB_ARGS ?= --set posteval.robustness_trials=4
GEN_ARGS ?= --set posteval.generalisation_cells=2 --set posteval.generalisation_repetitions=1 \
  --set posteval.generalisation_steps=20
else
$(error PRESET=$(PRESET): expected full, small or tiny)
endif
ifeq ($(filter $(PROTOCOL),chain thesis),)
$(error PROTOCOL=$(PROTOCOL): expected chain or thesis)
endif

# SET: settings (section.key=value, space-separated) for every simulated step, evolution and
# post-evaluation alike, e.g. SET=postures.reach_palm_down=0 (the configs ship the study's
# protocol: palm-down reach starts, the grasp thumb at 0.9, run.rng_seed = apart, dynamics.lcp =
# warm; docs/PROTOCOL.md, "The study's starts and solver"): each step's own ..._ARGS come first,
# then these
SET ?=
SET_BAD := $(strip $(foreach s,$(SET),$(if $(findstring =,$(s)),,$(s))))
ifneq ($(SET_BAD),)
$(error SET: '$(firstword $(SET_BAD))': expected section.key=value)
endif
SET_ARGS := $(foreach s,$(SET),--set $(s))

comma := ,
empty :=
space := $(empty) $(empty)
# a shell word of any text: single quotes, each ' as '\'' (SNAPSHOT, any path, goes through it)
sq = '$(subst ','\'',$(1))'

# OUT, PRIM_RUNS and CHAIN_RUNS name make targets and prerequisites, which make cannot quote: a
# space splits a name in two (`rm -rf $(OUT)/interim.tmp` with OUT='runs/replicate copy' removed
# runs/replicate), ':' '%' '#' '*' and the like mean something to make, a ',' splits the
# integrated runs' list of populations. So they are refused unless made of these characters
# (issue 48); recipes quote every path all the same (lists of them, $^, need no quotes then).
PATH_CHARS := a b c d e f g h i j k l m n o p q r s t u v w x y z A B C D E F G H I J K L M N O P \
  Q R S T U V W X Y Z 0 1 2 3 4 5 6 7 8 9 . _ - / + @
# what is left of $(1) once the characters listed in $(2) are taken out
path_rest = $(if $(2),$(call path_rest,$(subst $(firstword $(2)),,$(1)),$(wordlist 2,$(words $(2)),$(2))),$(1))
ifeq ($(strip $(OUT)),)
$(error OUT is empty: expected the replication's directory, e.g. OUT=runs/replicate)
endif
ifneq ($(words $(OUT)),1)
$(error OUT='$(OUT)': a name with white space, which make cannot quote in its targets; expected letters, digits and . _ - + @ / only, e.g. OUT=runs/replicate_copy)
endif
define check_paths
$(foreach p,$($(1)),$(if $(call path_rest,$(p),$(PATH_CHARS)),$(error $(1): '$(p)' holds '$(call path_rest,$(p),$(PATH_CHARS))', which make cannot quote in its targets; expected letters, digits and . _ - + @ / only)))
endef
$(call check_paths,OUT)
$(call check_paths,PRIM_RUNS)
$(call check_paths,CHAIN_RUNS)
CONDS := stct st ct ni
# the caretaker variants of the generalisation test (thesis §3.2.5: ST-CT0, ST0)
CONDS0 := stct st
SEEDS := $(shell seq 1 $(RUNS))
# the apps and tools of a build (tools/apps.mk; BUILD as the top Makefile names it)
include $(dir $(lastword $(MAKEFILE_LIST)))apps.mk
BUILD ?= build
EVOLVE := $(APPS)/evolve
POSTEVAL := $(APPS)/posteval
STATS := $(APPS)/stats
THREADS_ARG := $(if $(filter-out 0,$(THREADS)),--threads $(THREADS))

# The study from primitive runs that exist already (the committed ones, another machine's):
# PRIM_RUNS lists their directories (each with fitness.csv and population.genome) and, with
# PROTOCOL=chain, CHAIN_RUNS the chain stages that continued them, in the same order. The prims
# and chain steps then run nothing (nothing is written into those directories), and RUNS counts
# the integrated runs of each condition only, e.g. (README.md, "Replicating the study"):
#   make replicate RUNS=5 PRIM_RUNS='data/evolved/prims_s1 data/evolved/prims_s2' \
#     CHAIN_RUNS='data/evolved/chain_s1 data/evolved/chain_s2'
PRIM_RUNS ?=
CHAIN_RUNS ?=
GIVEN_PRIMS := $(patsubst %/,%,$(strip $(PRIM_RUNS)))
GIVEN_CHAINS := $(patsubst %/,%,$(strip $(CHAIN_RUNS)))
ifneq ($(GIVEN_PRIMS)$(GIVEN_CHAINS),)
ifeq ($(GIVEN_PRIMS),)
$(error CHAIN_RUNS without PRIM_RUNS: expected the primitive runs the chain runs continued, in the same order)
endif
ifeq ($(PROTOCOL),chain)
ifneq ($(words $(GIVEN_PRIMS)),$(words $(GIVEN_CHAINS)))
$(error PROTOCOL=chain: PRIM_RUNS has $(words $(GIVEN_PRIMS)) and CHAIN_RUNS $(words $(GIVEN_CHAINS)) directories: expected one chain run per primitive run)
endif
else ifneq ($(GIVEN_CHAINS),)
$(error CHAIN_RUNS with PROTOCOL=thesis, which has no chain stage)
endif
GIVEN_FILES := $(foreach d,$(GIVEN_PRIMS) $(GIVEN_CHAINS),$(d)/fitness.csv $(d)/population.genome)
GIVEN_MISSING := $(filter-out $(wildcard $(GIVEN_FILES)),$(GIVEN_FILES))
ifneq ($(GIVEN_MISSING),)
$(error PRIM_RUNS / CHAIN_RUNS: no such file: $(GIVEN_MISSING) (expected a completed run's directory))
endif
endif

PRIM_POPS := $(if $(GIVEN_PRIMS),$(GIVEN_PRIMS:%=%/population.genome),$(SEEDS:%=$(OUT)/prims-s%/population.genome))
CHAIN_POPS := $(if $(GIVEN_CHAINS),$(GIVEN_CHAINS:%=%/population.genome),$(SEEDS:%=$(OUT)/chain-s%/population.genome))
# the primitive runs the integration test and the integrated stage take
PRIMITIVES := $(if $(filter chain,$(PROTOCOL)),$(CHAIN_POPS),$(PRIM_POPS))
# seed by seed, the four conditions of each (make -j1 runs them in this order): a replication
# stopped part way has every condition with as many seeds as it got to
INT_POPS := $(foreach s,$(SEEDS),$(CONDS:%=$(OUT)/int-%-s$(s)/population.genome))
POST_INTEG := $(OUT)/posteval/integration/summary.csv
POST_ROB := $(CONDS:%=$(OUT)/posteval/robustness-%/summary.csv)
POST_GEN := $(CONDS:%=$(OUT)/posteval/generalisation-%/summary.csv) \
  $(CONDS0:%=$(OUT)/posteval/generalisation-%0/summary.csv)
SUMMARIES := $(OUT)/summary/integration.csv $(OUT)/summary/robustness.csv \
  $(OUT)/summary/generalisation.csv $(OUT)/summary/generalisation-trials.csv
STATS_OUT := $(OUT)/stats/table_3_1.txt $(OUT)/stats/table_3_2.txt $(OUT)/stats/table_3_3.txt \
  $(OUT)/stats/integration.txt $(OUT)/stats/robustness.txt $(OUT)/stats/generalisation.txt \
  $(OUT)/stats/selftalk.csv
REPORT := $(OUT)/report.md

.PHONY: FORCE all prims chain integration integrated robustness generalisation stats figures report jobs \
  cost status snapshot restore interim
.DELETE_ON_ERROR:
# a step's files stay when a later step fails: they are results
.SECONDARY:
# and when make is stopped: evolve and posteval write them atomically, so they are never
# partial, and a finished run resumed says "complete" without writing its population again
# (make's "Deleting file" after a run's last checkpoint lost its population.genome for good)
.PRECIOUS: $(PRIM_POPS) $(CHAIN_POPS) $(INT_POPS) $(POST_INTEG) $(POST_ROB) $(POST_GEN)

all: report
prims: $(PRIM_POPS)
chain: $(CHAIN_POPS)
integration: $(POST_INTEG)
integrated: $(INT_POPS)
robustness: $(POST_ROB)
generalisation: $(POST_GEN)
stats: $(STATS_OUT)
figures: $(OUT)/figures/.done
report: $(REPORT)

# the targets of one step, one per line: a cluster job array runs line $TASK_ID
jobs:
	@$(if $(filter prims,$(STEP)),printf '%s\n' $(PRIM_POPS),$(if $(filter chain,$(STEP)),printf '%s\n' $(CHAIN_POPS),$(if $(filter integrated,$(STEP)),printf '%s\n' $(INT_POPS),$(if $(filter robustness,$(STEP)),printf '%s\n' $(POST_ROB),$(if $(filter generalisation,$(STEP)),printf '%s\n' $(POST_GEN),echo "jobs: STEP=prims, chain, integrated, robustness or generalisation" >&2; exit 2)))))

# ---- the cost, before anything runs (tools/replicate_cost.py; docs/PROTOCOL.md, "Speed"): what
# one evaluation of each kind costs on this machine (build/eval_cost on COST_SAMPLE genotypes of
# the committed runs below, CPU time on one thread; measured once per host and build, cached in
# OUT/cost/costs.csv; REMEASURE=1 measures again), times the evaluations of each step's jobs
EVAL_COST ?= $(BUILD)/eval_cost
COST_SAMPLE ?= 4
COST_PRIM_POP ?= data/evolved/prims_s2/population.genome
COST_CHAIN_POP ?= data/evolved/chain_candidates/hcg_p2_from50/checkpoint
# % is the condition (stct, st, ct, ni)
COST_INT_POP ?= data/evolved/unchained/int_%_s1/population.genome
REMEASURE ?=
# status: the same prices applied to what OUT's files say is left (done jobs, generations run)
status: STATUS_ARG := --status
cost status:
	@$(PYTHON) tools/replicate_cost.py $(STATUS_ARG) --preset=$(PRESET) --protocol=$(PROTOCOL) --runs=$(RUNS) \
	  --threads=$(THREADS) --out='$(OUT)' --eval-cost=$(EVAL_COST) --sample=$(COST_SAMPLE) \
	  --prim-pop=$(COST_PRIM_POP) --chain-pop=$(COST_CHAIN_POP) --int-pop=$(COST_INT_POP) \
	  --prim-args='$(PRIM_ARGS) $(SET_ARGS)' --chain-args='$(CHAIN_ARGS) $(SET_ARGS)' \
	  --int-args='$(INT_ARGS) $(SET_ARGS)' --integ-args='$(INTEG_ARGS) $(SET_ARGS)' \
	  --rob-args='$(ROB_ARGS) $(SET_ARGS)' --gen-args='$(GEN_ARGS) $(SET_ARGS)' \
	  $(if $(GIVEN_PRIMS),--given-runs=$(words $(GIVEN_PRIMS))) \
	  $(if $(filter-out 0 no,$(REMEASURE)),--remeasure)

# ---- snapshots while it runs (storage that does not last, a repository; tools/snapshot.sh):
# snapshot copies OUT to SNAPSHOT, each run's checkpoint first, so the copy is a consistent
# resume point; restore copies SNAPSHOT back into an OUT that does not exist yet (nothing newer
# is overwritten), where the same make command resumes every job to the same files. Files name
# OUT (config.ini's integrated.populations), so restore to the OUT the snapshot was taken of.
SNAPSHOT ?=
NEED_SNAPSHOT = @test -n $(call sq,$(SNAPSHOT)) || { echo "$@: SNAPSHOT=DIR expected (where the snapshot goes or comes from)" >&2; exit 2; }
# tools/snapshot.sh refuses OUT and SNAPSHOT the same or one inside the other, a snapshot over a
# run that is ahead of it (OUT and SNAPSHOT swapped) and a restore into an OUT that exists; a
# restore is whole or not at all (copied beside, then renamed)
snapshot:
	$(NEED_SNAPSHOT)
	@sh tools/snapshot.sh $(call sq,$(OUT)) $(call sq,$(SNAPSHOT))
restore:
	$(NEED_SNAPSHOT)
	@sh tools/snapshot.sh --restore $(call sq,$(SNAPSHOT)) $(call sq,$(OUT))

# ---- interim: while the study runs, the robustness test (40 trials, seconds a run) of the
# integrated runs complete so far, with Table 3.1, the description and the successes by trial
# type of them, in OUT/interim/ (made anew each time, whole or not at all). The study's own
# robustness step comes after its last run; for the same runs it gives the same trials
# (tests/check_replicate.sh).
INT_DONE = $(patsubst %/population.genome,%,$(wildcard $(SEEDS:%=$(OUT)/int-$(1)-s%/population.genome)))
INTERIM_CONDS = $(strip $(foreach c,$(CONDS),$(if $(call INT_DONE,$(c)),$(c))))
interim: I = $(call sq,$(OUT)/interim.tmp)
interim:
	@test -n "$(INTERIM_CONDS)" || { echo "interim: no integrated run in $(OUT) is complete yet" >&2; exit 2; }
	@rm -rf $(I) && mkdir -p $(I)
	@$(foreach c,$(INTERIM_CONDS),$(POSTEVAL) robustness configs/integrated_$(c).cfg $(call INT_DONE,$(c)) \
	  --out $(call sq,$(OUT)/interim.tmp/robustness-$(c)) $(THREADS_ARG) $(ROB_ARGS) $(SET_ARGS) > /dev/null && ) true
	@awk 'FNR > 1 || NR == 1' $(foreach c,$(INTERIM_CONDS),$(call sq,$(OUT)/interim.tmp/robustness-$(c)/summary.csv)) > $(I)/robustness.csv
	@$(foreach t,table_3_1:table robustness:describe,$(STATS) $(lastword $(subst :, ,$(t))) \
	  $(I)/robustness.csv --test robustness > $(I)/$(t).raw && \
	  sed '1s|/interim\.tmp/|/interim/|' $(I)/$(t).raw > $(I)/$(firstword $(subst :, ,$(t))).txt && \
	  rm $(I)/$(t).raw && ) true
	@$(PYTHON) tools/replicate_report.py $(I) --types > $(I)/types.md
	@rm -rf $(call sq,$(OUT)/interim) && mv $(I) $(call sq,$(OUT)/interim)
	@echo "interim: robustness of the complete integrated runs ($(foreach c,$(INTERIM_CONDS),$(c) $(words $(call INT_DONE,$(c))))), in $(OUT)/interim/"
	@awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) h[$$i] = i; next } \
	  { printf "  %-12s %-6s %2d of %d\n", $$h["run_label"], $$h["condition"], $$h["successes"], $$h["trials"] }' \
	  $(call sq,$(OUT)/interim/robustness.csv)
	@cat $(call sq,$(OUT)/interim/table_3_1.txt) $(call sq,$(OUT)/interim/types.md)

# ---- evolution: --resume continues a killed run to the identical files (or starts it). It
# runs every time (FORCE): evolve writes population.genome before its last checkpoint, so a run
# stopped between the two has its population but not its end; evolve --resume finishes it, and
# says "complete" (writing nothing, so nothing after it is redone) for a run that is
$(OUT)/prims-s%/population.genome: FORCE
	@mkdir -p '$(OUT)'
	$(EVOLVE) configs/prims.cfg --seed $* --out '$(@D)' --resume $(THREADS_ARG) $(PRIM_ARGS) $(SET_ARGS) >> '$(@D).log'

# the chain stage continues primitive run N's final population, with the same seed
$(OUT)/chain-s%/population.genome: $(OUT)/prims-s%/population.genome FORCE
	$(EVOLVE) configs/chain_prim.cfg --seed $* --out '$(@D)' --resume $(THREADS_ARG) $(CHAIN_ARGS) $(SET_ARGS) \
	  --set stage.init_population='$<' >> '$(@D).log'

# every integrated run starts from the same assembled genotypes: the top 10 of each primitive run
$(OUT)/int-%/population.genome: $(PRIMITIVES) FORCE
	@mkdir -p '$(OUT)'
	$(EVOLVE) configs/integrated_$(word 1,$(subst -s, ,$*)).cfg --seed $(lastword $(subst -s, ,$*)) \
	  --out '$(@D)' --resume $(THREADS_ARG) $(INT_ARGS) $(SET_ARGS) \
	  --set integrated.populations='$(subst $(space),$(comma),$(strip $(PRIMITIVES)))' >> '$(@D).log'

FORCE:


# ---- post-evaluation (each writes DIR/trials.csv and DIR/summary.csv atomically; --resume
# continues a killed test from its DIR/posteval.journal)
$(POST_INTEG): $(PRIMITIVES)
	$(POSTEVAL) integration configs/prims.cfg $(PRIMITIVES) --out '$(@D)' --resume $(THREADS_ARG) $(INTEG_ARGS) $(SET_ARGS)

$(OUT)/posteval/robustness-%/summary.csv: $(INT_POPS)
	$(POSTEVAL) robustness configs/integrated_$*.cfg $(dir $(SEEDS:%=$(OUT)/int-$*-s%/x)) \
	  --out '$(@D)' --resume $(THREADS_ARG) $(ROB_ARGS) $(SET_ARGS)

$(OUT)/posteval/generalisation-%0/summary.csv: $(INT_POPS)
	$(POSTEVAL) generalisation configs/integrated_$*.cfg $(dir $(SEEDS:%=$(OUT)/int-$*-s%/x)) \
	  --caretaker --out '$(@D)' --resume $(THREADS_ARG) $(GEN_ARGS) $(SET_ARGS)

$(OUT)/posteval/generalisation-%/summary.csv: $(INT_POPS)
	$(POSTEVAL) generalisation configs/integrated_$*.cfg $(dir $(SEEDS:%=$(OUT)/int-$*-s%/x)) \
	  --out '$(@D)' --resume $(THREADS_ARG) $(GEN_ARGS) $(SET_ARGS)

# posteval writes trials.csv with summary.csv
$(OUT)/posteval/%/trials.csv: $(OUT)/posteval/%/summary.csv
	@test -f '$@'

# ---- one file per test, the conditions together (header once)
define concat
	@mkdir -p '$(@D)'
	awk 'FNR > 1 || NR == 1' $^ > '$@.tmp' && mv '$@.tmp' '$@'
endef
$(OUT)/summary/integration.csv: $(POST_INTEG)
	$(concat)
$(OUT)/summary/robustness.csv: $(POST_ROB)
	$(concat)
$(OUT)/summary/generalisation.csv: $(POST_GEN)
	$(concat)
$(OUT)/summary/generalisation-trials.csv: $(POST_GEN:summary.csv=trials.csv)
	$(concat)

# ---- statistics (./apps/stats): stdout to a file, moved into place when complete
$(OUT)/stats/table_3_1.txt: $(OUT)/summary/robustness.csv
	@mkdir -p '$(@D)'
	$(STATS) table '$<' --test robustness > '$@.tmp' && mv '$@.tmp' '$@'
$(OUT)/stats/table_3_2.txt: $(OUT)/summary/generalisation.csv
	@mkdir -p '$(@D)'
	$(STATS) table '$<' --test generalisation > '$@.tmp' && mv '$@.tmp' '$@'
$(OUT)/stats/selftalk.csv: $(OUT)/summary/generalisation-trials.csv
	@mkdir -p '$(@D)'
	$(STATS) selftalk '$<' $(GEN_ARGS) > '$@.tmp' && mv '$@.tmp' '$@'
$(OUT)/stats/table_3_3.txt: $(OUT)/summary/generalisation-trials.csv
	@mkdir -p '$(@D)'
	$(STATS) times '$<' $(GEN_ARGS) > '$@.tmp' && mv '$@.tmp' '$@'
$(OUT)/stats/%.txt: $(OUT)/summary/%.csv
	@mkdir -p '$(@D)'
	$(STATS) describe '$<' --test $* > '$@.tmp' && mv '$@.tmp' '$@'

# ---- figures (tools/fig_*.py): PNG and SVG
FIG = $(PYTHON) tools/$(1).py $(2) -o '$(OUT)/figures/$(3).png' -o '$(OUT)/figures/$(3).svg'

# Fig. 3.12: the words of the best individual of ST-CT and of ST (the run whose best solved the
# most robustness trials, ties the lower run: tools/best_run.py) in the integrated stage's four
# trial types (trials 0-3 of its last generation, type = trial mod 4), in self talk and again
# with the caretaker's words (replayed; the traces kept in figures/words-<cond>/, the words
# printed into fig3_12_<cond>.txt)
REPLAY := $(APPS)/replay
WORDS_self := --set integrated.words_even=selftalk --set integrated.fitness_even=integrated
WORDS_care := --set integrated.words_even=caretaker --set integrated.words_odd=caretaker
FIG3_12 := $(CONDS0:%=$(OUT)/figures/fig3_12_%.png)
$(OUT)/figures/fig3_12_%.png: $(OUT)/posteval/robustness-%/summary.csv $(INT_POPS)
	@mkdir -p '$(@D)/words-$*'
	set -- $$($(PYTHON) tools/best_run.py '$<') && test $$# = 3 && \
	  $(foreach k,0 1 2 3,$(foreach w,self care,$(REPLAY) "$(OUT)/$$1/best.genome" "$(OUT)/$$1/config.ini" \
	    --generation $$3 --trial $(k) $(WORDS_$(w)) --out '$(@D)/words-$*/$(w)-$(k).csv' > /dev/null && )) \
	  $(PYTHON) tools/fig_words.py $(foreach k,0 1 2 3,'$(@D)/words-$*/self-$(k).csv+$(@D)/words-$*/care-$(k).csv') \
	    $(foreach k,0 1 2 3,--label "type $(k)") --title "$$1's best, generation $$3" \
	    -o '$@' -o '$(@:.png=.svg)' > '$(@:.png=.txt)'

$(OUT)/figures/.done: $(PRIMITIVES) $(INT_POPS) $(SUMMARIES) $(OUT)/stats/selftalk.csv $(FIG3_12)
	@mkdir -p '$(@D)'
	$(call FIG,fig_prim_fitness,$(PRIM_POPS:/population.genome=),fig3_1)
	$(if $(filter chain,$(PROTOCOL)),$(call FIG,fig_chain,$(CHAIN_POPS:/population.genome=),fig_chain))
	$(call FIG,fig_integration,$(OUT)/summary/integration.csv $(FIG3_3_ARGS),fig3_3)
	$(foreach c,$(CONDS),$(call FIG,fig_int_fitness,$(SEEDS:%=$(OUT)/int-$(c)-s%) --start 1,fig3_int_$(c));)
	$(call FIG,fig_boxplot,$(OUT)/summary/robustness.csv --test robustness,fig3_4)
	$(call FIG,fig_boxplot,$(OUT)/summary/generalisation.csv --test generalisation,fig3_9)
	$(call FIG,fig_success_maps,$(OUT)/summary/generalisation-trials.csv,fig3_10)
	$(call FIG,fig_selftalk,$(OUT)/stats/selftalk.csv,fig3_11)
	touch '$@'

$(REPORT): $(STATS_OUT) $(OUT)/figures/.done
	$(PYTHON) tools/replicate_report.py '$(OUT)' --preset $(PRESET) --runs $(RUNS) --protocol $(PROTOCOL) \
	  $(if $(GIVEN_PRIMS),--prim-runs '$(GIVEN_PRIMS)' $(if $(GIVEN_CHAINS),--chain-runs '$(GIVEN_CHAINS)')) -o '$@'
