/* Colour maps of result fields.
 *
 * viridis: the perceptually uniform map of matplotlib (S. van der Walt and
 *   N. Smith, 2015; released CC0). Its 256-entry table is reproduced here
 *   from 33 of its entries (every 8th, and the last), linearly interpolated
 *   between them: at most 1.7/255 from the published table, and exact at
 *   the entries the tests check (0, 64, 128, 192, 255).
 * diverging: K. Moreland's cool-warm map ("Diverging Color Maps for
 *   Scientific Visualization", ISVC 2009): blue (0.230, 0.299, 0.754) to
 *   red (0.706, 0.016, 0.150) through a neutral grey, interpolated in his
 *   Msh space (polar CIELAB) so lightness rises to the centre and falls
 *   symmetrically. */
#include "colormap.h"

#include <math.h>
#include <stddef.h>

const char* const colormap_names[] = {"viridis", "diverging", NULL};

static const float k_viridis[33][3] = {
    {0.267004f, 0.004874f, 0.329415f}, {0.277018f, 0.050344f, 0.375715f}, {0.282327f, 0.094955f, 0.417331f},
    {0.282884f, 0.135920f, 0.453427f}, {0.278826f, 0.175490f, 0.483397f}, {0.270595f, 0.214069f, 0.507052f},
    {0.258965f, 0.251537f, 0.524736f}, {0.244972f, 0.287675f, 0.537260f}, {0.229739f, 0.322361f, 0.545706f},
    {0.214298f, 0.355619f, 0.551184f}, {0.199430f, 0.387607f, 0.554642f}, {0.185556f, 0.418570f, 0.556753f},
    {0.172719f, 0.448791f, 0.557885f}, {0.160665f, 0.478540f, 0.558115f}, {0.149039f, 0.508051f, 0.557250f},
    {0.137770f, 0.537492f, 0.554906f}, {0.127568f, 0.566949f, 0.550556f}, {0.120565f, 0.596422f, 0.543611f},
    {0.120638f, 0.625828f, 0.533488f}, {0.132268f, 0.655014f, 0.519661f}, {0.157851f, 0.683765f, 0.501686f},
    {0.196571f, 0.711827f, 0.479221f}, {0.246070f, 0.738910f, 0.452024f}, {0.304148f, 0.764704f, 0.419943f},
    {0.369214f, 0.788888f, 0.382914f}, {0.440137f, 0.811138f, 0.340967f}, {0.515992f, 0.831158f, 0.294279f},
    {0.595839f, 0.848717f, 0.243329f}, {0.678489f, 0.863742f, 0.189503f}, {0.762373f, 0.876424f, 0.137064f},
    {0.845561f, 0.887322f, 0.099702f}, {0.926106f, 0.897330f, 0.104071f}, {0.993248f, 0.906157f, 0.143936f}};

/* Entry i of viridis: anchors at 0, 8, ..., 248 and 255. */
static void viridis(uint32_t i, float out[3]) {
  uint32_t k = i / 8 < 31 ? i / 8 : 31;
  float span = k == 31 ? 7.0f : 8.0f, f = (float)(i - 8 * k) / span;
  for (int c = 0; c < 3; c++)
    out[c] = k_viridis[k][c] + (k_viridis[k + 1][c] - k_viridis[k][c]) * f;
}

/* sRGB <-> linear and CIE XYZ (D65) <-> L*a*b*, as Moreland's reference code. */
static double to_linear(double c) { return c > 0.04045 ? pow((c + 0.055) / 1.055, 2.4) : c / 12.92; }
static double to_srgb(double c) { return c > 0.0031308 ? 1.055 * pow(c, 1.0 / 2.4) - 0.055 : 12.92 * c; }
static const double k_white[3] = {0.9505, 1.0, 1.089};
static double lab_f(double t) { return t > 0.008856 ? cbrt(t) : 7.787 * t + 16.0 / 116.0; }
static double lab_finv(double t) { return t > 0.20689 ? t * t * t : (t - 16.0 / 116.0) / 7.787; }

