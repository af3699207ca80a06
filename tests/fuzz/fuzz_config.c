/* SPDX-License-Identifier: MIT
 * Fuzz target: the config reader (st_config_load's parser, lib/core/readers.h). Property: a text
 * it accepts is written back by st_config_write and reads back to the same configuration. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/readers.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  stConfig cfg, back;
  char err[2048];
  st_config_default(&cfg);
  if (st__config_parse("fuzz.cfg", (const char *)data, size, &cfg, err, sizeof err)) return 0;
  char *text = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&text, &len);
  if (!f) abort();
  if (st_config_write(f, &cfg) || fclose(f)) abort();
  st_config_default(&back);
  if (st__config_parse("written.cfg", text, len, &back, err, sizeof err)) {
    fprintf(stderr, "an accepted config does not read back: %s\n", err);
    abort();
  }
  if (memcmp(&cfg, &back, sizeof cfg)) {
    fprintf(stderr, "an accepted config reads back as another\n");
    abort();
  }
  free(text);
  return 0;
}
