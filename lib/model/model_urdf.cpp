// SPDX-License-Identifier: MIT
// libselftalk: URDF import (the library's only C++). urdfdom parses the robot, Eigen does the
// pose algebra, assimp reads collision meshes. Nothing thrown here reaches C: every failure
// becomes an stStatus and one line in the caller's error buffer.

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>
#include <sys/stat.h>
#include <tinyxml.h>

extern "C" {
#include "core/internal.h"
}
#include "model/model_internal.h"
#include "selftalk/io.h"
#include "selftalk/model.h"

namespace {

// ---- failures: thrown inside the importer, turned into (status, message) at the C boundary

struct Failure {
  stStatus status;
  std::string msg;
};

[[noreturn]] void fail(stStatus status, std::string msg) { throw Failure{status, std::move(msg)}; }

std::string quote(const std::string &s) { return "'" + s + "'"; }

// ---- urdfdom's console output: captured (and kept off the console) while it parses

class LogCapture : public console_bridge::OutputHandler {
 public:
  std::vector<std::string> errors;
  void log(const std::string &text, console_bridge::LogLevel level, const char *, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors.push_back(text);
  }
};

// console_bridge's handler and level are process-wide: loads serialise on this mutex, and the
// previous handler and level come back even when parsing throws
std::mutex g_console_mutex;

class ConsoleGuard {
 public:
  explicit ConsoleGuard(LogCapture *capture) : lock_(g_console_mutex) {
    level_ = console_bridge::getLogLevel();
    console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_ERROR);
    console_bridge::useOutputHandler(capture);
  }
  ~ConsoleGuard() {
    console_bridge::restorePreviousOutputHandler();
    console_bridge::setLogLevel(level_);
  }
  ConsoleGuard(const ConsoleGuard &) = delete;
  ConsoleGuard &operator=(const ConsoleGuard &) = delete;

 private:
  std::lock_guard<std::mutex> lock_;
  console_bridge::LogLevel level_;
};

// ---- files

// the whole file through the library's bounded reader (selftalk/io.h)
std::string read_file(const std::string &path) {
  char *data = nullptr, err[512];
  size_t len = 0;
  stStatus st = st_file_read(path.c_str(), ST_FILE_MAX, &data, &len, err, sizeof err);
  if (st) fail(st, err);
  std::string text(data, len);
  std::free(data);
  return text;
}

