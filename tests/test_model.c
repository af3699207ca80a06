/* SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdlib.h>
#include <sys/stat.h>

#include "selftalk/model.h"
#include "test_util.h"

#define HALF_PI "1.5707963267948966"
#define TOL 1e-9

static const double IDENT[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double ZERO9[9] = {0};
static const double ZERO3[3] = {0};
/* rpy (0, 0, pi/2) = Rz(90 deg): x -> y, y -> -x */
static const double RZ90[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
/* rpy (pi/2, 0, 0) = Rx(90 deg): y -> z, z -> -y */
static const double RX90[9] = {1, 0, 0, 0, 0, -1, 0, 1, 0};
/* rpy (pi/2, 0, pi/2) = Rz(90) Rx(90) (URDF: roll first, about fixed axes) */
static const double RZX90[9] = {0, 0, 1, 1, 0, 0, 0, 1, 0};

static int near_n(const double *got, const double *want, int n, double tol) {
  for (int i = 0; i < n; i++)
    if (!(fabs(got[i] - want[i]) <= tol)) {
      fprintf(stderr, "\n  element %d: got %.17g, expected %.17g\n", i, got[i], want[i]);
      return 0;
    }
  return 1;
}
#define ASSERT_VEC3(got, ...)                          \
  do {                                                 \
    const double want_[3] = {__VA_ARGS__};             \
    CU_ASSERT(near_n((got), want_, 3, TOL));           \
  } while (0)
#define ASSERT_MAT(got, want) CU_ASSERT(near_n((got), (want), 9, TOL))

/* writes dir/name; returns the path in buf */
static const char *write_in(char *buf, size_t n, const char *dir, const char *name,
                            const char *text) {
  snprintf(buf, n, "%s/%s", dir, name);
  FILE *f = fopen(buf, "w");
  CU_ASSERT_PTR_NOT_NULL_FATAL(f);
  fputs(text, f);
  fclose(f);
  return buf;
}

/* ---- (a) a hand-written tree: every field against numbers derived by hand ---- */

/* The transmission and the comment name joints in another order: only the top-level <joint>
 * elements decide the order of torso's children (j_rev before j_mimic, not alphabetical). */
static const char *TREE_URDF =
    "<?xml version=\"1.0\"?>\n"
    "<!-- <joint name=\"j_mimic\" type=\"fixed\"/> -->\n"
    "<robot name=\"tree\">\n"
    "  <transmission name=\"tr\"><type>simple</type>\n"
    "    <joint name=\"j_mimic\"><hardwareInterface>x</hardwareInterface></joint>\n"
    "    <actuator name=\"m\"/></transmission>\n"
    "  <link name=\"base_link\">\n"
    "    <inertial>\n"
    "      <origin xyz=\"0.1 0 0\" rpy=\"0 0 " HALF_PI "\"/>\n"
    "      <mass value=\"2\"/>\n"
    "      <inertia ixx=\"1\" ixy=\"0.1\" ixz=\"0\" iyy=\"2\" iyz=\"0\" izz=\"3\"/>\n"
    "    </inertial>\n"
    "    <visual><geometry><box size=\"9 9 9\"/></geometry></visual>\n"
    "    <collision><origin xyz=\"0 0 0.05\"/><geometry><box size=\"0.1 0.2 0.3\"/></geometry>"
    "</collision>\n"
    "    <collision><origin xyz=\"0.01 0.02 0.03\" rpy=\"" HALF_PI " 0 0\"/>"
    "<geometry><sphere radius=\"0.04\"/></geometry></collision>\n"
    "  </link>\n"
    "  <joint name=\"j_fixed\" type=\"fixed\">\n"
    "    <parent link=\"base_link\"/><child link=\"torso\"/>\n"
    "    <origin xyz=\"0 0 0.5\"/>\n"
    "  </joint>\n"
    "  <link name=\"torso\">\n"
    "    <collision><origin xyz=\"0 0 0.2\" rpy=\"" HALF_PI " 0 0\"/>"
    "<geometry><cylinder radius=\"0.05\" length=\"0.4\"/></geometry></collision>\n"
    "  </link>\n"
    "  <joint name=\"j_rev\" type=\"revolute\">\n"
    "    <parent link=\"torso\"/><child link=\"upper_arm\"/>\n"
    "    <origin xyz=\"0.1 0 0\" rpy=\"0 0 " HALF_PI "\"/>\n"
    "    <axis xyz=\"0 0 2\"/>\n"
    "    <limit lower=\"-1\" upper=\"1.5\" effort=\"10\" velocity=\"2\"/>\n"
    "  </joint>\n"
    "  <link name=\"upper_arm\">\n"
    "    <inertial><origin xyz=\"0 0 0.1\"/><mass value=\"1\"/>"
    "<inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.02\" iyz=\"0\" izz=\"0.03\"/></inertial>\n"
    "    <collision><geometry><sphere radius=\"0.03\"/></geometry></collision>\n"
    "  </link>\n"
    "  <joint name=\"j_cont\" type=\"continuous\">\n"
    "    <parent link=\"upper_arm\"/><child link=\"forearm\"/>\n"
    "    <origin xyz=\"0 0 0.3\" rpy=\"" HALF_PI " 0 " HALF_PI "\"/>\n"
    "    <axis xyz=\"1 0 0\"/>\n"
    "    <limit effort=\"5\" velocity=\"3\"/>\n"
    "  </joint>\n"
    "  <link name=\"forearm\"/>\n"
    "  <joint name=\"j_mimic\" type=\"revolute\">\n"
    "    <parent link=\"torso\"/><child link=\"finger\"/>\n"
    "    <origin xyz=\"0 0.05 0\"/>\n"
    "    <axis xyz=\"0 1 0\"/>\n"
    "    <limit lower=\"-0.5\" upper=\"0.5\" effort=\"1\" velocity=\"1\"/>\n"
    "    <mimic joint=\"j_rev\" multiplier=\"0.5\" offset=\"0.1\"/>\n"
    "  </joint>\n"
    "  <link name=\"finger\"/>\n"
    "</robot>\n";

static void test_model_tree(void) {
  char path[256], err[512] = "";
  stModel *m = NULL;
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp(path, sizeof path, ".urdf", TREE_URDF));
  stStatus st = st_model_load_urdf(path, &m, err, sizeof err);
  if (st != ST_OK) fprintf(stderr, "\n  %s\n", err);
  CU_ASSERT_EQUAL_FATAL(st, ST_OK);
  CU_ASSERT_PTR_NOT_NULL_FATAL(m);
  CU_ASSERT_PTR_EQUAL(m->buffer_, m); /* the struct lives in its one allocation */

  CU_ASSERT_EQUAL(m->nbody, 5);
  CU_ASSERT_EQUAL(m->ngeom, 4);
  CU_ASSERT_EQUAL(m->nvert, 0);
  CU_ASSERT_EQUAL(m->ntri, 0);

  /* depth-first, children in document order: finger (j_mimic, after j_rev) comes last */
  const char *names[5] = {"base_link", "torso", "upper_arm", "forearm", "finger"};
  const int parents[5] = {-1, 0, 1, 2, 1};
  for (int b = 0; b < 5; b++) {
    CU_ASSERT_STRING_EQUAL(m->body_name[b], names[b]);
    CU_ASSERT_EQUAL(m->body_parent[b], parents[b]);
    CU_ASSERT_EQUAL(st_model_body(m, names[b]), b);
  }

  /* inertia: base_link's inertial frame is Rz(90); I' = R I R^T swaps x and y and negates
   * ixy: [[1,.1,0],[.1,2,0],[0,0,3]] -> [[2,-.1,0],[-.1,1,0],[0,0,3]] */
  const double base_inertia[9] = {2, -0.1, 0, -0.1, 1, 0, 0, 0, 3};
  const double arm_inertia[9] = {0.01, 0, 0, 0, 0.02, 0, 0, 0, 0.03};
  CU_ASSERT_DOUBLE_EQUAL(m->body_mass[0], 2.0, 0.0);
  ASSERT_VEC3(m->body_com[0], 0.1, 0, 0);
  ASSERT_MAT(m->body_inertia[0], base_inertia);
  CU_ASSERT_DOUBLE_EQUAL(m->body_mass[1], 0.0, 0.0); /* no <inertial> */
  CU_ASSERT(near_n(m->body_com[1], ZERO3, 3, 0.0));
  CU_ASSERT(near_n(m->body_inertia[1], ZERO9, 9, 0.0));
  CU_ASSERT_DOUBLE_EQUAL(m->body_mass[2], 1.0, 0.0);
  ASSERT_VEC3(m->body_com[2], 0, 0, 0.1);
  ASSERT_MAT(m->body_inertia[2], arm_inertia);
  for (int b = 3; b < 5; b++) {
    CU_ASSERT_DOUBLE_EQUAL(m->body_mass[b], 0.0, 0.0);
    CU_ASSERT(near_n(m->body_inertia[b], ZERO9, 9, 0.0));
  }

  /* entry 0: no joint */
  CU_ASSERT_STRING_EQUAL(m->jnt_name[0], "");
  CU_ASSERT_EQUAL(m->jnt_mimic[0], -1);

  /* 1: j_fixed */
  CU_ASSERT_STRING_EQUAL(m->jnt_name[1], "j_fixed");
  CU_ASSERT_EQUAL(m->jnt_type[1], ST_JOINT_FIXED);
  ASSERT_VEC3(m->jnt_pos[1], 0, 0, 0.5);
  ASSERT_MAT(m->jnt_rot[1], IDENT);
  CU_ASSERT(near_n(m->jnt_axis[1], ZERO3, 3, 0.0));
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_range[1][0], 0.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_range[1][1], 0.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_effort[1], 0.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_velocity[1], 0.0, 0.0);
  CU_ASSERT_EQUAL(m->jnt_mimic[1], -1);

  /* 2: j_rev, rpy (0,0,pi/2), axis (0,0,2) normalised */
  CU_ASSERT_STRING_EQUAL(m->jnt_name[2], "j_rev");
  CU_ASSERT_EQUAL(m->jnt_type[2], ST_JOINT_REVOLUTE);
  ASSERT_VEC3(m->jnt_pos[2], 0.1, 0, 0);
  ASSERT_MAT(m->jnt_rot[2], RZ90);
  ASSERT_VEC3(m->jnt_axis[2], 0, 0, 1);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_range[2][0], -1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_range[2][1], 1.5, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_effort[2], 10.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_velocity[2], 2.0, 0.0);
  CU_ASSERT_EQUAL(m->jnt_mimic[2], -1);

  /* 3: j_cont, continuous -> revolute without limits, rpy (pi/2,0,pi/2) = Rz(90) Rx(90) */
  CU_ASSERT_STRING_EQUAL(m->jnt_name[3], "j_cont");
  CU_ASSERT_EQUAL(m->jnt_type[3], ST_JOINT_REVOLUTE);
  ASSERT_VEC3(m->jnt_pos[3], 0, 0, 0.3);
  ASSERT_MAT(m->jnt_rot[3], RZX90);
  ASSERT_VEC3(m->jnt_axis[3], 1, 0, 0);
  CU_ASSERT(isinf(m->jnt_range[3][0]) && m->jnt_range[3][0] < 0);
  CU_ASSERT(isinf(m->jnt_range[3][1]) && m->jnt_range[3][1] > 0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_effort[3], 5.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_velocity[3], 3.0, 0.0);
  CU_ASSERT_EQUAL(m->jnt_mimic[3], -1);

  /* 4: j_mimic follows j_rev, whose child upper_arm is body 2 */
  CU_ASSERT_STRING_EQUAL(m->jnt_name[4], "j_mimic");
  CU_ASSERT_EQUAL(m->jnt_type[4], ST_JOINT_REVOLUTE);
  ASSERT_VEC3(m->jnt_pos[4], 0, 0.05, 0);
  ASSERT_MAT(m->jnt_rot[4], IDENT);
  ASSERT_VEC3(m->jnt_axis[4], 0, 1, 0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_range[4][0], -0.5, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_range[4][1], 0.5, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_effort[4], 1.0, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_velocity[4], 1.0, 0.0);
  CU_ASSERT_EQUAL(m->jnt_mimic[4], 2);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_mimic_mult[4], 0.5, 0.0);
  CU_ASSERT_DOUBLE_EQUAL(m->jnt_mimic_offset[4], 0.1, 0.0);

  /* geoms: base_link's two (visual ignored), torso's cylinder, upper_arm's sphere */
  CU_ASSERT_EQUAL(m->geom_body[0], 0);
  CU_ASSERT_EQUAL(m->geom_type[0], ST_GEOM_BOX);
  ASSERT_VEC3(m->geom_size[0], 0.1, 0.2, 0.3);
  ASSERT_VEC3(m->geom_pos[0], 0, 0, 0.05);
  ASSERT_MAT(m->geom_rot[0], IDENT);

  CU_ASSERT_EQUAL(m->geom_body[1], 0);
  CU_ASSERT_EQUAL(m->geom_type[1], ST_GEOM_SPHERE);
  CU_ASSERT_DOUBLE_EQUAL(m->geom_size[1][0], 0.04, 0.0);
  ASSERT_VEC3(m->geom_pos[1], 0.01, 0.02, 0.03);
  ASSERT_MAT(m->geom_rot[1], RX90);

  CU_ASSERT_EQUAL(m->geom_body[2], 1);
  CU_ASSERT_EQUAL(m->geom_type[2], ST_GEOM_CYLINDER);
  ASSERT_VEC3(m->geom_size[2], 0.05, 0.4, 0);
  ASSERT_VEC3(m->geom_pos[2], 0, 0, 0.2);
  ASSERT_MAT(m->geom_rot[2], RX90);

  CU_ASSERT_EQUAL(m->geom_body[3], 2);
  CU_ASSERT_EQUAL(m->geom_type[3], ST_GEOM_SPHERE);
  CU_ASSERT_DOUBLE_EQUAL(m->geom_size[3][0], 0.03, 0.0);
  ASSERT_VEC3(m->geom_pos[3], 0, 0, 0);
  ASSERT_MAT(m->geom_rot[3], IDENT);
  for (int g = 0; g < 4; g++) CU_ASSERT_EQUAL(m->geom_nvert[g] + m->geom_ntri[g], 0);

  /* look-ups */
  CU_ASSERT_EQUAL(st_model_joint(m, "j_fixed"), 1);
  CU_ASSERT_EQUAL(st_model_joint(m, "j_mimic"), 4);
  CU_ASSERT_EQUAL(st_model_joint(m, ""), -1); /* the root's empty entry is not a joint */
  CU_ASSERT_EQUAL(st_model_joint(m, "base_link"), -1);
  CU_ASSERT_EQUAL(st_model_body(m, "j_rev"), -1);
  CU_ASSERT_EQUAL(st_model_body(m, "nope"), -1);
  st_model_destroy(m);
  st_model_destroy(NULL);
}

