// camera_path_json.cpp -- `tlod play` camera path files: a C shim over
// nlohmann::json (C++17, no exception leaves this file). Owned by the CLI;
// the format is in camera_path_json.h and docs/play.md.
#include "camera_path_json.h"

#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct PathError {
  std::string message;
};

[[noreturn]] void fail(const std::string& element, const std::string& problem) {
  throw PathError{element.empty() ? problem : element + ": " + problem};
}

double number(const nlohmann::json& v, const std::string& element) {
  if (!v.is_number()) fail(element, std::string("expected a number, got ") + v.type_name());
  double d = v.get<double>();
  if (!std::isfinite(d) || std::fabs(d) > FLT_MAX) fail(element, "number out of range");
  return d;
}

void vec3(const nlohmann::json& v, const std::string& element, double out[3]) {
  if (!v.is_array() || v.size() != 3)
    fail(element, std::string("expected an array of 3 numbers, got ") +
                      (v.is_array() ? "an array of " + std::to_string(v.size()) : std::string(v.type_name())));
  for (int i = 0; i < 3; i++)
    out[i] = number(v[size_t(i)], element + "[" + std::to_string(i) + "]");
}

std::vector<camera_path_json_key> parse(const std::string& text) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.what(): "[json.exception.parse_error.101] parse error at line 3, column 5: ..."
    std::string what = e.what();
    size_t at = what.find("parse error");
    fail("", at == std::string::npos ? what : what.substr(at));
  }
  if (!doc.is_object()) fail("", std::string("expected an object with \"keyframes\", got ") + doc.type_name());
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    const std::string& k = it.key();
    if (k != "keyframes" && k != "name" && k != "description")
      fail("", "unknown key '" + k + "' (expected keyframes, name, description)");
    if (k != "keyframes" && !it.value().is_string()) fail(k, "expected a string");
  }
  if (!doc.contains("keyframes")) fail("", "missing key 'keyframes'");
  const nlohmann::json& frames = doc["keyframes"];
  if (!frames.is_array()) fail("keyframes", std::string("expected an array, got ") + frames.type_name());
  std::vector<camera_path_json_key> keys;
  for (size_t i = 0; i < frames.size(); i++) {
    const std::string element = "keyframes[" + std::to_string(i) + "]";
    const nlohmann::json& f = frames[i];
    if (!f.is_object()) fail(element, std::string("expected an object, got ") + f.type_name());
    for (auto it = f.begin(); it != f.end(); ++it) {
      const std::string& k = it.key();
      if (k != "time" && k != "eye" && k != "target" && k != "up" && k != "fovy")
        fail(element, "unknown key '" + k + "' (expected time, eye, target, up, fovy)");
    }
    for (const char* required : {"time", "eye", "target"})
      if (!f.contains(required)) fail(element, std::string("missing key '") + required + "'");
    camera_path_json_key key = {};
    key.time = number(f["time"], element + ".time");
    vec3(f["eye"], element + ".eye", key.eye);
    vec3(f["target"], element + ".target", key.target);
    key.up[1] = 1.0;
    if (f.contains("up")) vec3(f["up"], element + ".up", key.up);
    key.fovy = 45.0;
    if (f.contains("fovy")) key.fovy = number(f["fovy"], element + ".fovy");
    keys.push_back(key);
  }
  return keys;
}

void put_error(char* error, size_t size, const std::string& msg) {
  if (!error || !size) return;
  std::snprintf(error, size, "%s", msg.c_str());
}

} // namespace

extern "C" bool camera_path_json_load(const char* path, camera_path_json_key** keys, uint32_t* count, char* error,
                                      size_t error_size) {
  if (keys) *keys = nullptr;
  if (count) *count = 0;
  if (!path || !keys || !count) {
    put_error(error, error_size, "camera_path_json_load: NULL argument");
    return false;
  }
  try {
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) { // ifstream opens a folder, then reads nothing
      put_error(error, error_size, std::string(path) + ": cannot open: " + std::strerror(EISDIR));
      return false;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      put_error(error, error_size, std::string(path) + ": cannot open: " + std::strerror(errno));
      return false;
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) {
      put_error(error, error_size, std::string(path) + ": read error");
      return false;
    }
    std::vector<camera_path_json_key> parsed = parse(text.str());
    auto* out = static_cast<camera_path_json_key*>(std::malloc(sizeof(camera_path_json_key) * (parsed.size() + 1)));
    if (!out) throw std::bad_alloc();
    if (!parsed.empty()) std::memcpy(out, parsed.data(), sizeof(camera_path_json_key) * parsed.size());
    *keys = out;
    *count = static_cast<uint32_t>(parsed.size());
    put_error(error, error_size, "");
    return true;
  } catch (const PathError& e) {
    put_error(error, error_size, std::string(path) + ": " + e.message);
  } catch (const std::bad_alloc&) {
    put_error(error, error_size, std::string(path) + ": out of memory");
  } catch (const std::exception& e) {
    put_error(error, error_size, std::string(path) + ": " + e.what());
  } catch (...) {
    put_error(error, error_size, std::string(path) + ": unknown error");
  }
  return false;
}

extern "C" void camera_path_json_free(camera_path_json_key* keys) { std::free(keys); }