std::string dir_of(const std::string &path) {
  size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

// ---- document order of the top-level <joint> elements. urdfdom keeps joints in a std::map
// (sorted by name), so a link's child joints come out alphabetically; this light scan of the
// text (comments, CDATA, <? ?>, <! > and quoted attributes skipped; only depth-1 elements, so
// <transmission><joint .../> is not counted) restores the order the author wrote.

std::string attr_value(const std::string &x, size_t p, size_t end, const char *want) {
  while (p < end) {
    while (p < end && std::isspace(static_cast<unsigned char>(x[p]))) p++;
    size_t n0 = p;
    while (p < end && x[p] != '=' && !std::isspace(static_cast<unsigned char>(x[p]))) p++;
    std::string name = x.substr(n0, p - n0);
    while (p < end && std::isspace(static_cast<unsigned char>(x[p]))) p++;
    if (p >= end || x[p] != '=') return "";
    p++;
    while (p < end && std::isspace(static_cast<unsigned char>(x[p]))) p++;
    if (p >= end || (x[p] != '"' && x[p] != '\'')) return "";
    char q = x[p++];
    size_t v0 = p;
    while (p < end && x[p] != q) p++;
    if (p >= end) return "";
    if (name == want) return x.substr(v0, p - v0);
    p++;
  }
  return "";
}

std::unordered_map<std::string, size_t> joint_doc_order(const std::string &x) {
  std::unordered_map<std::string, size_t> order;
  const size_t n = x.size(), npos = std::string::npos;
  size_t i = 0;
  int depth = 0;
  auto skip_to = [&](size_t from, const char *end_mark) {
    size_t e = x.find(end_mark, from);
    return e == npos ? npos : e + std::strlen(end_mark);
  };
  while ((i = x.find('<', i)) != npos) {
    if (x.compare(i, 4, "<!--") == 0) {
      i = skip_to(i + 4, "-->");
    } else if (x.compare(i, 9, "<![CDATA[") == 0) {
      i = skip_to(i + 9, "]]>");
    } else if (x.compare(i, 2, "<?") == 0) {
      i = skip_to(i + 2, "?>");
    } else if (x.compare(i, 2, "<!") == 0) {
      i = skip_to(i + 2, ">");
    } else if (x.compare(i, 2, "</") == 0) {
      depth--;
      i = skip_to(i + 2, ">");
    } else {
      size_t p = i + 1;
      while (p < n && !std::isspace(static_cast<unsigned char>(x[p])) && x[p] != '>' &&
             x[p] != '/')
        p++;
      size_t q = p;
      char quote_char = 0;
      for (; q < n; q++) {
        char c = x[q];
        if (quote_char) {
          if (c == quote_char) quote_char = 0;
        } else if (c == '"' || c == '\'') {
          quote_char = c;
        } else if (c == '>') {
          break;
        }
      }
      if (q >= n) break;
      bool self_closing = x[q - 1] == '/';
      if (depth == 1 && x.compare(i + 1, p - i - 1, "joint") == 0) {
        std::string name = attr_value(x, p, self_closing ? q - 1 : q, "name");
        if (!name.empty() && !order.count(name)) order.emplace(name, order.size());
      }
      if (!self_closing) depth++;
      i = q + 1;
    }
    if (i == npos) break;
  }
  return order;
}

// ---- loops of joints. urdfdom holds child links by shared_ptr: joints that make a link its own
// ancestor build a reference cycle it never frees, even when it then refuses the file (found by
// tests/fuzz/fuzz_urdf.c). The joint graph is checked before urdfdom sees the text, on the view
// of TinyXML, the parser urdfdom itself uses: <joint> children of <robot>, their <parent link>
// and <child link>.

using JointEdges = std::map<std::string, std::vector<std::pair<std::string, std::string>>>;

// parent link -> (child link, joint) for every joint that names both
JointEdges joint_edges(const TiXmlElement *robot) {
  JointEdges edges;
  for (const TiXmlElement *j = robot->FirstChildElement("joint"); j;
       j = j->NextSiblingElement("joint")) {
    const TiXmlElement *p = j->FirstChildElement("parent"), *c = j->FirstChildElement("child");
    const char *name = j->Attribute("name");
    const char *pl = p ? p->Attribute("link") : nullptr, *cl = c ? c->Attribute("link") : nullptr;
    if (pl && cl) edges[pl].emplace_back(cl, name ? name : "");
  }
  return edges;
}

// depth-first from every link, without recursion (a fuzzed chain can be long): a child found
// on the current path closes a loop
void check_joint_loops(const std::string &file, const std::string &text) {
  TiXmlDocument doc;
  doc.Parse(text.c_str());
  const TiXmlElement *robot = doc.Error() ? nullptr : doc.FirstChildElement("robot");
  if (!robot) return;  // urdfdom says why
  const JointEdges edges = joint_edges(robot);
  std::map<std::string, int> state;  // 1: on the current path, 2: done
  struct Frame {
    std::string link;
    size_t next;
  };
  for (const auto &start : edges) {
    if (state[start.first]) continue;
    std::vector<Frame> path{{start.first, 0}};
    state[start.first] = 1;
    while (!path.empty()) {
      Frame &f = path.back();
      auto it = edges.find(f.link);
      if (it == edges.end() || f.next >= it->second.size()) {
        state[f.link] = 2;
        path.pop_back();
        continue;
      }
      const auto &edge = it->second[f.next++];
      int &s = state[edge.first];
      if (s == 1)
        fail(ST_ERR_MODEL, file + ": joint " + quote(edge.second) + ": link " + quote(edge.first) +
                               " becomes its own ancestor (expected the joints to form a tree)");
      if (s == 0) {
        s = 1;
        path.push_back({edge.first, 0});
      }
    }
  }
}

// ---- pose algebra

void store_rot(const urdf::Rotation &r, double out[9]) {
  Eigen::Quaterniond q(r.w, r.x, r.y, r.z);
  q.normalize();  // urdfdom normalises already; cheap insurance
  Eigen::Matrix3d m = q.toRotationMatrix();
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) out[3 * i + j] = m(i, j);
}

void store_vec(const urdf::Vector3 &v, double out[3]) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
}

