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

#include <Eigen/Geometry>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

extern "C" {
#include "core/internal.h"
}
#include "model/model_internal.h"
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

std::string read_file(const std::string &path) {
  std::FILE *f = std::fopen(path.c_str(), "rb");
  if (!f) fail(ST_ERR_IO, path + ": cannot open (" + std::strerror(errno) + ")");
  std::string text;
  char buf[65536];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
  int bad = std::ferror(f), e = errno;
  std::fclose(f);
  if (bad) fail(ST_ERR_IO, path + ": cannot read (" + std::strerror(e) + ")");
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

  // a clear message for the common case (assimp's own says little about errno)
  std::FILE *probe = std::fopen(file.c_str(), "rb");
  if (!probe) fail(ST_ERR_IO, what + ": cannot read (" + file + ": " + std::strerror(errno) + ")");
  std::fclose(probe);

  const urdf::Vector3 &s = mesh.scale;
  if (!finite3(s)) fail(ST_ERR_MODEL, what + ": scale is not finite");

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
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      fail(ST_ERR_MODEL, what + ": vertex coordinates are not finite");
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

ModelPtr load(const std::string &file) {
  const std::string text = read_file(file);

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
  // urdfdom logs some errors (a collision it cannot read, say) and still returns a model
  // without the offending element: any error counts as a failed parse
  if (!urdf_model || !capture.errors.empty()) {
    std::string why;
    for (size_t i = 0; i < capture.errors.size() && i < 3; i++)
      why += (i ? "; " : "") + capture.errors[i];
    fail(ST_ERR_PARSE, file + ": malformed URDF (" +
                           (why.empty() ? std::string("urdfdom could not parse it")
                                        : "urdfdom: " + why) +
                           ")");
  }
  urdf::LinkConstSharedPtr root = urdf_model->getRoot();
  if (!root) fail(ST_ERR_MODEL, file + ": no root link");

  // ---- bodies: depth-first from the root, children in document order of their joints
  const auto doc_order = joint_doc_order(text);
  auto joint_key = [&](const urdf::JointSharedPtr &j) {
    auto it = doc_order.find(j->name);
    return std::make_pair(it == doc_order.end() ? std::numeric_limits<size_t>::max() : it->second,
                          j->name);
  };
  std::vector<const urdf::Link *> links;         // body order
  std::vector<const urdf::Joint *> parent_joint; // per body; nullptr for the root
  std::vector<int> parent_body;
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
    int b = static_cast<int>(links.size());
    body_of[p.link] = b;
    links.push_back(p.link);
    parent_joint.push_back(p.joint);
    parent_body.push_back(p.parent);
    std::vector<urdf::JointSharedPtr> children = p.link->child_joints;
    std::sort(children.begin(), children.end(),
              [&](const urdf::JointSharedPtr &a, const urdf::JointSharedPtr &c) {
                return joint_key(a) < joint_key(c);
              });
    for (auto it = children.rbegin(); it != children.rend(); ++it) {
      const urdf::JointSharedPtr &j = *it;
      if (!j) continue;
      auto child = urdf_model->links_.find(j->child_link_name);
      if (child == urdf_model->links_.end() || !child->second)
        fail(ST_ERR_MODEL, file + ": joint " + quote(j->name) + ": child link " +
                               quote(j->child_link_name) + " does not exist");
      stack.push_back({child->second.get(), j.get(), b});
    }
  }
  for (const auto &kv : urdf_model->links_)
    if (kv.second && !body_of.count(kv.second.get()))
      fail(ST_ERR_MODEL, file + ": link " + quote(kv.first) + ": not connected to the root link " +
                             quote(root->name));
  const int nbody = static_cast<int>(links.size());
  std::unordered_map<std::string, int> body_of_joint;
  for (int b = 1; b < nbody; b++) body_of_joint[parent_joint[b]->name] = b;

  // ---- collision geometry; meshes are read now, so the counts are known before allocating
  std::vector<GeomSrc> geoms;
  std::vector<MeshData> meshes;
  const std::string dir = dir_of(file);
  size_t nvert = 0, ntri = 0;
  for (int b = 0; b < nbody; b++) {
    const urdf::Link *l = links[b];
    std::vector<urdf::CollisionSharedPtr> cols = l->collision_array;
    if (cols.empty() && l->collision) cols.push_back(l->collision);
    int k = 0;
    for (const auto &c : cols) {
      k++;
      std::string what = file + ": link " + quote(l->name) + ": collision " + std::to_string(k);
      if (!c || !c->geometry) fail(ST_ERR_MODEL, what + ": no geometry");
      if (!finite_pose(c->origin)) fail(ST_ERR_MODEL, what + ": origin is not finite");
      int mesh = -1;
      if (c->geometry->type == urdf::Geometry::MESH) {
        const auto &m = static_cast<const urdf::Mesh &>(*c->geometry);
        meshes.push_back(
            load_mesh(file + ": link " + quote(l->name) + ": collision mesh " + quote(m.filename),
                      dir, m));
        mesh = static_cast<int>(meshes.size()) - 1;
        nvert += meshes.back().vert.size();
        ntri += meshes.back().tri.size();
        if (nvert > static_cast<size_t>(std::numeric_limits<int>::max() / 2) ||
            ntri > static_cast<size_t>(std::numeric_limits<int>::max() / 2))
          fail(ST_ERR_MODEL, file + ": too many mesh vertices or triangles");
      }
      geoms.push_back({b, c.get(), mesh});
    }
  }

  ModelPtr model(st__model_alloc(nbody, static_cast<int>(geoms.size()), static_cast<int>(nvert),
                                 static_cast<int>(ntri)));
  if (!model) throw std::bad_alloc();
  stModel *m = model.get();

  // ---- bodies and joints
  for (int b = 0; b < nbody; b++) {
    const urdf::Link *l = links[b];
    check_name(file, "link", l->name);
    st__strlcpy(m->body_name[b], l->name.c_str(), ST_NAME_MAX);
    m->body_parent[b] = parent_body[b];
    if (l->inertial) {
      const urdf::Inertial &in = *l->inertial;
      std::string what = file + ": link " + quote(l->name) + ": inertial";
      if (!std::isfinite(in.mass) || in.mass < 0)
        fail(ST_ERR_MODEL, what + ": mass must be finite and >= 0");
      if (!finite_pose(in.origin)) fail(ST_ERR_MODEL, what + ": origin is not finite");
      Eigen::Matrix3d inertia;
      inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      if (!inertia.allFinite()) fail(ST_ERR_MODEL, what + ": inertia is not finite");
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
    if (b == 0) continue;

    const urdf::Joint &j = *parent_joint[b];
    const std::string what = file + ": joint " + quote(j.name);
    check_name(file, "joint", j.name);
    st__strlcpy(m->jnt_name[b], j.name.c_str(), ST_NAME_MAX);
    if (!finite_pose(j.parent_to_joint_origin_transform))
      fail(ST_ERR_MODEL, what + ": origin is not finite");
    store_vec(j.parent_to_joint_origin_transform.position, m->jnt_pos[b]);
    store_rot(j.parent_to_joint_origin_transform.rotation, m->jnt_rot[b]);
    if (j.type == urdf::Joint::FIXED) {
      m->jnt_type[b] = ST_JOINT_FIXED;  // axis, range, effort and velocity stay 0
      if (j.mimic) fail(ST_ERR_MODEL, what + ": a fixed joint cannot mimic another joint");
      continue;
    }
    if (j.type != urdf::Joint::REVOLUTE && j.type != urdf::Joint::CONTINUOUS)
      fail(ST_ERR_MODEL, what + ": type " + joint_type_name(j.type) +
                             " not supported (expected revolute, continuous or fixed)");
    m->jnt_type[b] = ST_JOINT_REVOLUTE;
    if (!finite3(j.axis)) fail(ST_ERR_MODEL, what + ": axis is not finite");
    Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
    double norm = axis.norm();
    if (!(norm > 1e-12)) fail(ST_ERR_MODEL, what + ": axis is zero (expected a direction)");
    axis /= norm;
    for (int i = 0; i < 3; i++) m->jnt_axis[b][i] = axis[i];
    if (j.limits) {
      const urdf::JointLimits &lim = *j.limits;
      if (!std::isfinite(lim.effort) || !std::isfinite(lim.velocity) || lim.effort < 0 ||
          lim.velocity < 0)
        fail(ST_ERR_MODEL, what + ": limit effort and velocity must be finite and >= 0");
      m->jnt_effort[b] = lim.effort;
      m->jnt_velocity[b] = lim.velocity;
    }
    if (j.type == urdf::Joint::CONTINUOUS) {
      m->jnt_range[b][0] = -INFINITY;
      m->jnt_range[b][1] = INFINITY;
    } else {
      if (!j.limits) fail(ST_ERR_MODEL, what + ": revolute joint without <limit>");
      const urdf::JointLimits &lim = *j.limits;
      if (!std::isfinite(lim.lower) || !std::isfinite(lim.upper) || lim.lower > lim.upper)
        fail(ST_ERR_MODEL, what + ": limit lower " + std::to_string(lim.lower) + ", upper " +
                               std::to_string(lim.upper) + " (expected finite, lower <= upper)");
      m->jnt_range[b][0] = lim.lower;
      m->jnt_range[b][1] = lim.upper;
    }
  }

  // ---- mimic joints (every body's joint is known now)
  for (int b = 1; b < nbody; b++) {
    const urdf::Joint &j = *parent_joint[b];
    if (!j.mimic) continue;
    const std::string what = file + ": joint " + quote(j.name) + ": mimic joint " +
                             quote(j.mimic->joint_name);
    auto it = body_of_joint.find(j.mimic->joint_name);
    if (it == body_of_joint.end()) fail(ST_ERR_MODEL, what + ": no such joint");
    if (it->second == b) fail(ST_ERR_MODEL, what + ": a joint cannot mimic itself");
    if (m->jnt_type[it->second] != ST_JOINT_REVOLUTE)
      fail(ST_ERR_MODEL, what + ": the mimicked joint is fixed");
    if (!std::isfinite(j.mimic->multiplier) || !std::isfinite(j.mimic->offset))
      fail(ST_ERR_MODEL, what + ": multiplier and offset must be finite");
    m->jnt_mimic[b] = it->second;
    m->jnt_mimic_mult[b] = j.mimic->multiplier;
    m->jnt_mimic_offset[b] = j.mimic->offset;
  }

  // ---- geoms and mesh arrays
  int v0 = 0, t0 = 0;
  for (size_t g = 0; g < geoms.size(); g++) {
    const GeomSrc &src = geoms[g];
    const urdf::Collision &c = *src.col;
    const std::string what = file + ": link " + quote(links[src.body]->name) + ": collision " +
                             std::to_string(g + 1);
    m->geom_body[g] = src.body;
    store_vec(c.origin.position, m->geom_pos[g]);
    store_rot(c.origin.rotation, m->geom_rot[g]);
    double *size = m->geom_size[g];
    switch (c.geometry->type) {
      case urdf::Geometry::SPHERE:
        m->geom_type[g] = ST_GEOM_SPHERE;
        size[0] = static_cast<const urdf::Sphere &>(*c.geometry).radius;
        break;
      case urdf::Geometry::BOX: {
        m->geom_type[g] = ST_GEOM_BOX;
        store_vec(static_cast<const urdf::Box &>(*c.geometry).dim, size);
        break;
      }
      case urdf::Geometry::CYLINDER: {
        const auto &cyl = static_cast<const urdf::Cylinder &>(*c.geometry);
        m->geom_type[g] = ST_GEOM_CYLINDER;
        size[0] = cyl.radius;
        size[1] = cyl.length;
        break;
      }
      case urdf::Geometry::MESH: {
        const MeshData &md = meshes[src.mesh];
        m->geom_type[g] = ST_GEOM_MESH;
        m->geom_vert0[g] = v0;
        m->geom_nvert[g] = static_cast<int>(md.vert.size());
        m->geom_tri0[g] = t0;
        m->geom_ntri[g] = static_cast<int>(md.tri.size());
        for (const auto &v : md.vert) std::copy(v.begin(), v.end(), m->mesh_vert[v0++]);
        for (const auto &t : md.tri) std::copy(t.begin(), t.end(), m->mesh_tri[t0++]);
        break;
      }
      default:
        fail(ST_ERR_MODEL, what + ": unknown geometry type");
    }
    for (int i = 0; i < 3; i++)
      if (!std::isfinite(size[i]) || size[i] < 0)
        fail(ST_ERR_MODEL, what + ": size must be finite and >= 0");
  }
  return model;
}

// keeps the message on one line (names and library messages may hold newlines)
void one_line(char *err, size_t errsz) {
  if (!err || !errsz) return;
  for (char *p = err; *p; p++)
    if (*p == '\n' || *p == '\r') *p = ' ';
}

}  // namespace

extern "C" stStatus st_model_load_urdf(const char *path, stModel **model, char *err,
                                       size_t errsz) {
  if (model) *model = nullptr;
  if (!path || !model) {
    st__errf(err, errsz, "st_model_load_urdf: path and model are required");
    return ST_ERR_ARG;
  }
  try {
    *model = load(path).release();
    return ST_OK;
  } catch (const Failure &f) {
    st__errf(err, errsz, "%s", f.msg.c_str());
    one_line(err, errsz);
    return f.status;
  } catch (const std::bad_alloc &) {
    st__errf(err, errsz, "%s: out of memory", path);
    return ST_ERR_NOMEM;
  } catch (const std::exception &e) {
    st__errf(err, errsz, "%s: malformed URDF (%s)", path, e.what());
    one_line(err, errsz);
    return ST_ERR_PARSE;
  } catch (...) {
    st__errf(err, errsz, "%s: malformed URDF (unknown error)", path);
    return ST_ERR_PARSE;
  }
}
