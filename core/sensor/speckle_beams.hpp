// The receive pattern applied to the speckle field (speckle_field.cpp), a group of range bins at a time: the
// field's rows turned into columns, then each beam the weighted sum of its columns, in vectors as wide as the
// CPU has (the same sums, and so the same bits, whichever).
#pragma once
#include "core/data/scene.hpp"

#include <memory>
#include <vector>

namespace sonarsim {

/// Range bins formed together: the field of a group is stored column by column, kSpeckleGroupRows values (one
/// per bin) a column, so that forming a beam is a sum of whole columns, that many lanes wide: independent
/// sums enough to keep the adders busy (each lane's sum in the same order whatever the group).
constexpr int kSpeckleGroupRows = 16;

/// The receive pattern's amplitude by beam: beam b sums the fine columns column[start[b] ... start[b + 1])
/// with the weights beside them (ascending columns), in single precision like the field it forms.
struct BeamSums {
    std::vector<int> start, column;
    std::vector<float> weight;
};

/// BeamSums of the scene's receive pattern amplitudes, made once per geometry and pattern and kept (the
/// sensor stage reruns on the same geometry frame after frame).
std::shared_ptr<const BeamSums> shared_beam_sums(const SceneDesc& scene);

/// The field of a group by column (field[j * 2 kSpeckleGroupRows + t] re, kSpeckleGroupRows further on im)
/// from its rows (rows[t * 2 J + j] re, J further on im).
void to_columns(int J, const float* rows, float* field);

/// The beams of a group from its field (as to_columns leaves it; 64-byte aligned): (re, im) of beam b for the
/// group's row t into out[t * 2 N + b] and out[t * 2 N + N + b], t < rows; with `intensity`, instead
/// |scale[t] (re, im)|^2 into intensity[t * N + b] (a single-tap range filter's output).
void form_group(const BeamSums& sums, int N, const float* field, int rows, float* out, const double* scale,
                double* intensity);

} // namespace sonarsim