bool finite3(const urdf::Vector3 &v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool finite_pose(const urdf::Pose &p) {
  const urdf::Rotation &r = p.rotation;
  return finite3(p.position) && std::isfinite(r.x) && std::isfinite(r.y) &&
         std::isfinite(r.z) && std::isfinite(r.w);
}

// ---- what the world can simulate (docs/PROTOCOL.md, "Robot model": the limits and why).
// urdfdom parses numbers; these refuse the values that would abort libccd or ODE, or silently
// give NaN, naming the file and the element.

constexpr double kMaxOffset = 10.0;     // m: |xyz| of any origin (the arm spans ~1 m)
constexpr double kMinSize = 1e-6;       // m: shape sizes (0 aborts libccd's cylinder)
constexpr double kMaxSize = 10.0;       // m
constexpr double kMaxMeshCoord = 100.0; // m: mesh vertices, scaled (catches millimetre meshes)
constexpr double kMinScale = 1e-6, kMaxScale = 1e3;
constexpr double kMinMass = 1e-6, kMaxMass = 1e3;  // kg (1e308 aborts ODE's dxNormalize4)
constexpr double kMaxInertia = 1e3;     // kg m^2: principal moments
constexpr double kTriangleTol = 1e-4;   // relative slack of the triangle inequality (rounding)
constexpr double kMaxAngle = 2 * 3.14159265358979323846;  // rad: joint limits (degrees?)
constexpr double kMaxEffort = 1e4;      // N m
constexpr double kMaxVelocity = 1e3;    // rad/s

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

bool in_range(double v, double lo, double hi) { return v >= lo && v <= hi; }  // NaN: false

std::string range(double lo, double hi, const char *unit) {
  return num(lo) + ".." + num(hi) + " " + unit;
}

void check_origin(const std::string &what, const urdf::Pose &p) {
  if (!finite_pose(p)) fail(ST_ERR_MODEL, what + ": origin is not finite");
  const urdf::Vector3 &x = p.position;
  if (!(std::hypot(x.x, x.y, x.z) <= kMaxOffset))
    fail(ST_ERR_MODEL, what + ": origin xyz (" + num(x.x) + ", " + num(x.y) + ", " + num(x.z) +
                           ") is farther than " + num(kMaxOffset) + " m (expected |xyz| <= " +
                           num(kMaxOffset) + " m)");
}

void check_size(const std::string &what, const char *shape, const char *field, double v) {
  if (!in_range(v, kMinSize, kMaxSize))
    fail(ST_ERR_MODEL, what + ": " + shape + " " + field + " " + num(v) + " (expected " +
                           range(kMinSize, kMaxSize, "m") + ")");
}

// sphere, box and cylinder sizes; meshes are checked once read
void check_shape(const std::string &what, const urdf::Geometry &g) {
  switch (g.type) {
    case urdf::Geometry::SPHERE:
      check_size(what, "sphere", "radius", static_cast<const urdf::Sphere &>(g).radius);
      break;
    case urdf::Geometry::BOX: {
      const urdf::Vector3 &d = static_cast<const urdf::Box &>(g).dim;
      check_size(what, "box", "size x", d.x);
      check_size(what, "box", "size y", d.y);
      check_size(what, "box", "size z", d.z);
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto &c = static_cast<const urdf::Cylinder &>(g);
      check_size(what, "cylinder", "radius", c.radius);
      check_size(what, "cylinder", "length", c.length);
      break;
    }
    case urdf::Geometry::MESH: break;
    default: fail(ST_ERR_MODEL, what + ": unknown geometry type");
  }
}

void check_scale(const std::string &what, const urdf::Vector3 &s) {
  for (double v : {s.x, s.y, s.z})
    if (!in_range(std::fabs(v), kMinScale, kMaxScale))
      fail(ST_ERR_MODEL, what + ": scale " + num(s.x) + " " + num(s.y) + " " + num(s.z) +
                             " (expected each |scale| in " + range(kMinScale, kMaxScale, ")"));
}

// mass and inertia a rigid body can have: a mass in range, a finite symmetric tensor whose
// principal moments are positive, bounded and obey the triangle inequality
void check_inertial(const std::string &what, const urdf::Inertial &in, const Eigen::Matrix3d &I) {
  if (!in_range(in.mass, kMinMass, kMaxMass))
    fail(ST_ERR_MODEL, what + ": mass " + num(in.mass) + " kg (expected " +
                           range(kMinMass, kMaxMass, "kg") + ")");
  check_origin(what, in.origin);
  if (!I.allFinite()) fail(ST_ERR_MODEL, what + ": inertia is not finite");
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d e = eig.eigenvalues();  // ascending
  const std::string moments =
      "principal moments " + num(e[0]) + ", " + num(e[1]) + ", " + num(e[2]) + " kg m^2";
  if (!(e[0] > 0))
    fail(ST_ERR_MODEL, what + ": inertia is not positive definite (" + moments +
                           "; expected all > 0)");
  if (!(e[2] <= kMaxInertia))
    fail(ST_ERR_MODEL, what + ": inertia too large (" + moments + "; expected at most " +
                           num(kMaxInertia) + " kg m^2)");
  if (!(e[0] + e[1] >= e[2] * (1 - kTriangleTol)))
    fail(ST_ERR_MODEL, what + ": inertia breaks the triangle inequality (" + moments +
                           "; expected the largest <= the sum of the other two)");
}

void check_limits(const std::string &what, const urdf::JointLimits &lim, bool revolute) {
  if (!in_range(lim.effort, 0, kMaxEffort) || !in_range(lim.velocity, 0, kMaxVelocity))
    fail(ST_ERR_MODEL, what + ": limit effort " + num(lim.effort) + ", velocity " +
                           num(lim.velocity) + " (expected effort in " +
                           range(0, kMaxEffort, "N m") + ", velocity in " +
                           range(0, kMaxVelocity, "rad/s") + ")");
  if (revolute && !(in_range(lim.lower, -kMaxAngle, kMaxAngle) &&
                    in_range(lim.upper, -kMaxAngle, kMaxAngle) && lim.lower <= lim.upper))
    fail(ST_ERR_MODEL, what + ": limit lower " + num(lim.lower) + ", upper " + num(lim.upper) +
                           " (expected radians in -2 pi..2 pi, lower <= upper)");
}

// ---- meshes

struct MeshData {
  std::vector<std::array<double, 3>> vert;
  std::vector<std::array<int, 3>> tri;
};

const char *joint_type_name(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE: return "revolute";
    case urdf::Joint::CONTINUOUS: return "continuous";
    case urdf::Joint::PRISMATIC: return "prismatic";
    case urdf::Joint::FLOATING: return "floating";
    case urdf::Joint::PLANAR: return "planar";
    case urdf::Joint::FIXED: return "fixed";
    default: return "unknown";
  }
}

