// Implementation of the container writer for fields in strips (see container_strips.hpp).
#include <relume/error.hpp>
#include <string>

#include "container/container_encoding.hpp"
#include "container/container_strips.hpp"
#include "core/crc32.hpp"
#include "container/section_file_coding.hpp"
#include "core/atomic_file.hpp"
#include "core/disk_file.hpp"
#include "core/progress.hpp"
#include "model/compressed_field_checks.hpp"
#include "model/compressed_field_rows.hpp"

namespace relume {
namespace fs = std::filesystem;

namespace {

// The sections with an entry per stored row, in file order, and the file each is gathered in.
constexpr const char* row_section_names[] = {"clusters", "weights", "residual_offsets",
                                             "residual_indices", "residual_values"};

int row_section_index(std::string_view name) {
  for (int i = 0; i < int(std::size(row_section_names)); ++i)
    if (name == row_section_names[i]) return i;
  return -1;
}

std::string rows_text(const CompressedFieldStrips& strips, std::size_t s) {
  const int end = s + 1 < strips.first_rows.size() ? strips.first_rows[s + 1] : strips.shell.height;
  return "pixel rows " + std::to_string(strips.first_rows[s]) + " to " + std::to_string(end);
}

}  // namespace

ContainerLayout write_container_strips(const fs::path& path, const CompressedFieldStrips& strips,
                                       const ContainerOptions& options,
                                       const fs::path& scratch_folder) {
  const std::string where = "cannot write " + path.string();
  const CompressedField& shell = strips.shell;
  check_output_file_location(path);
  // 1. What the header and the widths need: counts, the longest residual row, and where the
  // stored rows are.
  StoredCounts counts;
  std::uint32_t longest = 0;
  std::vector<std::uint64_t> stored_functions;
  const std::uint64_t row_functions = std::uint64_t(shell.width) * std::uint64_t(shell.channels);
  const std::string title = "writing " + path.filename().string();
  ProgressReporter encoding(title + ": strips", 2 * strips.first_rows.size());
  for (std::size_t s = 0; s < strips.first_rows.size(); ++s) {
    encoding.advance();
    const CompressedField strip = strips.strip(s);
    validate_compressed_field(strip, where + " (" + rows_text(strips, s) + ")");
    counts.stored_rows += strip.stored_rows();
    counts.residual_nonzeros += strip.residual.nonzeros();
    longest = std::max(longest, strip.residual.longest_row());
    const std::uint64_t first_function = std::uint64_t(strips.first_rows[s]) * row_functions;
    for (const std::uint32_t p : strip.stored_function)
      stored_functions.push_back(first_function + p);
  }
  const StoredWidths widths = resolved_widths(shell, longest, options.light_index, where);

  // 2. The row sections' raw bytes, strip by strip; each strip's weights are predicted with the
  // last pixel row of the strip above as their upper neighbours.
  std::vector<DiskFile> raw;
  for (const char* name : row_section_names)
    raw.push_back(
        DiskFile::temporary(scratch_folder, path.filename().string() + "." + name, "raw section"));
  CompressedField above;
  for (std::size_t s = 0; s < strips.first_rows.size(); ++s) {
    encoding.advance();
    const CompressedField strip = strips.strip(s);
    CompressedField window = above;
    const std::size_t first_row = window.stored_rows();
    append_compressed_rows(window, strip);
    const RowSections rows = encode_row_sections(window, first_row, options, widths,
                                                 where + " (" + rows_text(strips, s) + ")");
    const std::string* parts[] = {&rows.clusters, &rows.weights, &rows.lengths, &rows.indices,
                                  &rows.values};
    for (std::size_t i = 0; i < raw.size(); ++i) raw[i].append(parts[i]->data(), parts[i]->size());
    if (strip.height > 0) above = compressed_rows(strip, strip.height - 1, 1);
  }
  encoding.finish();

  // 3. The file: a place for the preamble, the sections coded one by one, then the preamble.
  std::vector<StoredSection> sections =
      sections_in_file_order(encode_header(shell, counts, options, widths, where),
                             encode_field_sections(shell, stored_functions), {}, widths,
                             value_bytes(stored_weight_precision(shell, options)),
                             value_bytes(stored_residual_precision(shell, options)));
  std::vector<std::uint64_t>().swap(stored_functions);
  ContainerLayout layout = new_container_layout();
  // The row sections coded from their files first, all at once.
  std::vector<const DiskFile*> raw_files(raw.size());
  std::vector<int> element_bytes(raw.size());
  for (const StoredSection& section : sections)
    if (const int from_file = row_section_index(section.name); from_file >= 0) {
      raw_files[std::size_t(from_file)] = &raw[std::size_t(from_file)];
      element_bytes[std::size_t(from_file)] = section.element_bytes;
    }
  std::vector<FileCodedSection> coded_rows =
      code_section_files(raw_files, element_bytes, options.entropy_coding, scratch_folder,
                         options.coding_threads, title + ": coding sections (raw bytes x filters)");
  write_atomically(path, [&](const fs::path& temp) {
    DiskFile out = DiskFile::create(temp, "container");
    const std::string placeholder(layout.preamble_bytes, '\0');
    out.append(placeholder.data(), placeholder.size());
    std::vector<SectionCoding> codings;
    for (StoredSection& section : sections) {
      const std::uint64_t offset = out.size();
      const int from_file = row_section_index(section.name);
      if (from_file >= 0) {
        const DiskFile& file = raw[std::size_t(from_file)];
        FileCodedSection& coded = coded_rows[std::size_t(from_file)];
        append_coded_section(file, coded, out);
        codings.push_back(coded.coding);
        layout.sections.push_back({std::string(section.name), offset, coded.bytes, file.size(),
                                   coded.crc32, coded.coding.describe()});
        continue;
      }
      const std::size_t section_bytes = section.raw.size();
      const CodedSection coded = options.entropy_coding && section.name != "header"
                                     ? code_section(section.raw, section.element_bytes)
                                     : CodedSection{std::move(section.raw), {}};
      out.append(coded.bytes.data(), coded.bytes.size());
      codings.push_back(coded.coding);
      layout.sections.push_back({std::string(section.name), offset, coded.bytes.size(),
                                 section_bytes, crc32(coded.bytes), coded.coding.describe()});
    }
    layout.file_bytes = out.size();
    const std::string preamble = encode_preamble(layout, codings);
    out.write_at(0, preamble.data(), preamble.size());
    out.close();
  });
  return layout;
}

}  // namespace relume
