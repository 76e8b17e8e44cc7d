#include "sparse_cholesky.h"

#include <cholmod.h>

#include <Eigen/OrderingMethods>
#include <vector>

namespace splinecal {
namespace estimation_internal {

struct SparseCholesky::Cholmod {
  cholmod_common common;
  cholmod_factor* factor = nullptr;
  std::vector<int> perm;  // CHOLMOD factors H(perm, perm) = L L^T

  Cholmod() {
    cholmod_start(&common);
    common.print = 0;  // a matrix that is not positive definite is reported by ok(), not on stderr
  }
  ~Cholmod() {
    if (factor != nullptr) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
};

namespace {

// A CHOLMOD view of a dense column-major Eigen matrix (no copy).
cholmod_dense DenseView(const Eigen::MatrixXd& M) {
  cholmod_dense view{};
  view.nrow = static_cast<size_t>(M.rows());
  view.ncol = static_cast<size_t>(M.cols());
  view.nzmax = view.nrow * view.ncol;
  view.d = view.nrow;
  view.x = const_cast<double*>(M.data());
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  return view;
}

}  // namespace

SparseCholesky::SparseCholesky(const Eigen::SparseMatrix<double>& H)
    : cholmod_(std::make_unique<Cholmod>()) {
  const int n = static_cast<int>(H.rows());
  if (H.cols() != n) return;
  // The ordering exactly as Eigen's SimplicialLLT<..., Lower, AMDOrdering> computes it: AMD on
  // the full symmetric pattern built from the lower triangle; AMD returns P^-1, whose indices
  // are the rows CHOLMOD takes in turn.
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse_perm;
  {
    Eigen::SparseMatrix<double> full = H.selfadjointView<Eigen::Lower>();
    Eigen::AMDOrdering<int> amd;
    amd(full, inverse_perm);
  }
  cholmod_->perm.assign(inverse_perm.indices().data(), inverse_perm.indices().data() + n);

  Eigen::SparseMatrix<double> lower = H.triangularView<Eigen::Lower>();
  lower.makeCompressed();
  cholmod_sparse A{};
  A.nrow = A.ncol = static_cast<size_t>(n);
  A.nzmax = static_cast<size_t>(lower.nonZeros());
  A.p = lower.outerIndexPtr();
  A.i = lower.innerIndexPtr();
  A.x = lower.valuePtr();
  A.stype = -1;  // symmetric, lower triangle stored
  A.itype = CHOLMOD_INT;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;

  cholmod_common& c = cholmod_->common;
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_GIVEN;
  c.postorder = 0;  // keep the given ordering as it is (the factor, not just H^-1, must match)
  c.supernodal = CHOLMOD_SUPERNODAL;
  c.final_ll = 1;
  c.quick_return_if_not_posdef = 1;
  cholmod_->factor = cholmod_analyze_p(&A, cholmod_->perm.data(), nullptr, 0, &c);
  if (cholmod_->factor == nullptr || c.status != CHOLMOD_OK) return;
  cholmod_factorize(&A, cholmod_->factor, &c);
  ok_ = c.status == CHOLMOD_OK && cholmod_->factor->minor == static_cast<size_t>(n);
}

SparseCholesky::~SparseCholesky() = default;

Eigen::MatrixXd SparseCholesky::SolveSystem(int system, const Eigen::MatrixXd& B) const {
  cholmod_dense b = DenseView(B);
  cholmod_dense* x = cholmod_solve(system, cholmod_->factor, &b, &cholmod_->common);
  Eigen::MatrixXd X;
  if (x == nullptr) return X;
  X = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(x->x), B.rows(), B.cols());
  cholmod_free_dense(&x, &cholmod_->common);
  return X;
}

Eigen::MatrixXd SparseCholesky::SolveLt(const Eigen::MatrixXd& Z) const {
  if (!ok_) return Eigen::MatrixXd();
  // CHOLMOD_Lt solves L^T x = z in the factor's (permuted) coordinates; row k of the result is
  // row perm[k] of P^T x.
  const Eigen::MatrixXd X = SolveSystem(CHOLMOD_Lt, Z);
  if (X.rows() != Z.rows()) return X;
  Eigen::MatrixXd W(X.rows(), X.cols());
  for (Eigen::Index k = 0; k < X.rows(); ++k) W.row(cholmod_->perm[k]) = X.row(k);
  return W;
}

Eigen::MatrixXd SparseCholesky::Solve(const Eigen::MatrixXd& B) const {
  if (!ok_) return Eigen::MatrixXd();
  return SolveSystem(CHOLMOD_A, B);
}

}  // namespace estimation_internal
}  // namespace splinecal
