/// Self-tuning spectral clustering after L. Zelnik-Manor and P. Perona, "Self-tuning
/// spectral clustering", NIPS 2004 (ZP04 below; the method of paper §3.4). With n points
/// (rows), d features (columns) and K = neighbour_rank:
///
///  1. Standardise every column: z_ik = (f_ik - mean_k) / std_k, population std. A column
///     whose std is below 64 machine epsilons of its largest magnitude is constant: 0.
///  2. d_ij = ||z_i - z_j||; local scale sigma_i = d(i, K-th nearest neighbour of i), the
///     farthest point when n - 1 < K (ZP04 §2), raised to kSigmaFloor (see there).
///  3. A_ij = exp(-d_ij^2 / (sigma_i sigma_j)), A_ii = 0, D_i = sum_j A_ij,
///     L = D^{-1/2} A D^{-1/2} (ZP04 §2, §4 steps 2-3).
///  4. x_1, x_2, ... = unit eigenvectors of L by decreasing eigenvalue, each with its
///     largest-magnitude entry positive (ZP04 §4 step 4).
///  5. For C = 2 .. min(max_clusters, n): X = [x_1 .. x_C] (n x C), Z = X R with
///     R = G_1 G_2 .. G_K the product of K = C(C-1)/2 Givens rotations G_k = G(i_k, j_k,
///     theta_k), and the alignment cost (ZP04 §3)
///         J = sum_i sum_j Z_ij^2 / M_i^2,          M_i = max_j |Z_ij|,
///     minimised over theta by gradient descent with backtracking, the gradient being
///     (ZP04 §3 and appendix)
///         dJ/dtheta_k = sum_ij (2 Z_ij / M_i^2) dZ_ij - (2 Z_ij^2 / M_i^3) dM_i,
///         dZ/dtheta_k = X G_1 .. G_{k-1} (dG_k/dtheta_k) G_{k+1} .. G_K.
///     C + 1 starts from [Z_C, x_{C+1}] (ZP04 §4 step 5), at theta = 0 and, our addition,
///     also at theta = +-pi/8 on every angle, keeping the lowest J: theta = 0 is a
///     stationary maximum for two balanced groups (every row at 45 degrees).
///  6. Labels l_i = argmax_j |Z_ij| (ZP04 §4 step 7); groups renumbered by their smallest
///     member index.
///
/// Our own parts, not in ZP04:
///  - Quality. J / n = 1 + mean_i s_i with the spill s_i = (||Z_i||^2 - M_i^2) / M_i^2 of
///    point i onto the other axes; quality = n / J = 1 / (1 + mean spill), in [1/C, 1]
///    (1: every point on one axis). Unlike 1 - (J/n - 1)/(C - 1) or 1 - (J/n - 1)/C it
///    does not drift towards 1 as C grows (on a single blob those reach 0.97 at C = 10),
///    so one threshold serves every C. The group count is ZP04's rule, the largest C whose
///    quality is within quality_tolerance of the best, taken among admissible counts (next
///    point). The default tolerance 0.002 is twice the usual 0.001: with well separated
///    groups one or two points lying between two of them lower the quality of the right C
///    by 0.001-0.002 while merging those two groups stays perfectly crisp; 0.005 already
///    splits Gaussian blobs now and then (3 under-splits, 0 over-splits in 600 synthetic
///    runs at 0.001; 1 and 0 at 0.002; 0 and 3 at 0.005).
///  - Single-group rule (ZP04 always return at least two groups; one group is the null
///    hypothesis, whose alignment is trivially perfect). A count C is admissible when its
///    partition has at least two groups and is
///      crisp:     quality >= min_quality (0.95). For one Gaussian blob (2-D or 18-D), a
///                 ring or a uniform square, the leading eigenvectors vary smoothly over the
///                 data and many points sit between axes: qualities 0.8-0.92, rarely up to
///                 0.967 (about 2 % of 2-D samples of 100-200 points); separated groups
///                 give 0.99-1, two unit Gaussians 6 apart (40 points each) 0.95-0.99.
///      separated: every group's conductance cut(G, rest) / vol(G) = sum_{i in G, j not in
///                 G} A_ij / sum_{i in G} D_i <= max_conductance (0.1). This rejects
///                 partitions whose quality is high only because C is close to n (C = n
///                 always has quality 1), groups of at most K points whose local scale
///                 reaches into other groups (two points are never split), and the
///                 all-alike affinities of high-dimensional blobs (conductance 0.45-1).
///    No admissible count: one group.
///  - Isolated points: D_i < kIsolatedDegree (every affinity underflows, e.g. a point far
///    from sets of duplicates) would give L a zero row and spurious eigenvectors; such
///    points, and points whose eigenvector row is numerically zero, take no part in steps
///    4-5 and join the group of their nearest point (reported in the diagnostics).
///  - Eigenvectors. Only the leading ones are needed: Householder tridiagonalisation, all
///    eigenvalues of the tridiagonal matrix, inverse iteration for the leading ones, then
///    back-transformation; residuals and orthogonality are checked and Eigen's full
///    SelfAdjointEigenSolver is the fallback. Same subspaces, about 5 times faster at
///    n = 2000 than accumulating all n eigenvectors (13 s).
///  - Landmarks. Steps 2-5 hold four n x n matrices and cost O(n^3): a scan textured all over,
///    segmented at a fine scale, has thousands of texels (10,622 on a noisy stone of 1.1M
///    faces at 0.6%: 85 s of an 89 s run). Above max_points (m), steps 2-6 run on m
///    landmarks, points k n / m for k = 0 .. m - 1 (evenly spaced in the points' order, so a
///    sample in proportion to each kind of point, which keeps the local scales' meaning), and
///    every other point takes the group of its nearest landmark in the standardised features
///    (the first on ties). This is the nearest-neighbour extension of a subsample rather than
///    the Nystrom extension of the eigenvectors (Fowlkes et al., PAMI 2004): it needs no local
///    scale for the other points, and each point's group is that of the texel most like it.
///    A group needs more than neighbour_rank landmarks to separate (see neighbour_rank), so
///    one rarer than about (neighbour_rank + 1) n / m points may join its nearest group.
///
/// Cost: O(n^2 d) distances, O(n^3) tridiagonalisation (4/3 n^3 flops, the bulk), O(n^2)
/// per group count for the conductances, and per group count 3 descents of
/// O(iterations (n C^2 + C^4)). Measured on one core, 18 features: about 0.1-0.2 s for
/// n = 500 and 2-3 s for n = 2000. Memory: four n x n matrices of doubles (128 MB at
/// n = 2000). With landmarks, the same with n = m, plus O(n m d) for the nearest landmarks.
///
/// Deterministic: no randomness; ties go to the smallest index. The same input gives
/// bit-identical results with the same build (other compilers or flags, e.g. FMA
/// contraction, may change rounding).

