#include "fabrication/fabricate.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "fabrication/assembly_drawings.hpp"
#include "fabrication/cut_sheets.hpp"
#include "fabrication/dxf_writer.hpp"
#include "fabrication/pdf_writer.hpp"

#include <zip.h>

#include <cstdio>
#include <utility>

namespace egg::fabrication {
namespace {

std::string numbered(const std::string& stem, int number, int digits,
                     const std::string& extension) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "%0*d", digits, number);
  return stem + buffer + extension;
}

[[noreturn]] void zipFailed(zip_error_t* error, const std::string& what) {
  const std::string message = "cannot build cut.zip (" + what + "): " + zip_error_strerror(error);
  zip_error_fini(error);
  throw WriteError(message);
}

// A zip archive (deflated) of (name, content) pairs, built in memory through libzip so that the
// caller writes it atomically like every other file.
std::string zipArchive(const std::vector<std::pair<std::string, std::string>>& files) {
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* buffer = zip_source_buffer_create(nullptr, 0, 0, &error);
  if (!buffer) zipFailed(&error, "a memory buffer");
  zip_source_keep(buffer);  // read back after zip_close
  zip_t* archive = zip_open_from_source(buffer, ZIP_TRUNCATE, &error);
  if (!archive) {
    zip_source_free(buffer);
    zipFailed(&error, "open");
  }
  for (const auto& [name, text] : files) {
    zip_source_t* entry = zip_source_buffer(archive, text.data(), text.size(), 0);
    const zip_int64_t index =
        entry ? zip_file_add(archive, name.c_str(), entry, ZIP_FL_ENC_UTF_8) : -1;
    // Deflate level 1: the DXF and SVG text of a large roof is tens of MB, and level 1 costs a
    // fraction of the default's time for a few per cent more bytes; PDFs are deflated already.
    const bool pdf = name.size() >= 4 && name.compare(name.size() - 4, 4, ".pdf") == 0;
    if (index < 0 ||
        zip_set_file_compression(archive, static_cast<zip_uint64_t>(index),
                                 pdf ? ZIP_CM_STORE : ZIP_CM_DEFLATE, pdf ? 0 : 1) < 0) {
      if (entry && index < 0) zip_source_free(entry);
      zip_error_set(&error, zip_error_code_zip(zip_get_error(archive)), 0);
      zip_discard(archive);
      zip_source_free(buffer);
      zipFailed(&error, name);
    }
  }
  if (zip_close(archive) < 0) {
    zip_error_set(&error, zip_error_code_zip(zip_get_error(archive)), 0);
    zip_discard(archive);
    zip_source_free(buffer);
    zipFailed(&error, "close");
  }
  std::string bytes;
  if (zip_source_open(buffer) == 0) {
    zip_source_seek(buffer, 0, SEEK_END);
    const zip_int64_t size = zip_source_tell(buffer);
    zip_source_seek(buffer, 0, SEEK_SET);
    bytes.resize(size > 0 ? static_cast<size_t>(size) : 0);
    const zip_int64_t read = size > 0 ? zip_source_read(buffer, bytes.data(), size) : 0;
    zip_source_close(buffer);
    if (read != size) bytes.clear();
  }
  zip_source_free(buffer);
  if (bytes.empty()) zipFailed(&error, "read back");
  return bytes;
}

}  // namespace

std::vector<std::string> writeFabricationFiles(const FabricationResult& r,
                                               const std::filesystem::path& dir,
                                               const FabricationOutputs& outputs) {
  std::vector<std::string> files;
  std::vector<std::pair<std::string, std::string>> archived;  // cut.zip: the cut set and the BOM
  auto write = [&](const std::string& relative, const std::string& text) {
    if (relative.rfind("cut/", 0) == 0 || relative == "bom.csv")
      archived.emplace_back(relative, text);
    const auto path = dir / relative;
    std::error_code error;
    std::filesystem::create_directories(path.parent_path(), error);
    if (error)
      throw WriteError("cannot create the folder " + path.parent_path().string() + ": " +
                       error.message());
    writeFileAtomically(path, text);
    files.push_back(relative);
  };
  auto writeSheets = [&](const std::vector<Drawing>& sheets, const std::string& stem,
                         const std::string& pdf) {
    for (size_t i = 0; i < sheets.size(); ++i) {
      write(numbered("cut/" + stem, static_cast<int>(i + 1), 2, ".svg"), toSvg(sheets[i]));
      write(numbered("cut/" + stem, static_cast<int>(i + 1), 2, ".dxf"),
            toDxf(sheets[i], r.options.dxfVersion));
    }
    if (!sheets.empty())
      write("cut/" + pdf, toPdf(sheets, r.options.sheetPdf, r.options.paperSize));
  };
  const bool boards = r.options.stock == CutStock::Boards;
  if (outputs.cutFiles) {
    writeSheets(r.sheets, boards ? "board_" : "sheet_", boards ? "boards.pdf" : "sheets.pdf");
    if (boards) write("cut/boards.csv", boardsCsv(r));
    if (!r.assembly.empty()) write("cut/assembly.pdf", assemblyPdf(r));
  }
  if (outputs.stickers) writeSheets(r.stickerSheets, "stickers_", "stickers.pdf");
  if (outputs.supports) {
    write("supports/supports.csv", supportsCsv(r.supports));
    for (size_t i = 0; i < r.supports.size(); ++i) {
      if (!r.supports[i].block) continue;
      write(numbered("supports/support_", static_cast<int>(i + 1), 3, ".stl"),
            toBinaryStl(r.supportSolids[i], "eggshell support " + r.supports[i].id + " (mm)"));
    }
  }
  write("bom.csv", bomCsv(r));
  if ((outputs.cutFiles || outputs.stickers) && archived.size() > 1) {
    // One archive of the whole cut set for the workshop (the Yas writes over a thousand files).
    const std::string zip = zipArchive(archived);
    archived.clear();
    write("cut.zip", zip);
  }
  return files;
}

}  // namespace egg::fabrication
