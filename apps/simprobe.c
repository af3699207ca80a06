/* SPDX-License-Identifier: MIT
 * simprobe: puts the simulated iCub in a posture and prints what the library computes, so the
 * model can be checked against the real robot's numbers.
 *
 *   simprobe --deg TY,TP,SP,SR,SY,EL,WPS,WP,WY [--hand O,T,F] [--object X,Y,Z]
 *            [--config FILE] [--set section.key=value]
 *   simprobe --postures     one line per initial posture: "posture K PRIMITIVE ok|FAIL reason"
 *
 * Angles in degrees, iCub joint conventions (torso yaw, torso pitch, shoulder pitch, roll,
 * yaw, elbow, wrist pronosupination, pitch, yaw); hand DOF normalised 0..1 (thumb opposition,
 * thumb flexion, finger flexion; default 0 = open). Object: sphere centre (default P0). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app_common.h"
#include "selftalk/postures.h"
#include "selftalk/sensors.h"

static const char *prog = "simprobe";

static int parse_list(const char *s, double *v, int n) {
  char *end;
  for (int i = 0; i < n; i++) {
    v[i] = strtod(s, &end);
    if (end == s || !isfinite(v[i])) return -1;
    s = end;
    if (i < n - 1) {
      if (*s != ',') return -1;
      s++;
    }
  }
  return *s ? -1 : 0;
}

static void usage(FILE *f) {
  fprintf(f, "usage: simprobe --deg TY,TP,SP,SR,SY,EL,WPS,WP,WY [--hand O,T,F] [--object X,Y,Z]\n"
             "                [--config FILE] [--set section.key=value]...\n"
             "       simprobe --postures [--config FILE] [--set section.key=value]...\n");
}

int main(int argc, char **argv) {
  appConfigArgs ca;
  memset(&ca, 0, sizeof ca);
  const char *deg = NULL, *hand = NULL, *object = NULL;
  int postures = 0;
  for (int i = 1; i < argc; i++) {
    if (app_config_arg(&ca, argc, argv, &i, prog)) continue;
    if (!strcmp(argv[i], "--deg") && i + 1 < argc) deg = argv[++i];
    else if (!strcmp(argv[i], "--hand") && i + 1 < argc) hand = argv[++i];
    else if (!strcmp(argv[i], "--object") && i + 1 < argc) object = argv[++i];
    else if (!strcmp(argv[i], "--postures")) postures = 1;
    else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) return usage(stdout), 0;
    else {
      usage(stderr);
      app_die(prog, "unknown or incomplete option '%s'", argv[i]);
    }
  }
  if (!deg && !postures) {
    usage(stderr);
    app_die(prog, "--deg or --postures is required");
  }
  stConfig cfg;
  app_config_resolve(&ca, &cfg, prog);
  char err[1024];
  stRobot *robot = NULL;
  if (st_robot_create(&cfg, &robot, err, sizeof err)) app_die(prog, "%s", err);
  stScene scene;
  st_scene_from_config(&cfg, &scene);

  if (postures) {
    /* K = 4 primitive + k: reach 0-3, open 4-7, grasp 8-11, move 12-15 */
    int failed = 0;
    for (int prim = 0; prim < ST_NPRIM; prim++)
      for (int k = 0; k < ST_NPOSTURE; k++) {
        double q[ST_NDOF];
        char why[512];
        stStatus st = st_posture(robot, &scene, prim, k, q, why, sizeof why);
        if (!st && !st_posture_check(robot, &scene, prim, k, q, why, sizeof why)) st = ST_ERR_RANGE;
        if (st) failed++;
        printf("posture %d %s %s%s%s\n", 4 * prim + k, st_primitive_name(prim), st ? "FAIL " : "ok",
               st ? why : "", "");
      }
    st_robot_destroy(robot);
    return failed ? 1 : 0;
  }
  double a[9], h[3] = {0, 0, 0}, obj[3];
  if (parse_list(deg, a, 9)) app_die(prog, "--deg '%s': expected 9 comma-separated numbers (degrees)", deg);
  if (hand && parse_list(hand, h, 3)) app_die(prog, "--hand '%s': expected 3 comma-separated numbers in [0, 1]", hand);
  st_scene_object(&scene, 0, 0, NULL, obj);
  if (object && parse_list(object, obj, 3)) app_die(prog, "--object '%s': expected X,Y,Z in metres", object);
  double qhat[ST_NDOF];
  for (int d = 0; d < 9; d++) {
    double lo = robot->dof_lo[d] / (3.14159265358979323846 / 180), hi = robot->dof_hi[d] / (3.14159265358979323846 / 180);
    if (!(a[d] >= lo - 1e-9 && a[d] <= hi + 1e-9))
      app_die(prog, "--deg: %s = %g is outside its range [%g, %g] degrees", robot->dof_name[d], a[d], lo, hi);
    qhat[d] = st_robot_dof_qhat(robot, d, a[d] * 3.14159265358979323846 / 180);
  }
  for (int d = 0; d < 3; d++) {
    if (!(h[d] >= 0.0 && h[d] <= 1.0))
      app_die(prog, "--hand: %s = %g is outside its range [0, 1] (normalised)", robot->dof_name[9 + d], h[d]);
    qhat[9 + d] = h[d];
  }
  stWorld *w = NULL;
  if (st_world_create(robot, &scene, &w, err, sizeof err)) app_die(prog, "%s", err);
  double target[3];
  st_scene_target(&scene, 0, NULL, target);
  st_world_reset(w, qhat, obj, target);
  stSensorDef sd;
  st_sensor_def_from_config(&cfg, &sd);
  stQuantities q;
  st_quantities(w, &sd, &q);

  if (robot->ee_body >= 0) {
    const double *e = w->p[robot->ee_body];
    printf("ee %.6f %.6f %.6f\n", e[0], e[1], e[2]);
  }
  printf("palm %.6f %.6f %.6f\n", q.palm[0], q.palm[1], q.palm[2]);
  printf("palm_normal %.6f %.6f %.6f\n", q.normal[0], q.normal[1], q.normal[2]);
  static const char *tips[ST_NTIP] = {"thumb", "index", "middle", "ring", "little"};
  for (int i = 0; i < ST_NTIP; i++)
    printf("tip_%s %.6f %.6f %.6f\n", tips[i], q.tip[i][0], q.tip[i][1], q.tip[i][2]);
  printf("object %.6f %.6f %.6f\n", obj[0], obj[1], obj[2]);
  printf("h %.6f\np %.6f\n", q.h, q.p);
  printf("touch");
  for (int i = 0; i < ST_NTOUCH; i++) printf(" %d", w->contacts.touch[i]);
  printf("\ntable_contact %d\nobject_contact %d\n", w->contacts.arm_table, w->contacts.robot_object);
  printf("d_r %.6f\nd_g %.6f\nd_mhat %.6f\n", q.d_r, q.d_g, q.d_mhat);
  printf("qhat");
  for (int d = 0; d < ST_NDOF; d++) printf(" %.6f", qhat[d]);
  printf("\n");
  st_world_destroy(w);
  st_robot_destroy(robot);
  return 0;
}
