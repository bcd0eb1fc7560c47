// Implementation of the rate targets (see rate_control.hpp).
#include "compress/rate_control.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <relume/error.hpp>
#include <string>
#include <utility>

#include "compress/clustered_factorization.hpp"
#include "compress/global_basis.hpp"
#include "compress/global_basis_rate.hpp"
#include "compress/noise_model.hpp"
#include "core/memory_budget.hpp"
#include "core/text_numbers.hpp"
#include "model/field_psnr.hpp"

namespace relume {
namespace {

struct RatePoint {
  std::size_t entries = 0;  // residual entries kept, the best first
  std::uint64_t bytes = 0;
  double error = 0;  // Eq. 16 over the masked functions
  double psnr = 0;   // 8-bit, inside the region
};

nlohmann::ordered_json to_json(const RatePoint& point) {
  return {{"residual_entries", point.entries},
          {"bytes", point.bytes},
          {"error_masked", point.error},
          {"psnr_8bit", point.psnr}};
}

// `field` keeping, of each residual row, the prefix of entries whose gain is at least `cut`.
CompressedField with_entries_gaining(const CompressedField& field, const std::vector<float>& gains,
                                     float cut) {
  CompressedField kept = field;
  keep_entries_with_gain(kept.residual, gains, cut);
  return kept;
}

// One candidate's residual cut to any number of its best entries, measured as stored.
class RateCurve {
 public:
  RateCurve(const ReflectanceField& original, const CompressedField& stored,
            const std::vector<double>& row_weight, const ContainerOptions& container,
            const RateTarget& target, unsigned threads)
      : original_(original),
        stored_(stored),
        gains_(residual_gains(stored.residual, row_weight)),
        container_(container),
        target_(target),
        threads_(threads) {
    sorted_ = gains_;
    std::sort(sorted_.begin(), sorted_.end(), std::greater<float>());
  }

  std::size_t entries() const { return sorted_.size(); }

  CompressedField at(std::size_t entries) const {
    return with_entries_gaining(
        stored_, gains_, entries == 0 ? HUGE_VALF : sorted_[std::min(entries, sorted_.size()) - 1]);
  }

  // Each count is encoded and reconstructed once: the bisections ask for their ends again.
  RatePoint measure(std::size_t entries) {
    if (const auto known = measured_.find(entries); known != measured_.end()) return known->second;
    const CompressedField field = at(entries);
    RatePoint point;
    point.entries = field.residual.nonzeros();
    const StoredMeasure stored = measure_stored(original_, field, target_, container_, threads_);
    point.bytes = stored.bytes;
    point.error = stored.error;
    point.psnr = stored.psnr;
    points_.push_back(point);
    measured_.emplace(entries, point);
    return point;
  }

  const std::vector<RatePoint>& points() const { return points_; }