/* ---- (b) meshes written by the test: OBJ, ASCII STL and COLLADA with node transforms ---- */

/* outward-facing tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1) */
static const char *TET_OBJ =
    "# tetrahedron\n"
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

/* a triangle instanced by a node translated by (10,0,0) and by its child, translated by
 * a further (0,5,0); Z_UP must not be turned into Y-up */
static const char *TRI_DAE =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
    "  <asset><unit name=\"meter\" meter=\"1\"/><up_axis>Z_UP</up_axis></asset>\n"
    "  <library_geometries><geometry id=\"tri\" name=\"tri\"><mesh>\n"
    "    <source id=\"tri-pos\"><float_array id=\"tri-pos-array\" count=\"9\">"
    "0 0 0 1 0 0 0 1 0</float_array>\n"
    "      <technique_common><accessor source=\"#tri-pos-array\" count=\"3\" stride=\"3\">"
    "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
    "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source>\n"
    "    <vertices id=\"tri-vtx\"><input semantic=\"POSITION\" source=\"#tri-pos\"/></vertices>\n"
    "    <triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#tri-vtx\" offset=\"0\"/>"
    "<p>0 1 2</p></triangles>\n"
    "  </mesh></geometry></library_geometries>\n"
    "  <library_visual_scenes><visual_scene id=\"scene\">\n"
    "    <node id=\"a\" name=\"a\"><translate>10 0 0</translate><instance_geometry url=\"#tri\"/>\n"
    "      <node id=\"b\" name=\"b\"><translate>0 5 0</translate>"
    "<instance_geometry url=\"#tri\"/></node>\n"
    "    </node>\n"
    "  </visual_scene></library_visual_scenes>\n"
    "  <scene><instance_visual_scene url=\"#scene\"/></scene>\n"
    "</COLLADA>\n";