#include "geometry/clustering.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "geometry/detail/leading_eigenpairs.hpp"
#include "geometry/detail/parallel.hpp"

namespace geotex {
namespace {

constexpr const char* kStage = "clustering";

// Smallest local scale, in standardised units (every non-constant column has unit
// variance, so the data spread is of order 1). A point with K exact or rounding-level
// duplicates has sigma_i = 0 and exp(-0/0) is undefined. With the floor, duplicates get
// affinity 1 to each other and ~0 to every genuinely different point: a set of more than
// K identical feature vectors (identical texels repeated on a synthetic mesh) is a tight
// group of its own, which is what local scaling means for zero spread.
constexpr double kSigmaFloor = 1e-9;
constexpr const char* kSigmaFloorText = "1e-9";

// Total affinity below which a point counts as isolated: its nearest point is more than
// sqrt(46) ~ 6.8 local scales away (exp(-46) ~ 1e-20).
constexpr double kIsolatedDegree = 1e-20;

// Eigenvector rows shorter than this carry no direction (ordinary rows are about
// sqrt(C / n) long, rounding noise about 1e-15).
constexpr double kNullRowNorm = 1e-10;

// Rotation descent: iteration cap, and stop when an iteration gains less than this in J/n.
constexpr int kMaxDescentIterations = 500;
constexpr double kDescentTolerance = 1e-7;

std::size_t at(Eigen::Index i) { return static_cast<std::size_t>(i); }

}  // namespace

void check_clustering_params(const ClusteringParams& p) {
    auto fail = [](const std::string& what) {
        throw InvalidInput(std::string(kStage) + ": " + what);
    };
    if (p.neighbour_rank < 1)
        fail("neighbour_rank must be at least 1, got " + std::to_string(p.neighbour_rank));
    if (p.max_clusters < 1)
        fail("max_clusters must be at least 1, got " + std::to_string(p.max_clusters));
    if (!(p.quality_tolerance >= 0.0 && p.quality_tolerance <= 1.0))
        fail("quality_tolerance must lie in [0, 1], got " + std::to_string(p.quality_tolerance));
    if (!(p.min_quality >= 0.0 && p.min_quality <= 1.0))
        fail("min_quality must lie in [0, 1], got " + std::to_string(p.min_quality));
    if (!(p.max_conductance >= 0.0 && p.max_conductance <= 1.0))
        fail("max_conductance must lie in [0, 1], got " + std::to_string(p.max_conductance));
    if (p.max_points < 0 || p.max_points == 1)
        fail("max_points must be 0 (no limit) or at least 2, got " + std::to_string(p.max_points));
}

namespace {

/// Standardised copy of `f` (#points by #features), transposed to #features by #points so
/// that a point's features are contiguous. Throws InvalidInput on a non-finite value.
Eigen::MatrixXd standardised_points(const Eigen::MatrixXd& f) {
    for (Eigen::Index i = 0; i < f.rows(); ++i)
        for (Eigen::Index k = 0; k < f.cols(); ++k)
            if (!std::isfinite(f(i, k)))
                throw InvalidInput(std::string(kStage) + ": feature value at row " +
                                   std::to_string(i) + ", column " + std::to_string(k) +
                                   " is not finite (" + std::to_string(f(i, k)) + ") among " +
                                   std::to_string(f.rows()) + " x " + std::to_string(f.cols()) +
                                   " features; remove or impute non-finite features first");
    const Eigen::Index n = f.rows();
    Eigen::MatrixXd z(f.cols(), n);
    for (Eigen::Index k = 0; k < f.cols(); ++k) {
        // Divided by the largest magnitude first, squares cannot overflow.
        const double scale = f.col(k).cwiseAbs().maxCoeff();
        if (scale == 0.0) {
            z.row(k).setZero();
            continue;
        }
        const Eigen::ArrayXd y = f.col(k).array() / scale;
        const double mean = y.sum() / static_cast<double>(n);
        const double sd = std::sqrt((y - mean).square().sum() / static_cast<double>(n));
        // Variation at rounding level is no feature: dividing by it would blow noise up to
        // unit variance.
        if (sd <= 64.0 * std::numeric_limits<double>::epsilon()) {
            z.row(k).setZero();
            continue;
        }
        z.row(k) = ((y - mean) / sd).matrix().transpose();
    }
    return z;
}

/// #points by #points squared distances between the columns of `z`, computed pairwise (not
/// through the Gram matrix) so that duplicates are exactly 0.
Eigen::MatrixXd squared_distances(const Eigen::MatrixXd& z) {
    const Eigen::Index n = z.cols();
    Eigen::MatrixXd d2(n, n);
    for (Eigen::Index j = 0; j < n; ++j) {
        d2(j, j) = 0.0;
        for (Eigen::Index i = j + 1; i < n; ++i) {
            const double v = (z.col(i) - z.col(j)).squaredNorm();
            d2(i, j) = v;
            d2(j, i) = v;
        }
    }
    return d2;
}

/// sigma_i = distance to the K-th nearest other point (the farthest when there are fewer),
/// raised to kSigmaFloor; counts the raised ones in `num_floored`.
Eigen::VectorXd local_scales(const Eigen::MatrixXd& d2, int neighbour_rank, int* num_floored) {
    const Eigen::Index n = d2.rows();
    const std::size_t rank = at(std::min<Eigen::Index>(neighbour_rank, n - 1));
    Eigen::VectorXd sigma(n);
    std::vector<double> others(at(n - 1));
    *num_floored = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
        std::size_t m = 0;
        for (Eigen::Index j = 0; j < n; ++j)
            if (j != i) others[m++] = d2(j, i);
        std::nth_element(others.begin(), others.begin() + static_cast<std::ptrdiff_t>(rank - 1),
                         others.end());
        double s = std::sqrt(others[rank - 1]);
        if (s < kSigmaFloor) {
            s = kSigmaFloor;
            ++*num_floored;
        }
        sigma(i) = s;
    }
    return sigma;
}

/// Givens-rotation alignment of the columns of X with the axes (ZP04 §3).
class Alignment {
  public:
    /// `x`: #points by C; `active`: rows that take part in the cost.
    Alignment(const Eigen::MatrixXd& x, const std::vector<char>& active)
        : x_(x), active_(active), c_(static_cast<int>(x.cols())) {
        for (int i = 0; i < c_; ++i)
            for (int j = i + 1; j < c_; ++j) pairs_.emplace_back(i, j);
        num_active_ = 0;
        for (char a : active_) num_active_ += a ? 1 : 0;
    }

