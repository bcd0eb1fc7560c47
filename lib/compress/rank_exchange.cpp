// Implementation of what the ranks of a streamed compression exchange (see rank_exchange.hpp).
// Arrays travel as a count and their raw bytes (the ranks run the same binary on machines of one
// architecture), compressed fields as container bytes (lossless at float32).
#include "compress/rank_exchange.hpp"

#include <cstring>
#include <relume/container.hpp>

#include "container/container.hpp"
#include "container/container_bytes.hpp"

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

}  // namespace

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
    ContainerOptions lossless;
    lossless.weights = ValuePrecision::float32;
    lossless.residual = ValuePrecision::float32;
    const std::string field =
        encode_container(local.field, lossless, "cannot send a part", nullptr);
    put_array(out, field.data(), field.size());
    put_array(out, local.peaks.data(), local.peaks.size());
    put_array(out, local.sparse_counts.data(), local.sparse_counts.size());
    put_array(out, &local.objective, 1);
    put_array(out, &local.changed, 1);
    const double error[3] = {local.float32_masked.mean,
                             double(local.float32_masked.functions_averaged),
                             double(local.float32_masked.zero_energy_skipped)};
    put_array(out, error, 3);
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
    const std::vector<char> field = take_array<char>(in);
    part.field = decode_container(std::string(field.begin(), field.end()), where);
    part.peaks = take_array<double>(in);
    part.sparse_counts = take_array<double>(in);
    part.objective = take_array<double>(in).at(0);
    part.changed = take_array<double>(in).at(0);
    const std::vector<double> error = take_array<double>(in);
    if (error.size() != 3) in.fail("a malformed error");
    part.float32_masked = {error[0], std::int64_t(error[1]), std::int64_t(error[2])};
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

}  // namespace relume
