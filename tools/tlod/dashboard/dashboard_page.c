/* The dashboard page (dashboard_page.h): the embedded template with each
 * @NAME@ replaced by its asset, @DATA@ by the runs' JSON. */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include "dashboard_page.h"

#include <stdlib.h>
#include <string.h>

#include "dashboard_assets.h"
#include "dashboard_data.h"

/* The runs' JSON, with every '<' written \u003c so no string can close the
 * <script> element holding it ("</script>" in a scene name). */
static bool write_data(FILE* f, const run_set* runs, const dashboard_page_options* opt, char* err, size_t n) {
  char* text = NULL;
  size_t size = 0;
  FILE* mem = open_memstream(&text, &size);
  if (!mem) return snprintf(err, n, "page: out of memory"), false;
  bool ok = dashboard_data_write(mem, runs, opt, err, n);
  ok = fclose(mem) == 0 && ok;
  for (size_t i = 0; ok && text && i < size; i++) {
    if (text[i] == '<')
      fputs("\\u003c", f);
    else
      fputc(text[i], f);
  }
  free(text);
  return ok;
}

/* The text of the asset called name (between the @s), or NULL. */
static const char* asset(const char* name, size_t len) {
  static const struct {
    const char* name;
    const char* text;
  } assets[] = {{"UPLOT_CSS", dashboard_asset_uplot_css},
                {"DASHBOARD_CSS", dashboard_asset_css},
                {"UPLOT_LICENSE", dashboard_asset_uplot_license},
                {"UPLOT_JS", dashboard_asset_uplot_js},
                {"DASHBOARD_JS", dashboard_asset_js}};
  for (size_t i = 0; i < sizeof assets / sizeof assets[0]; i++) {
    if (strlen(assets[i].name) == len && !memcmp(assets[i].name, name, len)) return assets[i].text;
  }
  return NULL;
}

/* One step at the '@' at: the asset or data it names (*t moves past the
 * marker), or the '@' itself when it names nothing. */
static bool write_marker(FILE* f, const char** t, const char* at, const run_set* runs,
                         const dashboard_page_options* opt, char* err, size_t n) {
  const char* end = strchr(at + 1, '@');
  size_t len = end ? (size_t)(end - at - 1) : 0;
  const char* text = end ? asset(at + 1, len) : NULL;
  bool data = end && len == 4 && !memcmp(at + 1, "DATA", 4);
  *t = text || data ? end + 1 : at + 1;
  if (text) return fputs(text, f) >= 0;
  if (data) return write_data(f, runs, opt, err, n);
  return fputc('@', f) != EOF;
}

bool dashboard_page_write(FILE* f, const run_set* runs, const dashboard_page_options* opt, char* err, size_t err_size) {
  static const dashboard_page_options defaults = {0};
  const char* t = dashboard_asset_template;
  bool ok = true;
  while (ok && *t) {
    const char* at = strchr(t, '@');
    if (!at) at = t + strlen(t);
    fwrite(t, 1, (size_t)(at - t), f);
    t = at;
    if (*at) ok = write_marker(f, &t, at, runs, opt ? opt : &defaults, err, err_size);
  }
  if (ok && ferror(f)) ok = (snprintf(err, err_size, "page: write failed"), false);
  return ok;
}