// a clear message for the common case (assimp's own says little about errno), and the size
// limit of every input file: assimp reads the file itself
void probe_mesh_file(const std::string &what, const std::string &file) {
  struct stat sb;
  if (stat(file.c_str(), &sb) != 0)
    fail(ST_ERR_IO, what + ": cannot read (" + file + ": " + std::strerror(errno) + ")");
  if (!S_ISREG(sb.st_mode))
    fail(ST_ERR_IO, what + ": cannot read (" + file + ": not a regular file)");
  if (static_cast<unsigned long long>(sb.st_size) > ST_FILE_MAX)
    fail(ST_ERR_RANGE, what + ": " + file + ": larger than " + std::to_string(ST_FILE_MAX >> 20) +
                           " MiB (expected a mesh file of at most " + std::to_string(ST_FILE_MAX) +
                           " bytes)");
}

// what: "FILE: link 'x': collision mesh 'y'"
MeshData load_mesh(const std::string &what, const std::string &urdf_dir, const urdf::Mesh &mesh) {
  std::string file = mesh.filename;
  if (file.empty()) fail(ST_ERR_MODEL, what + ": empty filename");
  if (file.compare(0, 10, "package://") == 0)
    fail(ST_ERR_MODEL, what + ": package:// URIs are not supported (use a path relative to the "
                              "URDF's directory, an absolute path or file://)");
  if (file.compare(0, 7, "file://") == 0) {
    file.erase(0, 7);
  } else {
    size_t scheme = file.find("://");
    if (scheme != std::string::npos)
      fail(ST_ERR_MODEL, what + ": URI scheme '" + file.substr(0, scheme) +
                             "://' is not supported (use a file path or file://)");
  }
  if (file.empty()) fail(ST_ERR_MODEL, what + ": empty filename");
  if (file[0] != '/') file = urdf_dir + "/" + file;

  probe_mesh_file(what, file);
  const urdf::Vector3 &s = mesh.scale;
  check_scale(what, s);

  Assimp::Importer importer;
  // geometry only: dropping normals etc. lets JoinIdenticalVertices merge by position
  importer.SetPropertyInteger(
      AI_CONFIG_PP_RVC_FLAGS,
      aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
          aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
          aiComponent_TEXTURES | aiComponent_LIGHTS | aiComponent_CAMERAS | aiComponent_MATERIALS);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // URDF tools (rviz, gazebo) take COLLADA coordinates as they are: no Y-up conversion
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene *scene =
      importer.ReadFile(file, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_RemoveComponent | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode) {
    std::string e = importer.GetErrorString();
    fail(ST_ERR_PARSE, what + ": cannot read (assimp: " + (e.empty() ? "unknown error" : e) + ")");
  }

  MeshData out;
  const size_t max_count = static_cast<size_t>(std::numeric_limits<int>::max() / 2);
  std::vector<std::pair<const aiNode *, aiMatrix4x4>> stack;
  stack.emplace_back(scene->mRootNode, scene->mRootNode->mTransformation);
  while (!stack.empty()) {
    const aiNode *node = stack.back().first;
    aiMatrix4x4 t = stack.back().second;
    stack.pop_back();
    for (unsigned k = 0; k < node->mNumMeshes; k++) {
      if (node->mMeshes[k] >= scene->mNumMeshes) continue;
      const aiMesh *m = scene->mMeshes[node->mMeshes[k]];
      if (!m || !m->mVertices) continue;
      size_t base = out.vert.size();
      // a mirroring transform or scale would turn the triangles inside out: keep them outward
      bool flip = static_cast<double>(t.Determinant()) * s.x * s.y * s.z < 0;
      if (m->mNumVertices > max_count - base) fail(ST_ERR_MODEL, what + ": too many vertices");
      for (unsigned v = 0; v < m->mNumVertices; v++) {
        aiVector3D p = t * m->mVertices[v];
        out.vert.push_back({s.x * p.x, s.y * p.y, s.z * p.z});
      }
      for (unsigned f = 0; f < m->mNumFaces; f++) {
        const aiFace &face = m->mFaces[f];
        if (face.mNumIndices != 3) continue;  // points and lines carry no volume
        std::array<int, 3> tri;
        for (int c = 0; c < 3; c++) {
          if (face.mIndices[c] >= m->mNumVertices)
            fail(ST_ERR_PARSE, what + ": cannot read (assimp: face index out of range)");
          tri[c] = static_cast<int>(base + face.mIndices[c]);
        }
        if (flip) std::swap(tri[1], tri[2]);
        if (out.tri.size() >= max_count) fail(ST_ERR_MODEL, what + ": too many triangles");
        out.tri.push_back(tri);
      }
    }
    for (unsigned c = node->mNumChildren; c-- > 0;)
      if (node->mChildren[c])
        stack.emplace_back(node->mChildren[c], t * node->mChildren[c]->mTransformation);
  }
  if (out.tri.empty()) fail(ST_ERR_MODEL, what + ": the mesh has no triangles");
  for (const auto &v : out.vert)
    if (!(std::hypot(v[0], v[1], v[2]) <= kMaxMeshCoord))
      fail(ST_ERR_MODEL, what + ": vertex (" + num(v[0]) + ", " + num(v[1]) + ", " + num(v[2]) +
                             ") is not finite or farther than " + num(kMaxMeshCoord) +
                             " m from the origin (expected metres: a mesh in millimetres needs "
                             "scale=\"0.001 0.001 0.001\")");
  return out;
}

