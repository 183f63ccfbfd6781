/* Conventions shared by every equation of state in src/materials/.
 *
 * Each EOS lives in one header eos_NAME.h that compiles as C11 and as CUDA
 * C++ and holds, side by side:
 *   - EOS_NAME_PARAMS(X): the one list of its parameters.  Every entry is
 *     X(struct, field, "key", default, lo, lo_open, hi, unit kind, "doc"):
 *     the struct member, the YAML key, the default (NAN: required), the
 *     allowed range [lo, hi] (lo excluded when lo_open is 1), the kind of
 *     unit (MATERIAL_UNIT_*, used for unit conversion and documentation)
 *     and a one-line meaning.  The struct, the YAML parser, the range checks,
 *     the unit conversion and the reference documentation all come from it.
 *   - struct eos_NAME: the parameters (generated from the list, plus derived
 *     members).  Every struct has a member rho0 (reference density).
 *   - eos_NAME_eval(p, rho, u, &P, &c2): pressure and squared sound speed
 *     c^2 = (dP/drho)_s = (dP/drho)_u + P/rho^2 (dP/du)_rho, written together
 *     so that the derivative is taken of the very expression of P.  c2 may be
 *     zero or negative (tension, spinodal states): the material layer
 *     (material_eos) applies the material's cs_min floor.
 *   - eos_NAME_pressure / eos_NAME_sound_speed: thin wrappers.
 *   - eos_NAME_temperature(p, rho, u): the temperature where the EOS defines
 *     one (0 otherwise), eos_NAME_has_temperature(p).
 *   - eos_NAME_check(p, &key): cross-checks of the parameters beyond the
 *     per-key ranges; returns NULL or a message about parameter `key`. */
#ifndef BOLIDE_EOS_COMMON_H
#define BOLIDE_EOS_COMMON_H

#include <math.h>
#include <stddef.h>

#include "src/inline.h"

/** Expands one entry of an EOS_*_PARAMS list to a struct member. */
#define EOS_PARAM_FIELD(st, field, key, def, lo, lo_open, hi, kind, doc) double field;

#endif
