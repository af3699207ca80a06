# The apps a makefile of tools/ runs: those of the build under test, APPDIR as the top Makefile
# names it (make asan's tests run build-asan/apps; tests/run_all.sh exports APPDIR), ./apps by
# default. Included by replicate.mk, order_screen.mk and screen.mk.
APPDIR ?= apps
APPS := $(if $(filter /%,$(APPDIR)),$(APPDIR),./$(APPDIR))
