//! Conditioning of the float problem: a linear change of coordinates of the lifted space.
//!
//! Separation is invariant under any invertible linear map `T` of the lifted space: `x'`
//! separates `T·D` iff `y = Tᵀx'` separates `D`, since `x'·(T d) = (Tᵀx')·d`. The float GJK
//! therefore runs on `T·D` with a `T` chosen to make the closest-point solves well
//! conditioned, and hands back `y`; every answer is then checked exactly on the integer data,
//! so `T` only affects speed, never a decision.
//!
//! The simplest `T` scales each lifted coordinate by a power of two ([`LinearMap::diagonal`]).
//! That is not enough when the liftings are strongly correlated: the lifted points of a long,
//! nearly straight piece under the conic basis `x², xy, y², x, y` lie very close to a
//! 3-dimensional subspace (`xy ≈ m x² + c x`, `y² ≈ m xy + c y` along a line
//! `y ≈ m x + c`), and the Gram matrices of the simplices GJK builds there reach condition
//! numbers of `10¹³`–`10¹⁴`: the float solves see them as singular and the run stalls.
//! [`LinearMap::whitening`] takes `T = L⁻¹ S`, where `S` scales to unit variance and
//! `L Lᵀ` is the Cholesky factorization of the correlation matrix of the lifted inliers:
//! they then have unit covariance, and those Gram matrices come down to about `10⁷`.

use super::lifted::LiftedSet;

/// Running mean and scatter matrix of lifted points (Welford's update, in `f64`): of the
/// first [`Moments::count`] points of a set that only grows.
#[derive(Clone, Debug, Default)]
pub(crate) struct Moments {
    count: u64,
    mean: Vec<f64>,
    /// `Σ (F − mean)(F − mean)ᵀ`, row-major `n × n` (upper triangle kept).
    scatter: Vec<f64>,
    delta: Vec<f64>,
}

impl Moments {
    /// No point yet, in dimension `n`.
    pub fn new(n: usize) -> Moments {
        Moments {
            count: 0,
            mean: vec![0.0; n],
            scatter: vec![0.0; n * n],
            delta: vec![0.0; n],
        }
    }

    /// Forgets every point.
    pub fn clear(&mut self) {
        self.count = 0;
        self.mean.iter_mut().for_each(|v| *v = 0.0);
        self.scatter.iter_mut().for_each(|v| *v = 0.0);
    }

    /// Number of points added.
    pub fn count(&self) -> usize {
        self.count as usize
    }

    /// Adds the points of `set` not added yet (`set` only grows between
    /// [`Moments::clear`]s).
    pub fn catch_up(&mut self, set: &LiftedSet) {
        for i in self.count()..set.len() {
            self.add(set.lifted(i));
        }
    }

    /// Adds a lifted point.
    pub fn add(&mut self, f: &[i64]) {
        let n = self.mean.len();
        debug_assert_eq!(f.len(), n);
        self.count += 1;
        let k = self.count as f64;
        for i in 0..n {
            self.delta[i] = f[i] as f64 - self.mean[i];
            self.mean[i] += self.delta[i] / k;
        }
        // scatter += δ_before ⊗ (F − mean_after)
        for i in 0..n {
            let di = self.delta[i];
            for j in i..n {
                self.scatter[i * n + j] += di * (f[j] as f64 - self.mean[j]);
            }
        }
    }
}

/// Relative ridge added to the unit diagonal of the correlation matrix: keeps the Cholesky
/// factorization defined when the points span less than the whole space, and bounds the
/// amplification of any direction by `10⁶`.
const RIDGE: f64 = 1e-12;

/// A linear map `T` of the lifted space (row-major `n × n`), applied to points of `D` in
/// `f64`.
#[derive(Clone, Debug)]
pub(crate) struct LinearMap {
    n: usize,
    t: Vec<f64>,
    /// `T` is diagonal: its products skip the zeros (every support point of a diagonal run
    /// pulled its direction back through all `n²` entries).
    diagonal: bool,
}

impl LinearMap {
    /// Makes this `diag(scale)`, in place when it is a diagonal map of that dimension.
    pub fn set_diagonal(&mut self, scale: &[f64]) {
        let n = scale.len();
        if !(self.diagonal && self.n == n) {
            *self = LinearMap::diagonal(scale);
            return;
        }
        for (i, s) in scale.iter().enumerate() {
            self.t[i * n + i] = *s;
        }
    }

    /// `T = diag(scale)`.
    pub fn diagonal(scale: &[f64]) -> LinearMap {
        let n = scale.len();
        let mut t = vec![0.0; n * n];
        for (i, s) in scale.iter().enumerate() {
            t[i * n + i] = *s;
        }
        LinearMap {
            n,
            t,
            diagonal: true,
        }
    }

