/* tlod play -- the three trace formats in pieces, so a run's frames can be
 * appended window by window (play_trace_files.c): a head before the first
 * frame, the window's frames, a tail after the last. */
#ifndef TLOD_TOOLS_PLAY_TRACE_FORMAT_H
#define TLOD_TOOLS_PLAY_TRACE_FORMAT_H

#include "common/json_writer.h"
#include "play_trace.h"

/* trace.json: the settings and "frames": [ ... ], then the results (frames_completed, stopped, wall_s). */
void trace_json_head(json_writer* w, FILE* f, const play_trace* t);
void trace_json_frames(json_writer* w, const play_trace* t);
/* Window frame n's record (one element of "frames"), and the settings keys of the head. */
void trace_json_frame(json_writer* w, const play_trace* t, uint32_t n);
void trace_json_settings(json_writer* w, const play_trace* t);
bool trace_json_tail(json_writer* w, const play_trace* t);
/* "warning_count" and "warnings" (one string per line of text) into w. */
void json_warnings(json_writer* w, const char* text, uint32_t count);
/* objects.csv: the header line, then one row per frame and object. */
void objects_csv_head(FILE* f);
void objects_csv_frames(FILE* f, const play_trace* t);
/* trace.csv: the header line, then one row per frame. */
void trace_csv_head(FILE* f);
void trace_csv_frames(FILE* f, const play_trace* t);
/* chrome_trace.json: the events, then otherData. first: no event written yet. */
void chrome_trace_head(FILE* f);
void chrome_trace_frames(FILE* f, const play_trace* t, bool* first);
void chrome_trace_tail(FILE* f, const play_trace* t);

#endif