// ---- the import

struct ModelDeleter {
  void operator()(stModel *m) const { st_model_destroy(m); }
};
using ModelPtr = std::unique_ptr<stModel, ModelDeleter>;

struct GeomSrc {
  int body;
  const urdf::Collision *col;
  int mesh;  // index into meshes, or -1
};

void check_name(const std::string &file, const char *kind, const std::string &name) {
  if (name.size() >= ST_NAME_MAX)
    fail(ST_ERR_MODEL, file + ": " + kind + " " + quote(name) + ": name longer than " +
                           std::to_string(ST_NAME_MAX - 1) + " characters");
}

// file: the name messages give; dir: where relative mesh paths start
// the text through urdfdom: loops refused first (check_joint_loops), urdfdom's log captured;
// any error it logs counts as a failed parse (it logs some, a collision it cannot read say,
// and still returns a model without the offending element)
urdf::ModelInterfaceSharedPtr parse_text(const std::string &file, const std::string &text) {
  if (text.find('\0') != std::string::npos) {
    char err[512];
    const stStatus st = st_text_check(file.c_str(), text.data(), text.size(), err, sizeof err);
    fail(st, err);
  }
  check_joint_loops(file, text);
  urdf::ModelInterfaceSharedPtr urdf_model;
  LogCapture capture;
  {
    ConsoleGuard guard(&capture);
    try {
      urdf_model = urdf::parseURDF(text);
    } catch (const std::bad_alloc &) {
      throw;
    } catch (const std::exception &e) {
      capture.errors.push_back(e.what());
      urdf_model.reset();
    }
  }
  if (!urdf_model || !capture.errors.empty()) {
    std::string why;
    for (size_t i = 0; i < capture.errors.size() && i < 3; i++)
      why += (i ? "; " : "") + capture.errors[i];
    fail(ST_ERR_PARSE, file + ": malformed URDF (" +
                           (why.empty() ? std::string("urdfdom could not parse it")
                                        : "urdfdom: " + why) +
                           ")");
  }
  return urdf_model;
}

// the bodies in model order: depth-first from the root, children in document order of their
// joints
struct Tree {
  std::vector<const urdf::Link *> links;          // body order
  std::vector<const urdf::Joint *> parent_joint;  // per body; nullptr for the root
  std::vector<int> parent_body;
  std::unordered_map<std::string, int> body_of_joint;
};

