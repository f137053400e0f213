/* tlod play -- camera paths: keyframes from a file or from the scene bounds,
 * centripetal Catmull-Rom on eye and target (Barry-Goldman evaluation;
 * Yuksel, Schaefer, Keyser, "Parameterization and applications of
 * Catmull-Rom curves", 2011: no cusps or self-intersections within a
 * segment), linear on up and fovy. */
#include "camera_path.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera_path_json.h"

static const double kPi = 3.14159265358979323846;

bool camera_path_is_builtin(const char* name) {
  return name && (!strcmp(name, "orbit") || !strcmp(name, "flyby") || !strcmp(name, "zoom"));
}

void camera_path_free(camera_path* p) {
  free(p->keys);
  memset(p, 0, sizeof(*p));
}

double camera_path_duration(const camera_path* p) {
  return p->count >= 2 ? p->keys[p->count - 1].time - p->keys[0].time : 0.0;
}

double camera_path_frames(const camera_path* p, double fps) {
  double n = camera_path_duration(p) * fps;
  double frames = p->closed ? floor(n + 0.5) : floor(n + 1e-9) + 1.0;
  return frames < 1.0 ? 1.0 : frames;
}

/* Values every path must satisfy (files and built-ins alike). */
static bool key_finite(const camera_key* k) {
  for (int c = 0; c < 3; c++)
    if (!isfinite(k->eye[c]) || !isfinite(k->target[c]) || !isfinite(k->up[c])) return false;
  return true;
}

static bool check_keys(const camera_path* p, char* error, size_t error_size) {
  if (p->count < 2) {
    snprintf(error, error_size, "%s: keyframes: need at least 2 keyframes, got %u", p->name, p->count);
    return false;
  }
  for (uint32_t i = 0; i < p->count; i++) {
    const camera_key* k = &p->keys[i];
    double d = 0.0, u = 0.0;
    for (int c = 0; c < 3; c++) {
      d += (double)(k->target[c] - k->eye[c]) * (k->target[c] - k->eye[c]);
      u += (double)k->up[c] * k->up[c];
    }
    const char* problem = NULL;
    char buf[160];
    if (i > 0 && !(k->time > p->keys[i - 1].time)) {
      snprintf(buf, sizeof(buf), "time %g is not after keyframes[%u].time %g (times must increase)", k->time, i - 1,
               p->keys[i - 1].time);
      problem = buf;
    } else if (!key_finite(k)) {
      problem = "eye, target or up is not finite";
    } else if (!(d > 0.0)) {
      problem = "eye and target are the same point";
    } else if (!(u > 0.0)) {
      problem = "up is the zero vector";
    } else if (!(k->fovy > 0.0f && k->fovy < 179.0f)) {
      snprintf(buf, sizeof(buf), "fovy %g is outside (0, 179) degrees", (double)k->fovy);
      problem = buf;
    }
    if (problem) {
      snprintf(error, error_size, "%s: keyframes[%u]: %s", p->name, i, problem);
      return false;
    }
  }
  return true;
}

/* Takes over keys (file or glTF camera) and checks them as any path. */
static bool from_keys(const char* file, const char* name, camera_path_json_key* keys, uint32_t count, camera_path* out,
                      char* error, size_t error_size) {
  snprintf(out->name, sizeof(out->name), "%s", name);
  out->keys = calloc(count + 1u, sizeof(camera_key));
  if (!out->keys) {
    camera_path_json_free(keys);
    snprintf(error, error_size, "%s: out of memory", file);
    return false;
  }
  out->count = count;
  for (uint32_t i = 0; i < count; i++) {
    camera_key* k = &out->keys[i];
    k->time = keys[i].time;
    for (int c = 0; c < 3; c++) {
      k->eye[c] = (float)keys[i].eye[c];
      k->target[c] = (float)keys[i].target[c];
      k->up[c] = (float)keys[i].up[c];
    }
    k->fovy = (float)keys[i].fovy;
  }
  camera_path_json_free(keys);
  if (!check_keys(out, error, error_size)) {
    camera_path_free(out);
    return false;
  }
  return true;
}

bool camera_path_load(const char* file, camera_path* out, char* error, size_t error_size) {
  memset(out, 0, sizeof(*out));
  camera_path_json_key* keys = NULL;
  uint32_t count = 0;
  if (!camera_path_json_load(file, &keys, &count, error, error_size)) return false;
  return from_keys(file, file, keys, count, out, error, error_size);
}

