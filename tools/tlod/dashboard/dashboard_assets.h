/* The files tlod embeds for its dashboard page (tools/CMakeLists.txt runs
 * cmake/embed_text.cmake at build time): the page template, its script and
 * style (tools/dashboard/), and uPlot with its licence (node_modules/uplot). */
#ifndef TLOD_TOOLS_DASHBOARD_ASSETS_H
#define TLOD_TOOLS_DASHBOARD_ASSETS_H

#include <stddef.h>

extern const char dashboard_asset_template[], dashboard_asset_js[], dashboard_asset_css[];
extern const char dashboard_asset_uplot_js[], dashboard_asset_uplot_css[], dashboard_asset_uplot_license[];
extern const size_t dashboard_asset_template_size, dashboard_asset_js_size, dashboard_asset_css_size;
extern const size_t dashboard_asset_uplot_js_size, dashboard_asset_uplot_css_size, dashboard_asset_uplot_license_size;

#endif