/* unit cube [0,1]^3 as an ASCII STL of 12 outward triangles */
static void cube_stl(char *buf, size_t n) {
  static const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  size_t len = (size_t)snprintf(buf, n, "solid cube\n");
  for (int q = 0; q < 6; q++)
    for (int t = 0; t < 2; t++) {
      int c[3] = {quads[q][0], quads[q][t + 1], quads[q][t + 2]};
      len += (size_t)snprintf(buf + len, n - len, "facet normal 0 0 0\nouter loop\n");
      for (int k = 0; k < 3; k++)
        len += (size_t)snprintf(buf + len, n - len, "vertex %d %d %d\n", c[k] & 1,
                                (c[k] >> 1) & 1, (c[k] >> 2) & 1);
      len += (size_t)snprintf(buf + len, n - len, "endloop\nendfacet\n");
    }
  snprintf(buf + len, n - len, "endsolid cube\n");
}

/* is (x,y,z) among geom g's vertices? */
static int has_vert(const stModel *m, int g, double x, double y, double z) {
  for (int v = 0; v < m->geom_nvert[g]; v++) {
    const double *p = m->mesh_vert[m->geom_vert0[g] + v];
    if (fabs(p[0] - x) < 1e-6 && fabs(p[1] - y) < 1e-6 && fabs(p[2] - z) < 1e-6) return 1;
  }
  fprintf(stderr, "\n  geom %d: no vertex (%g, %g, %g)\n", g, x, y, z);
  return 0;
}

