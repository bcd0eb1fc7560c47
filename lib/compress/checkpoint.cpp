// Implementation of clustering checkpoints (see checkpoint.hpp). Layout: the line
// "relume-checkpoint 1", one line of JSON (fingerprint, sizes, iterations), then the raw
// little-endian arrays: bases (float32), assignment (int32), weights (float32).
#include "compress/checkpoint.hpp"

#include <cstring>
#include <nlohmann/json.hpp>
#include <relume/error.hpp>

#include "core/atomic_file.hpp"

namespace relume {
namespace {

constexpr const char* checkpoint_magic = "relume-checkpoint 1\n";

template <class T>
void append_raw(std::string& bytes, const T* data, std::size_t count) {
  bytes.append(reinterpret_cast<const char*>(data), count * sizeof(T));
}

}  // namespace

void write_checkpoint(const std::filesystem::path& path, const std::string& fingerprint,
                      const ClusterModel& model, const std::vector<IterationRecord>& iterations) {
  nlohmann::json records = nlohmann::json::array();
  for (const IterationRecord& record : iterations)
    records.push_back(
        {record.iteration, record.objective, record.changed, record.clusters, record.seconds});
  const nlohmann::json header = {
      {"fingerprint", fingerprint}, {"clusters", model.clusters},      {"terms", model.terms},
      {"lights", model.lights},     {"rows", model.assignment.size()}, {"iterations", records}};
  std::string bytes = checkpoint_magic + header.dump() + "\n";
  append_raw(bytes, model.bases.data(), model.bases.size());
  append_raw(bytes, model.assignment.data(), model.assignment.size());
  append_raw(bytes, model.weights.data(), std::size_t(model.weights.size()));
  write_file_atomically(path, bytes);
}

ClusteringResume read_checkpoint(const std::filesystem::path& path,
                                 const std::string& fingerprint) {
  const std::string bytes = read_file(path);
  const auto fail = [&](const std::string& what) {
    return Error("checkpoint " + path.string() + ": " + what);
  };
  const std::size_t magic_length = std::strlen(checkpoint_magic);
  if (bytes.compare(0, magic_length, checkpoint_magic) != 0)
    throw fail("not a relume checkpoint (bad first line)");
  const std::size_t line_end = bytes.find('\n', magic_length);
  if (line_end == std::string::npos) throw fail("truncated header");
  nlohmann::json header;
  try {
    header = nlohmann::json::parse(bytes.substr(magic_length, line_end - magic_length));
  } catch (const nlohmann::json::exception& e) {
    throw fail(std::string("damaged header: ") + e.what());
  }
  if (header.value("fingerprint", std::string()) != fingerprint)
    throw fail("it was written for another input or other settings (" +
               header.value("fingerprint", std::string("?")) + "; now " + fingerprint + ")");
  ClusteringResume resume;
  ClusterModel& model = resume.model;
  try {
    model.clusters = header.at("clusters").get<int>();
    model.terms = header.at("terms").get<int>();
    model.lights = header.at("lights").get<int>();
    const std::size_t rows = header.at("rows").get<std::size_t>();
    for (const auto& record : header.at("iterations")) {
      IterationRecord done;
      done.iteration = record.at(0).get<int>();
      done.objective = record.at(1).get<double>();
      done.changed = record.at(2).get<std::size_t>();
      done.clusters = record.at(3).get<int>();
      done.seconds = record.at(4).get<double>();
      resume.iterations.push_back(done);
    }
    const std::size_t basis_values = std::size_t(model.clusters) * model.terms * model.lights;
    const std::size_t expected =
        line_end + 1 + basis_values * 4 + rows * 4 + rows * model.terms * 4;
    if (model.clusters < 1 || model.terms < 1 || model.lights < 1 || bytes.size() != expected)
      throw fail("size " + std::to_string(bytes.size()) + " bytes does not match its header (" +
                 std::to_string(expected) + " expected)");
    const char* data = bytes.data() + line_end + 1;
    model.bases.resize(basis_values);
    std::memcpy(model.bases.data(), data, basis_values * 4);
    data += basis_values * 4;
    model.assignment.resize(rows);
    std::memcpy(model.assignment.data(), data, rows * 4);
    data += rows * 4;
    model.weights.resize(static_cast<Eigen::Index>(rows), model.terms);
    std::memcpy(model.weights.data(), data, rows * model.terms * 4);
  } catch (const nlohmann::json::exception& e) {
    throw fail(std::string("damaged header: ") + e.what());
  }
  for (const std::int32_t k : model.assignment)
    if (k < 0 || k >= model.clusters)
      throw fail("cluster id " + std::to_string(k) + " out of range");
  return resume;
}

}  // namespace relume
