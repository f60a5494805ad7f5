// feint/plot/map_figure.hpp - the map figure of a study of K targets and a pointer (docs/figures.md
// "The map"): one panel per strategy and version with the start, the targets, the mean robot path
// and the mean pointer over normalised time.
//
// Plain data in, no file read: the analysis computes the map (metrics::mean_map, into
// analysis::FigureData::map; the averaging and the canonical frame are in
// feint/metrics/mean_map.hpp), and this draws it.
#pragma once

#include <cstddef>
#include <string>

#include "feint/metrics/mean_map.hpp"
#include "feint/plot/canvas.hpp"

namespace feint::plot {

using metrics::kMapPoints;
using metrics::MapMean;
using metrics::MapPanel;
using metrics::MapPoint;
using metrics::MeanMap;

/// Colour of target k in a fixed layout, and of the pointers of its trials: vermillion, bluish
/// green, reddish purple, sky blue, black, then again (Okabe & Ito; never the conditions' blue and
/// orange, nor yellow, too light for a line). The canonical frame's true target has the first.
Colour target_colour(std::size_t k) noexcept;

/// One panel per strategy and version, the map at equal aspect (one metre, or one start-target
/// distance, is as long across as up), the panels sharing their scales.
Figure map_figure(const MeanMap& data);
std::string alt_text(const MeanMap& data);
/// The figure's caption (what is drawn, how the means are taken, on how many trials).
std::string map_caption(const MeanMap& data);

}  // namespace feint::plot
