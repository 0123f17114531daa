// The core's one 3x3 symmetric eigensolver: the eigenvector of the smallest eigenvalue, in
// closed form (the characteristic cubic's smallest root by Newton's method, then the largest
// cross product of two rows), the kernel's normal (Algorithm 1) and, with the tangents that
// complete it, the measurement's local frame. Its steps are written once
// (SymmetricEigensolverSteps.h) for one matrix and for one matrix per vector lane, so that the
// kernel's side-by-side solver gives the same bits. Plain C++17.
#ifndef pcbilateral_SymmetricEigensolver_h
#define pcbilateral_SymmetricEigensolver_h

namespace pcbilateral
{

/// Eigenvector of the smallest eigenvalue of a symmetric 3x3 matrix given by its upper
/// triangle (xx, xy, xz, yy, yz, zz), as a unit vector. (0, 0, 1) when every direction is an
/// eigenvector (a multiple of the identity, or non-finite entries).
void SmallestEigenvector(const double covariance[6], double eigenvector[3]);

/// SmallestEigenvector's threshold on e, the distance of the smallest root of its cubic from
/// -1/2: below it the two smallest eigenvalues are taken to meet, and the answer is any unit
/// vector orthogonal to the largest eigenvalue's eigenvector.
constexpr double MeetingEigenvalueRoots = 1e-6;

/// A right-handed orthonormal frame whose normal is SmallestEigenvector of the matrix (the
/// normal of a point set's least-squares plane, for a covariance) and whose tangents span that
/// plane, in an orientation fixed by the normal alone (a fit of a polynomial in the tangent
/// coordinates that spans all rotations of itself, a plane or a quadric, does not depend on it).
void TangentFrame(const double covariance[6],
  double normal[3],
  double tangentU[3],
  double tangentV[3]);

} // namespace pcbilateral

#endif
