// docs/model.md section 12.3: the energies of orders zero and first as quadratic forms in the elastic coordinates, the
// hand-assembled path's form for a beam that leaves the plane, placed block by block from the terms' matrices.
#pragma once

#include <Eigen/Dense>

#include "models/assembled/assembled_terms.hpp"
#include "models/assembled/forms.hpp"

namespace hubbeam {

/// The forms of a variant from the beam's matrices c and the model's m (c's with the terms it carries added).
QuadraticForms quadratic_forms(const VariantKey& key, const BeamMatrices& c, const ModelMatrices& m);

}  // namespace hubbeam