    /// Minimises J / #active over the angles; returns the rotated vectors and the cost.
    /// theta = 0 can be a stationary maximum: two balanced groups give
    /// x_2 = (u_A - u_B) / sqrt(2), so every row sits at 45 degrees and the one-sided
    /// gradients cancel. The descent therefore also starts from theta = +-pi/8 on every
    /// angle and keeps the lowest cost (the first on ties).
    Eigen::MatrixXd run(double* cost) const {
        const Eigen::Index k = static_cast<Eigen::Index>(pairs_.size());
        constexpr double kOffset = 0.39269908169872414;  // pi / 8
        Eigen::VectorXd best = descend(Eigen::VectorXd::Zero(k), cost);
        for (double offset : {kOffset, -kOffset}) {
            double f = 0.0;
            Eigen::VectorXd theta = descend(Eigen::VectorXd::Constant(k, offset), &f);
            if (f < *cost) {
                *cost = f;
                best = std::move(theta);
            }
        }
        return x_ * rotation(best);
    }

  private:
    /// Gradient descent with backtracking (Armijo) line search from `theta`.
    Eigen::VectorXd descend(Eigen::VectorXd theta, double* cost) const {
        Eigen::VectorXd grad(theta.size());
        double f = cost_and_gradient(theta, &grad);
        double step = 1.0;
        for (int iter = 0; iter < kMaxDescentIterations; ++iter) {
            const double gg = grad.squaredNorm();
            if (gg < 1e-24) break;
            bool accepted = false;
            Eigen::VectorXd trial;
            double f_trial = f;
            while (step > 1e-12) {
                trial = theta - step * grad;
                f_trial = cost_of(trial);
                if (f_trial <= f - 1e-4 * step * gg) {
                    accepted = true;
                    break;
                }
                step *= 0.5;
            }
            if (!accepted) break;
            const double gain = f - f_trial;
            theta = std::move(trial);
            f = cost_and_gradient(theta, &grad);
            step = std::min(step * 2.0, 64.0);
            if (gain < kDescentTolerance) break;
        }
        *cost = f;
        return theta;
    }

