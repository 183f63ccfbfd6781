/* von Mises strength: a constant yield stress Y0, reduced linearly to zero as
 * the specific internal energy approaches the melt energy (Benz & Asphaug
 * 1994, Sec. 2; Schaefer et al. 2016, Sec. 2.3).  theory/solids.md, "Yield". */
#ifndef BOLIDE_STRENGTH_VON_MISES_H
#define BOLIDE_STRENGTH_VON_MISES_H

#include "src/inline.h"

/** Yield stress Y0 times the melt factor (computed by the caller). */
BOLIDE_INLINE double strength_von_mises_yield(double Y0, double melt_factor) {
  return Y0 * melt_factor;
}

#endif
