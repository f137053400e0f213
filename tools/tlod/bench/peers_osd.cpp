/* tlod bench --peers -- the OpenSubdiv side (peers_osd.h): Far's refiners and
 * tables, Osd::CpuEvaluator, and a counting operator new for the heap figures. */
#include "peers_osd.h"

#include <malloc.h>
#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/osd/cpuEvaluator.h>
#include <opensubdiv/osd/cpuPatchTable.h>
#include <opensubdiv/version.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

using namespace OpenSubdiv;

/* ---- The heap: OpenSubdiv allocates through operator new, so a counting
 * operator new measures it (the bench is the only user of C++ while it
 * measures). Under AddressSanitizer the sanitizer owns operator new (its
 * nothrow and aligned forms too, which a replacement would mismatch with
 * the drivers' frees): the figure is then the sanitizer's count of bytes in
 * use, sampled, whose high mark is the in-use size at the samples. ---- */
#if defined(__SANITIZE_ADDRESS__)
#define PEERS_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PEERS_ASAN 1
#endif
#endif

namespace {
std::atomic<uint64_t> heap_high{0};

void note_high(uint64_t now) {
  uint64_t high = heap_high.load();
  while (now > high && !heap_high.compare_exchange_weak(high, now)) {
  }
}
} // namespace

#ifdef PEERS_ASAN
/* The sanitizer runtime's (GCC's and clang's); GCC ships no header for it. */
extern "C" size_t __sanitizer_get_current_allocated_bytes(void);
static uint64_t heap_now(void) {
  uint64_t now = __sanitizer_get_current_allocated_bytes();
  note_high(now);
  return now;
}
#else
namespace {
std::atomic<uint64_t> heap_in_use{0};

void* counted_alloc(size_t n) {
  void* p = std::malloc(n ? n : 1);
  if (!p) throw std::bad_alloc();
  note_high(heap_in_use += malloc_usable_size(p));
  return p;
}

void counted_free(void* p) noexcept {
  if (!p) return;
  heap_in_use -= malloc_usable_size(p);
  std::free(p);
}
} // namespace

void* operator new(size_t n) { return counted_alloc(n); }
void* operator new[](size_t n) { return counted_alloc(n); }
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, size_t) noexcept { counted_free(p); }
void operator delete[](void* p, size_t) noexcept { counted_free(p); }
static uint64_t heap_now(void) { return heap_in_use.load(); }
#endif

extern "C" uint64_t peers_osd_heap_now(void) { return heap_now(); }
extern "C" uint64_t peers_osd_heap_peak(void) {
  note_high(heap_now());
  return heap_high.load();
}
extern "C" void peers_osd_heap_reset_peak(void) { heap_high.store(heap_now()); }

/* ---- The refiners ---- */
namespace {
/* A primvar as Far::PrimvarRefiner and PatchTable::ComputeLocalPointValues want it. */
struct Point {
  float p[3];
  void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0.0f; }
  void AddWithWeight(const Point& s, float w) {
    p[0] += w * s.p[0];
    p[1] += w * s.p[1];
    p[2] += w * s.p[2];
  }
};

/* Isolation of the limit path's adaptive refinement around extraordinary
 * features, with Gregory end caps (OpenSubdiv's viewers default to 2-3). */
constexpr int kIsolation = 2;

using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
} // namespace

struct peers_osd {
  bool limit = false, loop = false;
  uint32_t level = 0, vertex_count = 0;
  std::vector<uint32_t> face_first, indices;
  std::vector<uint8_t> face_sizes;
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::vector<Point> points;       /* every refined level, then (limit) the local points */
  std::vector<size_t> level_first; /* first point of each level */
  std::unique_ptr<Far::PatchTable> patches;
  std::unique_ptr<Osd::CpuPatchTable> cpu_patches;
  std::vector<Osd::PatchCoord> samples, corners;
  std::vector<uint32_t> corner_vertex;
  std::vector<float> pos, du, dv, nrm;
};