bool camera_path_load_gltf(const char* scene, uint32_t camera, camera_path* out, char* error, size_t error_size) {
  memset(out, 0, sizeof(*out));
  camera_path_json_key* keys = NULL;
  uint32_t count = 0;
  if (!gltf_camera_path_load(scene, camera, &keys, &count, error, error_size)) return false;
  char name[300];
  snprintf(name, sizeof(name), "%s: camera %u", scene, camera);
  return from_keys(scene, name, keys, count, out, error, error_size);
}

/* ---- built-in paths ------------------------------------------------------ */

static void set_key(camera_key* k, double time, const double c[3], double r, const double eye[3],
                    const double target[3]) {
  k->time = time;
  for (int i = 0; i < 3; i++) {
    k->eye[i] = (float)(c[i] + r * eye[i]);
    k->target[i] = (float)(c[i] + r * target[i]);
    k->up[i] = i == 1 ? 1.0f : 0.0f;
  }
  k->fovy = 45.0f;
}

bool camera_path_builtin(const char* name, const float bmin[3], const float bmax[3], camera_path* out) {
  memset(out, 0, sizeof(*out));
  if (!camera_path_is_builtin(name)) return false;
  double c[3], r = 0.0;
  for (int i = 0; i < 3; i++) {
    c[i] = 0.5 * ((double)bmin[i] + bmax[i]);
    r += 0.25 * ((double)bmax[i] - bmin[i]) * ((double)bmax[i] - bmin[i]);
  }
  r = sqrt(r);
  if (!(r > 0.0) || !isfinite(r)) r = 1.0;
  /* Distance (in radii) at which the bounding sphere fills the 45 degree view. */
  const double d = 0.85 / tan(22.5 * kPi / 180.0);
  static const double origin[3] = {0, 0, 0};
  snprintf(out->name, sizeof(out->name), "%s", name);
  if (!strcmp(name, "orbit")) {
    /* One turn in 4 s, slightly from above; 16 segments of a closed spline. */
    enum { N = 16 };
    out->keys = calloc(N + 1, sizeof(camera_key));
    if (!out->keys) return false;
    for (int k = 0; k <= N; k++) {
      double a = 2.0 * kPi * (k % N) / N, eye[3] = {d * sin(a), 0.35 * d, d * cos(a)};
      set_key(&out->keys[k], 4.0 * k / N, c, r, eye, origin);
    }
    out->count = N + 1;
    out->closed = true;
  } else if (!strcmp(name, "flyby")) {
    /* From far left, low and close past the front of the scene (1.5 radii
     * from its centre at t = 3 s), out to the right and up: 6 s. */
    static const double eyes[5][3] = {
        {-4.0, 1.2, 3.0}, {-2.2, 0.5, 2.0}, {0.0, 0.25, 1.5}, {2.2, 0.6, 1.8}, {4.0, 2.0, 2.5}};
    static const double targets[5][3] = {{-0.5, 0, 0}, {-0.25, 0, 0}, {0, 0, 0}, {0.25, 0, 0}, {0.5, 0, 0}};
    out->keys = calloc(5, sizeof(camera_key));
    if (!out->keys) return false;
    for (int k = 0; k < 5; k++)
      set_key(&out->keys[k], 1.5 * k, c, r, eyes[k], targets[k]);
    out->count = 5;
  } else {
    /* zoom: from just outside the bounding sphere (1.3 radii) out to 24
     * radii (a few dozen pixels tall at 720p) and back in 4 s, geometric
     * steps so the apparent size changes at a steady rate; closed. */
    enum { N = 8 };
    const double close = 1.3, far = 24.0, q = pow(far / close, 1.0 / (N / 2));
    double dir[3] = {0.3, 0.25, 1.0}, len = sqrt(0.3 * 0.3 + 0.25 * 0.25 + 1.0);
    out->keys = calloc(N + 1, sizeof(camera_key));
    if (!out->keys) return false;
    for (int k = 0; k <= N; k++) {
      int step = k <= N / 2 ? k : N - k;
      double dist = close * pow(q, step), eye[3];
      for (int i = 0; i < 3; i++)
        eye[i] = dist * dir[i] / len;
      set_key(&out->keys[k], 4.0 * k / N, c, r, eye, origin);
    }
    out->count = N + 1;
    out->closed = true;
  }
  char err[256];
  if (!check_keys(out, err, sizeof(err))) { /* cannot happen: the keys above are valid */
    camera_path_free(out);
    return false;
  }
  return true;
}

