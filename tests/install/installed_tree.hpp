#pragma once
// `cmake --install` of this build into a DESTDIR under the test process's scratch directory, done once per
// process, with the paths the installed tree should have (cmake/install_system_files.cmake's rule: /etc and
// /lib for the prefix /usr, below the prefix otherwise).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "command_run.hpp"
#include "scratch_dir.hpp"

namespace imucal::testing {

struct InstalledTree {
  std::filesystem::path destdir;
  std::string prefix = IMUCAL_INSTALL_PREFIX;
  bool ok = false;
  std::string log;

  // A path as the installed programs see it (no DESTDIR) and the same file in the scratch tree.
  std::string bin(const std::string& name) const { return prefix + "/" IMUCAL_INSTALL_BINDIR "/" + name; }
  std::string etc() const { return prefix == "/usr" ? "/etc" : prefix + "/etc"; }
  std::string lib() const { return prefix == "/usr" ? "/lib" : prefix + "/lib"; }
  std::string inTree(const std::string& installed_path) const { return destdir.string() + installed_path; }
  std::string root() const { return inTree(prefix); }
};

inline const InstalledTree& installedTree() {
  static const InstalledTree tree = [] {
    InstalledTree t;
    t.destdir = processScratchDir("install") / "destdir";
    const CommandRun r = runCommand("DESTDIR='" + t.destdir.string() + "' '" IMUCAL_CMAKE_COMMAND "' --install '"
                                    IMUCAL_BUILD_DIR "'");
    t.ok = r.status == 0;
    t.log = r.output;
    return t;
  }();
  return tree;
}

}  // namespace imucal::testing
