/* vtk_model.c -- the test meshes' arrays and their VTK writers (legacy ASCII and binary, XML .vtu
 * ASCII), after the file format description "VTK File Formats" (VTK User's Guide, Kitware). */
#include "vtk_model.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void* grow(void* p, uint32_t* capacity, uint32_t need, size_t elem) {
  if (need <= *capacity) return p;
  uint32_t cap = *capacity ? *capacity : 64;
  while (cap < need)
    cap *= 2;
  p = realloc(p, (size_t)cap * elem);
  if (!p) {
    fprintf(stderr, "vtk_model: out of memory\n");
    abort();
  }
  *capacity = cap;
  return p;
}

uint32_t vtk_model_point(vtk_model* m, double x, double y, double z) {
  m->points = grow(m->points, &m->point_capacity, m->point_count + 1, 3 * sizeof(double));
  double* p = m->points + 3 * (size_t)m->point_count;
  p[0] = x, p[1] = y, p[2] = z;
  return m->point_count++;
}

void vtk_model_cell(vtk_model* m, uint8_t type, const uint32_t* nodes, uint32_t count) {
  /* types and offsets share one capacity: both grow to the same need */
  uint32_t cap = m->cell_capacity;
  m->types = grow(m->types, &cap, m->cell_count + 2, 1);
  cap = m->cell_capacity;
  m->offsets = grow(m->offsets, &cap, m->cell_count + 2, sizeof(uint32_t));
  m->cell_capacity = cap;
  m->conn = grow(m->conn, &m->conn_capacity, m->conn_count + count, sizeof(uint32_t));
  memcpy(m->conn + m->conn_count, nodes, count * sizeof(uint32_t));
  m->types[m->cell_count] = type;
  m->offsets[m->cell_count] = m->conn_count;
  m->conn_count += count;
  m->offsets[++m->cell_count] = m->conn_count;
}

double* vtk_model_field_add(vtk_model* m, const char* name, uint32_t components, bool cells) {
  vtk_model_field* f = &m->fields[m->field_count++];
  snprintf(f->name, sizeof f->name, "%s", name);
  f->components = components;
  f->cells = cells;
  f->data = calloc((size_t)components * (cells ? m->cell_count : m->point_count) + 1, sizeof(double));
  return f->data;
}

void vtk_model_free(vtk_model* m) {
  free(m->points);
  free(m->types);
  free(m->offsets);
  free(m->conn);
  for (uint32_t k = 0; k < m->field_count; ++k)
    free(m->fields[k].data);
  memset(m, 0, sizeof *m);
}

/* ---- legacy format ---- */

/* Legacy binary numbers are big-endian. */
static void put_be32(FILE* f, uint32_t v) {
  unsigned char b[4] = {(unsigned char)(v >> 24), (unsigned char)(v >> 16), (unsigned char)(v >> 8), (unsigned char)v};
  fwrite(b, 1, 4, f);
}

static void put_be64(FILE* f, double d) {
  uint64_t v;
  memcpy(&v, &d, 8);
  put_be32(f, (uint32_t)(v >> 32));
  put_be32(f, (uint32_t)v);
}

static void legacy_doubles(FILE* f, const double* d, size_t n, size_t per_line, bool binary) {
  for (size_t k = 0; k < n; ++k) {
    if (binary)
      put_be64(f, d[k]);
    else
      fprintf(f, "%.17g%c", d[k], (k + 1) % per_line ? ' ' : '\n');
  }
  if (binary) fputc('\n', f);
}

static void legacy_cells(FILE* f, const vtk_model* m, bool binary) {
  fprintf(f, "CELLS %u %u\n", m->cell_count, m->cell_count + m->conn_count);
  for (uint32_t c = 0; c < m->cell_count; ++c) {
    uint32_t n = m->offsets[c + 1] - m->offsets[c];
    binary ? put_be32(f, n) : (void)fprintf(f, "%u", n);
    for (uint32_t k = 0; k < n; ++k)
      binary ? put_be32(f, m->conn[m->offsets[c] + k]) : (void)fprintf(f, " %u", m->conn[m->offsets[c] + k]);
    if (!binary) fputc('\n', f);
  }
  fprintf(f, "%sCELL_TYPES %u\n", binary ? "\n" : "", m->cell_count);
  for (uint32_t c = 0; c < m->cell_count; ++c)
    binary ? put_be32(f, m->types[c]) : (void)fprintf(f, "%u\n", m->types[c]);
  if (binary) fputc('\n', f);
}