/* ---- evaluation ---------------------------------------------------------- */

/* Key i of the spline, with phantom ends: closed paths wrap round (the last
 * key repeats the first), open paths reflect the neighbour. */
static void spline_point(const camera_path* p, long i, bool eye, double out[3]) {
  long n = (long)p->count;
  const float* v;
  if (i >= 0 && i < n) {
    v = eye ? p->keys[i].eye : p->keys[i].target;
    for (int c = 0; c < 3; c++)
      out[c] = v[c];
    return;
  }
  if (p->closed) {
    long j = i < 0 ? n - 1 + i : i - (n - 1);
    spline_point(p, j, eye, out);
    return;
  }
  double a[3], b[3];
  spline_point(p, i < 0 ? 0 : n - 1, eye, a);
  spline_point(p, i < 0 ? 1 : n - 2, eye, b);
  for (int c = 0; c < 3; c++)
    out[c] = 2.0 * a[c] - b[c];
}

static double dist3(const double a[3], const double b[3]) {
  return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static void lerp3(const double a[3], const double b[3], double ta, double tb, double t, double out[3]) {
  double w = (t - ta) / (tb - ta);
  for (int c = 0; c < 3; c++)
    out[c] = (1.0 - w) * a[c] + w * b[c];
}

/* Centripetal Catmull-Rom between P1 and P2 at u in [0, 1]. */
static void catmull_rom(const double P0[3], const double P1[3], const double P2[3], const double P3[3], double u,
                        double out[3]) {
  double d12 = sqrt(dist3(P1, P2));
  if (u <= 0.0 || d12 < 1e-12) { /* also a held key: P1 == P2 stays put */
    lerp3(P1, P2, 0.0, 1.0, u <= 0.0 ? 0.0 : u, out);
    return;
  }
  if (u >= 1.0) {
    memcpy(out, P2, sizeof(double) * 3);
    return;
  }
  double d01 = sqrt(dist3(P0, P1)), d23 = sqrt(dist3(P2, P3));
  if (d01 < 1e-12) d01 = d12; /* repeated neighbour: a uniform step */
  if (d23 < 1e-12) d23 = d12;
  double t0 = 0.0, t1 = d01, t2 = t1 + d12, t3 = t2 + d23, t = t1 + u * d12;
  double A1[3], A2[3], A3[3], B1[3], B2[3];
  lerp3(P0, P1, t0, t1, t, A1);
  lerp3(P1, P2, t1, t2, t, A2);
  lerp3(P2, P3, t2, t3, t, A3);
  lerp3(A1, A2, t0, t2, t, B1);
  lerp3(A2, A3, t1, t3, t, B2);
  lerp3(B1, B2, t1, t2, t, out);
}

void camera_path_eval(const camera_path* p, double t, bool loop, tool_camera* cam) {
  double duration = camera_path_duration(p);
  if (!(t > 0.0)) t = 0.0;
  if (loop && duration > 0.0) {
    t = fmod(t, duration);
  } else if (t > duration) {
    t = duration;
  }
  double at = p->keys[0].time + t;
  /* The segment [keys[i].time, keys[i + 1].time) holding at. */
  uint32_t lo = 0, hi = p->count - 1;
  while (hi - lo > 1) {
    uint32_t mid = (lo + hi) / 2;
    if (p->keys[mid].time <= at) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  const camera_key *a = &p->keys[lo], *b = &p->keys[lo + 1];
  double u = (at - a->time) / (b->time - a->time);
  u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
  for (int which = 0; which < 2; which++) {
    double P[4][3], out[3];
    for (int k = 0; k < 4; k++)
      spline_point(p, (long)lo - 1 + k, which == 0, P[k]);
    catmull_rom(P[0], P[1], P[2], P[3], u, out);
    float* dst = which == 0 ? cam->eye : cam->target;
    for (int c = 0; c < 3; c++)
      dst[c] = (float)out[c];
  }
  double up[3], len = 0.0;
  for (int c = 0; c < 3; c++) {
    up[c] = (1.0 - u) * a->up[c] + u * b->up[c];
    len += up[c] * up[c];
  }
  len = sqrt(len);
  for (int c = 0; c < 3; c++)
    cam->up[c] = len > 1e-12 ? (float)(up[c] / len) : (c == 1 ? 1.0f : 0.0f);
  cam->fovy_deg = (float)((1.0 - u) * a->fovy + u * b->fovy);
}