    void rotate_columns(Eigen::MatrixXd& p, int k, double angle) const {
        const int i = pairs_[at(k)].first;
        const int j = pairs_[at(k)].second;
        const double c = std::cos(angle), s = std::sin(angle);
        const Eigen::VectorXd pi = p.col(i);
        p.col(i) = c * pi + s * p.col(j);
        p.col(j) = -s * pi + c * p.col(j);
    }

    Eigen::MatrixXd rotation(const Eigen::VectorXd& theta) const {
        Eigen::MatrixXd r = Eigen::MatrixXd::Identity(c_, c_);
        for (int k = 0; k < static_cast<int>(pairs_.size()); ++k) rotate_columns(r, k, theta(k));
        return r;
    }

    double cost_of(const Eigen::VectorXd& theta) const {
        return cost_of_rows(x_ * rotation(theta), nullptr);
    }

    /// J / #active for rotated vectors `z`; with `w`, also dJ/dZ / #active.
    double cost_of_rows(const Eigen::MatrixXd& z, Eigen::MatrixXd* w) const {
        double j_total = 0.0;
        if (w) w->setZero(z.rows(), z.cols());
        for (Eigen::Index i = 0; i < z.rows(); ++i) {
            if (!active_[at(i)]) continue;
            Eigen::Index m = 0;
            const double max_abs = z.row(i).cwiseAbs().maxCoeff(&m);
            const double m2 = max_abs * max_abs;
            const double s = z.row(i).squaredNorm();
            j_total += s / m2;
            if (w) {
                w->row(i) = (2.0 / m2) * z.row(i);
                (*w)(i, m) -= 2.0 * s * z(i, m) / (m2 * m2);
            }
        }
        const double scale = 1.0 / static_cast<double>(num_active_);
        if (w) *w *= scale;
        return j_total * scale;
    }