/* indices in range and distinct; returns the signed volume enclosed by the triangles */
static double check_tris(const stModel *m, int g) {
  double vol = 0;
  for (int t = 0; t < m->geom_ntri[g]; t++) {
    const int *tri = m->mesh_tri[m->geom_tri0[g] + t];
    for (int k = 0; k < 3; k++) CU_ASSERT(tri[k] >= 0 && tri[k] < m->geom_nvert[g]);
    CU_ASSERT(tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2]);
    const double *a = m->mesh_vert[m->geom_vert0[g] + tri[0]];
    const double *b = m->mesh_vert[m->geom_vert0[g] + tri[1]];
    const double *c = m->mesh_vert[m->geom_vert0[g] + tri[2]];
    vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
            a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
  }
  return vol;
}

static void test_model_mesh(void) {
  char dir[256], sub[300], path[400], cube_path[400], urdf[3000], stl[4096], err[512] = "";
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_tmpdir(dir, sizeof dir));
  snprintf(sub, sizeof sub, "%s/meshes", dir);
  CU_ASSERT_EQUAL_FATAL(mkdir(sub, 0777), 0);
  write_in(path, sizeof path, dir, "meshes/tet.obj", TET_OBJ);
  cube_stl(stl, sizeof stl);
  write_in(cube_path, sizeof cube_path, dir, "cube.stl", stl);
  write_in(path, sizeof path, dir, "tri.dae", TRI_DAE);
  snprintf(urdf, sizeof urdf,
           "<robot name=\"meshy\">\n"
           "  <link name=\"base\">\n"
           "    <collision><origin xyz=\"1 0 0\" rpy=\"0 0 " HALF_PI "\"/>\n"
           "      <geometry><mesh filename=\"meshes/tet.obj\" scale=\"2 3 4\"/></geometry>"
           "</collision>\n"
           "    <collision><geometry><mesh filename=\"meshes/tet.obj\" scale=\"-1 1 1\"/>"
           "</geometry></collision>\n"
           "  </link>\n"
           "  <joint name=\"j\" type=\"fixed\"><parent link=\"base\"/><child link=\"b\"/></joint>\n"
           "  <link name=\"b\">\n"
           "    <collision><geometry><mesh filename=\"file://%s\"/></geometry></collision>\n"
           "    <collision><geometry><mesh filename=\"tri.dae\" scale=\"2 1 1\"/></geometry>"
           "</collision>\n"
           "  </link>\n"
           "</robot>\n",
           cube_path);
  write_in(path, sizeof path, dir, "robot.urdf", urdf);

  stModel *m = NULL;
  stStatus st = st_model_load_urdf(path, &m, err, sizeof err);
  if (st != ST_OK) fprintf(stderr, "\n  %s\n", err);
  CU_ASSERT_EQUAL_FATAL(st, ST_OK);
  CU_ASSERT_EQUAL(m->nbody, 2);
  CU_ASSERT_EQUAL_FATAL(m->ngeom, 4);
  for (int g = 0; g < 4; g++) CU_ASSERT_EQUAL(m->geom_type[g], ST_GEOM_MESH);
  const int body[4] = {0, 0, 1, 1}, nvert[4] = {4, 4, 8, 6}, ntri[4] = {4, 4, 12, 2};
  int v0 = 0, t0 = 0;
  for (int g = 0; g < 4; g++) {
    CU_ASSERT_EQUAL(m->geom_body[g], body[g]);
    CU_ASSERT_EQUAL(m->geom_vert0[g], v0);
    CU_ASSERT_EQUAL(m->geom_nvert[g], nvert[g]);
    CU_ASSERT_EQUAL(m->geom_tri0[g], t0);
    CU_ASSERT_EQUAL(m->geom_ntri[g], ntri[g]);
    v0 += nvert[g];
    t0 += ntri[g];
  }
  CU_ASSERT_EQUAL(m->nvert, 22);
  CU_ASSERT_EQUAL(m->ntri, 22);
  if (m->nvert != 22 || m->ntri != 22) {
    st_model_destroy(m);
    return;
  }

  /* tetrahedron scaled (2,3,4), in its geom frame (the origin pose is kept apart) */
  ASSERT_VEC3(m->geom_pos[0], 1, 0, 0);
  ASSERT_MAT(m->geom_rot[0], RZ90);
  CU_ASSERT(has_vert(m, 0, 0, 0, 0));
  CU_ASSERT(has_vert(m, 0, 2, 0, 0));
  CU_ASSERT(has_vert(m, 0, 0, 3, 0));
  CU_ASSERT(has_vert(m, 0, 0, 0, 4));
  CU_ASSERT_DOUBLE_EQUAL(check_tris(m, 0), 2.0 * 3.0 * 4.0 / 6.0, 1e-6);

  /* mirrored: x negated, triangles re-wound so they still face outwards */
  CU_ASSERT(has_vert(m, 1, -1, 0, 0));
  CU_ASSERT(has_vert(m, 1, 0, 1, 0));
  CU_ASSERT(has_vert(m, 1, 0, 0, 1));
  CU_ASSERT_DOUBLE_EQUAL(check_tris(m, 1), 1.0 / 6.0, 1e-6);

  /* STL corners joined into 8 vertices */
  for (int c = 0; c < 8; c++) CU_ASSERT(has_vert(m, 2, c & 1, (c >> 1) & 1, (c >> 2) & 1));
  CU_ASSERT_DOUBLE_EQUAL(check_tris(m, 2), 1.0, 1e-6);

  /* COLLADA: node transforms compose, then the URDF scale (2,1,1) */
  CU_ASSERT(has_vert(m, 3, 20, 0, 0));
  CU_ASSERT(has_vert(m, 3, 22, 0, 0));
  CU_ASSERT(has_vert(m, 3, 20, 1, 0));
  CU_ASSERT(has_vert(m, 3, 20, 5, 0));
  CU_ASSERT(has_vert(m, 3, 22, 5, 0));
  CU_ASSERT(has_vert(m, 3, 20, 6, 0));
  check_tris(m, 3);
  st_model_destroy(m);
}

