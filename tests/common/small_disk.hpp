#pragma once
// A full disk made by the test: a tmpfs of a few KiB mounted on a fresh folder (the tests run as
// root; a machine that does not allow the mount fails the test loudly, it is never skipped),
// and fill() to take all but a little of its space. Unmounted when the object goes away.

#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "temp_dir.hpp"

namespace tactile::test {

class SmallDisk {
 public:
  // `read_only`: mounted read-only, a folder that even root cannot write in (root ignores mode
  // bits such as chmod 0555, not a read-only mount).
  explicit SmallDisk(std::size_t size_kib = 64, bool read_only = false) : dir_("small-disk") {
    const std::string options = "size=" + std::to_string(size_kib) + "k";
    if (::mount("tmpfs", dir_.path().c_str(), "tmpfs", read_only ? MS_RDONLY : 0,
                options.c_str()) != 0) {
      throw std::runtime_error("cannot mount a " + options + " tmpfs on " + dir_.path().string() +
                               " for a full-disk test: " + std::strerror(errno) +
                               " (the tests need root)");
    }
    mounted_ = true;
  }
  ~SmallDisk() {
    if (mounted_) ::umount2(dir_.path().c_str(), MNT_DETACH);
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;

  const std::filesystem::path& path() const { return dir_.path(); }
  std::filesystem::path operator/(const std::filesystem::path& p) const { return path() / p; }

  // Writes a filler file until the disk is full, then frees `leave_bytes` of it.
  void fill(std::size_t leave_bytes = 0) const {
    const auto filler = path() / "filler";
    {
      std::ofstream out(filler, std::ios::binary);
      const std::string block(1024, 'f');
      while (out.write(block.data(), static_cast<std::streamsize>(block.size()))) {
      }
    }
    const auto size = std::filesystem::file_size(filler);
    std::filesystem::resize_file(filler, size > leave_bytes ? size - leave_bytes : 0);
  }

 private:
  TempDir dir_;
  bool mounted_ = false;
};

}  // namespace tactile::test
