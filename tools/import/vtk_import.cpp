// vtk_import.cpp -- _tlod_import_vtk(): VTK's formats through VTK's readers into the import
// result (docs/vtk.md). The steps: list the files (vtk_series), read each with VTK
// (vtk_read) into plain arrays (vtk_dataset, vtk_fields), take the surface of step 0
// (vtk_boundary), keep only the points its faces and nodes use, then every step's positions
// and fields on those points. No VTK object outlives the read of its file.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <unordered_map>

#include "contained_file.h"
#include "import_error.hpp"
#include "import_output.hpp"
#include "vtk_boundary.hpp"
#include "vtk_cells.hpp"
#include "vtk_dataset.hpp"
#include "vtk_read.hpp"
#include "vtk_series.hpp"

namespace tlod_import_detail {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

struct Bytes {
  std::unique_ptr<unsigned char, decltype(&std::free)> data{nullptr, &std::free};
  size_t size = 0;
};

// A field of the output: every step's values on the output's vertices.
struct FieldOut {
  tlod_import_field info{};
  std::vector<float> data;
};

class VtkImport {
public:
  explicit VtkImport(const _tlod_import_job* job) : job_(job) {}

  tlod_result run() {
    list_steps();
    const Clock::time_point t0 = Clock::now();
    Dataset first = read_dataset(steps_[0].ref, "read");
    info_.read_ms += ms_since(t0);
    surface(first);
    fields_from(first, 0);
    for (size_t s = 1; s < steps_.size(); ++s)
      add_step(s, first);
    return finish(first);
  }

private:
  const _tlod_import_job* job_;
  std::vector<StepRef> steps_;
  OutputBase out_;
  tlod_import_vtk_info info_{};
  std::vector<uint8_t> sizes_;
  std::vector<uint32_t> nodes_;
  bool any_quads_ = false, any_nodes_ = false;
  std::vector<uint32_t> map_;  // file point -> output vertex (TLOD_NO_NODE: unused)
  std::vector<uint32_t> used_; // output vertex -> file point
  std::vector<FieldOut> fields_;
  std::vector<float> step_times_, step_positions_;
  std::vector<tlod_import_field> flat_fields_;
  std::string stage_;
  Clock::time_point last_progress_{};

  // -- budget, progress, messages -------------------------------------------------------
  void take(size_t bytes, const char* what) {
    if (!_tlod_budget_take(job_->budget, bytes))
      fail(TLOD_ERROR_OUT_OF_MEMORY, format("%s: %zu bytes exceed the import's memory budget (%zu bytes; "
                                            "tlod_import_desc.memory_limit)",
                                            what, bytes, job_->budget->limit));
  }

  size_t room() const {
    const _tlod_import_budget* b = job_->budget;
    return b->limit > b->used ? b->limit - b->used : 0;
  }

  void progress(const std::string& stage, double fraction) {
    if (!job_->progress) return;
    const Clock::time_point now = Clock::now();
    if (stage == stage_ && fraction < 1.0 && now - last_progress_ < std::chrono::milliseconds(50)) return;
    stage_ = stage;
    last_progress_ = now;
    job_->progress(job_->progress_user, stage.c_str(), fraction < 0 ? 0 : fraction > 1 ? 1 : fraction);
  }

  DatasetHooks dataset_hooks() {
    return {[this](size_t b, const char* w) { take(b, w); }, [this](const std::string& w) { out_.warn(w); }};
  }

  // -- files ----------------------------------------------------------------------------
  void list_steps() {
    const char* name = job_->name;
    if (strchr(name, '*')) {
      if (!job_->folder) fail(TLOD_ERROR_IO, "a numbered series ('*' in the name) cannot be read from memory");
      steps_ = numbered_steps(job_->folder, name);
    } else if (_tlod_str_ends_with_nocase(name, ".pvd")) {
      Bytes b = read_main();
      steps_ = pvd_steps(reinterpret_cast<const char*>(b.data.get()), b.size);
    } else {
      steps_ = {{"", 0.0f}};
    }
  }