/* ---- (c) errors: status, the file and the element in one line ---- */

/* loads text written as dir/name; asserts the status and that the message holds the path
 * and each needle */
static void expect_error(const char *dir, const char *name, const char *text, stStatus want,
                         const char *needle1, const char *needle2) {
  char path[400], err[512] = "";
  stModel *m = (stModel *)&m; /* must be reset to NULL */
  write_in(path, sizeof path, dir, name, text);
  stStatus st = st_model_load_urdf(path, &m, err, sizeof err);
  if (st != want) fprintf(stderr, "\n  %s: status %d, expected %d: %s\n", name, st, want, err);
  CU_ASSERT_EQUAL(st, want);
  CU_ASSERT_PTR_NULL(m);
  ST_ASSERT_CONTAINS(err, path);
  if (needle1) ST_ASSERT_CONTAINS(err, needle1);
  if (needle2) ST_ASSERT_CONTAINS(err, needle2);
  CU_ASSERT_PTR_NULL(strchr(err, '\n'));
}

#define ROBOT1(link_body) \
  "<robot name=\"r\"><link name=\"a\">" link_body "</link></robot>\n"
#define ROBOT2(joint)                                                                     \
  "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" " joint \
  "</joint></robot>\n"

static void test_model_errors(void) {
  char dir[256], path[400], err[512] = "";
  stModel *m = (stModel *)&m;
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_tmpdir(dir, sizeof dir));

  /* missing file */
  snprintf(path, sizeof path, "%s/nope.urdf", dir);
  CU_ASSERT_EQUAL(st_model_load_urdf(path, &m, err, sizeof err), ST_ERR_IO);
  CU_ASSERT_PTR_NULL(m);
  ST_ASSERT_CONTAINS(err, path);
  ST_ASSERT_CONTAINS(err, "cannot open: No such file or directory");
  CU_ASSERT_EQUAL(st_model_load_urdf(path, &m, NULL, 0), ST_ERR_IO); /* err is nullable */

  /* malformed XML, and a value urdfdom logs as an error yet would otherwise drop */
  expect_error(dir, "bad_xml.urdf", "<robot name=\"r\"><link name=\"a\"></robot>\n",
               ST_ERR_PARSE, "malformed URDF", "end tag");
  expect_error(dir, "empty.urdf", "", ST_ERR_PARSE, "malformed URDF", NULL);
  expect_error(dir, "bad_box.urdf",
               ROBOT1("<collision><geometry><box size=\"1 x 2\"/></geometry></collision>"),
               ST_ERR_PARSE, "malformed URDF", "collision element for Link [a]");

  /* unsupported or inconsistent content */
  expect_error(dir, "prismatic.urdf",
               ROBOT2("type=\"prismatic\"><parent link=\"a\"/><child link=\"b\"/>"
                      "<limit lower=\"0\" upper=\"1\" effort=\"1\" velocity=\"1\"/>"),
               ST_ERR_MODEL,
               "joint 'j': type prismatic not supported (expected revolute, continuous or fixed)",
               NULL);
  expect_error(dir, "floating.urdf",
               ROBOT2("type=\"floating\"><parent link=\"a\"/><child link=\"b\"/>"), ST_ERR_MODEL,
               "joint 'j': type floating not supported", NULL);
  expect_error(dir, "ghost.urdf",
               ROBOT2("type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/>"
                      "<mimic joint=\"ghost\"/>"),
               ST_ERR_MODEL, "joint 'j': mimic joint 'ghost'", "no such joint");
  expect_error(dir, "zero_axis.urdf",
               ROBOT2("type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/>"
                      "<axis xyz=\"0 0 0\"/>"),
               ST_ERR_MODEL, "joint 'j': axis is zero", NULL);
  expect_error(dir, "limits.urdf",
               ROBOT2("type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>"
                      "<limit lower=\"1\" upper=\"-1\" effort=\"1\" velocity=\"1\"/>"),
               ST_ERR_MODEL, "joint 'j': limit", "lower <= upper");

  /* meshes */
  expect_error(dir, "no_mesh.urdf",
               ROBOT1("<collision><geometry><mesh filename=\"missing.stl\"/></geometry>"
                      "</collision>"),
               ST_ERR_IO, "link 'a': collision mesh 'missing.stl': cannot read",
               "No such file or directory");
  expect_error(dir, "package.urdf",
               ROBOT1("<collision><geometry><mesh filename=\"package://robot/m.stl\"/>"
                      "</geometry></collision>"),
               ST_ERR_MODEL, "link 'a': collision mesh 'package://robot/m.stl'",
               "package:// URIs are not supported");
  write_in(path, sizeof path, dir, "junk.stl", "solid junk\nthis is not a mesh\n");
  expect_error(dir, "junk_mesh.urdf",
               ROBOT1("<collision><geometry><mesh filename=\"junk.stl\"/></geometry>"
                      "</collision>"),
               ST_ERR_PARSE, "link 'a': collision mesh 'junk.stl': cannot read (assimp: ", NULL);
}

