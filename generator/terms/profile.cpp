// A tabulated profile (docs/model.md section 11.2): the distributions are the stations' values times their hat
// functions, the field symbols m_x, ES_x, EI_x that the density integrator expands.
#include "generator_terms.hpp"

namespace hubbeam::gen {

BeamSection profile_section(const Symbols&, const FieldSymbols& f, const Extras&)
{
    return {f.m_x, f.ES_x, f.EI_x};
}

}  // namespace hubbeam::gen
