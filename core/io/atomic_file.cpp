#include "core/io/atomic_file.hpp"

#include "core/errors.hpp"

#include <unistd.h>

#include <cstdio>
#include <random>
#include <system_error>

namespace egg {

std::string temporarySuffix() {
  std::random_device rd;
  std::uniform_int_distribution<unsigned> digit(0, 35);
  std::string s;
  for (int i = 0; i < 8; ++i) {
    const unsigned d = digit(rd);
    s.push_back(static_cast<char>(d < 10 ? '0' + d : 'a' + d - 10));
  }
  return s;
}

void writeFileAtomically(const std::filesystem::path& path, const std::string& text) {
  namespace fs = std::filesystem;
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  // Same folder as the target: rename is atomic only within one file system.
  const fs::path temp = dir / ("." + path.filename().string() + ".tmp-" + temporarySuffix());
  {
    // C stdio rather than a stream: the close must be checked (NFS and quotas report errors
    // there) and the data synced before the rename, or a crash could leave an empty file under
    // the final name.
    std::FILE* out = std::fopen(temp.c_str(), "wb");
    if (!out) throw WriteError(path.string() + ": cannot create file (" + temp.string() + ")");
    const bool written = std::fwrite(text.data(), 1, text.size(), out) == text.size() && std::fflush(out) == 0 &&
                         ::fsync(::fileno(out)) == 0;
    const bool closed = std::fclose(out) == 0;
    if (!written || !closed) {
      std::error_code ignored;
      fs::remove(temp, ignored);
      throw WriteError(path.string() + ": write failed (disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(temp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw WriteError(path.string() + ": cannot move finished file into place: " + ec.message());
  }
}

}  // namespace egg
