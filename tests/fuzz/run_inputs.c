/* SPDX-License-Identifier: MIT
 * A fuzz target without libFuzzer: runs LLVMFuzzerTestOneInput once on each file named on the
 * command line, so a target's property is checked by make test on its seeds and regressions
 * with the default compiler (build/page_check: tests/check_html.sh). A failed property aborts. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int main(int argc, char **argv) {
  for (int i = 1; i < argc; i++) {
    FILE *f = fopen(argv[i], "rb");
    if (!f) {
      perror(argv[i]);
      return 2;
    }
    static uint8_t buf[1 << 22];
    const size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    /* a copy of exactly n bytes, so ASan sees a read past the input */
    uint8_t *in = malloc(n ? n : 1);
    if (!in) return 2;
    for (size_t k = 0; k < n; k++) in[k] = buf[k];
    LLVMFuzzerTestOneInput(in, n);
    free(in);
  }
  printf("%d inputs\n", argc - 1);
  return 0;
}