    double cost_and_gradient(const Eigen::VectorXd& theta, Eigen::VectorXd* grad) const {
        const int num_angles = static_cast<int>(pairs_.size());
        // prefix[k] = G_1 .. G_{k} (k factors), prefix[0] = I.
        std::vector<Eigen::MatrixXd> prefix(at(num_angles) + 1);
        prefix[0] = Eigen::MatrixXd::Identity(c_, c_);
        for (int k = 0; k < num_angles; ++k) {
            prefix[at(k) + 1] = prefix[at(k)];
            rotate_columns(prefix[at(k) + 1], k, theta(k));
        }
        Eigen::MatrixXd w;
        const double f = cost_of_rows(x_ * prefix.back(), &w);
        // dJ/dtheta_k = <B, P_k V_k Q_k> with B = X^T dJ/dZ, P_k the rotations before k and
        // Q_k those after; P_k V_k only has columns i and j, so each term costs O(C^2).
        const Eigen::MatrixXd b = x_.transpose() * w;
        Eigen::MatrixXd q = Eigen::MatrixXd::Identity(c_, c_);
        for (int k = num_angles - 1; k >= 0; --k) {
            const int i = pairs_[at(k)].first;
            const int j = pairs_[at(k)].second;
            const double c = std::cos(theta(k)), s = std::sin(theta(k));
            const Eigen::MatrixXd& p = prefix[at(k)];
            const Eigen::VectorXd u = -s * p.col(i) + c * p.col(j);
            const Eigen::VectorXd v = -c * p.col(i) - s * p.col(j);
            (*grad)(k) = u.dot(b * q.row(i).transpose()) + v.dot(b * q.row(j).transpose());
            const Eigen::RowVectorXd qi = q.row(i);
            q.row(i) = c * qi - s * q.row(j);
            q.row(j) = s * qi + c * q.row(j);
        }
        return f;
    }

