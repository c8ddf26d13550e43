#include "recording_files.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "imucal/io/errors.hpp"

namespace imucal::io {

namespace fs = std::filesystem;

std::string lowerAscii(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

namespace {

std::string baseName(const std::string& name) {
  const auto slash = name.find_last_of('/');
  return slash == std::string::npos ? name : name.substr(slash + 1);
}

// A zip's folders other than the recording's own: phyphox's metadata, the Finder's resource forks.
bool leftOut(const std::string& name) {
  const std::string lower = lowerAscii(name);
  return lower.rfind("meta/", 0) == 0 || lower.find("__macosx/") != std::string::npos || lower.empty() || lower.back() == '/';
}

}  // namespace

RecordingFiles::RecordingFiles(const std::string& path) : path_(path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    // The CSVs at the top, or one level down where a zip was unpacked into a folder of its own.
    for (const auto& top : fs::directory_iterator(path, ec)) {
      if (top.is_regular_file(ec)) {
        files_.push_back({top.path().filename().string(), top.path().string(), 0});
      } else if (top.is_directory(ec) && lowerAscii(top.path().filename().string()) != "meta") {
        for (const auto& inner : fs::directory_iterator(top.path(), ec))
          if (inner.is_regular_file(ec)) files_.push_back({inner.path().filename().string(), inner.path().string(), 0});
      }
    }
    std::sort(files_.begin(), files_.end(), [](const File& a, const File& b) { return a.full < b.full; });
  } else if (looksLikeZip(path)) {
    zip_ = std::make_unique<ZipArchive>(path);
    for (std::size_t i = 0; i < zip_->entries().size(); ++i) {
      const std::string& name = zip_->entries()[i].name;
      if (!leftOut(name)) files_.push_back({baseName(name), name, i});
    }
  } else {
    files_.push_back({fs::path(path).filename().string(), path, 0});
  }
}

std::vector<std::string> RecordingFiles::names() const {
  std::vector<std::string> out;
  for (const File& f : files_) out.push_back(f.base);
  return out;
}

const RecordingFiles::File* RecordingFiles::file(const std::string& name) const {
  const std::string lower = lowerAscii(name);
  for (const File& f : files_)
    if (lowerAscii(f.base) == lower) return &f;
  return nullptr;
}

std::optional<std::string> RecordingFiles::find(const std::string& base_name) const {
  const File* f = file(base_name);
  if (f == nullptr) return std::nullopt;
  return f->base;
}

std::string RecordingFiles::where(const std::string& name) const {
  const File* f = file(name);
  if (f == nullptr) return path_ + ":" + name;
  return zip_ ? path_ + ":" + f->full : f->full;
}

std::string RecordingFiles::firstLine(const std::string& name) const {
  std::string text;
  const File* f = file(name);
  if (f != nullptr && !zip_) {
    std::ifstream in(f->full, std::ios::binary);
    text.resize(4096);
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
  } else {
    text = read(name);
  }
  text = text.substr(0, text.find('\n'));
  if (!text.empty() && text.back() == '\r') text.pop_back();
  return text;
}

std::string RecordingFiles::read(const std::string& name) const {
  const File* f = file(name);
  if (f == nullptr) throw InputError(location(path_, 0) + "no " + excerpt(name));
  if (zip_) return zip_->read(zip_->entries()[f->entry]);
  std::ifstream in(f->full, std::ios::binary);
  if (!in) throw InputError(location(f->full, 0) + "cannot open");
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(in.tellg());
  if (size > kMaxZipEntryBytes)
    throw InputError(location(f->full, 0) + std::to_string(size) + " bytes, more than the " + std::to_string(kMaxZipEntryBytes) + " read");
  in.seekg(0);
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!in.read(text.data(), static_cast<std::streamsize>(size))) throw InputError(location(f->full, 0) + "read error");
  return text;
}

}  // namespace imucal::io