  // The model file itself; its reader already wrote the error, which we pass on.
  Bytes read_main() {
    Bytes b;
    unsigned char* data = nullptr;
    const tlod_result res = _tlod_import_read_file(job_, &data, &b.size);
    b.data.reset(data);
    if (res != TLOD_SUCCESS) {
      const std::string e = job_->error ? job_->error : "";
      const std::string prefix = std::string(job_->name) + ": ";
      fail(res, e.compare(0, prefix.size(), prefix) == 0 ? e.substr(prefix.size()) : e);
    }
    return b;
  }

  Bytes read_ref(const std::string& ref) {
    const std::string where = format("'%.200s'", ref.c_str());
    if (!job_->folder) fail(TLOD_ERROR_IO, where + ": refused: an external file of a model imported from memory");
    Bytes b;
    unsigned char* data = nullptr;
    const _tlod_contained_status st =
        _tlod_contained_read(job_->folder, ref.c_str(), _tlod_budget_file_limit(job_->budget), &data, &b.size);
    b.data.reset(data);
    if (st != _TLOD_CONTAINED_OK)
      fail(tlod_result(_tlod_contained_result(st)), where + ": " + _tlod_contained_message(st));
    _tlod_budget_add_input(job_->budget, b.size);
    take(b.size, where.c_str());
    return b;
  }

  std::string file_path(const std::string& ref) const {
    if (ref.empty()) return job_->memory ? "" : job_->path;
    return std::string(job_->folder && *job_->folder ? job_->folder : ".") + "/" + ref;
  }

  // One file (ref "" = the model) as a data set; a .pvtu is the merge of its pieces.
  Dataset read_dataset(const std::string& ref, const std::string& stage) {
    const std::string name = ref.empty() ? std::string(job_->name) : ref;
    try {
      Bytes b = ref.empty() ? read_main() : read_ref(ref);
      if (!_tlod_str_ends_with_nocase(name.c_str(), ".pvtu")) return read_piece(b, name, file_path(ref), stage);
      const std::vector<std::string> pieces = pvtu_pieces(reinterpret_cast<const char*>(b.data.get()), b.size, ref);
      Dataset all;
      for (size_t i = 0; i < pieces.size(); ++i) {
        Bytes p = read_ref(pieces[i]);
        Dataset d = read_piece(p, pieces[i], file_path(pieces[i]), stage);
        merge(all, std::move(d), pieces[i]);
        progress(stage, double(i + 1) / double(pieces.size()));
      }
      weld(all);
      return all;
    } catch (ImportError& e) {
      if (!ref.empty()) e.message = format("'%.200s': ", ref.c_str()) + e.message;
      throw;
    }
  }

  Dataset read_piece(const Bytes& b, const std::string& name, const std::string& path, const std::string& stage) {
    VtkFormat format_id;
    if (!vtk_format_of(name, &format_id))
      fail(TLOD_ERROR_UNSUPPORTED, "not a file VTK reads here (.vtk, .vtu, .vtp, .stl)");
    take(b.size, "VTK's copy of the file"); // its readers copy the bytes they are given
    const VtkSource src{name, format_id, reinterpret_cast<const char*>(b.data.get()), b.size,
                        path.empty() ? nullptr : path.c_str()};
    vtkSmartPointer<vtkDataSet> ds = read_vtk(
        src, room(), [this](const std::string& w) { out_.warn(w); }, [&](double f) { progress(stage, f); });
    Dataset d;
    convert_dataset(ds, dataset_hooks(), d);
    const Clock::time_point t0 = Clock::now();
    read_fields(ds, dataset_hooks(), d);
    info_.fields_ms += ms_since(t0);
    return d;
  }

