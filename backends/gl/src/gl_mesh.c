/* tesslod::gl -- CPU-mesh mode (tlod_gpu_eval OFF): an item's draw list
 * evaluated by the CPU tessellator (welded, with normals), uploaded into
 * one vertex and one index buffer of its device surface and drawn with one
 * glDrawElements. On a software rasteriser the GPU-evaluation path costs
 * every pattern vertex its surface evaluation in the vertex shader, shared
 * edge points several times; here each welded vertex is evaluated once,
 * and not at all while the draw list, surface and mesh stay unchanged. */
#include "gl_internal.h"

/* Orphans and refills the buffers; positions at 0, normals after them. */
static uint64_t upload(gl_mesh* m) {
  if (!m->vao) {
    GLuint bufs[2];
    glCreateBuffers(2, bufs);
    m->vertices = bufs[0], m->indices = bufs[1];
    glCreateVertexArrays(1, &m->vao);
    glVertexArrayElementBuffer(m->vao, m->indices);
    const GLuint attrib[2] = {TLOD_ATTRIB_MESH_POSITION, TLOD_ATTRIB_MESH_NORMAL};
    for (GLuint a = 0; a < 2; a++) {
      glEnableVertexArrayAttrib(m->vao, attrib[a]);
      glVertexArrayAttribFormat(m->vao, attrib[a], 3, GL_FLOAT, GL_FALSE, 0);
      glVertexArrayAttribBinding(m->vao, attrib[a], a);
    }
  }
  const tlod_cpu_mesh* c = m->eval.cpu;
  size_t half = sizeof(float[3]) * c->vertex_count, ib = sizeof(uint32_t[3]) * c->triangle_count;
  glNamedBufferData(m->vertices, (GLsizeiptr)(half ? 2 * half : 16), NULL, GL_STREAM_DRAW);
  if (half) {
    glNamedBufferSubData(m->vertices, 0, (GLsizeiptr)half, c->positions);
    glNamedBufferSubData(m->vertices, (GLintptr)half, (GLsizeiptr)half, c->normals);
  }
  glNamedBufferData(m->indices, (GLsizeiptr)(ib ? ib : 16), NULL, GL_STREAM_DRAW);
  if (ib) glNamedBufferSubData(m->indices, 0, (GLsizeiptr)ib, c->indices);
  glVertexArrayVertexBuffer(m->vao, 0, m->vertices, 0, sizeof(float[3]));
  glVertexArrayVertexBuffer(m->vao, 1, m->vertices, (GLintptr)half, sizeof(float[3]));
  m->index_count = 3 * c->triangle_count;
  return 2 * half + ib;
}

tlod_result _tlod_gl_mesh_update(tlod_context* ctx, const tlod_patterns* p, const _tlod_draw_ref* it, gl_mesh* m,
                                 bool* evaluated, uint64_t* bytes) {
  tlod_result r = _tlod_item_mesh_update(ctx, p, it, &m->eval, evaluated);
  if (r != TLOD_SUCCESS) m->index_count = 0;
  if (r == TLOD_SUCCESS && *evaluated) *bytes += upload(m);
  return r;
}

void _tlod_gl_mesh_draw(const gl_mesh* m) {
  if (!m->index_count) return;
  glBindVertexArray(m->vao);
  glDrawElements(GL_TRIANGLES, (GLsizei)m->index_count, GL_UNSIGNED_INT, NULL);
}

void _tlod_gl_mesh_free(tlod_context* ctx, gl_mesh* m) {
  GLuint bufs[2] = {m->vertices, m->indices};
  if (m->vao) {
    glDeleteBuffers(2, bufs);
    glDeleteVertexArrays(1, &m->vao);
  }
  _tlod_item_mesh_free(ctx, &m->eval);
  *m = (gl_mesh){0};
}
