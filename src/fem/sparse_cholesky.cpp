#include "sparse_cholesky.hpp"

#include <cholmod.h>

#include <dlfcn.h>

#include <cstring>
#include <mutex>
#include <stdexcept>

namespace needlekit::fem::detail {

namespace {
// The triangular solves are memory-bound: with OpenBLAS's threads they spin and run several times slower on a busy
// machine (measured 3.5x on 2 shared cores). Run them single-threaded when the BLAS is OpenBLAS (looked up at run
// time, so any BLAS links) and restore the thread count afterwards. The count is process-wide and solvers can run at
// once (the calibration's FE runs side by side): the first solve to enter saves it, the last to leave restores it
// (each saving and restoring for itself let one save the other's "one" and leave the process at one thread).
class SingleThreadedBlas {
public:
  SingleThreadedBlas() {
    if (!set_ || !get_) return;
    const std::lock_guard lock(mutex_);
    if (active_++ == 0) {
      saved_ = get_();
      set_(1);
    }
  }
  ~SingleThreadedBlas() {
    if (!set_ || !get_) return;
    const std::lock_guard lock(mutex_);
    if (--active_ == 0 && saved_ > 0) set_(saved_);
  }
  SingleThreadedBlas(const SingleThreadedBlas&) = delete;
  SingleThreadedBlas& operator=(const SingleThreadedBlas&) = delete;

private:
  using Set = void (*)(int);
  using Get = int (*)();
  static inline const Set set_ = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  static inline const Get get_ = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  static inline std::mutex mutex_;
  static inline int active_ = 0;  // solves in progress
  static inline int saved_ = 0;   // the count before the first of them
};
}  // namespace

struct SparseCholesky::Impl {
  cholmod_common common;
  cholmod_sparse* a = nullptr;
  cholmod_factor* factor = nullptr;
  int64_t n = 0;
};

SparseCholesky::SparseCholesky(int64_t n, const std::vector<int64_t>& colptr, const std::vector<int64_t>& rows)
    : impl_(std::make_unique<Impl>()) {
  auto& c = impl_->common;
  cholmod_l_start(&c);
  c.print = 0;
  c.error_handler = nullptr;
  c.quick_return_if_not_posdef = 1;
  c.supernodal = CHOLMOD_AUTO;
  // Nested dissection (METIS) gives far less fill than AMD on 3D meshes; AMD for small systems.
  c.nmethods = 1;
  c.method[0].ordering = n > 2000 ? CHOLMOD_METIS : CHOLMOD_AMD;
  c.postorder = 1;
  impl_->n = n;
  const auto nnz = static_cast<size_t>(colptr.back());
  impl_->a = cholmod_l_allocate_sparse(n, n, nnz, 1, 1, 1, CHOLMOD_REAL, &c);
  if (!impl_->a) throw std::runtime_error("CHOLMOD: out of memory allocating the matrix");
  std::memcpy(impl_->a->p, colptr.data(), colptr.size() * sizeof(int64_t));
  std::memcpy(impl_->a->i, rows.data(), nnz * sizeof(int64_t));
  std::memset(impl_->a->x, 0, nnz * sizeof(double));
  impl_->factor = cholmod_l_analyze(impl_->a, &c);
  if (!impl_->factor && n > 2000) {  // METIS unavailable: fall back to AMD
    c.method[0].ordering = CHOLMOD_AMD;
    impl_->factor = cholmod_l_analyze(impl_->a, &c);
  }
  if (!impl_->factor) throw std::runtime_error("CHOLMOD: symbolic analysis failed");
}

SparseCholesky::~SparseCholesky() {
  if (!impl_) return;
  cholmod_l_free_factor(&impl_->factor, &impl_->common);
  cholmod_l_free_sparse(&impl_->a, &impl_->common);
  cholmod_l_finish(&impl_->common);
}

bool SparseCholesky::factorize(const std::vector<double>& values) {
  std::memcpy(impl_->a->x, values.data(), values.size() * sizeof(double));
  const int ok = cholmod_l_factorize(impl_->a, impl_->factor, &impl_->common);
  return ok && impl_->common.status == CHOLMOD_OK && impl_->factor->minor == static_cast<size_t>(impl_->n);
}

std::vector<double> SparseCholesky::solve(const std::vector<double>& b) {
  const SingleThreadedBlas single;
  auto& c = impl_->common;
  cholmod_dense* rhs = cholmod_l_allocate_dense(impl_->n, 1, impl_->n, CHOLMOD_REAL, &c);
  std::memcpy(rhs->x, b.data(), b.size() * sizeof(double));
  cholmod_dense* x = cholmod_l_solve(CHOLMOD_A, impl_->factor, rhs, &c);
  std::vector<double> out(static_cast<const double*>(x->x), static_cast<const double*>(x->x) + impl_->n);
  cholmod_l_free_dense(&x, &c);
  cholmod_l_free_dense(&rhs, &c);
  return out;
}

double SparseCholesky::factor_nonzeros() const { return impl_->common.lnz; }
double SparseCholesky::factor_flops() const { return impl_->common.fl; }

}  // namespace needlekit::fem::detail