/* ---- (d) what the world cannot simulate, refused at load time (issue 17) ---- */

#define INERTIAL(mass, ixx, iyy, izz) \
  "<inertial><mass value=\"" mass "\"/><inertia ixx=\"" ixx "\" ixy=\"0\" ixz=\"0\" iyy=\"" iyy \
  "\" iyz=\"0\" izz=\"" izz "\"/></inertial>"
#define COLLISION(geom) "<collision><geometry>" geom "</geometry></collision>"
#define FIXED_AT(xyz) \
  "type=\"fixed\"><origin xyz=\"" xyz "\"/><parent link=\"a\"/><child link=\"b\"/>"
#define REVOLUTE(limit) \
  "type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><limit " limit "/>"

static void test_model_unsimulable(void) {
  char dir[256];
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_tmpdir(dir, sizeof dir));
  /* degenerate shapes: a zero-length cylinder aborted the process inside libccd */
  expect_error(dir, "cyl_len0.urdf", ROBOT1(COLLISION("<cylinder radius=\"0.01\" length=\"0\"/>")),
               ST_ERR_MODEL, "link 'a': collision 1: cylinder length 0 (expected 1e-06..10 m)", NULL);
  expect_error(dir, "cyl_r.urdf", ROBOT1(COLLISION("<cylinder radius=\"-0.01\" length=\"0.1\"/>")),
               ST_ERR_MODEL, "link 'a': collision 1: cylinder radius -0.01 (expected 1e-06..10 m)", NULL);
  expect_error(dir, "box0.urdf", ROBOT1(COLLISION("<box size=\"0.1 0 0.1\"/>")), ST_ERR_MODEL,
               "link 'a': collision 1: box size y 0 (expected 1e-06..10 m)", NULL);
  expect_error(dir, "sphere_tiny.urdf", ROBOT1(COLLISION("<sphere radius=\"1e-9\"/>")), ST_ERR_MODEL,
               "link 'a': collision 1: sphere radius 1e-09 (expected 1e-06..10 m)", NULL);
  expect_error(dir, "sphere_big.urdf", ROBOT1(COLLISION("<sphere radius=\"11\"/>")), ST_ERR_MODEL,
               "link 'a': collision 1: sphere radius 11 (expected 1e-06..10 m)", NULL);
  /* masses and inertias: 1e308 kg aborted ODE (dxNormalize4); zero mass and a tensor that is
   * not positive definite failed only at the first dynamic evaluation, without the file */
  expect_error(dir, "mass_huge.urdf", ROBOT1(INERTIAL("1e308", "1", "1", "1")), ST_ERR_MODEL,
               "link 'a': inertial: mass 1e+308 kg (expected 1e-06..1000 kg)", NULL);
  expect_error(dir, "mass0.urdf", ROBOT1(INERTIAL("0", "1e-4", "1e-4", "1e-4")), ST_ERR_MODEL,
               "link 'a': inertial: mass 0 kg (expected 1e-06..1000 kg)", NULL);
  expect_error(dir, "inertia_npd.urdf", ROBOT1(INERTIAL("1", "1e-3", "-1e-3", "1e-3")), ST_ERR_MODEL,
               "link 'a': inertial: inertia is not positive definite (principal moments -0.001, "
               "0.001, 0.001 kg m^2; expected all > 0)", NULL);
  /* principal moments 1, 1, 3: 1 + 1 < 3, no rigid body has them */
  expect_error(dir, "inertia_tri.urdf", ROBOT1(INERTIAL("1", "1", "1", "3")), ST_ERR_MODEL,
               "link 'a': inertial: inertia breaks the triangle inequality (principal moments 1, "
               "1, 3 kg m^2; expected the largest <= the sum of the other two)", NULL);
  expect_error(dir, "inertia_big.urdf", ROBOT1(INERTIAL("1", "2000", "2000", "2000")), ST_ERR_MODEL,
               "link 'a': inertial: inertia too large", "expected at most 1000 kg m^2");
  /* transforms: 1e308 is finite, and simprobe printed nan with exit 0 */
  expect_error(dir, "origin_huge.urdf", ROBOT2(FIXED_AT("1e308 0 0")), ST_ERR_MODEL,
               "joint 'j': origin xyz (1e+308, 0, 0) is farther than 10 m (expected |xyz| <= 10 m)",
               NULL);
  expect_error(dir, "origin_11.urdf", ROBOT2(FIXED_AT("0 6 9")), ST_ERR_MODEL,
               "joint 'j': origin xyz (0, 6, 9) is farther than 10 m", NULL);
  expect_error(dir, "col_origin.urdf",
               ROBOT1("<collision><origin xyz=\"0 0 -20\"/><geometry><sphere radius=\"0.1\"/>"
                      "</geometry></collision>"),
               ST_ERR_MODEL, "link 'a': collision 1: origin xyz (0, 0, -20) is farther than 10 m", NULL);
  /* limits in degrees, not radians; an effort no motor has */
  expect_error(dir, "limit_deg.urdf", ROBOT2(REVOLUTE("lower=\"-90\" upper=\"90\" effort=\"1\" velocity=\"1\"")),
               ST_ERR_MODEL, "joint 'j': limit lower -90, upper 90 (expected radians in -2 pi..2 pi", NULL);
  expect_error(dir, "effort.urdf", ROBOT2(REVOLUTE("lower=\"0\" upper=\"1\" effort=\"1e308\" velocity=\"1\"")),
               ST_ERR_MODEL, "joint 'j': limit effort 1e+308, velocity 1 (expected effort in 0..10000 N m", NULL);
  expect_error(dir, "axis_huge.urdf",
               ROBOT2("type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/>"
                      "<axis xyz=\"1e308 1e308 0\"/>"),
               ST_ERR_MODEL, "joint 'j': axis is not finite", NULL);
  /* loops of joints: urdfdom leaked the links of a loop (a shared_ptr cycle, found by fuzzing)
   * and the self-loop passed it; refused before urdfdom sees the text */
  expect_error(dir, "self_loop.urdf", ROBOT2("type=\"fixed\"><parent link=\"b\"/><child link=\"b\"/>"),
               ST_ERR_MODEL, "joint 'j': link 'b' becomes its own ancestor (expected the joints to "
               "form a tree)", NULL);
  expect_error(dir, "loop.urdf",
               "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>"
               "<joint name=\"j1\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>"
               "<joint name=\"j2\" type=\"fixed\"><parent link=\"b\"/><child link=\"c\"/></joint>"
               "<joint name=\"j3\" type=\"fixed\"><parent link=\"c\"/><child link=\"b\"/></joint>"
               "</robot>\n",
               ST_ERR_MODEL, "joint 'j3': link 'b' becomes its own ancestor", NULL);
  /* a mesh in millimetres (no scale) and a scale of 0 */
  char path[400];
  write_in(path, sizeof path, dir, "mm.stl",
           "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 500 0 0\n"
           "vertex 0 500 0\nendloop\nendfacet\nendsolid t\n");
  expect_error(dir, "mesh_mm.urdf", ROBOT1(COLLISION("<mesh filename=\"mm.stl\"/>")), ST_ERR_MODEL,
               "link 'a': collision mesh 'mm.stl': vertex (500, 0, 0) is not finite or farther "
               "than 100 m from the origin", "scale=\"0.001 0.001 0.001\"");
  expect_error(dir, "mesh_scale0.urdf",
               ROBOT1(COLLISION("<mesh filename=\"mm.stl\" scale=\"0.001 0 0.001\"/>")), ST_ERR_MODEL,
               "link 'a': collision mesh 'mm.stl': scale 0.001 0 0.001 (expected each |scale| in "
               "1e-06..1000 )", NULL);
  /* a mesh file that never ends is not handed to assimp */
  expect_error(dir, "mesh_dev.urdf", ROBOT1(COLLISION("<mesh filename=\"/dev/zero\"/>")), ST_ERR_IO,
               "collision mesh '/dev/zero': cannot read (/dev/zero: not a regular file)", NULL);
}