    const Eigen::MatrixXd& x_;
    const std::vector<char>& active_;
    int c_;
    int num_active_ = 0;
    std::vector<std::pair<int, int>> pairs_;
};

/// Renumbers labels 0, 1, ... in order of first appearance (so groups are numbered by
/// their smallest member index); returns the number of groups.
int canonicalise(std::vector<int>& labels) {
    std::vector<int> map;
    int num_groups = 0;
    for (int& l : labels) {
        if (at(l) >= map.size()) map.resize(at(l) + 1, -1);
        if (map[at(l)] < 0) map[at(l)] = num_groups++;
        l = map[at(l)];
    }
    return num_groups;
}

/// Gives every point labelled -1 the label of its nearest labelled point (smallest index
/// on ties); all become 0 when none is labelled.
void join_nearest(std::vector<int>& labels, const Eigen::MatrixXd& d2) {
    const std::vector<int> known = labels;
    const auto n = static_cast<Eigen::Index>(labels.size());
    for (Eigen::Index i = 0; i < n; ++i) {
        if (known[at(i)] >= 0) continue;
        Eigen::Index best = -1;
        for (Eigen::Index j = 0; j < n; ++j)
            if (known[at(j)] >= 0 && (best < 0 || d2(i, j) < d2(i, best))) best = j;
        labels[at(i)] = best < 0 ? 0 : known[at(best)];
    }
}

/// Largest conductance over the groups: cut(G, rest) / vol(G), the fraction of a group's
/// affinity that leaves it (0 for a group without affinity, which only isolated points
/// could form).
double max_conductance(const Eigen::MatrixXd& a, const std::vector<int>& labels, int num_groups) {
    std::vector<double> cut(at(num_groups), 0.0), vol(at(num_groups), 0.0);
    for (Eigen::Index j = 0; j < a.cols(); ++j) {
        const std::size_t g = at(labels[at(j)]);
        for (Eigen::Index i = 0; i < a.rows(); ++i) {
            vol[g] += a(i, j);
            if (at(labels[at(i)]) != g) cut[g] += a(i, j);
        }
    }
    double worst = 0.0;
    for (std::size_t g = 0; g < cut.size(); ++g)
        if (vol[g] > 0.0) worst = std::max(worst, cut[g] / vol[g]);
    return worst;
}

/// One tried group count.
struct Candidate {
    std::vector<int> labels;  ///< #points, canonical
    int num_groups = 0;
    double quality = 0.0;
    double conductance = 1.0;
    int num_unassigned = 0;  ///< points labelled by their nearest neighbour
};

ClusteringResult single_group(Eigen::Index n, ClusteringResult result) {
    result.labels.assign(at(n), 0);
    result.num_clusters = 1;
    return result;
}

/// Steps 2-6 of the method on the standardised points `z` (#features by #points); `noun`
/// names the points in the diagnostics.
ClusteringResult spectral_groups(const Eigen::MatrixXd& z, const ClusteringParams& params,
                                 const std::string& noun) {
    ClusteringResult result;
    const Eigen::Index n = z.cols();
    const Eigen::MatrixXd d2 = squared_distances(z);
    int num_floored = 0;
    const Eigen::VectorXd sigma = local_scales(d2, params.neighbour_rank, &num_floored);
    if (num_floored > 0)
        result.diagnostics.push_back(
            {kStage, std::to_string(num_floored) + " of " + std::to_string(n) + " " + noun +
                         " have neighbour_rank or more duplicates; their local scale "
                         "was raised to " +
                         kSigmaFloorText +
                         " (standardised units), so they link to their duplicates only"});

    Eigen::MatrixXd a(n, n);
    for (Eigen::Index j = 0; j < n; ++j)
        for (Eigen::Index i = 0; i < n; ++i)
            a(i, j) = i == j ? 0.0 : std::exp(-d2(i, j) / (sigma(i) * sigma(j)));

    // Points with (almost) no affinity are left out of the spectral part.
    std::vector<Eigen::Index> core;
    for (Eigen::Index i = 0; i < n; ++i)
        if (a.col(i).sum() >= kIsolatedDegree) core.push_back(i);
    const Eigen::Index m = static_cast<Eigen::Index>(core.size());
    const int num_isolated = static_cast<int>(n - m);
    if (num_isolated > 0)
        result.diagnostics.push_back(
            {kStage, std::to_string(num_isolated) + " of " + std::to_string(n) + " " + noun +
                         " have no affinity to any other (isolated); each joined the group "
                         "of its nearest"});
    if (m < 2) return single_group(n, std::move(result));

    Eigen::MatrixXd l(m, m);
    Eigen::VectorXd inv_sqrt_degree(m);
    for (Eigen::Index c = 0; c < m; ++c) {
        double degree = 0.0;
        for (Eigen::Index r = 0; r < m; ++r) degree += a(core[at(r)], core[at(c)]);
        inv_sqrt_degree(c) = 1.0 / std::sqrt(degree);
    }
    for (Eigen::Index c = 0; c < m; ++c)
        for (Eigen::Index r = 0; r < m; ++r)
            l(r, c) = inv_sqrt_degree(r) * a(core[at(r)], core[at(c)]) * inv_sqrt_degree(c);

    const int max_groups = static_cast<int>(std::min<Eigen::Index>(params.max_clusters, m));
    const detail::Spectrum spectrum = detail::leading_eigenpairs(l, max_groups);

    std::vector<Candidate> candidates;
    Eigen::MatrixXd x = spectrum.vectors.leftCols(1);
    for (int c = 2; c <= max_groups; ++c) {
        Eigen::MatrixXd xc(m, c);
        xc << x, spectrum.vectors.col(c - 1);
        std::vector<char> active(at(m));
        for (Eigen::Index r = 0; r < m; ++r) active[at(r)] = xc.row(r).norm() > kNullRowNorm;
        Candidate cand;
        double cost = static_cast<double>(c);
        if (std::find(active.begin(), active.end(), 1) != active.end())
            x = Alignment(xc, active).run(&cost);
        else
            x = xc;
        cand.quality = 1.0 / cost;
        cand.labels.assign(at(n), -1);
        for (Eigen::Index r = 0; r < m; ++r) {
            if (!active[at(r)]) continue;
            Eigen::Index axis = 0;
            x.row(r).cwiseAbs().maxCoeff(&axis);
            cand.labels[at(core[at(r)])] = static_cast<int>(axis);
        }
        cand.num_unassigned =
            static_cast<int>(std::count(cand.labels.begin(), cand.labels.end(), -1));
        join_nearest(cand.labels, d2);
        cand.num_groups = canonicalise(cand.labels);
        cand.conductance = max_conductance(a, cand.labels, cand.num_groups);
        result.quality.push_back(cand.quality);
        result.conductance.push_back(cand.conductance);
        candidates.push_back(std::move(cand));
    }

    auto admissible = [&](const Candidate& cd) {
        return cd.num_groups >= 2 && cd.quality >= params.min_quality &&
               cd.conductance <= params.max_conductance;
    };
    double best = -1.0;
    for (const Candidate& cd : candidates)
        if (admissible(cd)) best = std::max(best, cd.quality);
    const Candidate* chosen = nullptr;
    for (const Candidate& cd : candidates)
        if (admissible(cd) && cd.quality >= best - params.quality_tolerance) chosen = &cd;
    if (!chosen) return single_group(n, std::move(result));

    result.labels = chosen->labels;
    result.num_clusters = chosen->num_groups;
    const int num_weak = chosen->num_unassigned - num_isolated;
    if (num_weak > 0)
        result.diagnostics.push_back(
            {kStage, std::to_string(num_weak) + " of " + std::to_string(n) + " " + noun +
                         " have a negligible eigenvector row (almost no affinity); each "
                         "joined the group of its nearest"});
    return result;
}

/// The nearest of `landmarks` (columns of `z`) to every column of `z`: its position in
/// `landmarks`, the first on ties. Brute force over #points x #landmarks distances: the
/// features (18) are too many for a space-partitioning tree to prune, and the cost is a small
/// part of what the spectral step saves.
std::vector<int> nearest_landmarks(const Eigen::MatrixXd& z,
                                   const std::vector<Eigen::Index>& landmarks) {
    Eigen::MatrixXd points_of(z.rows(), static_cast<Eigen::Index>(landmarks.size()));
    for (std::size_t k = 0; k < landmarks.size(); ++k)
        points_of.col(static_cast<Eigen::Index>(k)) = z.col(landmarks[k]);
    std::vector<int> nearest(at(z.cols()));
    detail::parallel_for(
        static_cast<int>(z.cols()),
        [&](int i) {
            int best = 0;
            double best_d2 = std::numeric_limits<double>::infinity();
            for (Eigen::Index k = 0; k < points_of.cols(); ++k) {
                const double d2 = (points_of.col(k) - z.col(i)).squaredNorm();
                if (d2 < best_d2) {
                    best_d2 = d2;
                    best = static_cast<int>(k);
                }
            }
            nearest[at(i)] = best;
        },
        64);
    return nearest;
}

}  // namespace

