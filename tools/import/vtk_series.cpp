// vtk_series.cpp -- the files of a .pvd, a .pvtu or a numbered series (vtk_series.hpp). Only
// names are read here; the files themselves are opened under the folder rule by vtk_import.cpp.
#include "vtk_series.hpp"

#include <dirent.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "import_error.hpp"
#include "vtk_preflight.hpp"

namespace tlod_import_detail {

std::vector<StepRef> pvd_steps(const char* data, size_t size) {
  std::vector<StepRef> steps;
  xml_tags(data, size, "DataSet", [&](const char* b, const char* e) {
    std::string file, t;
    if (!xml_attribute(b, e, "file", &file))
      fail(TLOD_ERROR_PARSE, format("DataSet %zu: no file attribute", steps.size()));
    float time = float(steps.size());
    if (xml_attribute(b, e, "timestep", &t)) {
      char* stop = nullptr;
      time = strtof(t.c_str(), &stop);
      if (t.empty() || *stop || !std::isfinite(time))
        fail(TLOD_ERROR_PARSE,
             format("DataSet %zu: timestep \"%.32s\" is not a finite number", steps.size(), t.c_str()));
    }
    for (const StepRef& s : steps)
      if (s.time == time)
        fail(TLOD_ERROR_UNSUPPORTED, format("DataSet %zu '%.200s': timestep %g given twice (parts of one step are "
                                            "not read; merge them into one .pvtu)",
                                            steps.size(), file.c_str(), double(time)));
    steps.push_back({file, time});
  });
  if (steps.empty()) fail(TLOD_ERROR_PARSE, "no <DataSet> in the collection");
  return steps;
}

std::vector<StepRef> numbered_steps(const char* folder, const std::string& pattern) {
  const size_t star = pattern.find('*');
  const std::string prefix = pattern.substr(0, star), suffix = pattern.substr(star + 1);
  if (suffix.find('*') != std::string::npos) fail(TLOD_ERROR_UNSUPPORTED, "more than one '*' in the name");
  DIR* dir = opendir(folder && *folder ? folder : ".");
  if (!dir) fail(TLOD_ERROR_IO, "cannot list the model's folder");
  std::vector<std::pair<unsigned long long, std::string>> found;
  while (const dirent* d = readdir(dir)) {
    const std::string n = d->d_name;
    if (n.size() <= prefix.size() + suffix.size() || n.compare(0, prefix.size(), prefix) != 0 ||
        n.compare(n.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string digits = n.substr(prefix.size(), n.size() - prefix.size() - suffix.size());
    if (digits.size() > 18 || digits.find_first_not_of("0123456789") != std::string::npos) continue;
    found.emplace_back(std::stoull(digits), n);
  }
  closedir(dir);
  if (found.empty()) fail(TLOD_ERROR_IO, "no file matches the numbered series");
  std::sort(found.begin(), found.end());
  std::vector<StepRef> steps;
  for (const auto& f : found)
    steps.push_back({f.second, float(steps.size())});
  return steps;
}

std::vector<std::string> pvtu_pieces(const char* data, size_t size, const std::string& self) {
  const size_t slash = self.rfind('/');
  const std::string base = slash == std::string::npos ? "" : self.substr(0, slash + 1);
  std::vector<std::string> pieces;
  xml_tags(data, size, "Piece", [&](const char* b, const char* e) {
    std::string src;
    if (!xml_attribute(b, e, "Source", &src))
      fail(TLOD_ERROR_PARSE, format("Piece %zu: no Source attribute", pieces.size()));
    // An absolute Source stays absolute (and is refused by the folder rule).
    pieces.push_back(!src.empty() && src[0] == '/' ? src : base + src);
  });
  if (pieces.empty()) fail(TLOD_ERROR_PARSE, "no <Piece Source=...> in the .pvtu");
  return pieces;
}

} // namespace tlod_import_detail
