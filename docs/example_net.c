/* SPDX-License-Identifier: MIT
 * Example: link the network and the GA alone (libselftalk-core, no simulator) into your own
 * program. A toy task stands in for the robot: evolve a network whose 12 joint outputs match a
 * target posture whatever the focus input. Build against an installed copy with
 *
 *   cc example_net.c $(pkg-config --cflags --libs selftalk-core) -o example_net
 *
 * (or `--libs selftalk` for the whole library). Prints one line per generation. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <selftalk/selftalk.h>

/* mean squared distance of the joint outputs from a target posture over a few focus inputs */
static double toy_fitness(const stNetParams *p) {
  double err = 0.0;
  for (int trial = 0; trial < 4; trial++) {
    stNetState s;
    st_net_reset(p, &s);
    double in[ST_NET_NIN] = {0}, out[ST_NET_NOUT];
    in[ST_NET_IN_FOCUS + trial % 3] = trial < 2 ? 1.0 : -1.0;
    in[ST_NET_IN_LING] = 10.0; /* the word "reach" */
    st_net_step(p, &s, in, out);
    for (int k = 0; k < ST_NET_NDOF; k++) {
      double target = 0.2 + 0.05 * k;
      err += (out[k] - target) * (out[k] - target);
    }
  }
  return -err / 4.0; /* higher is better */
}

int main(int argc, char **argv) {
  int generations = argc > 1 ? atoi(argv[1]) : 30;
  stGaDef def = st_ga_default_def(); /* the thesis's GA: 100 genotypes, 10 elites, 20 parents */
  def.seed = 2024;
  def.mutation_rate = 0.005;
  stGa *ga = NULL;
  char err[256];
  if (st_ga_create(&def, NULL, 0, NULL, &ga, err, sizeof err)) {
    fprintf(stderr, "example_net: %s\n", err);
    return 1;
  }
  double fitness[100];
  for (int gen = 0; gen < generations; gen++) {
    for (int i = 0; i < def.population; i++) { /* evaluation could run anywhere: ask/tell */
      stNetParams p;
      st_net_decode(NULL, ST_ARCH_BASE, st_ga_genome(ga, i), &p, NULL, 0);
      fitness[i] = toy_fitness(&p);
    }
    st_ga_tell(ga, fitness);
    double best = fitness[st_ga_ranked(ga, 0)], mean = 0.0;
    for (int i = 0; i < def.population; i++) mean += fitness[i] / def.population;
    printf("generation %3d  best %9.5f  mean %9.5f\n", gen, best, mean);
    st_ga_next(ga);
  }
  st_ga_destroy(ga);
  return 0;
}
