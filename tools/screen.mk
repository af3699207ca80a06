# Screening a chaining candidate (issue 23; docs/PROTOCOL.md, "Screening chaining candidates"):
# main-prim continued from a committed final population with the candidate's keys for GENS
# generations, then the integration test on the top 10 of the result, with the caretaker and
# with no words (SPEC 12), then one table row. The control is the candidate `control`: the same
# population, the same generations, the default keys. Every candidate runs its GENS generations
# (ga.success_genotypes = ga.population: no early completion), so rows compare like for like.
# A stopped screen continues where it stopped (evolve --resume, posteval --resume).
#
#   make -f tools/screen.mk [CAND=control] [POP=prims_s4] [GENS=20] [SEED=1] [OUT=runs/screen] [THREADS=0]
#                           [SET='section.key=value ...']
#   make -f tools/screen.mk list          the candidates and their keys
#   make -f tools/screen.mk report        the table rows of every screen under OUT
#
# POP names a committed primitive run (data/evolved/POP/population.genome) or a population file.

CAND ?= control
POP ?= prims_s4
GENS ?= 20
SEED ?= 1
OUT ?= runs/screen
THREADS ?= 0
PYTHON ?= /usr/bin/python3
include $(dir $(lastword $(MAKEFILE_LIST)))apps.mk
# SET: settings for the screen's evolution and both its integration tests alike (as
# tools/replicate.mk's), e.g. SET='postures.reach_palm_down=0 dynamics.lcp=dense': a candidate's
# starts are then those of its test too. A screen's directory is named after SET's values, so
# screens of one candidate under other settings never share (and resume) one directory.
SET ?=
empty :=
space := $(empty) $(empty)
SET_BAD := $(strip $(foreach s,$(SET),$(if $(findstring =,$(s)),,$(s))))
ifneq ($(SET_BAD),)
$(error SET: '$(firstword $(SET_BAD))': expected section.key=value)
endif
SET_ARGS := $(foreach s,$(SET),--set $(s))
SET_TAG := $(if $(SET),-$(subst =,,$(subst .,,$(subst $(space),-,$(strip $(SET))))))

# the candidates: config keys on configs/main_prim.cfg (one line each; add a row to add one)
KEYS_control :=
KEYS_grasp_gap := --set postures.grasp_gap=0.06
KEYS_ik := --set postures.ik_torso_pitch=20 --set postures.ik_wrist_prosup=0 --set postures.ik_wrist_pitch=-45
KEYS_vary := --set postures.vary_starts=true
KEYS_handover := --set stage.handover=true
KEYS_handover_fallback := --set stage.handover=true --set stage.handover_fallback=true
KEYS_chain := --set stage.chain_trials=8
KEYS_handover_chain := --set stage.handover=true --set stage.chain_trials=8
CHAIN_SUM := --set stage.chain_trials=8 --set stage.chain_combine=sum --set stage.chain_progress=10
KEYS_chain_sum := $(CHAIN_SUM)
KEYS_chain_gated := $(CHAIN_SUM) --set stage.chain_gate=8
KEYS_handover_chain_gated := --set stage.handover=true $(CHAIN_SUM) --set stage.chain_gate=8
KEYS_handover_chain_sum := --set stage.handover=true $(CHAIN_SUM)
# the same with twice the thesis's bit-flip rate: more exploration where no genotype chains
KEYS_handover_chain_gated_mut := $(KEYS_handover_chain_gated) --set ga.mutation_rate=0.01
# grasp's partly extended starts (k=2,3) flexed as open's end leaves the hand in the chains that
# break (0.4, the largest the posture check accepts): whether grasp learns to close on the ball
# from there; it replaces two of the thesis's starts, so a result would be replayed on the 16
# fixed trials and, if it helps, built as extra trials (docs/notebook/chain_stage.md, "More exploration")
KEYS_handover_chain_gated_flex := $(KEYS_handover_chain_gated) --set postures.grasp_partial_flex=0.4
# and 6 cm up (all four grasp starts): high and partly flexed at once, as the chains hand over
KEYS_handover_chain_gated_highflex := $(KEYS_handover_chain_gated_flex) --set postures.grasp_gap=0.06
# the hand-over trials rolled in by the generation's elite (the previous generation's best), not
# by each individual: every individual learns from the same, better chained starts, and a
# primitive is not rewarded for a predecessor of its own that hands over in an easy state
KEYS_handover_elite_chain_gated := $(KEYS_handover_chain_gated) --set stage.handover_rollin=elite
# grasp's and open's fixed starts varied each generation (palm offset 2 cm, tilt 20 deg, arm
# configurations towards reach's): the grasp hand-overs that fail drift sideways from an arm
# configuration no fixed start has (docs/PROTOCOL.md, "Screening chaining candidates")
KEYS_handover_chain_gated_vary := $(KEYS_handover_chain_gated) --set postures.vary_starts=true
KEYS_handover_chain_gated_vary_extra := $(KEYS_handover_chain_gated_vary) --set postures.vary_trials=extra
# replace for 30 generations, then extra (configs/chain_prim.cfg first had 30, now 60: 30 were
# too few from prims_s1 and prims_s4, chain_candidates/sched30_s*)
KEYS_handover_chain_gated_vary_sched := $(KEYS_handover_chain_gated_vary_extra) \
  --set postures.vary_replace_generations=30