    /// The whitening map of the points summarized by `moments` (see the module docs), or
    /// `None` when they are too few or the factorization fails numerically (the caller then
    /// uses a diagonal map).
    pub fn whitening(moments: &Moments) -> Option<LinearMap> {
        let n = moments.mean.len();
        if moments.count() < LinearMap::min_points(n) {
            return None;
        }
        // S: unit variance per coordinate.
        let s: Vec<f64> = (0..n)
            .map(|i| {
                let v = moments.scatter[i * n + i];
                (v > 0.0 && v.is_finite()).then(|| 1.0 / v.sqrt())
            })
            .collect::<Option<_>>()?;
        // Cholesky factor L of the correlation matrix S C S + ρI.
        let mut l = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..=i {
                let c = moments.scatter[j * n + i] * s[i] * s[j];
                let mut v = if i == j { c + RIDGE } else { c };
                for k in 0..j {
                    v -= l[i * n + k] * l[j * n + k];
                }
                if i == j {
                    if !(v > 0.0 && v.is_finite()) {
                        return None;
                    }
                    l[i * n + i] = v.sqrt();
                } else {
                    l[i * n + j] = v / l[j * n + j];
                }
            }
        }
        // T = L⁻¹ S, lower triangular: solve L T = S column by column.
        let mut t = vec![0.0; n * n];
        for j in 0..n {
            for i in j..n {
                let mut v = if i == j { s[j] } else { 0.0 };
                for k in j..i {
                    v -= l[i * n + k] * t[k * n + j];
                }
                t[i * n + j] = v / l[i * n + i];
            }
        }
        t.iter().all(|v| v.is_finite()).then_some(LinearMap {
            n,
            t,
            diagonal: false,
        })
    }

    /// Fewest points for [`LinearMap::whitening`] in dimension `n`: a few more than the
    /// `n + 1` that can span the space.
    pub fn min_points(n: usize) -> usize {
        2 * (n + 1)
    }

    /// Dimension of the lifted space.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// `T d`.
    #[cfg(test)]
    pub fn apply(&self, d: &[i64]) -> Vec<f64> {
        let mut out = Vec::new();
        self.apply_with_into(|j| d[j], &mut out);
        out
    }

    /// `T d` for the vector with coordinates `d(0), …, d(n−1)` (computed once each), into
    /// `out`'s buffer.
    pub fn apply_with_into(&self, d: impl Fn(usize) -> i64, out: &mut Vec<f64>) {
        let n = self.n;
        out.clear();
        if self.diagonal {
            out.extend((0..n).map(|j| self.t[j * n + j] * d(j) as f64));
            return;
        }
        out.resize(n, 0.0);
        for j in 0..n {
            let dj = d(j) as f64;
            if dj == 0.0 {
                continue;
            }
            for (i, o) in out.iter_mut().enumerate() {
                *o += self.t[i * n + j] * dj;
            }
        }
    }

    /// `Tᵀ x` into `out`: the direction in lifted coordinates of the direction `x` of the
    /// mapped space.
    pub fn pull_back_into(&self, x: &[f64], out: &mut Vec<f64>) {
        let n = self.n;
        out.clear();
        if self.diagonal {
            out.extend(x.iter().enumerate().map(|(i, xi)| self.t[i * n + i] * xi));
            return;
        }
        out.resize(n, 0.0);
        for (i, xi) in x.iter().enumerate() {
            for (o, a) in out.iter_mut().zip(&self.t[i * n..(i + 1) * n]) {
                *o += a * xi;
            }
        }
    }

    /// `Tᵀ x`.
    pub fn pull_back(&self, x: &[f64]) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.n);
        self.pull_back_into(x, &mut out);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whitened_points_have_unit_covariance() {
        // Strongly correlated liftings of points near a line: (x², xy, y², x, y).
        let mut m = Moments::new(5);
        let mut pts = Vec::new();
        for x in 0i64..400 {
            for dy in [-1i64, 0, 1] {
                let y = (x * 7) / 3 + dy + (x * x) / 5000;
                pts.push(vec![x * x, x * y, y * y, x, y]);
            }
        }
        for p in &pts {
            m.add(p);
        }
        let t = LinearMap::whitening(&m).expect("full rank");
        let mapped: Vec<Vec<f64>> = pts.iter().map(|p| t.apply(p)).collect();
        let k = mapped.len() as f64;
        let mean: Vec<f64> = (0..5)
            .map(|i| mapped.iter().map(|p| p[i]).sum::<f64>() / k)
            .collect();
        for i in 0..5 {
            for j in 0..5 {
                let c: f64 = mapped
                    .iter()
                    .map(|p| (p[i] - mean[i]) * (p[j] - mean[j]))
                    .sum();
                let want = if i == j { 1.0 } else { 0.0 };
                // Up to the ridge, which shrinks the thinnest directions a little.
                assert!((c - want).abs() < 1e-2, "covariance[{i}][{j}] = {c}");
            }
        }
        // Tᵀ is the adjoint of T.
        let x = [0.3, -1.0, 2.0, 0.5, -0.25];
        let y = t.pull_back(&x);
        for p in pts.iter().take(20) {
            let lhs: f64 = x.iter().zip(t.apply(p)).map(|(a, b)| a * b).sum();
            let rhs: f64 = y.iter().zip(p).map(|(a, &b)| a * b as f64).sum();
            assert!((lhs - rhs).abs() <= 1e-9 * (1.0 + lhs.abs()));
        }
    }

    #[test]
    fn too_few_or_flat_points_give_no_whitening() {
        let mut m = Moments::new(2);
        m.add(&[1, 2]);
        assert!(LinearMap::whitening(&m).is_none());
        // A constant coordinate has no variance to scale by.
        for x in 0..10 {
            m.add(&[x, 2]);
        }
        assert!(LinearMap::whitening(&m).is_none());
    }
}