namespace {
Far::TopologyRefiner* make_refiner(const peers_osd_desc* d, bool loop) {
  std::vector<int> sizes(d->face_sizes, d->face_sizes + d->face_count);
  size_t n = 0;
  for (int s : sizes)
    n += (size_t)s;
  std::vector<int> idx(d->indices, d->indices + n);
  Far::TopologyDescriptor td;
  td.numVertices = (int)d->vertex_count;
  td.numFaces = (int)d->face_count;
  td.numVertsPerFace = sizes.data();
  td.vertIndicesPerFace = idx.data();
  Sdc::Options so;
  so.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  return Factory::Create(td, Factory::Options(loop ? Sdc::SCHEME_LOOP : Sdc::SCHEME_CATMARK, so));
}

/* Control points into level 0, then every refined level from the one before. */
void refine_levels(peers_osd* o, const float* control) {
  std::copy(control, control + 3 * (size_t)o->vertex_count, o->points[0].p);
  Far::PrimvarRefiner pr(*o->refiner);
  for (int l = 1; l <= o->refiner->GetMaxLevel(); l++) {
    Point* src = &o->points[o->level_first[l - 1]];
    Point* dst = &o->points[o->level_first[l]];
    pr.Interpolate(l, src, dst);
  }
}

void size_levels(peers_osd* o, size_t extra) {
  o->level_first.assign(1, 0);
  for (int l = 0; l <= o->refiner->GetMaxLevel(); l++)
    o->level_first.push_back(o->level_first.back() + (size_t)o->refiner->GetLevel(l).GetNumVertices());
  o->points.resize(o->level_first.back() + extra);
}

void add_coord(const Far::PatchMap& map, int face, float u, float v, std::vector<Osd::PatchCoord>& out) {
  const Far::PatchTable::PatchHandle* h = map.FindPatch(face, u, v);
  if (h) out.emplace_back(*h, u, v);
}

/* Half-open grids: n x n per quad ptex face, the n(n+1)/2 points i + j < n per Loop triangle. */
void add_grid(peers_osd* o, const Far::PatchMap& map, int face, int n, bool triangle) {
  for (int j = 0; j < n; j++) {
    for (int i = 0; i < (triangle ? n - j : n); i++)
      add_coord(map, face, (float)i / (float)n, (float)j / (float)n, o->samples);
  }
}

void add_corners(peers_osd* o, const Far::PatchMap& map, int ptex, uint32_t f) {
  static const float quad[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, tri[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  uint32_t n = o->face_sizes[f];
  for (uint32_t c = 0; c < n; c++) {
    const float* uv = o->loop ? tri[c] : n == 4 ? quad[c] : quad[0];
    int face = o->loop || n == 4 ? ptex : ptex + (int)c; /* a non-quad's sub-face c starts at corner c */
    size_t before = o->corners.size();
    add_coord(map, face, uv[0], uv[1], o->corners);
    if (o->corners.size() > before) o->corner_vertex.push_back(o->indices[o->face_first[f] + c]);
  }
}

void make_samples(peers_osd* o) {
  Far::PatchMap map(*o->patches);
  Far::PtexIndices ptex(*o->refiner);
  int n = 1 << o->level;
  for (uint32_t f = 0; f < (uint32_t)o->face_sizes.size(); f++) {
    int id = ptex.GetFaceId((Far::Index)f), sides = o->face_sizes[f];
    if (o->loop || sides == 4) {
      add_grid(o, map, id, n, o->loop);
    } else {
      for (int k = 0; k < sides; k++)
        add_grid(o, map, id + k, n / 2, false);
    }
    add_corners(o, map, id, f);
  }
}

void make_limit(peers_osd* o, const float* control) {
  Far::PatchTableFactory::Options po(kIsolation);
  po.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
  o->refiner->RefineAdaptive(po.GetRefineAdaptiveOptions());
  o->patches.reset(Far::PatchTableFactory::Create(*o->refiner, po));
  o->cpu_patches.reset(Osd::CpuPatchTable::Create(o->patches.get()));
  make_samples(o);
  size_levels(o, (size_t)o->patches->GetNumLocalPoints());
  refine_levels(o, control);
  o->patches->ComputeLocalPointValues(&o->points[0], &o->points[o->level_first.back()]);
}

void eval_coords(peers_osd* o, const std::vector<Osd::PatchCoord>& c, float* p, float* du, float* dv) {
  Osd::BufferDescriptor d3(0, 3, 3);
  const Osd::CpuPatchTable* t = o->cpu_patches.get();
  if (du)
    Osd::CpuEvaluator::EvalPatches(o->points[0].p, d3, p, d3, du, d3, dv, d3, (int)c.size(), c.data(),
                                   t->GetPatchArrayBuffer(), t->GetPatchIndexBuffer(), t->GetPatchParamBuffer());
  else
    Osd::CpuEvaluator::EvalPatches(o->points[0].p, d3, p, d3, (int)c.size(), c.data(), t->GetPatchArrayBuffer(),
                                   t->GetPatchIndexBuffer(), t->GetPatchParamBuffer());
}

void unit_normals(peers_osd* o) {
  for (size_t i = 0; i < o->samples.size(); i++) {
    const float *a = &o->du[3 * i], *b = &o->dv[3 * i];
    float n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    float s = len > 0.0f ? 1.0f / len : 0.0f;
    for (int k = 0; k < 3; k++)
      o->nrm[3 * i + k] = n[k] * s;
  }
}

double distance3(const float* a, const float* b) {
  double x = (double)a[0] - b[0], y = (double)a[1] - b[1], z = (double)a[2] - b[2];
  return std::sqrt(x * x + y * y + z * z);
}
} // namespace

#define PEERS_STR(x) #x
#define PEERS_XSTR(x) PEERS_STR(x)
extern "C" const char* peers_osd_version(void) {
  return PEERS_XSTR(OPENSUBDIV_VERSION_MAJOR) "." PEERS_XSTR(OPENSUBDIV_VERSION_MINOR) "." PEERS_XSTR(
      OPENSUBDIV_VERSION_PATCH);
}

extern "C" peers_osd* peers_osd_create(const peers_osd_desc* d, char* err, size_t err_size) {
  auto o = std::make_unique<peers_osd>();
  o->limit = d->limit;
  o->level = d->level;
  o->vertex_count = d->vertex_count;
  o->face_sizes.assign(d->face_sizes, d->face_sizes + d->face_count);
  o->loop = std::all_of(o->face_sizes.begin(), o->face_sizes.end(), [](uint8_t s) { return s == 3; });
  for (uint8_t s : o->face_sizes) {
    o->face_first.push_back((uint32_t)o->indices.size());
    o->indices.insert(o->indices.end(), d->indices + o->indices.size(), d->indices + o->indices.size() + s);
  }
  o->refiner.reset(make_refiner(d, o->loop));
  if (!o->refiner) {
    std::snprintf(err, err_size, "OpenSubdiv: the topology of the %u faces was refused", d->face_count);
    return nullptr;
  }
  if (d->limit) {
    make_limit(o.get(), d->positions);
  } else {
    o->refiner->RefineUniform(Far::TopologyRefiner::UniformOptions((int)d->level));
  }
  return o.release();
}

extern "C" void peers_osd_destroy(peers_osd* o) { delete o; }

extern "C" const char* peers_osd_scheme(const peers_osd* o) { return o->loop ? "loop" : "catmull-clark"; }

extern "C" uint64_t peers_osd_output_count(const peers_osd* o) {
  return o->limit ? o->samples.size() : (uint64_t)o->refiner->GetLevel((int)o->level).GetNumVertices();
}

extern "C" void peers_osd_evaluate(peers_osd* o, const float* control, bool deforming) {
  if (!o->limit) {
    if (o->points.empty()) size_levels(o, 0);
    refine_levels(o, control);
    return;
  }
  if (deforming) {
    refine_levels(o, control);
    o->patches->ComputeLocalPointValues(&o->points[0], &o->points[o->level_first.back()]);
  }
  size_t n = 3 * o->samples.size();
  if (o->pos.size() != n) o->pos.resize(n), o->du.resize(n), o->dv.resize(n), o->nrm.resize(n);
  eval_coords(o, o->samples, o->pos.data(), o->du.data(), o->dv.data());
  unit_normals(o);
}

extern "C" double peers_osd_vertex_distance(const peers_osd* o, const float* input) {
  double worst = 0.0;
  if (!o->limit) {
    const Point* last = &o->points[o->level_first[o->level]];
    for (uint32_t v = 0; v < o->vertex_count; v++)
      worst = std::max(worst, distance3(last[v].p, input + 3 * (size_t)v));
    return worst;
  }
  std::vector<float> at(3 * o->corners.size());
  eval_coords(const_cast<peers_osd*>(o), o->corners, at.data(), nullptr, nullptr);
  for (size_t i = 0; i < o->corners.size(); i++)
    worst = std::max(worst, distance3(&at[3 * i], input + 3 * (size_t)o->corner_vertex[i]));
  return worst;
}

extern "C" double peers_osd_volume(const peers_osd* o) {
  if (o->limit) return 0.0;
  const Far::TopologyLevel& lv = o->refiner->GetLevel((int)o->level);
  const Point* p = &o->points[o->level_first[o->level]];
  double vol = 0.0;
  for (int f = 0; f < lv.GetNumFaces(); f++) {
    Far::ConstIndexArray fv = lv.GetFaceVertices(f);
    for (int k = 1; k + 1 < fv.size(); k++) { /* a fan: exact for planar faces, the usual measure for quads */
      const float *a = p[fv[0]].p, *b = p[fv[k]].p, *c = p[fv[k + 1]].p;
      vol += ((double)a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) +
              (double)a[1] * ((double)b[2] * c[0] - (double)b[0] * c[2]) +
              (double)a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0])) /
             6.0;
    }
  }
  return vol;
}
