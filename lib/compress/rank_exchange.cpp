// Implementation of what the ranks of a streamed compression exchange (see rank_exchange.hpp).
// Arrays travel as a count and their raw bytes (the ranks run the same binary on machines of one
// architecture), compressed fields as container bytes (lossless at float32).
#include "compress/rank_exchange.hpp"

#include <algorithm>
#include <cstring>
#include <relume/container.hpp>
#include <relume/error.hpp>

#include "container/container.hpp"
#include "container/container_bytes.hpp"
#include "model/compressed_field_rows.hpp"

namespace relume {
namespace {

template <class T>
void put_array(ByteWriter& out, const T* values, std::size_t count) {
  out.u64(count);
  out.bytes(std::string_view(reinterpret_cast<const char*>(values), count * sizeof(T)));
}

template <class T>
std::vector<T> take_array(ByteReader& in) {
  const std::uint64_t count = in.u64();
  if (count > in.remaining() / sizeof(T)) in.fail("an array longer than the message");
  std::vector<T> values(count);
  const std::string_view bytes = in.bytes(count * sizeof(T));
  if (count > 0) std::memcpy(values.data(), bytes.data(), bytes.size());
  return values;
}

template <class T>
void put_value(ByteWriter& out, const T& value) {
  out.bytes(std::string_view(reinterpret_cast<const char*>(&value), sizeof(T)));
}

template <class T>
T take_value(ByteReader& in) {
  T value;
  std::memcpy(&value, in.bytes(sizeof(T)).data(), sizeof(T));
  return value;
}

void put_error(ByteWriter& out, const RelativeError& error) {
  put_value(out, error.mean);
  put_value(out, error.functions_averaged);
  put_value(out, error.zero_energy_skipped);
}

RelativeError take_error(ByteReader& in) {
  RelativeError error;
  error.mean = take_value<double>(in);
  error.functions_averaged = take_value<std::int64_t>(in);
  error.zero_energy_skipped = take_value<std::int64_t>(in);
  return error;
}

// A compressed field as container bytes that decode to exactly its values: float32 where they
// are not quantized, unchanged integers where they are. The sections go raw: zstd at the file's
// level compresses a few tens of MB/s, far slower than any link between ranks.
void put_field(ByteWriter& out, const CompressedField& field, const std::string& where) {
  ContainerOptions lossless;
  lossless.weights = ValuePrecision::float32;
  lossless.residual = ValuePrecision::float32;
  lossless.entropy_coding = false;
  const std::string bytes = encode_container(field, lossless, where, nullptr);
  put_array(out, bytes.data(), bytes.size());
}

CompressedField take_field(ByteReader& in, const std::string& where) {
  const std::vector<char> bytes = take_array<char>(in);
  return decode_container(std::string(bytes.begin(), bytes.end()), where);
}

// A field that may be empty (height 0: nothing built into it).
void put_field_if_any(ByteWriter& out, const CompressedField& field, const std::string& where) {
  out.u32(field.height > 0);
  if (field.height > 0) put_field(out, field, where);
}

CompressedField take_field_if_any(ByteReader& in, const std::string& where) {
  return in.u32() != 0 ? take_field(in, where) : CompressedField{};
}

}  // namespace

void move_scratch_rows(Ranks& ranks, const ScratchRows& from,
                       const std::vector<std::uint64_t>& held,
                       const std::vector<std::uint64_t>& wanted, std::size_t block_rows,
                       ScratchRows& to) {
  const std::size_t size = std::size_t(ranks.size()), own = std::size_t(ranks.rank());
  // Round k moves every rank's wanted rows [wanted + k * block_rows, ... + block_rows).
  std::uint64_t rounds = 0;
  for (std::size_t r = 0; r < size; ++r)
    rounds =
        std::max<std::uint64_t>(rounds, (wanted[r + 1] - wanted[r] + block_rows - 1) / block_rows);
  for (std::uint64_t round = 0; round < rounds; ++round) {
    std::vector<std::string> messages(size);
    for (std::size_t r = 0; r < size; ++r) {
      const std::uint64_t begin = std::min(wanted[r] + round * block_rows, wanted[r + 1]);
      const std::uint64_t end = std::min(begin + block_rows, wanted[r + 1]);
      const std::uint64_t first = std::max(begin, held[own]), last = std::min(end, held[own + 1]);
      ByteWriter out;
      if (first < last) {
        const ScratchBlock block =
            from.read_block(std::size_t(first - held[own]), std::size_t(last - first));
        put_array(out, block.halves.data(), block.halves.size());
        put_array(out, block.norms.data(), block.norms.size());
      }
      messages[r] = out.take();
    }
    // Each rank's window comes from consecutive ranks in rank order: stacked, they are in order.
    const std::vector<std::string> received = ranks.exchange(std::move(messages));
    for (std::size_t r = 0; r < size; ++r) {
      if (received[r].empty()) continue;
      ByteReader in(received[r], "the scratch rows of rank " + std::to_string(r));
      ScratchBlock block;
      block.halves = take_array<std::uint16_t>(in);
      block.norms = take_array<float>(in);
      to.append_block(block);
    }
  }
}

std::vector<std::int32_t> move_assignment(Ranks& ranks, const std::vector<std::int32_t>& assignment,
                                          const std::vector<std::uint64_t>& held,
                                          const std::vector<std::uint64_t>& wanted) {
  const std::size_t size = std::size_t(ranks.size()), own = std::size_t(ranks.rank());
  std::vector<std::string> messages(size);
  for (std::size_t r = 0; r < size; ++r) {
    const std::uint64_t first = std::max(wanted[r], held[own]);
    const std::uint64_t last = std::min(wanted[r + 1], held[own + 1]);
    ByteWriter out;
    if (first < last) put_array(out, assignment.data() + (first - held[own]), last - first);
    messages[r] = out.take();
  }
  // This rank's wanted rows come from consecutive ranks in rank order.
  const std::vector<std::string> received = ranks.exchange(std::move(messages));
  std::vector<std::int32_t> moved;
  for (std::size_t r = 0; r < size; ++r) {
    if (received[r].empty()) continue;
    ByteReader in(received[r], "the clusters of rank " + std::to_string(r));
    const std::vector<std::int32_t> part = take_array<std::int32_t>(in);
    moved.insert(moved.end(), part.begin(), part.end());
  }
  if (moved.size() != wanted[own + 1] - wanted[own])
    throw Error("internal: rank " + std::to_string(own) + " got " + std::to_string(moved.size()) +
                " clusters for " + std::to_string(wanted[own + 1] - wanted[own]) + " rows");
  return moved;
}

WorkingRows gather_sample(Ranks& ranks, const WorkingRows& local) {
  if (ranks.size() == 1) return local;
  ByteWriter out;
  out.u32(std::uint32_t(local.lights()));
  put_array(out, local.values.data(), std::size_t(local.values.size()));
  put_array(out, local.norms.data(), local.norms.size());
  const std::vector<std::string> parts = ranks.gather_to_root(out.data());
  WorkingRows sample;
  if (!ranks.root()) return sample;
  std::vector<float> values;
  for (std::size_t r = 0; r < parts.size(); ++r) {
    ByteReader in(parts[r], "the sample of rank " + std::to_string(r));
    const int lights = int(in.u32());
    if (lights != local.lights()) in.fail("another number of lights");
    const std::vector<float> part_values = take_array<float>(in);
    const std::vector<float> part_norms = take_array<float>(in);
    values.insert(values.end(), part_values.begin(), part_values.end());
    sample.norms.insert(sample.norms.end(), part_norms.begin(), part_norms.end());
  }
  sample.values =
      Eigen::Map<RowMatrixF>(values.data(), Eigen::Index(sample.norms.size()), local.lights());
  return sample;
}

void broadcast_bases(Ranks& ranks, ClusterModel& model) {
  if (ranks.size() == 1) return;
  std::string bytes;
  if (ranks.root()) {
    ByteWriter out;
    out.u32(std::uint32_t(model.clusters));
    out.u32(std::uint32_t(model.terms));
    out.u32(std::uint32_t(model.lights));
    put_array(out, model.bases.data(), model.bases.size());
    bytes = out.take();
  }
  ranks.broadcast(bytes);
  if (ranks.root()) return;
  ByteReader in(bytes, "the bases from the root");
  model.clusters = int(in.u32());
  model.terms = int(in.u32());
  model.lights = int(in.u32());
  model.bases = take_array<float>(in);
}

void sum_fits_to_root(Ranks& ranks, std::vector<BasisIrlsFit>& fits) {
  if (ranks.size() == 1 || fits.empty()) return;
  const std::size_t each = fits.front().sums().size();
  std::vector<double> sums(each * fits.size());
  for (std::size_t k = 0; k < fits.size(); ++k)
    std::copy(fits[k].sums().begin(), fits[k].sums().end(),
              sums.begin() + std::ptrdiff_t(k * each));
  ranks.sum_to_root(sums.data(), sums.size());
  if (!ranks.root()) return;
  for (std::size_t k = 0; k < fits.size(); ++k)
    std::copy(sums.begin() + std::ptrdiff_t(k * each),
              sums.begin() + std::ptrdiff_t((k + 1) * each), fits[k].sums().begin());
}

std::vector<BuiltPart> gather_parts(Ranks& ranks, BuiltPart&& local) {
  std::vector<BuiltPart> parts;
  if (ranks.size() == 1) {
    parts.push_back(std::move(local));
    return parts;
  }
  ByteWriter out;
  if (!ranks.root()) {
    put_field_if_any(out, local.field, "cannot send a part");
    put_field_if_any(out, local.sampled, "cannot send a part's sample");
    out.u64(local.residual_nonzeros);
    put_array(out, local.peaks.data(), local.peaks.size());
    put_array(out, local.sparse_counts.data(), local.sparse_counts.size());
    put_value(out, local.objective);
    put_value(out, local.changed);
    put_error(out, local.float32_masked);
    const ReflectanceField& sample = local.original_sample;
    out.u32(std::uint32_t(sample.width));
    out.u32(std::uint32_t(sample.height));
    out.u32(std::uint32_t(sample.channels));
    out.u32(std::uint32_t(sample.lights()));
    put_array(out, sample.values.data(), std::size_t(sample.values.size()));
    put_array(out, sample.mask.data(), sample.mask.size());
    std::vector<std::int32_t> rows;
    for (const auto& [first, count] : local.sample_rows) rows.insert(rows.end(), {first, count});
    put_array(out, rows.data(), rows.size());
  }
  const std::vector<std::string> messages = ranks.gather_to_root(out.data());
  if (!ranks.root()) return parts;
  parts.push_back(std::move(local));
  for (std::size_t r = 1; r < messages.size(); ++r) {
    const std::string where = "the part of rank " + std::to_string(r);
    ByteReader in(messages[r], where);
    BuiltPart part;
    part.field = take_field_if_any(in, where);
    part.sampled = take_field_if_any(in, where);
    part.residual_nonzeros = in.u64();
    part.peaks = take_array<double>(in);
    part.sparse_counts = take_array<double>(in);
    part.objective = take_value<double>(in);
    part.changed = take_value<double>(in);
    part.float32_masked = take_error(in);
    ReflectanceField& sample = part.original_sample;
    sample.width = int(in.u32());
    sample.height = int(in.u32());
    sample.channels = int(in.u32());
    const int lights = int(in.u32());
    const std::vector<float> values = take_array<float>(in);
    sample.values = Eigen::Map<const RowMatrixF>(
        values.data(), Eigen::Index(values.size() / std::size_t(std::max(lights, 1))), lights);
    sample.mask = take_array<std::uint8_t>(in);
    const std::vector<std::int32_t> rows = take_array<std::int32_t>(in);
    for (std::size_t i = 0; i + 1 < rows.size(); i += 2)
      part.sample_rows.emplace_back(rows[i], rows[i + 1]);
    parts.push_back(std::move(part));
  }
  return parts;
}

void gather_strips_to_root(Ranks& ranks, CompressedStripFile& strips) {
  if (ranks.size() == 1) return;
  std::vector<double> counts(std::size_t(ranks.size()), 0.0);
  counts[std::size_t(ranks.rank())] = double(strips.strips());
  ranks.sum_everywhere(counts.data(), counts.size());
  // Rank by rank, strip by strip, so that the root appends them in order.
  for (int r = 1; r < ranks.size(); ++r)
    for (std::size_t s = 0; s < std::size_t(counts[std::size_t(r)]); ++s) {
      std::vector<std::string> to(std::size_t(ranks.size()));
      if (ranks.rank() == r) {
        ByteWriter out;
        put_field(out, strips.read(s), "cannot send a strip to the root");
        to[0] = out.take();
      }
      const std::vector<std::string> received = ranks.exchange(std::move(to));
      if (!ranks.root()) continue;
      const std::string where = "strip " + std::to_string(s) + " of rank " + std::to_string(r);
      ByteReader in(received[std::size_t(r)], where);
      strips.append(take_field(in, where));
    }
}

void broadcast_strip_storage(Ranks& ranks, StripStorage& storage) {
  if (ranks.size() == 1) return;
  std::string bytes;
  if (ranks.root()) {
    ByteWriter out;
    out.u32(storage.quantized);
    put_value(out, storage.steps);
    put_value(out, storage.weights);
    put_value(out, storage.residual);
    const BasisAlignment& alignment = storage.alignment;
    put_array(out, alignment.bases.data(), alignment.bases.size());
    out.u64(alignment.active.size());
    for (std::size_t k = 0; k < alignment.active.size(); ++k) {
      put_array(out, alignment.active[k].data(), alignment.active[k].size());
      const Eigen::MatrixXd& transform = alignment.weight_transform[k];
      out.u64(std::uint64_t(transform.rows()));
      put_array(out, transform.data(), std::size_t(transform.size()));
    }
    bytes = out.take();
  }
  ranks.broadcast(bytes);
  if (ranks.root()) return;
  ByteReader in(bytes, "the stored precision from the root");
  storage.quantized = in.u32() != 0;
  storage.steps = take_value<QuantizationSteps>(in);
  storage.weights = take_value<ValuePrecision>(in);
  storage.residual = take_value<ValuePrecision>(in);
  BasisAlignment& alignment = storage.alignment;
  alignment.bases = take_array<float>(in);
  const std::uint64_t clusters = in.u64();
  if (clusters > in.remaining()) in.fail("more clusters than the message holds");
  alignment.active.resize(clusters);
  alignment.weight_transform.resize(clusters);
  for (std::size_t k = 0; k < clusters; ++k) {
    alignment.active[k] = take_array<int>(in);
    const std::uint64_t rows = in.u64();
    const std::vector<double> values = take_array<double>(in);
    if (rows == 0 ? !values.empty() : values.size() % rows != 0)
      in.fail("a weight transform whose values do not fill its rows");
    alignment.weight_transform[k] = Eigen::Map<const Eigen::MatrixXd>(
        values.data(), Eigen::Index(rows), Eigen::Index(rows == 0 ? 0 : values.size() / rows));
  }
}

CompressedField scatter_bands(Ranks& ranks, const CompressedField& whole,
                              const std::vector<int>& bands) {
  const auto rows_of = [&](int r) {
    const int first = bands.at(std::size_t(r));
    return compressed_rows(whole, first, bands.at(std::size_t(r) + 1) - first);
  };
  if (ranks.size() == 1) return rows_of(0);
  std::vector<std::string> parts;
  if (ranks.root()) {
    for (int r = 0; r < ranks.size(); ++r) {
      ByteWriter out;
      put_field(out, rows_of(r), "cannot send the band of rank " + std::to_string(r));
      parts.push_back(out.take());
    }
  }
  const std::string band = ranks.scatter_from_root(std::move(parts));
  ByteReader in(band, "the band of rank " + std::to_string(ranks.rank()));
  return take_field(in, "the band of rank " + std::to_string(ranks.rank()));
}

FieldErrors gather_errors(Ranks& ranks, FieldErrors local, std::int64_t first_function) {
  if (ranks.size() == 1) return local;
  ByteWriter out;
  if (!ranks.root()) {
    put_value(out, first_function);
    put_error(out, local.all);
    put_error(out, local.masked);
    out.u64(local.masked_by_prefix.size());
    for (const auto& [cap, error] : local.masked_by_prefix) {
      put_value(out, cap);
      put_error(out, error);
    }
    const PerLightError& light = local.per_light;
    put_value(out, light.largest);
    put_value(out, light.function);
    put_value(out, light.light);
    put_value(out, light.mean_of_largest);
    put_array(out, light.functions_above.data(), light.functions_above.size());
    put_value(out, light.functions_measured);
    put_value(out, light.zero_peak_skipped);
    put_value(out, light.negative_values);
    put_value(out, light.values_measured);
    put_value(out, light.most_negative);
    put_value(out, local.psnr);
    put_value(out, local.psnr_pixels);
    put_value(out, local.psnr_mask_pixels);
  }
  const std::vector<std::string> messages = ranks.gather_to_root(out.data());
  if (!ranks.root()) return local;
  // As measure_streamed_errors merges strips: the root's band is the first.
  FieldErrors total;
  merge_field_errors(total, local, first_function);
  for (std::size_t r = 1; r < messages.size(); ++r) {
    ByteReader in(messages[r], "the errors of rank " + std::to_string(r));
    const auto first = take_value<std::int64_t>(in);
    FieldErrors errors;
    errors.all = take_error(in);
    errors.masked = take_error(in);
    const std::uint64_t caps = in.u64();
    if (caps > in.remaining()) in.fail("more residual caps than the message holds");
    for (std::uint64_t i = 0; i < caps; ++i) {
      const int cap = take_value<int>(in);
      errors.masked_by_prefix.emplace_back(cap, take_error(in));
    }
    PerLightError& light = errors.per_light;
    light.largest = take_value<double>(in);
    light.function = take_value<std::int64_t>(in);
    light.light = take_value<int>(in);
    light.mean_of_largest = take_value<double>(in);
    light.functions_above = take_array<double>(in);
    light.functions_measured = take_value<std::int64_t>(in);
    light.zero_peak_skipped = take_value<std::int64_t>(in);
    light.negative_values = take_value<std::int64_t>(in);
    light.values_measured = take_value<std::int64_t>(in);
    light.most_negative = take_value<double>(in);
    errors.psnr = take_value<Psnr8>(in);
    errors.psnr_pixels = take_value<std::int64_t>(in);
    errors.psnr_mask_pixels = take_value<std::int64_t>(in);
    merge_field_errors(total, errors, first);
  }
  return total;
}

}  // namespace relume