  // Appends piece to all (ids offset); its fields must be those of the first piece.
  void merge(Dataset& all, Dataset&& piece, const std::string& name) {
    const uint32_t base = uint32_t(all.point_count());
    if (all.points.empty() && all.cells.size() == 0) {
      all = std::move(piece);
      return;
    }
    if (uint64_t(base) + piece.point_count() > (uint64_t(1) << 31))
      fail(TLOD_ERROR_UNSUPPORTED, "pieces hold more than 2^31 points");
    all.points.insert(all.points.end(), piece.points.begin(), piece.points.end());
    const uint64_t conn = all.cells.conn.size();
    for (uint32_t id : piece.cells.conn)
      all.cells.conn.push_back(id + base);
    for (size_t i = 1; i < piece.cells.offsets.size(); ++i)
      all.cells.offsets.push_back(piece.cells.offsets[i] + conn);
    all.cells.types.insert(all.cells.types.end(), piece.cells.types.begin(), piece.cells.types.end());
    for (FieldData& f : all.fields) {
      const FieldData* g = find_field(piece, f);
      if (!g)
        fail(TLOD_ERROR_INVALID_MESH,
             format("piece '%.200s': no field '%.64s' (the first piece has it)", name.c_str(), f.name.c_str()));
      f.values.insert(f.values.end(), g->values.begin(), g->values.end());
    }
  }

  static const FieldData* find_field(const Dataset& d, const FieldData& like) {
    for (const FieldData& f : d.fields)
      if (f.name == like.name && f.units == like.units && f.from_cells == like.from_cells &&
          f.components == like.components)
        return &f;
    return nullptr;
  }

  // Pieces repeat the points on their shared faces: bitwise equal positions become one point,
  // so that those faces are interior (docs/vtk.md section 2). The first copy's values are kept.
  void weld(Dataset& d) {
    struct Key {
      double x, y, z;
      bool operator==(const Key& o) const { return memcmp(this, &o, sizeof o) == 0; }
    };
    struct Hash {
      size_t operator()(const Key& k) const {
        uint64_t h[3];
        memcpy(h, &k, sizeof h);
        return size_t((h[0] * 0x9E3779B97F4A7C15ull) ^ (h[1] * 0xC2B2AE3D27D4EB4Full) ^ (h[2] * 0x165667B19E3779F9ull));
      }
    };
    const size_t n = d.point_count();
    take(n * 48, "welding the pieces");
    std::unordered_map<Key, uint32_t, Hash> first;
    first.reserve(n);
    std::vector<uint32_t> to(n);
    std::vector<uint32_t> keep;
    for (size_t i = 0; i < n; ++i) {
      const Key k{d.points[3 * i], d.points[3 * i + 1], d.points[3 * i + 2]};
      const auto it = first.emplace(k, uint32_t(keep.size()));
      if (it.second) keep.push_back(uint32_t(i));
      to[i] = it.first->second;
    }
    for (uint32_t& id : d.cells.conn)
      id = to[id];
    std::vector<double> pts(keep.size() * 3);
    for (size_t i = 0; i < keep.size(); ++i)
      memcpy(&pts[3 * i], &d.points[3 * size_t(keep[i])], 24);
    d.points.swap(pts);
    for (FieldData& f : d.fields) {
      std::vector<float> v(keep.size() * f.components);
      for (size_t i = 0; i < keep.size(); ++i)
        memcpy(&v[i * f.components], &f.values[size_t(keep[i]) * f.components], 4 * f.components);
      f.values.swap(v);
    }
  }

  // -- the surface of step 0 -------------------------------------------------------------
  void surface(const Dataset& d) {
    const Clock::time_point t0 = Clock::now();
    Surface s;
    const SurfaceHooks hooks{[this](size_t b, const char* w) { take(b, w); },
                             [this](double f) { progress("boundary", f); }};
    extract_surface(d.cells, d.points.data(), hooks, s);
    if (s.sizes.empty())
      fail(TLOD_ERROR_UNSUPPORTED,
           format("no surface: none of its %zu cells is a surface or volume cell (%llu "
                  "ignored, %llu degenerate)",
                  d.cells.size(), (unsigned long long)s.cells_ignored, (unsigned long long)s.degenerate_cells));
    compact(d, s);
    fill_info(d, s);
    info_.boundary_ms = ms_since(t0);
  }

