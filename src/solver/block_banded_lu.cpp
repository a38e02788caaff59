#include "src/solver/block_banded_lu.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "src/core/worker_threads.hpp"

namespace panoptic {
namespace {

// A lower block with fewer than this share of non-zeros is multiplied as sparse times
// dense: the transport's blocks hold a few entries per row (a bin, its porosity moment,
// Sigma_g), a block filled by the elimination (bandwidth > 1) is dense.
constexpr long kSparseShareInverse = 16;

// Whether the pivots of a factorised block are all non-zero and finite.
template <class Lu>
bool usable(const Lu& lu) {
  const auto d = lu.matrixLU().diagonal().cwiseAbs();
  return d.allFinite() && (d.size() == 0 || d.minCoeff() > 0.0);
}

// Why n_blocks cells of block_size variables do not fit `pattern`; empty when they do.
std::string size_refusal(const SparsityPattern& pattern, int n_blocks, int block_size) {
  const long n_cell_part = static_cast<long>(n_blocks) * block_size;
  if (n_blocks < 1 || block_size < 1 || n_cell_part > pattern.size())
    return std::to_string(n_blocks) + " cells of " + std::to_string(block_size) +
           " variables do not fit a matrix of size " + std::to_string(pattern.size());
  return "";
}

}  // namespace

BlockStructureRefused::BlockStructureRefused(const std::string& why)
    : std::invalid_argument("BlockBandedLU: " + why), reason(why) {}

std::string BlockBandedLU::refusal(const SparsityPattern& pattern, int n_blocks,
                                   int block_size) {
  if (std::string why = size_refusal(pattern, n_blocks, block_size); !why.empty())
    return why;
  const long n = pattern.size();
  const long n_cell_part = static_cast<long>(n_blocks) * block_size;
  const auto col_ptr = pattern.col_ptr();
  const auto rows = pattern.row_index();
  for (long c = n_cell_part; c < n; ++c)
    for (auto p = col_ptr[c]; p < col_ptr[c + 1]; ++p)
      if (rows[p] < n_cell_part)
        return "the row of variable " + std::to_string(rows[p] % block_size) +
               " of cell " + std::to_string(rows[p] / block_size) +
               " depends on global variable " + std::to_string(c - n_cell_part) +
               " (the block solver needs cell rows free of the globals)";
  return "";
}

BlockBandedLU::BlockBandedLU(const SparsityPattern& pattern, int n_blocks, int block_size)
    : n_(n_blocks), b_(block_size) {
  if (const std::string why = refusal(pattern, n_blocks, block_size); !why.empty())
    throw BlockStructureRefused(why);
  n_cell_part_ = static_cast<long>(n_) * b_;
  n_g_ = static_cast<int>(pattern.size() - n_cell_part_);
  const auto col_ptr = pattern.col_ptr();
  const auto rows = pattern.row_index();
  long n_coupling = 0;
  for (long c = 0; c < n_cell_part_; ++c)
    for (auto p = col_ptr[c]; p < col_ptr[c + 1]; ++p) {
      if (rows[p] >= n_cell_part_) {
        ++n_coupling;
        continue;
      }
      w_ = std::max<int>(w_, static_cast<int>(std::abs(rows[p] / b_ - c / b_)));
    }

  allocate(n_coupling);
  // c_value_ is sized before the pointers into it are taken: they stay valid.
  std::size_t t = 0;
  for (long c = 0; c < pattern.size(); ++c)
    for (auto p = col_ptr[c]; p < col_ptr[c + 1]; ++p) {
      const long r = rows[p];
      double* to = nullptr;
      if (r < n_cell_part_) {
        Matrix& m = block(static_cast<int>(r / b_), static_cast<int>(c / b_));
        to = &m(r % b_, c % b_);
      } else if (c < n_cell_part_) {
        c_row_.push_back(static_cast<int>(r - n_cell_part_));
        c_col_.push_back(c);
        to = &c_value_[t++];
      } else {
        to = &g_(r - n_cell_part_, c - n_cell_part_);
      }
      add_destination(static_cast<std::size_t>(p), to);
    }
  destination_.shrink_to_fit();
}

BlockBandedLU::BlockBandedLU(const SparsityPattern& pattern, int n_blocks, int block_size,
                             CellBlocksOnly)
    : n_(n_blocks), b_(block_size) {
  if (const std::string why = size_refusal(pattern, n_blocks, block_size); !why.empty())
    throw std::invalid_argument(why);
  n_cell_part_ = static_cast<long>(n_) * b_;
  allocate(0);
  const auto col_ptr = pattern.col_ptr();
  const auto rows = pattern.row_index();
  for (long c = 0; c < n_cell_part_; ++c) {
    const long first = c / b_ * b_;
    for (auto p = col_ptr[c]; p < col_ptr[c + 1]; ++p)
      if (rows[p] >= first && rows[p] < first + b_)
        add_destination(static_cast<std::size_t>(p),
                        &block(static_cast<int>(c / b_), static_cast<int>(c / b_))(
                            rows[p] % b_, c % b_));
  }
  destination_.shrink_to_fit();
}

void BlockBandedLU::allocate(long n_coupling) {
  blocks_.resize(static_cast<std::size_t>(n_) * (2 * w_ + 1));
  for (int i = 0; i < n_; ++i)
    for (int j = std::max(0, i - w_); j <= std::min(n_ - 1, i + w_); ++j)
      block(i, j).setZero(b_, b_);
  lower_sparse_.resize(blocks_.size());
  lower_is_sparse_.assign(blocks_.size(), 0);
  pivots_.resize(static_cast<std::size_t>(n_));
  g_.setZero(n_g_, n_g_);
  scratch_.resize(std::max(b_, n_g_));
  scratch_block_.resize(b_, b_);
  c_row_.reserve(static_cast<std::size_t>(n_coupling));
  c_col_.reserve(static_cast<std::size_t>(n_coupling));
  c_value_.assign(static_cast<std::size_t>(n_coupling), 0.0);
}

void BlockBandedLU::add_destination(std::size_t p, double* to) {
  if (!destination_.empty()) {
    CopyRun& last = destination_.back();
    if (last.from + last.length == p && last.to + last.length == to) {
      ++last.length;
      return;
    }
  }
  destination_.push_back({to, p, 1});
}

bool BlockBandedLU::factorize(std::span<const double> values) {
  return fill_and_factorize(values, std::nullopt);
}

bool BlockBandedLU::factorize_newton(std::span<const double> jacobian, double c) {
  return fill_and_factorize(jacobian, c);
}

bool BlockBandedLU::fill_and_factorize(std::span<const double> values,
                                       std::optional<double> newton_c) {
  // zeroed and filled in bands by the worker threads: every entry has a destination of
  // its own
  parallel_bands(blocks_.size(), [&](std::size_t lo, std::size_t hi) {
    for (std::size_t b = lo; b < hi; ++b) blocks_[b].setZero();
  });
  g_.setZero();
  const double minus_c = newton_c ? -*newton_c : 0.0;
  parallel_bands(destination_.size(), [&](std::size_t lo, std::size_t hi) {
    for (std::size_t q = lo; q < hi; ++q) {
      const double* from = values.data() + destination_[q].from;
      double* to = destination_[q].to;
      if (!newton_c)
        std::copy_n(from, destination_[q].length, to);
      else  // newton_matrix's (-c) J, then 1 + on the diagonal below
        for (std::size_t i = 0; i < destination_[q].length; ++i)
          to[i] = minus_c * from[i];
    }
  });
  if (newton_c) {
    for (int k = 0; k < n_; ++k)
      for (int d = 0; d < b_; ++d) block(k, k)(d, d) = 1.0 + block(k, k)(d, d);
    for (int d = 0; d < n_g_; ++d) g_(d, d) = 1.0 + g_(d, d);
  }

  if (w_ == 0) {
    // independent blocks (the GMRES preconditioner's): factorised by the worker threads
    std::vector<char> ok(static_cast<std::size_t>(n_), 0);
    parallel_for(n_, [&](int k, int) {
      factorize_pivot(k);
      ok[static_cast<std::size_t>(k)] = usable(*pivots_[k]);
    });
    if (std::ranges::find(ok, 0) != ok.end()) return false;
  }
  // Block Gaussian elimination (right-looking): at step k the blocks of row k and of
  // column k are final; U_kj <- D_k^-1 U_kj, then A_ij -= A_ik (D_k^-1 U_kj) for the
  // rows i and columns j within the band below and right of k.
  for (int k = 0; w_ > 0 && k < n_; ++k) {
    factorize_pivot(k);
    if (!usable(*pivots_[k])) return false;
    const int last = std::min(n_ - 1, k + w_);
    for (int j = k + 1; j <= last; ++j) {
      scratch_block_ = block(k, j);
      block(k, j) = pivots_[k]->solve(scratch_block_);
    }
    for (int i = k + 1; i <= last; ++i) {
      const std::size_t s = slot(i, k);
      const Matrix& lower = blocks_[s];
      const long nnz = (lower.array() != 0.0).count();
      lower_is_sparse_[s] = nnz * kSparseShareInverse < static_cast<long>(b_) * b_;
      if (lower_is_sparse_[s]) lower_sparse_[s] = lower.sparseView();
      for (int j = k + 1; j <= last; ++j) {
        if (lower_is_sparse_[s])
          block(i, j).noalias() -= lower_sparse_[s] * block(k, j);
        else
          block(i, j).noalias() -= lower * block(k, j);
      }
    }
  }
  if (n_g_ > 0) {
    g_lu_.compute(g_);
    if (!usable(g_lu_)) return false;
  }
  return true;
}

void BlockBandedLU::factorize_pivot(int k) {
  // in place: the LU overwrites the pivot block, which the elimination does not read
  // again (Eigen's in-place decomposition, the same kernel as on a copy)
  if (pivots_[k])
    pivots_[k]->compute(block(k, k));
  else
    pivots_[k].emplace(block(k, k));
}

void BlockBandedLU::subtract_lower_product(int i, int j,
                                           const Eigen::Ref<const Eigen::VectorXd>& x,
                                           Eigen::Ref<Eigen::VectorXd> y) const {
  const std::size_t s = slot(i, j);
  if (lower_is_sparse_[s])
    y.noalias() -= lower_sparse_[s] * x;
  else
    y.noalias() -= blocks_[s] * x;
}

bool BlockBandedLU::solve(std::span<double> x) const {
  Eigen::Map<Eigen::VectorXd> v(x.data(), static_cast<Eigen::Index>(x.size()));
  if (w_ == 0) {
    // independent blocks: x_k = D_k^-1 b_k by the worker threads, each with its scratch
    const auto threads = static_cast<std::size_t>(worker_threads());
    if (worker_scratch_.size() < threads) worker_scratch_.resize(threads);
    parallel_for(n_, [&](int k, int worker) {
      Eigen::VectorXd& s = worker_scratch_[static_cast<std::size_t>(worker)];
      auto xk = v.segment(static_cast<Eigen::Index>(k) * b_, b_);
      s = pivots_[k]->solve(xk);
      xk = s;
    });
  }
  // Forward: y_k = D_k^-1 (b_k - sum_i A_ki y_i), the rows below updated as each y_k is
  // known; backward: x_k = y_k - sum_j (D_k^-1 U_kj) x_j.
  for (int k = 0; w_ > 0 && k < n_; ++k) {
    auto xk = v.segment(static_cast<Eigen::Index>(k) * b_, b_);
    scratch_.head(b_) = pivots_[k]->solve(xk);
    xk = scratch_.head(b_);
    for (int i = k + 1; i <= std::min(n_ - 1, k + w_); ++i)
      subtract_lower_product(i, k, xk, v.segment(static_cast<Eigen::Index>(i) * b_, b_));
  }
  for (int k = n_ - 1; k >= 0; --k)
    for (int j = k + 1; j <= std::min(n_ - 1, k + w_); ++j)
      v.segment(static_cast<Eigen::Index>(k) * b_, b_).noalias() -=
          block(k, j) * v.segment(static_cast<Eigen::Index>(j) * b_, b_);
  if (n_g_ > 0) {
    auto xg = v.tail(n_g_);
    for (std::size_t t = 0; t < c_value_.size(); ++t)
      xg(c_row_[t]) -= c_value_[t] * v(c_col_[t]);
    scratch_.head(n_g_) = g_lu_.solve(xg);
    xg = scratch_.head(n_g_);
  }
  return v.allFinite();
}

}  // namespace panoptic
