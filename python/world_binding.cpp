// World and Cell: a program grown in time, its word as Python objects (World.word) or as
// columns of numpy arrays (World.arrays), read without a record per cell.

#include <cmath>
#include <limits>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "core/limits.h"
#include "core/word.h"
#include "interpreters/set_registry.h"
#include "python/bindings.h"
#include "python/handles.h"

namespace py = pybind11;

namespace ontogen::python {

namespace {

// A vector handed to numpy without a copy: the array owns it.
template <typename T>
py::array_t<T> arrayOf(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* held = new std::vector<T>(std::move(values));
  py::capsule owner(held, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, held->data(), owner);
}

// The word's columns, cell by cell in pool order (a system cell followed by its pool's
// cells), as World.arrays gives them.
class ColumnsVisitor final : public WordVisitor {
 public:
  explicit ColumnsVisitor(size_t cells) {
    ids.reserve(cells);
    parents.reserve(cells);
    ages.reserve(cells);
    labels.reserve(cells);
    paramCounts.reserve(cells);
  }

  void cell(const WordCellView& cell) override {
    ids.push_back(shownId(cell.id));
    parents.push_back(shownParent(cell.parent));
    ages.push_back(cell.age);
    labels.push_back(labelIndex(cell.label));
    paramCounts.push_back(static_cast<uint32_t>(cell.params.size()));
    params.insert(params.end(), cell.params.begin(), cell.params.end());
    widest = std::max(widest, cell.params.size());
    if (!cell.position.empty() || !positions.empty()) {
      // Cells before the first with a position have none.
      positions.resize(3 * (ids.size() - 1), std::numeric_limits<double>::quiet_NaN());
      for (size_t k = 0; k < 3; ++k)
        positions.push_back(k < cell.position.size() ? cell.position[k] : std::numeric_limits<double>::quiet_NaN());
    }
  }

  std::vector<uint64_t> ids;
  std::vector<int64_t> parents;
  std::vector<double> ages;
  std::vector<int32_t> labels;
  std::vector<std::string> labelNames;
  std::vector<double> params;          // every cell's, one after another
  std::vector<uint32_t> paramCounts;   // per cell
  size_t widest = 0;                   // the most parameters a cell has
  std::vector<double> positions;       // 3 per cell once a cell has one

 private:
  // A master's label is one string for the program's life: its address finds its index
  // without hashing the text (a name hashed once per master).
  int32_t labelIndex(std::string_view label) {
    if (label.data() == lastLabel_.data() && label.size() == lastLabel_.size()) return lastIndex_;
    auto found = byAddress_.find(label.data());
    int32_t index;
    if (found != byAddress_.end() && labelNames[static_cast<size_t>(found->second)] == label) {
      index = found->second;
    } else {
      auto named = byName_.find(std::string(label));
      if (named == byName_.end()) {
        named = byName_.emplace(std::string(label), static_cast<int32_t>(labelNames.size())).first;
        labelNames.emplace_back(label);
      }
      index = named->second;
      byAddress_[label.data()] = index;
    }
    lastLabel_ = label;
    lastIndex_ = index;
    return index;
  }

