#include "fabrication/fabricate.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "fabrication/assembly_drawings.hpp"
#include "fabrication/cut_sheets.hpp"
#include "fabrication/dxf_writer.hpp"
#include "fabrication/pdf_writer.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <zip.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <future>
#include <numeric>
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
std::string zipArchive(const std::vector<std::pair<std::string, const std::string*>>& files) {
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
    zip_source_t* entry = zip_source_buffer(archive, text->data(), text->size(), 0);
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
  // Every file's text is a pure function of the result: they are made in parallel (TBB), then
  // written one after the other in a fixed order. On the Yas (571 sheets, 270 MB of DXF, SVG and
  // PDF) making them is nearly all of the stage, and sheets.pdf alone is a third of it.
  std::vector<std::pair<std::string, std::function<std::string()>>> jobs;
  auto add = [&](std::string relative, std::function<std::string()> make) {
    jobs.emplace_back(std::move(relative), std::move(make));
  };
  auto addSheets = [&](const std::vector<Drawing>& sheets, const std::string& stem,
                       const std::string& pdf) {
    for (size_t i = 0; i < sheets.size(); ++i) {
      const Drawing* sheet = &sheets[i];
      add(numbered("cut/" + stem, static_cast<int>(i + 1), 2, ".svg"),
          [sheet] { return toSvg(*sheet); });
      add(numbered("cut/" + stem, static_cast<int>(i + 1), 2, ".dxf"),
          [sheet, &r] { return toDxf(*sheet, r.options.dxfVersion, r.options.paperSize); });
    }
    if (!sheets.empty()) {
      add("cut/" + pdf,
          [&r, &sheets] { return toPdf(sheets, r.options.sheetPdf, r.options.paperSize); });
    }
  };
  const bool boards = r.options.stock == CutStock::Boards;
  if (outputs.cutFiles) {
    addSheets(r.sheets, boards ? "board_" : "sheet_", boards ? "boards.pdf" : "sheets.pdf");
    if (boards) add("cut/boards.csv", [&r] { return boardsCsv(r); });
    if (!r.assembly.empty()) add("cut/assembly.pdf", [&r] { return assemblyPdf(r); });
  }
  if (outputs.stickers) addSheets(r.stickerSheets, "stickers_", "stickers.pdf");
  if (outputs.supports) {
    add("supports/supports.csv", [&r] { return supportsCsv(r.supports); });
    for (size_t i = 0; i < r.supports.size(); ++i) {
      if (!r.supports[i].block) continue;
      add(numbered("supports/support_", static_cast<int>(i + 1), 3, ".stl"), [&r, i] {
        return toBinaryStl(r.supportSolids[i], "eggshell support " + r.supports[i].id + " (mm)");
      });
    }
  }
  add("bom.csv", [&r] { return bomCsv(r); });

  // The PDFs (the longest jobs) start first, so that they run while the sheets are made.
  std::vector<size_t> schedule(jobs.size());
  std::iota(schedule.begin(), schedule.end(), size_t{0});
  const auto isPdf = [&](size_t k) {
    const std::string& name = jobs[k].first;
    return name.size() >= 4 && name.compare(name.size() - 4, 4, ".pdf") == 0;
  };
  std::stable_partition(schedule.begin(), schedule.end(), isPdf);
  std::vector<std::string> texts(jobs.size());
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, jobs.size(), 1),
      [&](const tbb::blocked_range<size_t>& range) {
        for (size_t k = range.begin(); k != range.end(); ++k)
          texts[schedule[k]] = jobs[schedule[k]].second();
      },
      tbb::simple_partitioner());  // job by job: a PDF is worth hundreds of sheets

  // Then cut.zip is deflated on one thread while the files are written on others (each write
  // waits for its fsync): on the Yas, 2.0 s of deflating and 1.8 s of writing one after the
  // other before.
  std::vector<std::pair<std::string, const std::string*>> archived;  // the cut set and the BOM
  for (size_t k = 0; k < jobs.size(); ++k) {
    const std::string& relative = jobs[k].first;
    if (relative.rfind("cut/", 0) == 0 || relative == "bom.csv")
      archived.emplace_back(relative, &texts[k]);
  }
  std::future<std::string> zip;
  if ((outputs.cutFiles || outputs.stickers) && archived.size() > 1)
    zip = std::async(std::launch::async, [&archived] { return zipArchive(archived); });
  std::vector<std::string> files;
  try {
    for (size_t k = 0; k < jobs.size(); ++k) {
      const auto folder = (dir / jobs[k].first).parent_path();
      std::error_code error;
      std::filesystem::create_directories(folder, error);
      if (error)
        throw WriteError("cannot create the folder " + folder.string() + ": " + error.message());
    }
    tbb::parallel_for(size_t{0}, jobs.size(),
                      [&](size_t k) { writeFileAtomically(dir / jobs[k].first, texts[k]); });
  } catch (...) {
    if (zip.valid()) zip.wait();  // it reads the texts
    throw;
  }
  for (const auto& job : jobs) files.push_back(job.first);
  if (zip.valid()) {
    // One archive of the whole cut set for the workshop (the Yas writes over a thousand files).
    writeFileAtomically(dir / "cut.zip", zip.get());
    files.push_back("cut.zip");
  }
  return files;
}

}  // namespace egg::fabrication