  // Keeps the points that faces and nodes use, in file order.
  void compact(const Dataset& d, const Surface& s) {
    const size_t n = d.point_count();
    map_.assign(n, TLOD_NO_NODE);
    for (uint32_t id : s.corners)
      map_[id] = 0;
    for (uint32_t id : s.nodes)
      if (id != TLOD_NO_NODE) map_[id] = 0, any_nodes_ = true;
    for (size_t i = 0; i < n; ++i)
      if (map_[i] == 0) map_[i] = uint32_t(used_.size()), used_.push_back(uint32_t(i));
    if (used_.size() > _TLOD_IMPORT_MAX_VERTICES || s.corners.size() > _TLOD_IMPORT_MAX_INDICES)
      fail(TLOD_ERROR_UNSUPPORTED, format("surface of %zu points and %zu corners: past the import's output limits",
                                          used_.size(), s.corners.size()));
    take(used_.size() * 12 + s.corners.size() * 4 + s.sizes.size() * (1 + 4 * TLOD_FACE_NODES), "surface");
    out_.positions = step_positions(d);
    for (uint32_t id : s.corners)
      out_.indices.push_back(map_[id]);
    sizes_ = s.sizes;
    for (uint8_t k : sizes_)
      any_quads_ = any_quads_ || k == 4;
    if (!any_nodes_) return;
    nodes_.reserve(s.nodes.size());
    for (uint32_t id : s.nodes)
      nodes_.push_back(id == TLOD_NO_NODE ? TLOD_NO_NODE : map_[id]);
  }

  std::vector<float> step_positions(const Dataset& d) const {
    std::vector<float> p(used_.size() * 3);
    for (size_t v = 0; v < used_.size(); ++v)
      for (int k = 0; k < 3; ++k)
        p[3 * v + size_t(k)] = float(d.points[3 * size_t(used_[v]) + size_t(k)]);
    return p;
  }

  void fill_info(const Dataset& d, const Surface& s) {
    info_.points = d.point_count();
    info_.cells = d.cells.size();
    for (int t = 0; t < 256; ++t) {
      if (!s.type_counts[size_t(t)] || info_.cell_type_count == TLOD_IMPORT_MAX_CELL_TYPES) continue;
      tlod_import_cell_count& c = info_.cell_types[info_.cell_type_count++];
      c.vtk_type = uint32_t(t);
      const CellKind* k = cell_kind(t);
      snprintf(c.name, sizeof c.name, "%s", k ? k->name : "unknown");
      c.count = s.type_counts[size_t(t)];
    }
    info_.volume_cells = s.volume_cells;
    info_.boundary_triangles = s.triangles;
    info_.boundary_quads = s.quads;
    info_.second_order_faces = s.second_order_faces;
    info_.interior_faces = s.interior_faces;
    info_.non_manifold_faces = s.non_manifold_faces;
    info_.cells_reoriented = s.cells_reoriented;
    info_.degenerate_cells = s.degenerate_cells;
    info_.cells_collapsed = s.cells_collapsed;
    info_.polygons_triangulated = s.polygons_triangulated;
    info_.strips_converted = s.strips_converted;
    info_.cells_ignored = s.cells_ignored;
    if (s.non_manifold_faces)
      out_.warn(
          format("%llu faces shared by three or more cells: kept once", (unsigned long long)s.non_manifold_faces));
    if (s.degenerate_cells)
      out_.warn(format("%llu cells with repeated points dropped", (unsigned long long)s.degenerate_cells));
  }

  // -- fields and steps -------------------------------------------------------------------
  void fields_from(const Dataset& d, size_t step) {
    const Clock::time_point t0 = Clock::now();
    const size_t v = used_.size();
    if (step == 0)
      for (const FieldData& f : d.fields) {
        FieldOut o;
        snprintf(o.info.name, sizeof o.info.name, "%s", f.name.c_str());
        snprintf(o.info.units, sizeof o.info.units, "%s", f.units.c_str());
        o.info.components = f.components;
        o.info.from_cells = f.from_cells;
        fields_.push_back(std::move(o));
      }
    for (size_t i = 0; i < fields_.size(); ++i) {
      const FieldData* f = step == 0 ? &d.fields[i] : find_field(d, as_data(fields_[i]));
      if (!f) fail(TLOD_ERROR_INVALID_MESH, format("no field '%.64s' (step 0 has it)", fields_[i].info.name));
      const size_t k = f->components;
      take(v * k * 4, "fields");
      for (size_t j = 0; j < v; ++j)
        fields_[i].data.insert(fields_[i].data.end(), &f->values[used_[j] * k], &f->values[used_[j] * k] + k);
      if (step == 0) progress("fields", double(i + 1) / double(fields_.size()));
    }
    info_.fields_ms += ms_since(t0);
  }