  std::unordered_map<const char*, int32_t> byAddress_;
  std::unordered_map<std::string, int32_t> byName_;
  std::string_view lastLabel_;
  int32_t lastIndex_ = 0;
};

py::dict arraysOf(WorldHandle& handle) {
  std::unique_ptr<ColumnsVisitor> columns;
  withoutGil([&](const std::function<void()>&) {
    std::lock_guard lock(handle.mutex);
    columns = std::make_unique<ColumnsVisitor>(static_cast<size_t>(handle.world->totalCells()));
    visitWord(*handle.world, *columns);
  });
  const auto n = static_cast<py::ssize_t>(columns->ids.size());
  const auto k = static_cast<py::ssize_t>(columns->widest);
  // n x k, NaN past a cell's own parameters; the flat list is already that when every
  // cell has k of them.
  std::vector<double> params;
  if (columns->params.size() == static_cast<size_t>(n * k)) {
    params = std::move(columns->params);
  } else {
    params.assign(static_cast<size_t>(n * k), std::numeric_limits<double>::quiet_NaN());
    size_t from = 0;
    for (size_t i = 0; i < columns->paramCounts.size(); ++i) {
      std::copy_n(columns->params.begin() + static_cast<std::ptrdiff_t>(from), columns->paramCounts[i],
                  params.begin() + static_cast<std::ptrdiff_t>(i * columns->widest));
      from += columns->paramCounts[i];
    }
  }
  py::dict arrays;
  arrays["id"] = arrayOf(std::move(columns->ids), {n});
  arrays["parent"] = arrayOf(std::move(columns->parents), {n});
  arrays["age"] = arrayOf(std::move(columns->ages), {n});
  arrays["label"] = arrayOf(std::move(columns->labels), {n});
  arrays["labels"] = py::cast(columns->labelNames);
  arrays["params"] = arrayOf(std::move(params), {n, k});
  if (!columns->positions.empty()) {
    columns->positions.resize(static_cast<size_t>(3 * n), std::numeric_limits<double>::quiet_NaN());
    arrays["position"] = arrayOf(std::move(columns->positions), {n, 3});
  }
  return arrays;
}

py::list wordOf(WorldHandle& handle) {
  std::vector<WordCell> word;
  withoutGil([&](const std::function<void()>&) {
    std::lock_guard lock(handle.mutex);
    word = captureWord(*handle.world);
  });
  py::list cells;
  for (WordCell& cell : word) cells.append(py::cast(std::move(cell)));
  return cells;
}

void advance(WorldHandle& handle, double until) {
  if (!std::isfinite(until)) throw py::value_error("advance: the time must be a finite number of seconds");
  withoutGil([&](const std::function<void()>& checkInterrupt) {
    std::lock_guard lock(handle.mutex);
    growTo(*handle.world, until, handle.dt, handle.def.limits, checkInterrupt);
  });
}

}  // namespace

void growTo(World& world, double until, double dt, const WorldLimits& limits,
            const std::function<void()>& checkInterrupt) {
  if (until <= world.time()) return;  // time runs forward only
  // The whole growth is checked against the step limit at once, as advanceTo checks it.
  checkStepLimit(world.stats().steps, std::ceil((until - world.time()) / dt), dt, until, limits);
  // Step by step along the grid k * dt, where a stop changes nothing (as a run's frames
  // stop), so that Ctrl-C is seen between steps.
  while (world.time() < until - timeTolerance(until)) {
    const double next = (std::floor(world.time() / dt + 1e-9) + 1) * dt;
    world.advanceTo(std::min(next, until), dt);
    checkInterrupt();
  }
}

namespace {

std::string cellRepr(const WordCell& cell) {
  std::string text = "<ontogen.Cell " + cell.label;
  if (!cell.params.empty()) {
    text += "(";
    for (size_t i = 0; i < cell.params.size(); ++i) text += (i ? ", " : "") + py::repr(py::float_(cell.params[i])).cast<std::string>();
    text += ")";
  }
  return text + " id " + std::to_string(shownId(cell.id)) + ">";
}

}  // namespace

std::shared_ptr<WorldHandle> makeWorld(std::shared_ptr<ProgramHandle> program, uint64_t seed, unsigned threads) {
  auto handle = std::make_shared<WorldHandle>();
  handle->def.seed = seed;
  handle->def.threads = threads;
  handle->def.environment = queryEnvironmentOf(*program->program);
  handle->dt = program->program->dt;
  handle->program = std::move(program);
  withoutGil([&](const std::function<void()>&) {
    handle->world = std::make_unique<World>(handle->program->program, handle->def);
  });
  return handle;
}

void bindWorld(py::module_& module) {
  py::class_<WordCell>(module, "Cell", "A cell of a world's word (World.word).")
      .def_property_readonly("label", [](const WordCell& c) { return c.label; })
      .def_property_readonly("params", [](const WordCell& c) { return py::tuple(py::cast(c.params)); },
                             "Its parameters (state values in declaration order).")
      .def_property_readonly("developed", [](const WordCell& c) { return py::tuple(py::cast(c.developed)); },
                             "Its parameters after the development function.")
      .def_property_readonly("age", [](const WordCell& c) { return c.age; }, "Seconds.")
      .def_property_readonly("id", [](const WordCell& c) { return shownId(c.id); },
                             "Its stable id (the low 53 bits, as words show it and rules read it).")
      .def_property_readonly("parent", [](const WordCell& c) { return shownParent(c.parent); },
                             "The id of the cell it hangs from, -1 for none.")
      .def_property_readonly("position",
                             [](const WordCell& c) -> py::object {
                               if (c.position.empty()) return py::none();
                               return py::tuple(py::cast(c.position));
                             },
                             "Grid coordinates or spatial x, y, z; None in a linear pool.")
      .def_property_readonly("pool",
                             [](const WordCell& c) -> py::object {
                               if (!c.system) return py::none();
                               return py::cast(c.pool);
                             },
                             "A system cell's cells (a list); None for other cells.")
      .def("__repr__", &cellRepr);

  py::class_<WorldHandle, std::shared_ptr<WorldHandle>>(module, "World", "A program growing in time (Program.world).")
      .def("advance", &advance, py::arg("until"),
           "Grows the world to `until` seconds (time only runs forward), the GIL released; Ctrl-C stops it "
           "between steps.")
      .def_property_readonly("time", [](WorldHandle& w) {
        py::gil_scoped_release release;  // a growth in another thread holds the lock
        std::lock_guard lock(w.mutex);
        return w.world->time();
      }, "Seconds of developmental time.")
      .def_property_readonly("seed", [](const WorldHandle& w) { return w.def.seed; })
      .def_property_readonly("program", [](const WorldHandle& w) { return w.program; })
      .def("word", &wordOf, "The word's cells in pool order (a list of Cell).")
      .def("arrays", &arraysOf,
           "The word as numpy columns: id (uint64), parent (int64, -1: none), age, label (indices into "
           "labels), labels, params (n x k, NaN where a cell has fewer), and position (n x 3) for grid and "
           "spatial pools.");
}

}  // namespace ontogen::python