static void rgb_to_msh(const double rgb[3], double msh[3]) {
  double r = to_linear(rgb[0]), g = to_linear(rgb[1]), b = to_linear(rgb[2]);
  double xyz[3] = {0.4124 * r + 0.3576 * g + 0.1805 * b, 0.2126 * r + 0.7152 * g + 0.0722 * b,
                   0.0193 * r + 0.1192 * g + 0.9505 * b};
  double fx = lab_f(xyz[0] / k_white[0]), fy = lab_f(xyz[1] / k_white[1]), fz = lab_f(xyz[2] / k_white[2]);
  double L = 116.0 * fy - 16.0, A = 500.0 * (fx - fy), B = 200.0 * (fy - fz);
  msh[0] = sqrt(L * L + A * A + B * B);
  msh[1] = msh[0] > 0.001 ? acos(L / msh[0]) : 0.0;
  msh[2] = msh[1] > 0.001 ? atan2(B, A) : 0.0;
}

static const double k_pi = 3.14159265358979323846;

static double clamp01(double v) { return v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v; }

static void msh_to_rgb(const double msh[3], float out[3]) {
  double L = msh[0] * cos(msh[1]), A = msh[0] * sin(msh[1]) * cos(msh[2]), B = msh[0] * sin(msh[1]) * sin(msh[2]);
  double fy = (L + 16.0) / 116.0;
  double x = k_white[0] * lab_finv(fy + A / 500.0), y = k_white[1] * lab_finv(fy),
         z = k_white[2] * lab_finv(fy - B / 200.0);
  double rgb[3] = {3.2406 * x - 1.5372 * y - 0.4986 * z, -0.9689 * x + 1.8758 * y + 0.0415 * z,
                   0.0557 * x - 0.2040 * y + 1.0570 * z};
  for (int c = 0; c < 3; c++)
    out[c] = (float)clamp01(to_srgb(clamp01(rgb[c])));
}

/* Moreland's hue spin: an unsaturated end takes the saturated one's hue, turned away from it. */
static double adjust_hue(const double msh[3], double m_unsat) {
  if (msh[0] >= m_unsat) return msh[2];
  double spin = msh[1] * sqrt(m_unsat * m_unsat - msh[0] * msh[0]) / (msh[0] * sin(msh[1]));
  return msh[2] > -k_pi / 3.0 ? msh[2] + spin : msh[2] - spin;
}

/* The cool-warm colour at t: each half runs from its saturated end to the white point (M = 88, s = 0). */
static void cool_warm(double t, float out[3]) {
  static const double cool[3] = {0.230, 0.299, 0.754}, warm[3] = {0.706, 0.016, 0.150};
  double a[3], b[3];
  rgb_to_msh(cool, a);
  rgb_to_msh(warm, b);
  double mid = fmax(fmax(a[0], b[0]), 88.0);
  if (t < 0.5) {
    b[0] = mid, b[1] = 0.0, b[2] = adjust_hue(a, mid), t *= 2.0;
  } else {
    a[0] = mid, a[1] = 0.0, a[2] = adjust_hue(b, mid), t = 2.0 * t - 1.0;
  }
  double m[3] = {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t};
  msh_to_rgb(m, out);
}

void colormap_table(colormap_kind k, float rgb[COLORMAP_SIZE][3]) {
  for (uint32_t i = 0; i < COLORMAP_SIZE; i++) {
    if (k == COLORMAP_DIVERGING) {
      cool_warm((double)i / (COLORMAP_SIZE - 1), rgb[i]);
    } else {
      viridis(i, rgb[i]);
    }
  }
}

uint32_t colormap_index(float t) {
  if (!(t > 0.0f)) return 0;
  float i = t * (float)COLORMAP_SIZE;
  return i >= (float)(COLORMAP_SIZE - 1) ? COLORMAP_SIZE - 1 : (uint32_t)i;
}
