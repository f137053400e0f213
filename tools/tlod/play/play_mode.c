/* tlod play -- the modes: adaptive, uniform:L, flat. */
#include <stdio.h>
#include <string.h>

#include "common/strict_number.h"
#include "play_options.h"

#define STR_OF2(x) #x
#define STR_OF(x) STR_OF2(x)

const char* play_mode_parse(const char* text, play_mode* m) {
  memset(m, 0, sizeof(*m));
  uint32_t level = 0;
  number_status s = NUMBER_SYNTAX;
  if (!strcmp(text, "adaptive")) {
    m->kind = MODE_ADAPTIVE;
    snprintf(m->name, sizeof(m->name), "adaptive");
  } else if (!strcmp(text, "flat")) {
    m->kind = MODE_FLAT;
    snprintf(m->name, sizeof(m->name), "flat");
  } else if (!strncmp(text, "uniform:", 8) &&
             (s = number_parse_u32(text + 8, NULL, 0, TLOD_MAX_LEVEL, &level)) == NUMBER_OK) {
    m->kind = MODE_UNIFORM;
    m->level = level;
    snprintf(m->name, sizeof(m->name), "uniform:%u", level);
  } else {
    return s == NUMBER_RANGE ? "level out of range 0.." STR_OF(TLOD_MAX_LEVEL)
                             : "expected adaptive, uniform:L (L = 0.." STR_OF(TLOD_MAX_LEVEL) ") or flat";
  }
  snprintf(m->dir, sizeof(m->dir), "%s", m->name);
  char* colon = strchr(m->dir, ':');
  if (colon) *colon = '-';
  return NULL;
}

/* uniform:L uses the UNIFORM policy (every visible patch at L; culling
 * applies); flat and uniform:0 the error rule with an epsilon no patch
 * exceeds (level 0 everywhere). */
tlod_scheduler_desc play_mode_desc(const play_options* o, const play_mode* m, const char* label) {
  if (m->kind == MODE_ADAPTIVE)
    return (tlod_scheduler_desc){.epsilon_px = o->epsilon,
                                 .max_level = o->max_level,
                                 .policy = o->policy,
                                 .morph = TLOD_MORPH_TIME,
                                 .label = label};
  if (m->kind == MODE_UNIFORM && m->level > 0)
    return (tlod_scheduler_desc){
        .max_level = m->level, .policy = TLOD_POLICY_UNIFORM, .morph = TLOD_MORPH_NONE, .label = label};
  return (tlod_scheduler_desc){.policy = TLOD_POLICY_FLAT, .morph = TLOD_MORPH_NONE, .label = label};
}

uint32_t play_modes_max_level(const play_options* o) {
  uint32_t lmax = 1;
  for (uint32_t k = 0; k < o->mode_count; k++) {
    uint32_t l = o->modes[k].kind == MODE_ADAPTIVE ? o->max_level : o->modes[k].level;
    lmax = l > lmax ? l : lmax;
  }
  return lmax;
}