Tree order_bodies(const std::string &file, const std::string &text,
                  const urdf::ModelInterface &urdf_model) {
  urdf::LinkConstSharedPtr root = urdf_model.getRoot();
  if (!root) fail(ST_ERR_MODEL, file + ": no root link");
  const auto doc_order = joint_doc_order(text);
  auto joint_key = [&](const urdf::JointSharedPtr &j) {
    auto it = doc_order.find(j->name);
    return std::make_pair(it == doc_order.end() ? std::numeric_limits<size_t>::max() : it->second,
                          j->name);
  };
  Tree t;
  std::unordered_map<const urdf::Link *, int> body_of;
  struct Pending {
    const urdf::Link *link;
    const urdf::Joint *joint;
    int parent;
  };
  std::vector<Pending> stack{{root.get(), nullptr, -1}};
  while (!stack.empty()) {
    Pending p = stack.back();
    stack.pop_back();
    if (body_of.count(p.link))
      fail(ST_ERR_MODEL, file + ": link " + quote(p.link->name) + ": more than one parent joint");
    int b = static_cast<int>(t.links.size());
    body_of[p.link] = b;
    t.links.push_back(p.link);
    t.parent_joint.push_back(p.joint);
    t.parent_body.push_back(p.parent);
    std::vector<urdf::JointSharedPtr> children = p.link->child_joints;
    std::sort(children.begin(), children.end(),
              [&](const urdf::JointSharedPtr &a, const urdf::JointSharedPtr &c) {
                return joint_key(a) < joint_key(c);
              });
    for (auto it = children.rbegin(); it != children.rend(); ++it) {
      const urdf::JointSharedPtr &j = *it;
      if (!j) continue;
      auto child = urdf_model.links_.find(j->child_link_name);
      if (child == urdf_model.links_.end() || !child->second)
        fail(ST_ERR_MODEL, file + ": joint " + quote(j->name) + ": child link " +
                               quote(j->child_link_name) + " does not exist");
      stack.push_back({child->second.get(), j.get(), b});
    }
  }
  for (const auto &kv : urdf_model.links_)
    if (kv.second && !body_of.count(kv.second.get()))
      fail(ST_ERR_MODEL, file + ": link " + quote(kv.first) + ": not connected to the root link " +
                             quote(root->name));
  for (size_t b = 1; b < t.links.size(); b++)
    t.body_of_joint[t.parent_joint[b]->name] = static_cast<int>(b);
  return t;
}

// collision geometry, checked; meshes are read now, so the counts are known before allocating
struct Geoms {
  std::vector<GeomSrc> src;
  std::vector<MeshData> meshes;
  size_t nvert = 0, ntri = 0;
};

Geoms gather_geoms(const std::string &file, const std::string &dir, const Tree &t) {
  Geoms g;
  for (size_t b = 0; b < t.links.size(); b++) {
    const urdf::Link *l = t.links[b];
    std::vector<urdf::CollisionSharedPtr> cols = l->collision_array;
    if (cols.empty() && l->collision) cols.push_back(l->collision);
    int k = 0;
    for (const auto &c : cols) {
      std::string what = file + ": link " + quote(l->name) + ": collision " + std::to_string(++k);
      if (!c || !c->geometry) fail(ST_ERR_MODEL, what + ": no geometry");
      check_origin(what, c->origin);
      check_shape(what, *c->geometry);
      int mesh = -1;
      if (c->geometry->type == urdf::Geometry::MESH) {
        const auto &m = static_cast<const urdf::Mesh &>(*c->geometry);
        g.meshes.push_back(
            load_mesh(file + ": link " + quote(l->name) + ": collision mesh " + quote(m.filename),
                      dir, m));
        mesh = static_cast<int>(g.meshes.size()) - 1;
        g.nvert += g.meshes.back().vert.size();
        g.ntri += g.meshes.back().tri.size();
        if (g.nvert > static_cast<size_t>(std::numeric_limits<int>::max() / 2) ||
            g.ntri > static_cast<size_t>(std::numeric_limits<int>::max() / 2))
          fail(ST_ERR_MODEL, file + ": too many mesh vertices or triangles");
      }
      g.src.push_back({static_cast<int>(b), c.get(), mesh});
    }
  }
  return g;
}