static void legacy_fields(FILE* f, const vtk_model* m, bool cells, bool binary) {
  uint32_t n = cells ? m->cell_count : m->point_count;
  bool header = false;
  for (uint32_t k = 0; k < m->field_count; ++k) {
    const vtk_model_field* fd = &m->fields[k];
    if (fd->cells != cells) continue;
    if (!header) fprintf(f, "%s %u\n", cells ? "CELL_DATA" : "POINT_DATA", n);
    header = true;
    if (fd->components == 1)
      fprintf(f, "SCALARS %s double 1\nLOOKUP_TABLE default\n", fd->name);
    else
      fprintf(f, "VECTORS %s double\n", fd->name);
    legacy_doubles(f, fd->data, (size_t)n * fd->components, fd->components, binary);
  }
}

static void write_legacy(FILE* f, const vtk_model* m, bool binary) {
  fprintf(f, "# vtk DataFile Version 3.0\ntesslod test mesh\n%s\nDATASET UNSTRUCTURED_GRID\n",
          binary ? "BINARY" : "ASCII");
  fprintf(f, "POINTS %u double\n", m->point_count);
  legacy_doubles(f, m->points, 3 * (size_t)m->point_count, 3, binary);
  legacy_cells(f, m, binary);
  legacy_fields(f, m, false, binary);
  legacy_fields(f, m, true, binary);
}

/* ---- XML .vtu, ASCII data arrays ---- */

static void xml_doubles(FILE* f, const char* attrs, const double* d, size_t n) {
  fprintf(f, "<DataArray type=\"Float64\" %s format=\"ascii\">\n", attrs);
  for (size_t k = 0; k < n; ++k)
    fprintf(f, "%.17g%c", d[k], (k + 1) % 12 ? ' ' : '\n');
  fprintf(f, "\n</DataArray>\n");
}

static void xml_fields(FILE* f, const vtk_model* m, bool cells) {
  fprintf(f, "<%s>\n", cells ? "CellData" : "PointData");
  for (uint32_t k = 0; k < m->field_count; ++k) {
    const vtk_model_field* fd = &m->fields[k];
    if (fd->cells != cells) continue;
    char attrs[128];
    snprintf(attrs, sizeof attrs, "Name=\"%s\" NumberOfComponents=\"%u\"", fd->name, fd->components);
    xml_doubles(f, attrs, fd->data, (size_t)fd->components * (cells ? m->cell_count : m->point_count));
  }
  fprintf(f, "</%s>\n", cells ? "CellData" : "PointData");
}

static void xml_ints(FILE* f, const char* type, const char* name, const uint32_t* v, const uint8_t* b, size_t n) {
  fprintf(f, "<DataArray type=\"%s\" Name=\"%s\" format=\"ascii\">\n", type, name);
  for (size_t k = 0; k < n; ++k)
    fprintf(f, "%u%c", v ? v[k] : b[k], (k + 1) % 16 ? ' ' : '\n');
  fprintf(f, "\n</DataArray>\n");
}

static void write_xml(FILE* f, const vtk_model* m) {
  fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
             "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>\n");
  fprintf(f, "<Piece NumberOfPoints=\"%u\" NumberOfCells=\"%u\">\n", m->point_count, m->cell_count);
  xml_fields(f, m, false);
  xml_fields(f, m, true);
  fprintf(f, "<Points>\n");
  xml_doubles(f, "NumberOfComponents=\"3\"", m->points, 3 * (size_t)m->point_count);
  fprintf(f, "</Points>\n<Cells>\n");
  xml_ints(f, "Int64", "connectivity", m->conn, NULL, m->conn_count);
  xml_ints(f, "Int64", "offsets", m->offsets + 1, NULL, m->cell_count);
  xml_ints(f, "UInt8", "types", NULL, m->types, m->cell_count);
  fprintf(f, "</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
}

bool vtk_model_write(const vtk_model* m, const char* path, vtk_format format) {
  FILE* f = fopen(path, "wb");
  if (!f) {
    fprintf(stderr, "%s: cannot write\n", path);
    return false;
  }
  if (format == VTK_XML_ASCII)
    write_xml(f, m);
  else
    write_legacy(f, m, format == VTK_LEGACY_BINARY);
  bool ok = !ferror(f);
  ok = fclose(f) == 0 && ok;
  if (!ok) fprintf(stderr, "%s: write failed\n", path);
  return ok;
}
