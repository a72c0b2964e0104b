#pragma once

#include <optional>
#include <vector>

namespace floorgrid {

/// The noise scale sigma (per axis, metres) of 2-D residual distances |T p - q| of which only
/// those within `truncation` are trusted: the inliers of a threshold, among outliers. Isotropic
/// Gaussian noise makes the distances Rayleigh(sigma); cut at t, their median m satisfies
/// F(m) = F(t) / 2 with F(r) = 1 - exp(-r^2 / (2 sigma^2)), solved here for sigma. For t much
/// larger than sigma this is the usual m / sqrt(2 ln 2); for t near sigma it corrects for the
/// distances the cut removed. Distances above `truncation` are ignored; `parameters` (the
/// transform's degrees of freedom, fitted to these residuals) inflates sigma by
/// sqrt(2 k / (2 k - parameters)) for the k distances kept, as residuals of a least-squares
/// fit are smaller than the noise.
///
/// std::nullopt when sigma is not identifiable: fewer than `parameters` + 2 distances within
/// the cut, or a median above 0.69 t (the distances fill the disc of radius t about evenly, so
/// the noise is at least about twice t). `distances` is reordered.
std::optional<double> truncated_rayleigh_scale(std::vector<double>& distances, double truncation,
                                               int parameters);

}  // namespace floorgrid