// body b's name, parent, mass, centre of mass and inertia (about the COM, body axes)
void fill_body(const std::string &file, stModel *m, int b, const urdf::Link &l, int parent) {
  check_name(file, "link", l.name);
  st__strlcpy(m->body_name[b], l.name.c_str(), ST_NAME_MAX);
  m->body_parent[b] = parent;
  if (!l.inertial) return;  // a massless frame
  const urdf::Inertial &in = *l.inertial;
  Eigen::Matrix3d inertia;
  inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  check_inertial(file + ": link " + quote(l.name) + ": inertial", in, inertia);
  const urdf::Rotation &r = in.origin.rotation;
  Eigen::Matrix3d rot = Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
  // the tensor is given in the inertial frame; body axes: R I R^T (kept exactly symmetric)
  Eigen::Matrix3d ib = rot * inertia * rot.transpose();
  ib = 0.5 * (ib + ib.transpose()).eval();
  m->body_mass[b] = in.mass;
  store_vec(in.origin.position, m->body_com[b]);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) m->body_inertia[b][3 * i + j] = ib(i, j);
}

// a revolute (or continuous) joint's unit axis, limits and range
void fill_revolute(const std::string &what, stModel *m, int b, const urdf::Joint &j) {
  m->jnt_type[b] = ST_JOINT_REVOLUTE;
  if (!finite3(j.axis)) fail(ST_ERR_MODEL, what + ": axis is not finite");
  Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
  double norm = axis.norm();
  if (!(norm > 1e-12)) fail(ST_ERR_MODEL, what + ": axis is zero (expected a direction)");
  if (!std::isfinite(norm)) fail(ST_ERR_MODEL, what + ": axis is not finite");
  axis /= norm;
  for (int i = 0; i < 3; i++) m->jnt_axis[b][i] = axis[i];
  if (j.limits) {
    const urdf::JointLimits &lim = *j.limits;
    check_limits(what, lim, j.type == urdf::Joint::REVOLUTE);
    m->jnt_effort[b] = lim.effort;
    m->jnt_velocity[b] = lim.velocity;
  }
  if (j.type == urdf::Joint::CONTINUOUS) {
    m->jnt_range[b][0] = -INFINITY;
    m->jnt_range[b][1] = INFINITY;
  } else {
    if (!j.limits) fail(ST_ERR_MODEL, what + ": revolute joint without <limit>");
    m->jnt_range[b][0] = j.limits->lower;
    m->jnt_range[b][1] = j.limits->upper;
  }
}

// body b's parent joint
void fill_joint(const std::string &file, stModel *m, int b, const urdf::Joint &j) {
  const std::string what = file + ": joint " + quote(j.name);
  check_name(file, "joint", j.name);
  st__strlcpy(m->jnt_name[b], j.name.c_str(), ST_NAME_MAX);
  check_origin(what, j.parent_to_joint_origin_transform);
  store_vec(j.parent_to_joint_origin_transform.position, m->jnt_pos[b]);
  store_rot(j.parent_to_joint_origin_transform.rotation, m->jnt_rot[b]);
  if (j.type == urdf::Joint::FIXED) {
    m->jnt_type[b] = ST_JOINT_FIXED;  // axis, range, effort and velocity stay 0
    if (j.mimic) fail(ST_ERR_MODEL, what + ": a fixed joint cannot mimic another joint");
    return;
  }
  if (j.type != urdf::Joint::REVOLUTE && j.type != urdf::Joint::CONTINUOUS)
    fail(ST_ERR_MODEL, what + ": type " + joint_type_name(j.type) +
                           " not supported (expected revolute, continuous or fixed)");
  fill_revolute(what, m, b, j);
}

// mimic joints, once every body's joint is known
void fill_mimics(const std::string &file, stModel *m, const Tree &t) {
  for (int b = 1; b < m->nbody; b++) {
    const urdf::Joint &j = *t.parent_joint[b];
    if (!j.mimic) continue;
    const std::string what = file + ": joint " + quote(j.name) + ": mimic joint " +
                             quote(j.mimic->joint_name);
    auto it = t.body_of_joint.find(j.mimic->joint_name);
    if (it == t.body_of_joint.end()) fail(ST_ERR_MODEL, what + ": no such joint");
    if (it->second == b) fail(ST_ERR_MODEL, what + ": a joint cannot mimic itself");
    if (m->jnt_type[it->second] != ST_JOINT_REVOLUTE)
      fail(ST_ERR_MODEL, what + ": the mimicked joint is fixed");
    if (!std::isfinite(j.mimic->multiplier) || !std::isfinite(j.mimic->offset))
      fail(ST_ERR_MODEL, what + ": multiplier and offset must be finite");
    m->jnt_mimic[b] = it->second;
    m->jnt_mimic_mult[b] = j.mimic->multiplier;
    m->jnt_mimic_offset[b] = j.mimic->offset;
  }
}