/* the file itself: NUL bytes (TinyXML would stop at the first one) and no end */
static void test_model_hostile_files(void) {
  static const char text[] = "<robot name=\"r\"><link name=\"a\"/></robot>\n\0<junk/>";
  char path[256], err[512];
  stModel *m = (stModel *)&m;
  CU_ASSERT_PTR_NOT_NULL_FATAL(st_test_write_tmp_n(path, sizeof path, ".urdf", text, sizeof text - 1));
  CU_ASSERT_EQUAL(st_model_load_urdf(path, &m, err, sizeof err), ST_ERR_PARSE);
  CU_ASSERT_PTR_NULL(m);
  ST_ASSERT_CONTAINS(err, path);
  ST_ASSERT_CONTAINS(err, ":2: NUL byte at column 1 (expected a text file)");
  CU_ASSERT_EQUAL(st_model_load_urdf("/dev/zero", &m, err, sizeof err), ST_ERR_RANGE);
  CU_ASSERT_STRING_EQUAL(err, "/dev/zero: larger than 64 MiB (expected an input file of at most "
                              "67108864 bytes)");
}

/* ---- (e) the shipped iCub arm of data/: it must be there and load ---- */

static void test_model_icub(void) {
  const char *path = "data/icub_left_arm.urdf";
  char err[512] = "";
  stModel *m = NULL;
  stStatus st = st_model_load_urdf(path, &m, err, sizeof err);
  if (st != ST_OK) fprintf(stderr, "\n  %s does not load: %s\n", path, err);
  CU_ASSERT_EQUAL_FATAL(st, ST_OK);
  int elbow = st_model_joint(m, "l_elbow"), hand = st_model_body(m, "l_hand");
  CU_ASSERT(elbow > 0);
  CU_ASSERT(hand > 0);
  if (elbow > 0) CU_ASSERT_EQUAL(m->jnt_type[elbow], ST_JOINT_REVOLUTE);
  for (int b = 1; b < m->nbody; b++) CU_ASSERT(m->body_parent[b] >= 0 && m->body_parent[b] < b);
  st_model_destroy(m);
}

void st_suite_model(void) {
  ST_ADD_SUITE("model");
  ST_ADD_TEST(test_model_tree);
  ST_ADD_TEST(test_model_mesh);
  ST_ADD_TEST(test_model_errors);
  ST_ADD_TEST(test_model_unsimulable);
  ST_ADD_TEST(test_model_hostile_files);
  ST_ADD_TEST(test_model_icub);
}
