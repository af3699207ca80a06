/* SPDX-License-Identifier: MIT
 * neteval: runs the controller network of a saved genotype on input rows from stdin.
 *
 *   neteval GENOME [--arch base|A|B] [--index K] [--config FILE] [--set section.key=value]
 *
 * One input row per line (25 numbers for base, 26 for A/B with the secondary linguistic input
 * last); one output row per line (13 outputs, plus the 4 emitted linguistic values for A/B),
 * in full precision. Network state persists from line to line, as within one trial. A line is
 * at most NETEVAL_LINE_MAX bytes and holds no NUL byte (stdin is a stream, so it is read line by
 * line, bounded, not through st_text_read). */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "selftalk/genome.h"
#include "selftalk/net.h"

static const char *prog = "neteval";

/* 26 numbers at full precision take under 700 bytes; this leaves room for any spacing */
#define NETEVAL_LINE_MAX 65536

/* Reads one line of stdin into buf (NUL-terminated, newline dropped): 1 on a line, 0 at the end
 * of input; a line longer than NETEVAL_LINE_MAX bytes or holding a NUL byte is refused. */
static int read_line(char *buf, long lineno) {
  size_t n = 0;
  int ch;
  while ((ch = getchar()) != EOF && ch != '\n') {
    if (ch == 0) app_die(prog, "stdin:%ld: NUL byte at column %zu", lineno, n + 1);
    if (n == NETEVAL_LINE_MAX)
      app_die(prog, "stdin:%ld: line longer than %d bytes (expected one row of numbers)", lineno,
              NETEVAL_LINE_MAX);
    buf[n++] = (char)ch;
  }
  if (ch == EOF && ferror(stdin)) app_die(prog, "stdin:%ld: read error", lineno);
  buf[n] = 0;
  return ch != EOF || n > 0;
}

static void usage(FILE *f) {
  fprintf(f,
          "usage: neteval GENOME [--arch base|A|B] [--index K] [--config FILE] [--set s.k=v]...\n"
          "  reads input rows from stdin (25 numbers for base, 26 for A and B), prints outputs\n"
          "  (13 for base; 13 + 4 linguistic values for A and B); state persists across lines.\n"
          "  --arch defaults to the config's network.arch; --index picks a genotype of GENOME (0).\n");
}

int main(int argc, char **argv) {
  appConfigArgs ca;
  memset(&ca, 0, sizeof ca);
  const char *genome_path = NULL, *arch_name = NULL;
  int index = 0;
  for (int i = 1; i < argc; i++) {
    if (app_config_arg(&ca, argc, argv, &i, prog)) continue;
    if (!strcmp(argv[i], "--arch") && i + 1 < argc) {
      arch_name = argv[++i];
    } else if (!strcmp(argv[i], "--index") && i + 1 < argc) {
      char *end;
      long v = strtol(argv[++i], &end, 10);
      if (*end || v < 0 || v > 1000000) app_die(prog, "--index '%s': expected a non-negative integer", argv[i]);
      index = (int)v;
    } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      usage(stdout);
      return 0;
    } else if (argv[i][0] == '-' && argv[i][1]) {
      usage(stderr);
      app_die(prog, "unknown or incomplete option '%s'", argv[i]);
    } else if (!genome_path) {
      genome_path = argv[i];
    } else {
      app_die(prog, "unexpected argument '%s'", argv[i]);
    }
  }
  if (!genome_path) {
    usage(stderr);
    app_die(prog, "missing GENOME file");
  }
  stConfig cfg;
  app_config_resolve(&ca, &cfg, prog);
  int arch = cfg.network_arch;
  if (arch_name && (arch = st_arch_parse(arch_name)) < 0)
    app_die(prog, "--arch '%s': unknown architecture (expected base, A or B)", arch_name);

  char err[1024];
  stGenomeSet set;
  if (st_genome_set_read(genome_path, st_arch_ngenes((stNetArch)arch), &set, err, sizeof err))
    app_die(prog, "%s", err);
  if (index >= set.count) app_die(prog, "--index %d: %s has %d genotypes", index, genome_path, set.count);
  stNetDef def = st_net_def_from_config(&cfg);
  stNetParams params;
  if (st_net_decode(&def, (stNetArch)arch, &set.genome[index], &params, err, sizeof err))
    app_die(prog, "%s: %s", genome_path, err);
  st_genome_set_free(&set);

  stNetState state;
  st_net_reset(&params, &state);
  int nin = st_net_ninputs((stNetArch)arch), nout = st_net_noutputs((stNetArch)arch);
  double in[ST_NET_MAX_IN], out[ST_NET_MAX_OUT];
  static char line[NETEVAL_LINE_MAX + 1];
  long lineno = 0;
  while (read_line(line, lineno + 1)) {
    lineno++;
    char *p = line;
    int n = 0;
    for (;;) {
      while (isspace((unsigned char)*p)) p++;
      if (!*p) break;
      char *end;
      errno = 0;
      double v = strtod(p, &end);
      if (end == p || (*end && !isspace((unsigned char)*end)) || !isfinite(v)) {
        char *tok_end = p;
        while (*tok_end && !isspace((unsigned char)*tok_end)) tok_end++;
        *tok_end = 0;
        app_die(prog, "stdin:%ld: field %d '%s' is not a number (expected %d numbers per row)",
                lineno, n + 1, p, nin);
      }
      if (n == nin) app_die(prog, "stdin:%ld: more than %d numbers (expected %d for architecture %s)",
                            lineno, nin, nin, st_arch_name((stNetArch)arch));
      in[n++] = v;
      p = end;
    }
    if (n == 0) continue; /* blank line */
    if (n < nin)
      app_die(prog, "stdin:%ld: %d numbers (expected %d for architecture %s)", lineno, n, nin,
              st_arch_name((stNetArch)arch));
    st_net_step(&params, &state, in, out);
    for (int k = 0; k < nout; k++) printf(k ? " %.17g" : "%.17g", out[k]);
    putchar('\n');
  }
  if (fflush(stdout) || ferror(stdout)) app_die(prog, "write error on stdout");
  return 0;
}