// geoms and mesh arrays (shapes checked by gather_geoms)
void fill_geoms(stModel *m, const Geoms &geoms) {
  int v0 = 0, t0 = 0;
  for (size_t g = 0; g < geoms.src.size(); g++) {
    const GeomSrc &src = geoms.src[g];
    const urdf::Geometry &geo = *src.col->geometry;
    m->geom_body[g] = src.body;
    store_vec(src.col->origin.position, m->geom_pos[g]);
    store_rot(src.col->origin.rotation, m->geom_rot[g]);
    double *size = m->geom_size[g];
    if (geo.type == urdf::Geometry::SPHERE) {
      m->geom_type[g] = ST_GEOM_SPHERE;
      size[0] = static_cast<const urdf::Sphere &>(geo).radius;
    } else if (geo.type == urdf::Geometry::BOX) {
      m->geom_type[g] = ST_GEOM_BOX;
      store_vec(static_cast<const urdf::Box &>(geo).dim, size);
    } else if (geo.type == urdf::Geometry::CYLINDER) {
      m->geom_type[g] = ST_GEOM_CYLINDER;
      size[0] = static_cast<const urdf::Cylinder &>(geo).radius;
      size[1] = static_cast<const urdf::Cylinder &>(geo).length;
    } else {
      const MeshData &md = geoms.meshes[src.mesh];
      m->geom_type[g] = ST_GEOM_MESH;
      m->geom_vert0[g] = v0;
      m->geom_nvert[g] = static_cast<int>(md.vert.size());
      m->geom_tri0[g] = t0;
      m->geom_ntri[g] = static_cast<int>(md.tri.size());
      for (const auto &v : md.vert) std::copy(v.begin(), v.end(), m->mesh_vert[v0++]);
      for (const auto &tr : md.tri) std::copy(tr.begin(), tr.end(), m->mesh_tri[t0++]);
    }
  }
}

// file: the name messages give; dir: where relative mesh paths start
ModelPtr load(const std::string &file, const std::string &dir, const std::string &text) {
  const urdf::ModelInterfaceSharedPtr urdf_model = parse_text(file, text);
  const Tree t = order_bodies(file, text, *urdf_model);
  const Geoms geoms = gather_geoms(file, dir, t);
  const int nbody = static_cast<int>(t.links.size());
  ModelPtr model(st__model_alloc(nbody, static_cast<int>(geoms.src.size()),
                                 static_cast<int>(geoms.nvert), static_cast<int>(geoms.ntri)));
  if (!model) throw std::bad_alloc();
  stModel *m = model.get();
  for (int b = 0; b < nbody; b++) {
    fill_body(file, m, b, *t.links[b], t.parent_body[b]);
    if (b > 0) fill_joint(file, m, b, *t.parent_joint[b]);
  }
  fill_mimics(file, m, t);
  fill_geoms(m, geoms);
  return model;
}

// keeps the message on one line (names and library messages may hold newlines)
void one_line(char *err, size_t errsz) {
  if (!err || !errsz) return;
  for (char *p = err; *p; p++)
    if (*p == '\n' || *p == '\r') *p = ' ';
}

// runs an import, turning every failure into a status and one line in err
template <class F>
stStatus guarded(const char *name, F import, stModel **model, char *err, size_t errsz) {
  try {
    *model = import().release();
    return ST_OK;
  } catch (const Failure &f) {
    st__errf(err, errsz, "%s", f.msg.c_str());
    one_line(err, errsz);
    return f.status;
  } catch (const std::bad_alloc &) {
    st__errf(err, errsz, "%s: out of memory", name);
    return ST_ERR_NOMEM;
  } catch (const std::exception &e) {
    st__errf(err, errsz, "%s: malformed URDF (%s)", name, e.what());
    one_line(err, errsz);
    return ST_ERR_PARSE;
  } catch (...) {
    st__errf(err, errsz, "%s: malformed URDF (unknown error)", name);
    return ST_ERR_PARSE;
  }
}

}  // namespace

extern "C" stStatus st__model_parse_urdf(const char *name, const char *dir, const char *text,
                                         size_t len, stModel **model, char *err, size_t errsz) {
  if (model) *model = nullptr;
  if (!name || !dir || (!text && len) || !model) {
    st__errf(err, errsz, "st__model_parse_urdf: name, dir, text and model are required");
    return ST_ERR_ARG;
  }
  return guarded(name, [&] { return load(name, dir, std::string(text, len)); }, model, err, errsz);
}

extern "C" stStatus st_model_load_urdf(const char *path, stModel **model, char *err,
                                       size_t errsz) {
  if (model) *model = nullptr;
  if (!path || !model) {
    st__errf(err, errsz, "st_model_load_urdf: path and model are required");
    return ST_ERR_ARG;
  }
  return guarded(path, [&] { return load(path, dir_of(path), read_file(path)); }, model, err,
                 errsz);
}
