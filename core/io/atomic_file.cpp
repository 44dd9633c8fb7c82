#include "core/io/atomic_file.hpp"

#include "core/errors.hpp"

#include <fstream>
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
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw WriteError(path.string() + ": cannot create file (" + temp.string() + ")");
    out << text;
    out.flush();
    if (!out) {
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
