// image_load.cpp -- an importer's image: its bytes and its pixels (image_load.hpp).
// Owned by the import/export layer.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "contained_file.h"
#include "image_decode.h"
#include "image_load.hpp"

namespace tlod_import_detail {

namespace {

void take(_tlod_import_budget* budget, size_t bytes, const char* what) {
  if (!_tlod_budget_take(budget, bytes))
    fail(TLOD_ERROR_OUT_OF_MEMORY,
         format("%s exceeds the import's memory budget (tlod_import_desc.memory_limit)", what));
}

void note_mime(Image& im) {
  const char* sniffed = _tlod_image_sniff(im.encoded.data(), im.encoded.size());
  if (!im.info.mime[0] && sniffed) std::snprintf(im.info.mime, sizeof im.info.mime, "%s", sniffed);
}

} // namespace

void image_read_file(const char* folder, const std::string& ref, _tlod_import_budget* budget, Image& im) {
  if (!folder) fail(TLOD_ERROR_IO, "refused: an external file of a model imported from memory");
  unsigned char* data = nullptr;
  size_t size = 0;
  const _tlod_contained_status st =
      _tlod_contained_read(folder, ref.c_str(), _tlod_budget_file_limit(budget), &data, &size);
  if (st != _TLOD_CONTAINED_OK) fail(TLOD_ERROR_IO, _tlod_contained_message(st));
  const std::unique_ptr<unsigned char, void (*)(void*)> hold(data, std::free);
  _tlod_budget_add_input(budget, size);
  take(budget, size, "the image file");
  im.encoded.assign(data, data + size);
  note_mime(im);
}

void image_keep_bytes(const unsigned char* data, size_t size, _tlod_import_budget* budget, Image& im) {
  take(budget, size, "the image");
  im.encoded.assign(data, data + size);
  note_mime(im);
}

void image_decode(_tlod_import_budget* budget, Image& im) {
  _tlod_image img{};
  char detail[128];
  const _tlod_image_status st =
      _tlod_image_decode(im.encoded.data(), im.encoded.size(), budget, &img, detail, sizeof detail);
  const char* phrase = _tlod_image_message(st);
  if (st != _TLOD_IMAGE_OK)
    fail(TLOD_ERROR_PARSE, detail[0] && std::strcmp(detail, phrase) ? format("%s (%s)", phrase, detail) : phrase);
  const std::unique_ptr<unsigned char, void (*)(void*)> hold(img.rgba, std::free);
  const size_t bytes = size_t(img.width) * img.height * 4;
  take(budget, bytes, "the decoded image");
  im.rgba.assign(img.rgba, img.rgba + bytes);
  im.info.width = img.width;
  im.info.height = img.height;
}

} // namespace tlod_import_detail
