/* tlod play --serve: the page at /. The dashboard's page in live mode: its
 * embedded config says where the events are ("live": "/events"). */
#include <stdlib.h>
#include <string.h>

#include "play_serve_internal.h"

/* Until the dashboard's page builder is linked in: a minimal page that
 * follows the stream and shows the frame count and drops. */
static const char placeholder[] =
    "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>tlod live</title></head><body>\n"
    "<script type=\"application/json\" id=\"tlod-config\">{\"live\":\"/events\",\"run\":\"/run.json\"}</script>\n"
    "<p>tlod play: <span id=\"frames\">0</span> frames, <span id=\"dropped\">0</span> dropped</p>\n"
    "<script>\n"
    "const es = new EventSource('/events');\n"
    "let n = 0;\n"
    "es.onmessage = (e) => { const f = JSON.parse(e.data); n++;\n"
    "  document.getElementById('frames').textContent = n;\n"
    "  document.getElementById('dropped').textContent = f.dropped; };\n"
    "es.addEventListener('end', () => es.close());\n"
    "</script></body></html>\n";

char* serve_page(size_t* len) {
  *len = sizeof(placeholder) - 1;
  char* page = malloc(*len + 1);
  if (page) memcpy(page, placeholder, *len + 1);
  return page;
}