 private:
  const ReflectanceField& original_;
  const CompressedField& stored_;
  std::vector<float> gains_, sorted_;
  const ContainerOptions& container_;
  const RateTarget& target_;
  unsigned threads_;
  std::vector<RatePoint> points_;
  std::map<std::size_t, RatePoint> measured_;  // by the count asked for
};

// Given !good(lo) and good(hi) for a monotone good(n): the last n known not good and the first
// known good, within 0.1% of hi of each other.
std::pair<std::size_t, std::size_t> bisect(std::size_t lo, std::size_t hi,
                                           const std::function<bool(std::size_t)>& good) {
  const std::size_t tolerance = std::max<std::size_t>(1, hi / 1000);
  while (hi - lo > tolerance) {
    const std::size_t mid = lo + (hi - lo) / 2;
    (good(mid) ? hi : lo) = mid;
  }
  return {lo, hi};
}

struct CurveChoice {
  RatePoint point;
  bool met = false;
};

// The most entries whose container fits `bytes`. A point that fits keeps fewer entries than all
// of them and so has at most their PSNR: when that does not beat `to_beat` (the best choice's),
// no bisection is made and the curve's fewest-bytes point is the choice.
CurveChoice fit_bytes(RateCurve& curve, std::uint64_t bytes, double to_beat) {
  const RatePoint none = curve.measure(0);
  if (none.bytes > bytes) return {none, false};
  const RatePoint all = curve.measure(curve.entries());
  if (all.bytes <= bytes) return {all, true};
  if (all.psnr <= to_beat) return {none, true};
  const std::size_t fits = bisect(0, curve.entries(), [&](std::size_t n) {
                             return curve.measure(n).bytes > bytes;
                           }).first;
  const RatePoint point = curve.measure(fits);
  return {point, point.bytes <= bytes};
}

// The fewest entries whose PSNR reaches `psnr`. A point that reaches it keeps at least the curve's
// fewest-bytes point's bytes: when they are not below `to_beat` (the best choice's), no
// bisection is made.
CurveChoice reach_psnr(RateCurve& curve, double psnr, std::uint64_t to_beat) {
  const RatePoint none = curve.measure(0);
  if (none.psnr >= psnr) return {none, true};
  if (none.bytes >= to_beat) return {none, false};
  const RatePoint all = curve.measure(curve.entries());
  if (all.psnr < psnr) return {all, false};
  const std::size_t enough = bisect(0, curve.entries(), [&](std::size_t n) {
                               return curve.measure(n).psnr >= psnr;
                             }).second;
  const RatePoint point = curve.measure(enough);
  return {point, point.psnr >= psnr};
}

std::string region_text(const std::vector<std::uint8_t>& region) {
  if (region.empty()) return "the field's mask";
  const auto inside = std::count_if(region.begin(), region.end(), [](std::uint8_t v) { return v; });
  if (std::size_t(inside) == region.size()) return "the whole frame";
  return "the given mask (" + std::to_string(inside) + " pixels)";
}

// Whether `a` is a better choice than `b` for the target.
bool better(const CurveChoice& a, const CurveChoice& b, const RateTarget& target) {
  if (a.met != b.met) return a.met;
  if (target.bytes > 0) return a.met ? a.point.psnr > b.point.psnr : a.point.bytes < b.point.bytes;
  return a.met ? a.point.bytes < b.point.bytes : a.point.psnr > b.point.psnr;
}

nlohmann::ordered_json to_json(const PlanesRatePoint& point) {
  return {{"plane_bytes", point.plane_bytes},
          {"bytes", point.bytes},
          {"error_masked", point.error},
          {"psnr_8bit", point.psnr}};
}

// The weight of each stored row's residual entries in the ranking: 1 inside the target's region
// (everywhere without one), 0 outside.
std::vector<double> region_row_weights(const CompressedField& stored,
                                       const std::vector<std::uint8_t>& region) {
  std::vector<double> row_weight(stored.stored_rows(), 1.0);
  if (!region.empty())
    for (std::size_t r = 0; r < row_weight.size(); ++r) {
      const std::uint64_t pixel = stored.stored_function[r] / std::uint64_t(stored.channels);
      row_weight[r] = region[pixel] ? 1.0 : 0.0;
    }
  return row_weight;
}

// The fewest bytes a residual entry has cost in any container stored so far: over each curve, the
// bytes its entries added per entry (its most and fewest entries measured), halved as a margin
// for pairs whose residual codes more tightly; 0 before any curve measured two counts.
class EntryCost {
 public:
  void add(const std::vector<RatePoint>& points) {
    const auto [fewest, most] = std::minmax_element(
        points.begin(), points.end(),
        [](const RatePoint& a, const RatePoint& b) { return a.entries < b.entries; });
    if (fewest == points.end() || most->entries <= fewest->entries) return;
    const double per_entry =
        (double(most->bytes) - double(fewest->bytes)) / double(most->entries - fewest->entries);
    if (per_entry > 0 && (least_ == 0 || per_entry < least_)) least_ = per_entry;
  }
  // At most how many entries a container of `bytes` holds (all of them while nothing is known).
  std::size_t most_entries(std::uint64_t bytes) const {
    if (least_ == 0) return std::numeric_limits<std::size_t>::max();
    return std::size_t(double(bytes) / (0.5 * least_));
  }

