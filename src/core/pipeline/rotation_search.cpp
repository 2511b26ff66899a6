/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * Pass 1's rotations: the peaks of the range, occupancy-magnitude and
 * orientation-histogram correlations on SO(3).
 */
#include "pipeline/cloud_spectra.h"
#include "pipeline/pose.h"
#include "pipeline/rotation_search.h"
#include "pipeline/stage_tasks.h"
#include "so3/so3_correlation.h"
#include "uncertainty/peak_neighborhood.h"

#include <cmath>

namespace pcl::phaser::detail {
namespace {

/** The spare orientation peaks (on a partial view the right one ranked below ten
 *  others). */
constexpr int kSpareOrientationPeaks = 10;

/** The hypothesis of \a peak of \a C (output bandwidth \a bandwidth), its score the
 *  correlation over \a norm (0 when \a norm is not positive). */
Hypothesis peakHypothesis(const So3CorrelationGrid& C, const So3GridIndex& peak,
                          int bandwidth, double norm, bool from_orientation)
{
  Hypothesis h;
  h.rotation = rotationFromEuler(gridEuler(peak, bandwidth));
  h.rotation_score = norm > 0.0 ? C(peak) / norm : 0.0;
  h.from_orientation = from_orientation;
  return h;
}

/** Peaks of the correlation of the occupancy magnitudes, which need no common center
 *  (objects). */
void magnitudeHypotheses(const SourceContext& source, std::vector<Hypothesis>& out)
{
  const TargetModel& target = source.target;
  const int threads = source.settings.params.num_threads;
  SpatialGridParameters grid;
  grid.voxel_size = target.coarse.grid.voxel_size;
  const MagnitudeShells shells =
      magnitudeShells(occupancySpectrum(makeSpatialGrid(source.coarse_points, grid),
                                        source.coarse_points, threads),
                      kMagnitudeBandwidth);
  const So3CorrelationGrid C = correlateShells(target.magnitude, shells, threads);
  const double norm = target.magnitude.norm * shells.norm;
  for (const So3GridIndex& peak :
       distinctPeaks(C, kMagnitudeCandidates, kHypothesisSeparation, threads))
    out.push_back(peakHypothesis(C, peak, kMagnitudeBandwidth, norm, true));
}

/** The peaks of the range correlation \a correlation of spectra of norms
 *  target.spherical_norm and \a source_norm. */
std::vector<Hypothesis> rangeHypotheses(const SourceContext& source,
                                        const So3CorrelationGrid& correlation,
                                        double source_norm)
{
  const StageSettings& settings = source.settings;
  std::vector<So3GridIndex> peaks;
  if (settings.params.rotation_candidates > 1)
    peaks = distinctPeaks(correlation, settings.params.rotation_candidates,
                          kHypothesisSeparation, settings.params.num_threads);
  if (peaks.empty())
    peaks.push_back(correlation.argmax(settings.params.num_threads));
  // Both norms are positive (sphericalSpectrum).
  const double norm = source.target.spherical_norm * source_norm;
  std::vector<Hypothesis> out;
  for (const So3GridIndex& peak : peaks)
    out.push_back(
        peakHypothesis(correlation, peak, settings.params.bandwidth, norm, false));
  return out;
}

/** The peaks of the orientation-histogram correlation on the rows the priors allow:
 *  the first orientation_candidates into \a rotations.hypotheses, the next into
 *  rotations.spare. */
void orientationHypotheses(const SourceContext& source, RotationHypotheses& rotations)
{
  const StageSettings& settings = source.settings;
  const TargetModel& target = source.target;
  const int bandwidth = settings.params.orientation_bandwidth;
  const SphericalSpectrum O =
      orientationSpectrum(source.patches, bandwidth, settings.params.num_threads);
  const So3CorrelationGrid Co = So3Correlator::instance(bandwidth)->correlate(
      target.orientation, O, settings.params.num_threads,
      source.allowed.rotationRows(bandwidth));
  const double norm =
      std::sqrt(spectrumSquaredNorm(target.orientation) * spectrumSquaredNorm(O));
  const std::vector<So3GridIndex> peaks =
      distinctPeaks(Co, settings.params.orientation_candidates + kSpareOrientationPeaks,
                    kHypothesisSeparation, settings.params.num_threads);
  for (std::size_t k = 0; k < peaks.size(); ++k)
    (static_cast<int>(k) < settings.params.orientation_candidates ? rotations.hypotheses
                                                                  : rotations.spare)
        .push_back(peakHypothesis(Co, peaks[k], bandwidth, norm, true));
}

} // namespace

RotationHypotheses rotationSearch(const SourceContext& source, StageTimes& times)
{
  const StageSettings& settings = source.settings;
  const TargetModel& target = source.target;
  const SphericalSpectrum H =
      sphericalSpectrum(source.points, source.channels, settings,
                        settings.params.num_threads, "source", times);
  const auto start = Clock::now();
  const So3CorrelationGrid C =
      So3Correlator::instance(settings.params.bandwidth)
          ->correlate(target.spherical, H, settings.params.num_threads,
                      source.allowed.rotationRows(settings.params.bandwidth));
  times.so3 += msSince(start);
  const auto begin = Clock::now();
  RotationHypotheses rotations;
  rotations.hypotheses = rangeHypotheses(source, C, std::sqrt(spectrumSquaredNorm(H)));
  times.so3 += msSince(begin);
  if (source.objects()) {
    const auto magnitude_start = Clock::now();
    magnitudeHypotheses(source, rotations.hypotheses);
    times.orientation += msSince(magnitude_start);
  }
  if (target.orientation.size() == 0) // none about centroids or without candidates
    return rotations;
  const auto orientation_start = Clock::now();
  orientationHypotheses(source, rotations);
  times.orientation += msSince(orientation_start);
  return rotations;
}

} // namespace pcl::phaser::detail
