// The patch method's stats as every method reports them (SolveReport): the summary line the
// commands print and the numbers of the stats file's "patch" entry.
#include <fmt/format.h>
#include <radiosity/patch_radiosity.h>

#include <algorithm>
#include <nlohmann/json.hpp>

namespace rad {

namespace {

// How the form factors came: rows cast (and kept from before: the master table, its cache), or
// a whole table read from the cache (the pairwise and exact estimators).
std::string formFactorsOf(const PatchRadiosityStats& p) {
  const char* kept = p.cacheLoaded ? "from the cache" : "kept";
  if (p.rowsComputed == 0 && p.rowsReused > 0)
    return fmt::format("loaded in {:.2f} s, {} rows {}", p.formFactorSeconds, p.rowsReused, kept);
  if (p.cacheLoaded && p.rowsComputed == 0)
    return fmt::format("loaded in {:.2f} s", p.cacheLoadSeconds);
  const double rays = double(p.rays - p.lightRays);
  std::string text = fmt::format("{:.2f} s, {:.1f} M rays/s", p.formFactorSeconds,
                                 rays / std::max(p.formFactorSeconds, 1e-9) * 1e-6);
  if (p.rowsReused > 0)
    text += fmt::format(", {} rows cast, {} {}", p.rowsComputed, p.rowsReused, kept);
  return text;
}

nlohmann::json detailsOf(const PatchRadiosityStats& p) {
  return {{"patch_size", p.patchSize},
          {"nodes", p.nodes},
          {"vertices", p.vertices},
          {"table_entries", p.nonZeros},
          {"exact_columns", p.exactColumns},
          {"table_bytes", p.tableBytes},
          {"dropped_entry_fraction", p.droppedEntryFraction},
          {"dropped_sum_fraction", p.droppedSumFraction},
          {"dropped_worst_row_fraction", p.droppedWorstRowFraction},
          {"rows_dropping_over_1_percent", p.rowsDroppingOverOnePercent},
          {"row_sum",
           {{"min", p.rowSumMin},
            {"mean", p.rowSumMean},
            {"max", p.rowSumMax},
            {"estimated_max", p.rowSumEstimatedMax},
            {"rows_scaled", p.rowsScaledToClosure},
            {"reflected_share_max", p.reflectedShareMax},
            {"scaled_for_reflection", p.scaledForReflection}}},
          {"cache_loaded", p.cacheLoaded},
          {"cache_file", p.cacheFile},
          {"solver", p.solver},
          {"diverging", p.diverging},
          {"shots", p.shots},
          {"rays_per_s", double(p.rays - p.lightRays) / std::max(p.formFactorSeconds, 1e-9)},
          {"light_rays", p.lightRays},
          {"rows_computed", p.rowsComputed},
          {"rows_reused", p.rowsReused},
          {"master_rows", p.masterRows},
          {"base_patches", p.basePatches},
          {"refined_splits", p.refinedSplits},
          {"refine_rounds", p.refineRounds},
          {"light_rays_per_s", double(p.lightRays) / std::max(p.lightSeconds, 1e-9)},
          {"memory_bytes", p.memoryBytes},
          {"seconds",
           {{"mesh", p.meshSeconds},
            {"form_factors", p.formFactorSeconds},
            {"cache_load", p.cacheLoadSeconds},
            {"light", p.lightSeconds},
            {"solve", p.solveSeconds}}}};
}

}  // namespace

SolveReport PatchRadiosity::report() const {
  const PatchRadiosityStats& p = stats();
  SolveReport r;
  const double residual = p.residuals.empty() ? 0.0 : p.residuals.back();
  r.summary = fmt::format(
      "{} patches, form factors {} ({} entries, {:.1f} MB, rows sum to {:.3f} on average), {} {} "
      "sweeps, residual {:.2g}{}",
      p.patches, formFactorsOf(p), p.nonZeros, double(p.tableBytes) / 1e6, p.rowSumMean,
      p.iterations, p.solver, residual,
      p.converged   ? ""
      : p.diverging ? " (diverging)"
                    : " (not converged)");
  r.patches = p.patches;
  r.detailEdge = 0.5f * p.patchSize;  // a patch interpolates between its vertices
  r.rays = p.rays;
  r.prepareSeconds = p.meshSeconds + p.formFactorSeconds + p.cacheLoadSeconds;
  r.solveSeconds = p.lightSeconds + p.solveSeconds;
  r.iterations = p.iterations;
  r.residuals = p.residuals;
  r.converged = p.converged;
  r.warnings = p.warnings;
  r.detailsJson = detailsOf(p).dump();
  return r;
}

}  // namespace rad
