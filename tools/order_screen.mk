# The integrated stage's trial-type order screened (issue 47 item 2; SPEC 13; docs/PROTOCOL.md,
# "Integrated stage", Trials): each condition in CONDS and seed in SEEDS evolved from the same
# assembled population under each order in ORDERS (integrated.trial_order), then the robustness
# test (40 trials, the best of the last generation; the test's own table, whatever the order), and
# one table: successes by type, the first generation with an autonomous bonus and with all of it,
# the types succeeded autonomously. The runs use the shipped configs (palm-down starts; since
# 2026-11-28 also warm and rng_seed apart, which the screen of issue 47 gave with EVOLVE_ARGS).
# Every job resumes where it stopped (evolve --resume, posteval --resume).
#
#   make -f tools/order_screen.mk [SEEDS='1 2 3'] [CONDS='stct ct'] [ORDERS='mod4 pairs'] [GENS=100]
#                                 [POP=A,B,...] [OUT=runs/order_screen] [THREADS=0] [-j2]
#   make -f tools/order_screen.mk report      the table of every run done so far under OUT

SEEDS ?= 1 2 3
CONDS ?= stct ct
ORDERS ?= mod4 pairs
GENS ?= 100
# the palm-down study's founders (the chain runs' top 10 each: data/evolved/study_palm_down)
POP ?= data/evolved/chain_s1/population.genome,data/evolved/chain_s2/population.genome,data/evolved/chain_s4/population.genome
OUT ?= runs/order_screen
THREADS ?= 0
# extra arguments of the evolution and of the test (tests/check_order_screen.sh makes them tiny)
EVOLVE_ARGS ?=
ROB_ARGS ?=
PYTHON ?= /usr/bin/python3
include $(dir $(lastword $(MAKEFILE_LIST)))apps.mk
THREADS_ARG := $(if $(filter-out 0,$(THREADS)),--threads $(THREADS))

ifneq ($(filter-out stct st ct ni,$(CONDS)),)
$(error CONDS='$(CONDS)': expected conditions among stct st ct ni)
endif
ifneq ($(filter-out mod4 pairs,$(ORDERS)),)
$(error ORDERS='$(ORDERS)': expected orders among mod4 pairs)
endif
empty :=
ifneq ($(findstring $(empty) $(empty),$(OUT)),)
$(error OUT='$(OUT)': expected a path without white space)
endif

# a run is OUT/COND-ORDER-sSEED
RUNS := $(foreach s,$(SEEDS),$(foreach c,$(CONDS),$(foreach o,$(ORDERS),$(OUT)/$(c)-$(o)-s$(s))))
word3 = $(word $(2),$(subst -, ,$(notdir $(1))))

.PHONY: all report FORCE
.DELETE_ON_ERROR:
.SECONDARY:
.PRECIOUS: $(RUNS:%=%/population.genome) $(RUNS:%=%/robustness/summary.csv)

all: $(RUNS:%=%/robustness/summary.csv)
	@$(MAKE) --no-print-directory -f tools/order_screen.mk report OUT='$(OUT)'

report:
	@$(PYTHON) tools/order_screen_report.py '$(OUT)'

# FORCE: evolve --resume finishes a run stopped between its population and its last checkpoint
$(OUT)/%/population.genome: FORCE
	@mkdir -p '$(@D)'
	$(APPS)/evolve 'configs/integrated_$(call word3,$*,1).cfg' --seed '$(patsubst s%,%,$(call word3,$*,3))' \
	  --generations '$(GENS)' --out '$(@D)' --resume $(THREADS_ARG) \
	  --set 'integrated.trial_order=$(call word3,$*,2)' --set 'integrated.populations=$(POP)' \
	  $(EVOLVE_ARGS) >> '$(@D).log'

$(OUT)/%/robustness/summary.csv: $(OUT)/%/population.genome
	$(APPS)/posteval robustness 'configs/integrated_$(call word3,$*,1).cfg' '$(OUT)/$*' \
	  --out '$(OUT)/$*/robustness' --resume $(THREADS_ARG) $(ROB_ARGS) > /dev/null

FORCE:
