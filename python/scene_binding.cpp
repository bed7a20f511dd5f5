// World.scene and Scene: what the drawing sets make of a world's word, as numpy arrays
// laid out as the OBJ file `ontogen run` writes (its vertices, in its order: the mesh's
// positions, then the segments' ends, a segment that starts where the previous one ended
// sharing its vertex), so the two can be compared vertex for vertex. Scene.glb and
// World.animation give the .glb `ontogen run --format glb` writes, which the notebook's
// 3-D view shows (python/ontogen/display.py).

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <vector>

#include <glm/geometric.hpp>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "interpreters/formats/glb_writer.h"
#include "interpreters/formats/skinned_glb_writer.h"
#include "interpreters/interpret.h"
#include "interpreters/palette.h"
#include "interpreters/scene.h"
#include "interpreters/set_registry.h"
#include "python/bindings.h"
#include "python/handles.h"

namespace py = pybind11;

namespace ontogen::python {

namespace {

/// A Scene and its arrays, made once.
struct SceneHandle {
  Scene scene;
  py::object vertices, normals, colors, indices, lines, nodes;
};

template <typename T>
py::array_t<T> arrayOf(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* held = new std::vector<T>(std::move(values));
  py::capsule owner(held, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, held->data(), owner);
}

bool continues(const std::vector<Segment>& segments, size_t i) {
  return i > 0 && segments[i].start == segments[i - 1].end;
}

void appendColor(std::vector<float>& colors, uint32_t material) {
  const Color c = paletteColor(material);
  colors.insert(colors.end(), {static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b), 1.0f});
}

void makeArrays(SceneHandle& handle) {
  const Geometry& geometry = handle.scene.geometry;
  const Mesh& mesh = geometry.mesh();
  const std::vector<Segment>& segments = geometry.segments();
  const size_t meshVertices = mesh.positions.size();
  std::vector<float> vertices, normals, colors;
  std::vector<uint32_t> indices, lines;
  // A position's normal: the mean of its corners' (a cylinder's rim is shared by its side
  // and its cap); its colour: its first triangle's.
  std::vector<glm::dvec3> normalSum(meshVertices, glm::dvec3(0.0));
  std::vector<uint32_t> material(meshVertices, std::numeric_limits<uint32_t>::max());
  for (const Triangle& triangle : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const uint32_t p = triangle.position[k];
      normalSum[p] += mesh.normals[triangle.normal[k]];
      if (material[p] == std::numeric_limits<uint32_t>::max()) material[p] = triangle.material;
      indices.push_back(p);
    }
  for (size_t i = 0; i < meshVertices; ++i) {
    const glm::dvec3& p = mesh.positions[i];
    vertices.insert(vertices.end(), {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
    const double length = glm::length(normalSum[i]);
    const glm::dvec3 n = length > 0 ? normalSum[i] / length : glm::dvec3(0.0);
    normals.insert(normals.end(), {static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z)});
    appendColor(colors, material[i] == std::numeric_limits<uint32_t>::max() ? 0 : material[i]);
  }
  uint32_t last = static_cast<uint32_t>(meshVertices) - 1;  // the vertex a segment ended at
  auto addVertex = [&](const glm::dvec3& p, uint32_t segmentMaterial) {
    vertices.insert(vertices.end(), {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
    normals.insert(normals.end(), {0.0f, 0.0f, 0.0f});
    appendColor(colors, segmentMaterial);
    return ++last;
  };
  for (size_t i = 0; i < segments.size(); ++i) {
    const uint32_t start = continues(segments, i) ? last : addVertex(segments[i].start, segments[i].material);
    const uint32_t end = addVertex(segments[i].end, segments[i].material);
    lines.insert(lines.end(), {start, end});
  }
  const auto n = static_cast<py::ssize_t>(vertices.size() / 3);
  handle.vertices = arrayOf(std::move(vertices), {n, 3});
  handle.normals = arrayOf(std::move(normals), {n, 3});
  handle.colors = arrayOf(std::move(colors), {n, 4});
  handle.indices = arrayOf(std::move(indices), {static_cast<py::ssize_t>(mesh.triangles.size()), 3});
  handle.lines = arrayOf(std::move(lines), {static_cast<py::ssize_t>(segments.size()), 2});

  // One record per drawing cell: id, parent (-1: none), its 4 x 4 transform (columns H,
  // L, U and the position where the turtle stood as it began).
  struct NodeRecord {
    uint64_t id;
    int64_t parent;
    double transform[4][4];
  };
  static_assert(sizeof(NodeRecord) == 144);
  py::module_ numpy = py::module_::import("numpy");
  py::list fields;
  fields.append(py::make_tuple("id", "<u8"));
  fields.append(py::make_tuple("parent", "<i8"));
  fields.append(py::make_tuple("transform", "<f8", py::make_tuple(4, 4)));
  py::array nodes = numpy.attr("zeros")(handle.scene.nodes.size(), numpy.attr("dtype")(fields));
  auto* records = static_cast<NodeRecord*>(nodes.mutable_data());
  for (size_t i = 0; i < handle.scene.nodes.size(); ++i) {
    const SceneNode& node = handle.scene.nodes[i];
    NodeRecord record{shownId(node.id), shownParent(node.parent), {}};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) record.transform[r][c] = node.orientation[c][r];
      record.transform[r][3] = node.position[r];
    }
    record.transform[3][3] = 1;
    std::memcpy(&records[i], &record, sizeof record);
  }
  handle.nodes = nodes;
}

// The sets named, made as a run makes them, recording the scene's nodes (the .glb's cells).
std::vector<std::unique_ptr<InterpretationSet>> drawingSets(const Program& program,
                                                            const std::vector<std::string>& names) {
  SetOptions options;
  options.sceneNodes = true;
  std::vector<std::unique_ptr<InterpretationSet>> drawing;
  for (const std::string& name : names) {
    std::unique_ptr<InterpretationSet> set;
    try {
      set = makeInterpretationSet(name, program.rootSystem().settings, options);
    } catch (const std::invalid_argument& error) {
      throw py::value_error(error.what());
    }
    if (!set) throw py::value_error("scene: there is no set '" + name + "'");
    if (!set->drawsScene()) throw py::value_error("scene: the set '" + name + "' draws no scene");
    drawing.push_back(std::move(set));
  }
  return drawing;
}

// What `drawing` makes of the world's word now, as a run draws a frame. The world's lock is held.
void draw(const World& grown, const std::string& stem, std::vector<std::unique_ptr<InterpretationSet>>& drawing,
          Scene& scene) {
  scene.time = grown.time();
  for (auto& set : drawing) {
    set->beginFrame(FrameTarget{".", stem, 0, 1, grown.time()});
    interpretWord(grown, *set);
    set->contribute(scene);
  }
}

// Frames collected into one .glb, written as `ontogen run` writes it (formats/scene_output.cpp):
// one skin from the first frame that holds a skeleton, else persistent parts.
class GlbFrames {
 public:
  void add(const Scene& scene) {
    if (skinned_.frameCount() > 0 || !scene.skeleton.empty())
      skinned_.addFrame(scene);
    else
      parts_.addFrame(scene);
  }
  std::string bytes() const {
    std::ostringstream out;
    if (skinned_.frameCount() > 0)
      skinned_.write(out);
    else
      parts_.write(out);
    return std::move(out).str();
  }

 private:
  GlbAnimationWriter parts_;
  SkinnedGlbWriter skinned_;
};

// Program's #interpret sets that draw a scene, else geometry: what a World shows itself with.
std::vector<std::string> shownSets(const Program& program) {
  std::vector<std::string> shown;
  for (const std::string& name : program.interpretSets) {
    std::unique_ptr<InterpretationSet> set = makeInterpretationSet(name, program.rootSystem().settings);
    if (set && set->drawsScene()) shown.push_back(name);
  }
  if (shown.empty()) shown.push_back("geometry");
  return shown;
}

}  // namespace


void bindScene(py::module_& module) {
  py::class_<SceneHandle, std::shared_ptr<SceneHandle>>(module, "Scene",
                                                        "What the drawing sets make of a word (World.scene).")
      .def_readonly("vertices", &SceneHandle::vertices, "N x 3 float32, model units; the OBJ's vertices in its order.")
      .def_readonly("normals", &SceneHandle::normals, "N x 3 float32 (zero at the ends of lines).")
      .def_readonly("colors", &SceneHandle::colors, "N x 4 float32, RGBA as displayed (sRGB).")
      .def_readonly("indices", &SceneHandle::indices, "M x 3 uint32: the triangles, anticlockwise seen from outside.")
      .def_readonly("lines", &SceneHandle::lines, "K x 2 uint32: the zero-radius line segments.")
      .def_readonly("nodes", &SceneHandle::nodes,
                    "One record per drawing cell: id (uint64), parent (int64, -1: none), transform (4 x 4).")
      .def_property_readonly("time", [](const SceneHandle& s) { return s.scene.time; }, "Seconds.")
      .def(
          "glb",
          [](const SceneHandle& s) {
            GlbFrames glb;
            glb.add(s.scene);
            return py::bytes(glb.bytes());
          },
          "The scene as the .glb `ontogen run --format glb` writes of one frame.");

  py::class_<WorldHandle, std::shared_ptr<WorldHandle>> world =
      py::reinterpret_borrow<py::class_<WorldHandle, std::shared_ptr<WorldHandle>>>(
          py::type::of<WorldHandle>());
  world.def(
      "scene",
      [](WorldHandle& handle, const std::vector<std::string>& sets) {
        auto made = std::make_shared<SceneHandle>();
        std::vector<std::unique_ptr<InterpretationSet>> drawing = drawingSets(*handle.program->program, sets);
        withoutGil([&](const std::function<void()>&) {
          std::lock_guard lock(handle.mutex);
          draw(*handle.world, handle.program->stem, drawing, made->scene);
        });
        makeArrays(*made);
        return made;
      },
      py::arg("sets") = std::vector<std::string>{"geometry"},
      "What the drawing sets (geometry, creature, physics) make of the word now, as a Scene.");
  world.def(
      "_animation",
      [](WorldHandle& handle, double until, int frames, const std::vector<std::string>& sets) {
        if (!std::isfinite(until)) throw py::value_error("animation: the time must be a finite number of seconds");
        if (frames < 1) throw py::value_error("animation: an animation needs at least one frame");
        std::vector<std::unique_ptr<InterpretationSet>> drawing = drawingSets(*handle.program->program, sets);
        GlbFrames glb;
        std::vector<double> times;
        withoutGil([&](const std::function<void()>& checkInterrupt) {
          std::lock_guard lock(handle.mutex);
          World& grown = *handle.world;
          // Frames spread over [now, until] as a run spreads them over [from, until].
          const double from = grown.time();
          const double to = std::max(until, from);
          for (int frame = 0; frame < frames; ++frame) {
            const double t = frames == 1 ? to : from + (to - from) * frame / (frames - 1);
            growTo(grown, t, handle.dt, handle.def.limits, checkInterrupt);
            Scene scene;
            draw(grown, handle.program->stem, drawing, scene);
            glb.add(scene);
            times.push_back(grown.time());
          }
        });
        std::string bytes = glb.bytes();
        return py::make_tuple(py::bytes(bytes), times);
      },
      py::arg("until"), py::arg("frames"), py::arg("sets"),
      "Grows the world to `until`, drawing `frames` frames spread over [now, until]: (.glb bytes, frame times).");
  world.def_property_readonly(
      "_shown_sets", [](const WorldHandle& handle) { return shownSets(*handle.program->program); },
      "The #interpret sets that draw a scene, else geometry.");
}

}  // namespace ontogen::python
