#pragma once
// The files of an app's export, whether the user unpacked it into a folder or kept the zip: each by its
// base name (apps put the CSVs at the top or in one folder named after the recording), its text read
// whole, and its name for messages ("rec/Gyroscope.csv" or "rec.zip:Gyroscope.csv").
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "imucal/io/zip_archive.hpp"

namespace imucal::io {

class RecordingFiles {
 public:
  // A folder (its files, not its subfolders' but one level down, as an unpacked zip holds them) or a zip
  // archive; a single file is a recording of that one file. Throws InputError naming the path.
  explicit RecordingFiles(const std::string& path);

  // Base names, as stored, of the files the recording holds (a zip's "meta/" and "__MACOSX/" left out).
  std::vector<std::string> names() const;
  // The file of that base name, compared without regard to case; nullopt when there is none.
  std::optional<std::string> find(const std::string& base_name) const;
  // Its text, whole (at most kMaxZipEntryBytes). Throws InputError naming it.
  std::string read(const std::string& name) const;
  // Its first line (a folder's file: from its first 4 KiB; a zip entry is read whole, and checked).
  std::string firstLine(const std::string& name) const;
  // How messages name it.
  std::string where(const std::string& name) const;
  bool isZip() const { return zip_ != nullptr; }
  const std::string& path() const { return path_; }

 private:
  struct File {
    std::string base;  // name without folders
    std::string full;  // path on disk, or the zip entry's name
    std::size_t entry = 0;
  };
  std::string path_;
  std::unique_ptr<ZipArchive> zip_;
  std::vector<File> files_;
  const File* file(const std::string& name) const;
};

// Lower case, ASCII only: file and column names as apps vary them ("Magnetic Field x" / "Magnetic field x").
std::string lowerAscii(std::string s);

}  // namespace imucal::io
