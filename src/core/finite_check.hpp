// Whether a writer runs check_finite (core/texture.hpp) on the texture it is
// given: on level 0 of a mip chain, lower levels being always checked.
// `already_checked` when its caller has: write_outputs checks a texture once
// for all its formats (a 128^3 RGBA volume is 32 MB to scan per format).
#pragma once

namespace skybake {

enum class FiniteCheck { run, already_checked };

}  // namespace skybake