ClusteringResult make_clustering(const Eigen::MatrixXd& features, const ClusteringParams& params) {
    check_clustering_params(params);
    const Eigen::Index n = features.rows();
    if (n == 0) return {};
    const Eigen::MatrixXd z = standardised_points(features);
    if (n == 1 || params.max_clusters == 1) return single_group(n, {});
    if (params.max_points == 0 || n <= params.max_points)
        return spectral_groups(z, params, "points");

    // Landmarks: point k n / m for k = 0 .. m - 1, a sample in proportion to each kind of
    // point, so that the local scales and the groups keep their shape. Standardised with
    // every point, so that the landmarks and the others are measured alike.
    const Eigen::Index m = params.max_points;
    std::vector<Eigen::Index> landmarks(at(m));
    for (Eigen::Index k = 0; k < m; ++k) landmarks[at(k)] = k * n / m;
    Eigen::MatrixXd zl(z.rows(), m);
    for (Eigen::Index k = 0; k < m; ++k) zl.col(k) = z.col(landmarks[at(k)]);
    ClusteringResult result = spectral_groups(zl, params, "landmarks");
    // A landmark keeps its own group: an identical earlier landmark could be its nearest.
    std::vector<int> labels(at(n), -1);
    for (Eigen::Index k = 0; k < m; ++k) labels[at(landmarks[at(k)])] = result.labels[at(k)];
    const std::vector<int> nearest = nearest_landmarks(z, landmarks);
    for (Eigen::Index i = 0; i < n; ++i)
        if (labels[at(i)] < 0) labels[at(i)] = result.labels[at(nearest[at(i)])];
    result.labels = std::move(labels);
    result.num_clusters = canonicalise(result.labels);
    result.num_landmarks = static_cast<int>(m);
    result.diagnostics.push_back(
        {kStage, std::to_string(n) + " points are more than max_points (" + std::to_string(m) +
                     "): the spectral step grouped " + std::to_string(m) +
                     " landmarks evenly spaced among them, and every other point joined the "
                     "group of its nearest landmark"});
    return result;
}

}  // namespace geotex
