// Implementation of the coding of sections held in files (see section_file_coding.hpp).
#include "container/section_file_coding.hpp"

#include <zstd.h>

#include <functional>
#include <mutex>
#include <relume/error.hpp>
#include <string>
#include <vector>

#include "core/crc32.hpp"
#include "core/interruption.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"

namespace relume {
namespace {

// Bytes read from a file at a time.
constexpr std::size_t chunk_bytes = std::size_t(4) << 20;

using ByteSink = std::function<void(const char* data, std::size_t bytes)>;

// The raw bytes of `raw` after `filter`, in pieces, as section_coding's filters produce them
// whole: each byte plane (all first bytes, all second bytes, ...) of the numbers or of their
// deltas, one plane after the other.
void filtered_bytes(const DiskFile& raw, SectionFilter filter, int element_bytes,
                    const ByteSink& sink) {
  std::vector<char> chunk(chunk_bytes);
  if (filter == SectionFilter::none) {
    for (std::uint64_t at = 0; at < raw.size(); at += chunk_bytes) {
      throw_if_interrupted();
      const std::size_t bytes = std::size_t(std::min<std::uint64_t>(chunk_bytes, raw.size() - at));
      raw.read_at(at, chunk.data(), bytes);
      sink(chunk.data(), bytes);
    }
    return;
  }
  const std::size_t width = std::size_t(element_bytes);
  std::vector<char> plane(chunk_bytes / width);
  for (std::size_t b = 0; b < width; ++b) {
    std::uint64_t previous = 0;
    for (std::uint64_t at = 0; at < raw.size(); at += chunk_bytes) {
      throw_if_interrupted();
      const std::size_t bytes = std::size_t(std::min<std::uint64_t>(chunk_bytes, raw.size() - at));
      raw.read_at(at, chunk.data(), bytes);
      const std::size_t count = bytes / width;
      for (std::size_t i = 0; i < count; ++i) {
        std::uint64_t value = 0;
        for (std::size_t k = width; k-- > 0;)
          value = (value << 8) | static_cast<unsigned char>(chunk[i * width + k]);
        std::uint64_t stored = value;
        if (filter == SectionFilter::delta_shuffle) {
          stored = value - previous;  // the first number's "previous" is 0: itself
          previous = value;
        }
        plane[i] = static_cast<char>((stored >> (8 * b)) & 0xFF);
      }
      sink(plane.data(), count);
    }
  }
}

// `raw` after `filter`, zstd-coded into `coded`.
void zstd_file(const DiskFile& raw, SectionFilter filter, int element_bytes, DiskFile& coded) {
  ZSTD_CCtx* context = ZSTD_createCCtx();
  if (!context) throw Error("zstd cannot start a compression (out of memory)");
  const std::unique_ptr<ZSTD_CCtx, std::size_t (*)(ZSTD_CCtx*)> owner(context, ZSTD_freeCCtx);
  ZSTD_CCtx_setParameter(context, ZSTD_c_compressionLevel, section_zstd_level);
  ZSTD_CCtx_setParameter(context, ZSTD_c_checksumFlag, 1);
  ZSTD_CCtx_setPledgedSrcSize(context, raw.size());
  std::vector<char> out(ZSTD_CStreamOutSize());
  const auto step = [&](const char* data, std::size_t bytes, ZSTD_EndDirective mode) {
    ZSTD_inBuffer in{data, bytes, 0};
    for (;;) {
      ZSTD_outBuffer buffer{out.data(), out.size(), 0};
      const std::size_t left = ZSTD_compressStream2(context, &buffer, &in, mode);
      if (ZSTD_isError(left))
        throw Error(std::string("zstd cannot compress: ") + ZSTD_getErrorName(left));
      coded.append(out.data(), buffer.pos);
      if (mode == ZSTD_e_end ? left == 0 : in.pos == in.size) return;
    }
  };
  filtered_bytes(raw, filter, element_bytes,
                 [&](const char* data, std::size_t bytes) { step(data, bytes, ZSTD_e_continue); });
  step(nullptr, 0, ZSTD_e_end);
}

}  // namespace

std::vector<FileCodedSection> code_section_files(const std::vector<const DiskFile*>& raws,
                                                 const std::vector<int>& element_bytes,
                                                 bool entropy_coding,
                                                 const std::filesystem::path& scratch_folder,
                                                 unsigned threads, const std::string& title) {
  struct Candidate {
    std::size_t section = 0;
    std::size_t order = 0;  // among its section's candidates
    SectionFilter filter = SectionFilter::none;
  };
  std::vector<FileCodedSection> sections(raws.size());
  std::vector<Candidate> candidates;
  std::uint64_t candidate_bytes = 0;
  for (std::size_t i = 0; i < raws.size(); ++i) {
    if (raws[i]->size() % std::uint64_t(element_bytes[i]) != 0)
      throw Error("internal: a section of " + std::to_string(raws[i]->size()) +
                  " bytes is not made of " + std::to_string(element_bytes[i]) + "-byte numbers");
    sections[i].bytes = raws[i]->size();
    if (!entropy_coding) continue;
    const std::vector<SectionFilter> filters = candidate_filters(element_bytes[i]);
    for (std::size_t order = 0; order < filters.size(); ++order)
      candidates.push_back({i, order, filters[order]});
    candidate_bytes += raws[i]->size() * filters.size();
  }
  // The best candidate so far of each section, by size and then order: the one a sequential
  // search keeps, whatever order the threads finish in.
  std::vector<std::size_t> best_order(raws.size(), 0);
  std::mutex best_mutex;
  ProgressReporter progress(title, candidate_bytes);
  parallel_for(candidates.size(), threads, [&](std::size_t c, unsigned) {
    const Candidate& candidate = candidates[c];
    const DiskFile& raw = *raws[candidate.section];
    DiskFile coded = DiskFile::temporary(
        scratch_folder,
        raw.path().filename().string() + ".coded" + std::to_string(int(candidate.filter)),
        "coded section");
    const int width = element_bytes[candidate.section];
    zstd_file(raw, candidate.filter, width, coded);
    progress.advance(raw.size());
    const std::lock_guard lock(best_mutex);
    FileCodedSection& section = sections[candidate.section];
    const bool better =
        coded.size() < section.bytes || (section.coded && coded.size() == section.bytes &&
                                         candidate.order < best_order[candidate.section]);
    if (!better) return;
    section.bytes = coded.size();
    section.coding = {true, candidate.filter, width};
    best_order[candidate.section] = candidate.order;
    section.coded.reset();
    section.coded.emplace(std::move(coded));
  });
  progress.finish();
  return sections;
}

void append_coded_section(const DiskFile& raw, FileCodedSection& section, DiskFile& out) {
  section.crc32 = 0;
  const DiskFile& stored = section.coded ? *section.coded : raw;
  filtered_bytes(stored, SectionFilter::none, 1, [&](const char* data, std::size_t bytes) {
    section.crc32 = crc32(data, bytes, section.crc32);
    out.append(data, bytes);
  });
}

}  // namespace relume