 private:
  double least_ = 0;
};

// For a byte target: whether a factored pair reaches at most `best_psnr` as it is (float) with the
// `most_entries` residual entries that gain the most inside the region (its whole residual when
// it has no more), the most any way of storing it in the target's bytes reaches; if so, `tried`
// and stderr say it.
bool float_model_cannot_win(const ReflectanceField& field, const GridCandidate& grid,
                            const RateTarget& target, double best_psnr, std::size_t most_entries,
                            unsigned threads, bool quiet, nlohmann::ordered_json& tried) {
  const CompressedField* model = &grid.full;
  CompressedField capped;
  const std::size_t entries = grid.full.residual.nonzeros();
  if (most_entries < entries) {
    const std::vector<float> gains =
        residual_gains(grid.full.residual, region_row_weights(grid.full, target.region));
    std::vector<float> ranked = gains;
    std::nth_element(ranked.begin(), ranked.begin() + std::ptrdiff_t(most_entries), ranked.end(),
                     std::greater<float>());
    // Entries gaining exactly the cut's gain are all kept: never fewer than most_entries + 1.
    capped = with_entries_gaining(grid.full, gains, ranked[most_entries]);
    model = &capped;
  }
  const double ceiling =
      psnr_8bit(field, *model, target.psnr_white, all_residual_entries, threads, target.region)
          .masked;
  if (ceiling > best_psnr) return false;
  const bool whole = model == &grid.full;
  const std::string residual_used = whole
                                        ? "its whole residual"
                                        : std::to_string(model->residual.nonzeros()) + " of its " +
                                              std::to_string(entries) + " residual entries";
  tried.push_back({{"model", "clustered"},
                   {"terms", grid.options.clustering.terms},
                   {"clusters", grid.full.clusters},
                   {"met", false},
                   {"ceiling_psnr_8bit", ceiling},
                   {"ceiling_residual_entries", model->residual.nonzeros()},
                   {"not_stored", whole ? "its full residual in float does not beat the best"
                                        : "in float, with the most residual entries the "
                                          "target's bytes can hold, it does not beat the best"}});
  if (!quiet)
    std::fprintf(stderr,
                 "compress: rate target: %d terms, %d clusters: at most %.2f dB with %s in "
                 "float, not stored\n",
                 grid.options.clustering.terms, grid.full.clusters, ceiling, residual_used.c_str());
  return true;
}

// The one-basis model fitted to the target at basis sizes chosen by hill climbing: from the
// middle of global_basis_sizes, to the neighbouring size that does better until none does (the
// PSNR at given bytes rises with the size until the weights' bytes outweigh it), larger sizes
// tried first. A byte target compares the sizes at their first container that fits (one
// codestream each, BytesFit::first_fit) and brings only the size chosen within 1.5% of the
// bytes. Every size's basis is stored for the noise `noise_sigma` (global_basis_field).
// Each fit is offered to `offer` with its options; sizes whose weight planes would not fit in
// memory are not tried. `stats`: what the model's parameters record.
void try_global_basis(
    const ReflectanceField& field, const CompressionOptions& options, const CompressionStats& stats,
    const std::vector<float>& noise_sigma, const RateTarget& target,
    const ContainerOptions& container, nlohmann::ordered_json& tried,
    const std::function<void(GlobalBasisFit&, const CompressionOptions&)>& offer) {
  const unsigned threads = options.clustering.threads;
  std::vector<int> sizes = global_basis_sizes(field.lights());
  // The planes, their integers, OpenJPEG's copy and the decoded floats: about 16 bytes a sample.
  const std::uint64_t per_term = 16 * std::uint64_t(field.channels) * std::uint64_t(field.pixels());
  const std::uint64_t budget = memory_budget().bytes;
  while (!sizes.empty() && per_term * std::uint64_t(sizes.back()) > budget) sizes.pop_back();
  if (sizes.empty()) return;
  const Eigen::MatrixXd directions = global_basis_directions(field, sizes.back());
  struct SizeFit {
    CurveChoice choice;
    PlanesFitStart learned;
    bool settled = true;
    std::size_t tried_entry = 0;  // its entry in `tried`
  };
  std::map<std::size_t, SizeFit> done;  // by index into sizes
  PlanesFitStart start;
  const auto fit_size = [&](std::size_t index, BytesFit how_close) -> const SizeFit& {
    const int terms = sizes[index];
    CompressionOptions sized = options;
    sized.clustering.terms = terms;
    ContainerOptions planned = container;
    if (target.parameters_json) planned.parameters_json = target.parameters_json(sized, stats);
    const auto note_point = [&](const PlanesRatePoint& point) {
      if (!options.clustering.quiet)
        std::fprintf(stderr,
                     "compress: rate target: one basis of %d terms: weights in %llu bytes -> "
                     "%llu bytes, %.2f dB\n",
                     terms, static_cast<unsigned long long>(point.plane_bytes),
                     static_cast<unsigned long long>(point.bytes), point.psnr);
    };
    const auto earlier = done.find(index);
    GlobalBasisFit fit = fit_global_basis(
        field, directions, terms, noise_sigma, target, planned, threads,
        earlier != done.end() ? earlier->second.learned : start, note_point, how_close);
    start = fit.learned;
    nlohmann::ordered_json points = nlohmann::ordered_json::array();
    if (earlier != done.end()) points = tried[earlier->second.tried_entry]["points"];
    for (const PlanesRatePoint& point : fit.points) points.push_back(to_json(point));
    nlohmann::ordered_json entry = {
        {"model", "global_basis"},      {"terms", terms},  {"clusters", 1}, {"met", fit.met},
        {"choice", to_json(fit.point)}, {"points", points}};
    std::size_t tried_entry = tried.size();
    if (earlier != done.end())
      tried[tried_entry = earlier->second.tried_entry] = std::move(entry);
    else
      tried.push_back(std::move(entry));
    if (!options.clustering.quiet)
      std::fprintf(stderr,
                   "compress: rate target: one basis of %d terms, weights as JPEG 2000 planes -> "
                   "%llu bytes, %.2f dB, error %.5f%s\n",
                   terms, static_cast<unsigned long long>(fit.point.bytes), fit.point.psnr,
                   fit.point.error, fit.met ? "" : " (target not met)");
    const SizeFit size_fit{{{0, fit.point.bytes, fit.point.error, fit.point.psnr}, fit.met},
                           fit.learned,
                           fit.settled,
                           tried_entry};
    offer(fit, sized);
    return done.insert_or_assign(index, size_fit).first->second;
  };
  const auto evaluate = [&](std::size_t index) -> const CurveChoice& {
    if (const auto found = done.find(index); found != done.end()) return found->second.choice;
    return fit_size(index, BytesFit::first_fit).choice;
  };
  // A byte target's gain in PSNR from `at` to the next size up, predicted when `at` and the two
  // sizes below it met the target (next_size_gain).
  const auto predicted_gain = [&](std::size_t at) -> std::optional<double> {
    if (target.bytes == 0 || at < 2 || at + 1 >= sizes.size()) return std::nullopt;
    std::array<int, 3> terms;
    std::array<double, 3> psnr;
    for (std::size_t i = 0; i < 3; ++i) {
      const auto found = done.find(at - 2 + i);
      if (found == done.end() || !found->second.choice.met) return std::nullopt;
      terms[i] = sizes[at - 2 + i];
      psnr[i] = found->second.choice.point.psnr;
    }
    return next_size_gain(terms, psnr, sizes[at + 1]);
  };
  std::size_t at = sizes.size() / 2;
  evaluate(at);  // also the only size of a field of 4 lights or fewer
  // Upward first, while each step pays (or is predicted to); downward only when the first step up
  // did not pay: the curve has one peak, so once a larger size did better no smaller one can win.
  for (const bool up : {true, false}) {
    bool moved = false;
    for (;;) {
      const std::size_t neighbour = up ? at + 1 : at - 1;  // at - 1 wraps below 0
      if (neighbour >= sizes.size()) break;
      if (const std::optional<double> gain = up ? predicted_gain(at) : std::nullopt;
          gain && *gain <= 0) {
        const std::string why =
            "predicted to lose " + number_text(std::round(-*gain * 100) / 100) + " dB against " +
            std::to_string(sizes[at]) + " terms (a parabola through the PSNRs of " +
            std::to_string(sizes[at - 2]) + ", " + std::to_string(sizes[at - 1]) + " and " +
            std::to_string(sizes[at]) + " terms against the size's logarithm)";
        tried.push_back({{"model", "global_basis"},
                         {"terms", sizes[neighbour]},
                         {"clusters", 1},
                         {"met", false},
                         {"predicted_gain_db", *gain},
                         {"not_stored", why}});
        if (!options.clustering.quiet)
          std::fprintf(stderr, "compress: rate target: one basis of %d terms: not fitted, %s\n",
                       sizes[neighbour], why.c_str());
        break;
      }
      if (!better(evaluate(neighbour), done.at(at).choice, target)) break;
      at = neighbour;
      moved = true;
    }
    if (moved) break;
  }
  if (!done.at(at).settled) fit_size(at, BytesFit::close);
}

}  // namespace

StoredMeasure measure_stored(const ReflectanceField& original, const CompressedField& field,
                             const RateTarget& target, const ContainerOptions& container,
                             unsigned threads) {
  StoredMeasure measure;
  measure.bytes = plan_container(field, container).file_bytes;
  const PsnrAndError measured = psnr_8bit_and_error(original, field, target.psnr_white,
                                                    all_residual_entries, threads, target.region);
  measure.error = measured.error.mean;
  measure.psnr = measured.psnr.masked;
  return measure;
}

namespace {

// A byte target's one basis, chosen: its basis refitted to its coded weights, for more PSNR in
// the same bytes (refit_fitted_basis), `choice` and the size's entry of `tried` updated. Measured
// once, for the size the climb chose (each size refitted would cost a measure more per size for a
// few hundredths of a dB between sizes). A PSNR target's search is over bytes, which the refit
// does not lower: it would only lift the PSNR past the target's 0.1 dB, so it is not refitted.
void refit_chosen_basis(const ReflectanceField& field, const RateTarget& target,
                        const ContainerOptions& container, unsigned threads, bool quiet,
                        const CompressionStats& stats, TargetSearch& best, CurveChoice& choice,
                        nlohmann::ordered_json& tried) {
  ContainerOptions planned = container;
  if (target.parameters_json) planned.parameters_json = target.parameters_json(best.options, stats);
  const int terms = best.options.clustering.terms;
  PlanesRatePoint point{best.field.coded_weights.codestream.size(), choice.point.bytes,
                        choice.point.error, choice.point.psnr};
  const bool refit =
      refit_fitted_basis(field, best.field, point, choice.met, target, planned, threads);
  for (auto& entry : tried)
    if (entry["model"] == "global_basis" && entry["terms"] == terms)
      entry["basis_refit"] = refit ? to_json(point) : nlohmann::ordered_json();
  if (refit) {
    choice.point = {0, point.bytes, point.error, point.psnr};
    choice.met = point.bytes <= target.bytes;
  }
  if (quiet) return;
  if (refit)
    std::fprintf(stderr,
                 "compress: rate target: one basis of %d terms, its basis refitted to the coded "
                 "weights -> %llu bytes, %.2f dB\n",
                 terms, static_cast<unsigned long long>(point.bytes), point.psnr);
  else
    std::fprintf(stderr,
                 "compress: rate target: one basis of %d terms, its basis refitted to the coded "
                 "weights: not kept (no better within the target)\n",
                 terms);
}

}  // namespace

TargetSearch compress_to_rate_target(const ReflectanceField& field,
                                     const CompressionOptions& options, const RateTarget& target,
                                     const ContainerOptions& container,
                                     const QuantizationBudget* quantization,
                                     CompressionStats& stats) {
  if ((target.bytes > 0) == (target.psnr > 0))
    throw Error("a rate target is a byte count or a PSNR, exactly one of them");
  if (target.psnr > 0 && !std::isfinite(target.psnr))
    throw Error("the target PSNR must be a finite number of dB, got " +
                std::to_string(target.psnr));
  if (!target.region.empty() && target.region.size() != std::size_t(field.pixels()))
    throw Error("the PSNR region has " + std::to_string(target.region.size()) +
                " pixels, the field " + std::to_string(field.pixels()));
  const unsigned threads = options.clustering.threads;
  TargetSearch best;
  std::optional<CurveChoice> best_choice;
  StoredAs best_stored_as;
  nlohmann::ordered_json tried = nlohmann::ordered_json::array();
  std::vector<StoredAs> ways =
      quantization ? target.stored_as : std::vector<StoredAs>{StoredAs{}};  // float: unused
  if (ways.empty()) throw Error("a rate target needs at least one way to store");
  // The coarsest ways first: a way at least as fine in both budgets as one whose smallest
  // container was too large stores more bytes and is not tried.
  std::stable_sort(ways.begin(), ways.end(), [](const StoredAs& a, const StoredAs& b) {
    return a.term_budget != b.term_budget ? a.term_budget > b.term_budget
                                          : a.quantization_budget > b.quantization_budget;
  });
  if (!target.clustered && !target.one_basis) throw Error("a rate target needs a model to weigh");
  // The one-basis model first: what it reaches tells the grid which pairs cannot win.
  CompressionOptions global_options = options;
  global_options.clustering.clusters = 1;
  CompressionStats global_stats;
  global_stats.functions = field.functions();
  global_stats.clusters_asked = global_stats.clusters = 1;
  global_stats.one_basis = true;
  // One noise model for both models: the clustered rows' dark pixels and the one basis's steps
  // (none known where the user gave a noise floor).
  const NoiseModel noise = noise_model_for(field, options);
  if (target.one_basis)
    try_global_basis(
        field, global_options, global_stats, noise.sigma, target, container, tried,
        [&](GlobalBasisFit& fit, const CompressionOptions& sized) {
          const CurveChoice choice{{0, fit.point.bytes, fit.point.error, fit.point.psnr}, fit.met};
          if (best_choice && !better(choice, *best_choice, target)) return;
          best_choice = choice;
          best.field = std::move(fit.field);
          best.quantization.reset();
          best.options = sized;
          best_stored_as = StoredAs{};
          stats = global_stats;
          stats.stored_rows = best.field.stored_rows();
        });
  if (best_choice && target.bytes > 0)
    refit_chosen_basis(field, target, container, threads, options.clustering.quiet, stats, best,
                       *best_choice, tried);
  // A pair of the grid cannot win with at least the terms and clusters of a pair whose smallest
  // container was already larger than the target's bytes, or than the fewest bytes that reached
  // the target PSNR: more terms or clusters only add bytes. For a byte target, no pair can win
  // once the error of what no pair stores row by row (the dark pixels, the same for every pair)
  // leaves less PSNR than the best choice's. Such pairs are not factored.
  std::vector<std::pair<int, int>> too_large;
  std::optional<double> unstored_ceiling;  // the PSNR with every stored row exact
  bool none_can_win = false;
  nlohmann::ordered_json skipped = nlohmann::ordered_json::array();
  std::size_t skipped_as_larger = 0;
  EntryCost entry_cost;
  // The rows every pair is factored from, prepared once.
  std::optional<PreparedField> prepared;
  if (target.clustered) prepared = prepare_field(field, options, noise);
  // For a byte target whose best choice met it: whether the PSNR with every stored row exact (the
  // dark pixels' error, what no pair's model changes) is no more than the best choice's.
  const auto update_none_can_win = [&] {
    if (target.bytes == 0 || !best_choice || !best_choice->met) return;
    if (!unstored_ceiling)
      unstored_ceiling =
          psnr_8bit_of_unstored(field, zero_model_field(field, *prepared, options.transform),
                                target.psnr_white, threads, target.region)
              .masked;
    none_can_win = *unstored_ceiling <= best_choice->point.psnr;
  };
  if (target.clustered) update_none_can_win();
  const auto cannot_win = [&](int terms, int clusters) {
    const bool dominated =
        std::any_of(too_large.begin(), too_large.end(), [&](const std::pair<int, int>& pair) {
          return terms >= pair.first && clusters >= pair.second;
        });
    if (none_can_win || dominated)
      skipped.push_back({{"terms", terms},
                         {"clusters", clusters},
                         {"why", none_can_win ? "the dark pixels' error alone leaves less PSNR "
                                                "than the best choice"
                                              : "a smaller pair's smallest container was "
                                                "already too large"}});
    skipped_as_larger += !none_can_win && dominated;
    return none_can_win || dominated;
  };
  if (target.clustered)
    for_each_grid_candidate(
        field, options,
        [&](GridCandidate& grid) {
          // For a byte target, a pair that cannot beat the best choice as factored is not
          // stored and measured in its ways.
          update_none_can_win();
          if (target.bytes > 0 && best_choice && best_choice->met) {
            if (float_model_cannot_win(field, grid, target, best_choice->point.psnr,
                                       entry_cost.most_entries(target.bytes), threads,
                                       options.clustering.quiet, tried))
              return;
          }
          const auto affordable = [&] {
            return target.bytes > 0                  ? target.bytes
                   : best_choice && best_choice->met ? best_choice->point.bytes
                                                     : std::numeric_limits<std::uint64_t>::max();
          };
          std::uint64_t smallest = std::numeric_limits<std::uint64_t>::max();
          std::vector<StoredAs> too_large_ways;
          std::size_t finer_ways_skipped = 0;
          for (const StoredAs& way : ways) {
            if (std::any_of(too_large_ways.begin(), too_large_ways.end(), [&](const StoredAs& w) {
                  return way.term_budget <= w.term_budget &&
                         way.quantization_budget <= w.quantization_budget;
                })) {
              tried.push_back({{"model", "clustered"},
                               {"terms", grid.options.clustering.terms},
                               {"clusters", grid.full.clusters},
                               {"term_budget", way.term_budget},
                               {"quantization_budget", way.quantization_budget},
                               {"met", false},
                               {"not_stored",
                                "a coarser way's smallest container was already "
                                "too large"}});
              ++finer_ways_skipped;
              continue;
            }
            CompressedField stored = grid.full;
            std::optional<QuantizationChoice> quantized;
            if (quantization) {
              QuantizationBudget budget = *quantization;
              budget.term_increase = way.term_budget;
              budget.relative_increase = way.quantization_budget;
              quantized = quantize_with_budget(field, stored, budget);
            }
            const std::vector<double> row_weight = region_row_weights(stored, target.region);
            ContainerOptions planned = container;
            if (target.parameters_json)
              planned.parameters_json = target.parameters_json(grid.options, grid.stats);
            RateCurve curve(field, stored, row_weight, planned, target, threads);
            const bool met = best_choice && best_choice->met;
            const CurveChoice choice =
                target.bytes > 0
                    ? fit_bytes(curve, target.bytes,
                                met ? best_choice->point.psnr
                                    : -std::numeric_limits<double>::infinity())
                    : reach_psnr(curve, target.psnr,
                                 met ? best_choice->point.bytes
                                     : std::numeric_limits<std::uint64_t>::max());
            const std::uint64_t no_residual = curve.points().front().bytes;
            smallest = std::min(smallest, no_residual);
            entry_cost.add(curve.points());
            nlohmann::ordered_json points = nlohmann::ordered_json::array();
            for (const RatePoint& point : curve.points()) points.push_back(to_json(point));
            tried.push_back({{"model", "clustered"},
                             {"terms", grid.options.clustering.terms},
                             {"clusters", stored.clusters},
                             {"term_budget", way.term_budget},
                             {"quantization_budget", way.quantization_budget},
                             {"met", choice.met},
                             {"choice", to_json(choice.point)},
                             {"points", points}});
            if (!options.clustering.quiet)
              std::fprintf(stderr,
                           "compress: rate target: %d terms, %d clusters, term budget %g, "
                           "quantization budget "
                           "%g -> %llu bytes, %.2f dB, error %.5f%s\n",
                           grid.options.clustering.terms, stored.clusters, way.term_budget,
                           way.quantization_budget,
                           static_cast<unsigned long long>(choice.point.bytes), choice.point.psnr,
                           choice.point.error, choice.met ? "" : " (target not met)");
            if (!best_choice || better(choice, *best_choice, target)) {
              best_choice = choice;
              best.field = curve.at(choice.point.entries);
              best.quantization = quantized;
              best.options = grid.options;
              best_stored_as = way;
              stats = grid.stats;
              stats.residual_nonzeros = best.field.residual.nonzeros();
            }
            if (no_residual > affordable()) too_large_ways.push_back(way);
          }
          if (!options.clustering.quiet && finer_ways_skipped > 0)
            std::fprintf(stderr,
                         "compress: rate target: %d terms, %d clusters: %zu finer ways not "
                         "stored, a coarser way's smallest container was already too large\n",
                         grid.options.clustering.terms, grid.full.clusters, finer_ways_skipped);
          if (smallest > affordable())
            too_large.emplace_back(grid.options.clustering.terms, grid.options.clustering.clusters);
        },
        cannot_win, prepared ? &*prepared : nullptr);
  prepared.reset();
  if (!options.clustering.quiet && skipped_as_larger > 0)
    std::fprintf(stderr,
                 "compress: rate target: %zu larger (terms, clusters) pairs not factored: a "
                 "smaller pair's smallest container was already too large\n",
                 skipped_as_larger);
  if (!options.clustering.quiet && none_can_win)
    std::fprintf(stderr,
                 "compress: rate target: the dark pixels' error alone leaves at most %.2f dB, "
                 "%zu (terms, clusters) pairs not factored\n",
                 *unstored_ceiling, skipped.size() - skipped_as_larger);
  nlohmann::ordered_json goal;
  if (target.bytes > 0)
    goal = {{"bytes", target.bytes},
            {"best_psnr_over", region_text(target.region)},
            {"white", target.psnr_white}};
  else
    goal = {{"psnr_8bit", target.psnr},
            {"white", target.psnr_white},
            {"region", region_text(target.region)}};
  best.explanation = {
      {"target", goal},
      {"method",
       target.bytes > 0
           ? "one basis for all functions, its weight planes coded as JPEG 2000 in the bytes "
             "left, at basis sizes found by hill climbing; then each (terms, clusters) pair "
             "factored once with its full residual (not the pairs at least as large as one whose "
             "smallest container did not fit, nor any once the dark pixels' error alone leaves "
             "less PSNR than the best so far) and, unless that in float does not beat the best "
             "so far with its whole residual or with the most entries the target's bytes hold "
             "(at half the fewest bytes an entry cost in the containers stored so far), stored "
             "in each way tried (term and quantization budgets, the coarsest first, not the ways "
             "at least as fine as one whose smallest container did not fit), the residual "
             "entries inside the region ranked by e^2 and the most kept whose container fits "
             "(bisection, not made when even the full "
             "residual's PSNR does not beat the best so far); of all that fit, the highest "
             "8-bit PSNR over the region wins"
           : "one basis for all functions, its weight planes coded as JPEG 2000 in the fewest "
             "bytes that reach the target (regula falsi on the bytes), at basis sizes found by "
             "hill climbing; then each (terms, clusters) pair factored once with its full "
             "residual (not the pairs at least as large as one whose smallest container was "
             "larger than the best that reached it) and stored in each way tried (term and "
             "quantization budgets, the coarsest first, not the ways at least as fine as one "
             "whose smallest container was larger than the best that reached it), the residual "
             "entries inside the region ranked by e^2 and the fewest kept whose 8-bit PSNR reaches "
             "the target (bisection, not made when "
             "even no residual is as large as the best so far); of all that reach it, the "
             "smallest container wins"},
      {"met", best_choice && best_choice->met},
      {"tried", tried},
      {"not_factored", skipped},
      {"chosen",
       {{"terms", best.options.clustering.terms},
        {"clusters", best.field.clusters},
        {"term_budget", best_stored_as.term_budget},
        {"quantization_budget", best_stored_as.quantization_budget},
        {"point", best_choice ? to_json(best_choice->point) : nlohmann::ordered_json()}}}};
  return best;
}

}  // namespace relume