  static FieldData as_data(const FieldOut& o) {
    FieldData f;
    f.name = o.info.name;
    f.units = o.info.units;
    f.components = o.info.components;
    f.from_cells = o.info.from_cells;
    return f;
  }

  void add_step(size_t s, const Dataset& first) {
    const std::string stage = format("step %zu/%zu", s + 1, steps_.size());
    const Clock::time_point t0 = Clock::now();
    Dataset d = read_dataset(steps_[s].ref, stage);
    info_.read_ms += ms_since(t0);
    try {
      if (d.point_count() != first.point_count() || d.cells.types != first.cells.types ||
          d.cells.offsets != first.cells.offsets || d.cells.conn != first.cells.conn)
        fail(TLOD_ERROR_INVALID_MESH, format("step %zu: its points or cells differ from step 0's (a series must keep "
                                             "its cells)",
                                             s));
      if (step_positions_.empty()) step_positions_ = out_.positions;
      const std::vector<float> p = step_positions(d);
      take(p.size() * 4, "step positions");
      step_positions_.insert(step_positions_.end(), p.begin(), p.end());
      fields_from(d, s);
    } catch (ImportError& e) {
      e.message = format("'%.200s': ", steps_[s].ref.c_str()) + e.message;
      throw;
    }
  }

  // -- the result -------------------------------------------------------------------------
  void ranges(FieldOut& f) {
    const size_t k = f.info.components;
    for (size_t j = 0; j < k; ++j)
      f.info.min[j] = INFINITY, f.info.max[j] = -INFINITY;
    f.info.magnitude_min = INFINITY;
    f.info.magnitude_max = -INFINITY;
    for (size_t t = 0; t + k <= f.data.size(); t += k) {
      double m = 0;
      for (size_t j = 0; j < k; ++j) {
        const float x = f.data[t + j];
        f.info.min[j] = std::fmin(f.info.min[j], x);
        f.info.max[j] = std::fmax(f.info.max[j], x);
        m += double(x) * x;
      }
      f.info.magnitude_min = std::fmin(f.info.magnitude_min, float(std::sqrt(m)));
      f.info.magnitude_max = std::fmax(f.info.magnitude_max, float(std::sqrt(m)));
    }
  }

  tlod_result finish(const Dataset&) {
    const Clock::time_point t0 = Clock::now();
    for (FieldOut& f : fields_) {
      ranges(f);
      f.info.data = f.data.data();
      flat_fields_.push_back(f.info);
    }
    info_.fields_ms += ms_since(t0);
    tlod_import_part part{};
    snprintf(part.name, sizeof part.name, "%s", job_->name);
    part.face_count = uint32_t(sizes_.size());
    part.vertex_count = uint32_t(used_.size());
    for (float& c : part.base_color)
      c = 1.0f;
    part.material = part.node = TLOD_IMPORT_NONE;
    out_.parts.push_back(part);
    _tlod_import_data d{};
    out_.fill(d);
    d.face_count = uint32_t(sizes_.size());
    d.face_sizes = any_quads_ ? sizes_.data() : nullptr;
    d.face_nodes = any_nodes_ ? nodes_.data() : nullptr;
    d.polygons_triangulated = uint32_t(std::min<uint64_t>(info_.polygons_triangulated, UINT32_MAX));
    d.strips_fans_converted = uint32_t(std::min<uint64_t>(info_.strips_converted, UINT32_MAX));
    d.field_count = uint32_t(flat_fields_.size());
    d.fields = flat_fields_.data();
    d.vtk = &info_;
    if (steps_.size() > 1) {
      for (const StepRef& s : steps_)
        step_times_.push_back(s.time);
      d.step_count = uint32_t(steps_.size());
      d.step_times = step_times_.data();
      d.step_positions = step_positions_.data();
    }
    return _tlod_import_finish(job_, &d);
  }
};

} // namespace
} // namespace tlod_import_detail

tlod_result _tlod_import_vtk(const _tlod_import_job* job) {
  return tlod_import_detail::guarded(job, "VTK", [&] { return tlod_import_detail::VtkImport(job).run(); });
}