# the chain stage as configs/chain_prim.cfg ships it, continued from a chain run's final population
# (POP=chain_sN): its drawn starts as they were at its end (extra, no replace phase), its stop rule
# off as every screen's; with SET's starts this is issue 46's screen (a) (docs/PROTOCOL.md)
KEYS_chain_continued := $(KEYS_handover_chain_gated_vary_extra) --set stage.chain_complete=fixed_chained \
  --set postures.vary_replace_generations=0
CANDIDATES := control grasp_gap ik vary handover handover_fallback chain handover_chain chain_sum \
  chain_gated handover_chain_gated handover_chain_sum handover_chain_gated_mut \
  handover_chain_gated_flex handover_chain_gated_highflex handover_chain_gated_vary handover_chain_gated_vary_extra handover_chain_gated_vary_sched \
  handover_elite_chain_gated chain_continued

ifeq ($(filter $(CAND),$(CANDIDATES)),)
$(error CAND=$(CAND): expected one of $(CANDIDATES))
endif

POPFILE := $(if $(wildcard data/evolved/$(POP)/population.genome),data/evolved/$(POP)/population.genome,$(POP))
DIR := $(OUT)/$(CAND)-$(notdir $(basename $(POP:%/population.genome=%)))-s$(SEED)$(SET_TAG)
THREADS_ARG := $(if $(filter-out 0,$(THREADS)),--threads $(THREADS))
SHELL := /bin/bash

.PHONY: screen list report
.DELETE_ON_ERROR:

screen: $(DIR)/integration/summary.csv $(DIR)/integration-nowords/summary.csv
	@$(PYTHON) tools/screen_report.py $(DIR)

list:
	@$(foreach c,$(CANDIDATES),echo "$(c): $(or $(KEYS_$(c)),(the default keys))";)

report:
	@$(PYTHON) tools/screen_report.py $(sort $(dir $(wildcard $(OUT)/*/integration/summary.csv)))

$(DIR)/population.genome:
	mkdir -p $(DIR) && set -o pipefail && $(APPS)/evolve configs/main_prim.cfg --seed $(SEED) \
	  --generations $(GENS) --out $(DIR) --resume $(THREADS_ARG) \
	  --set stage.init_population=$(POPFILE) --set ga.success_genotypes=100 $(KEYS_$(CAND)) $(SET_ARGS) \
	  2>&1 | tee -a $(DIR)/progress.log

$(DIR)/integration/summary.csv: $(DIR)/population.genome
	$(APPS)/posteval integration configs/prims.cfg $(DIR)/population.genome --out $(DIR)/integration \
	  --resume $(THREADS_ARG) $(SET_ARGS)

$(DIR)/integration-nowords/summary.csv: $(DIR)/population.genome
	$(APPS)/posteval integration configs/prims.cfg $(DIR)/population.genome --no-words \
	  --out $(DIR)/integration-nowords --resume $(THREADS_ARG) $(SET_ARGS)
