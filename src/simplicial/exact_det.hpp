// simplicial/exact_det.hpp — private: exact determinants of double matrices
// (GMP), the reference path for any dimension.
#pragma once

#include "exact/rational.hpp"

namespace polyvol::simplicial {

// det of the n x n matrix whose column c is cols[c][0..n) (finite doubles),
// exactly: the entries are scaled by one power of two to integers and the
// determinant is taken by Bareiss's fraction-free elimination (every division
// exact), then scaled back.
exact::Rational exact_det(int n, const double* const* cols);

}  // namespace polyvol::simplicial
