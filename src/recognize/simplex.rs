//! The simplex of the GJK variant and its closest point to the origin.
//!
//! A simplex is a set of affinely independent points `w_0, …, w_k` of `D` (the support points
//! kept so far) with barycentric weights `λ_i > 0`, `Σ λ_i = 1`; its current point is
//! `x = Σ λ_i w_i`. [`Simplex::closest_point_to_origin`] is the paper's
//! closestPointToOrigin with its removeVertices ([`Simplex::remove_vertices`]): the closest
//! point of the simplex to the origin, the vertices that are not needed removed, by Wolfe's
//! minor cycle (P. Wolfe, *Finding the nearest point in a polytope*, Math. Programming 11, 1976),
//! which works in any dimension with `O(k³)` work instead of the `2^k` faces of Johnson's
//! sub-algorithm:
//!
//! 1. `μ` = weights of the point of the *affine* hull of the simplex nearest to the origin:
//!    minimize `‖Σ μ_i w_i‖²` subject to `Σ μ_i = 1`, i.e. solve
//!    `[G 1; 1ᵀ 0] [μ; ρ] = [0; 1]` with the Gram matrix `G_ij = w_i·w_j`.
//! 2. If every `μ_i > 0`, that point lies in the relative interior: it is the closest point.
//! 3. Otherwise walk from `λ` towards `μ` until the first weight reaches zero
//!    (`θ = min_{μ_i ≤ 0} λ_i / (λ_i − μ_i)`), drop the vertices whose weight vanished, and
//!    repeat.

use super::bareiss;
use super::gram::{Grams, GRAM};
use super::scalar::Scalar;
use super::support::Tag;
use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Zero};

/// A vertex of the simplex: a point of `D` and where it came from.
#[derive(Clone, Debug)]
pub(crate) struct Vertex<T> {
    /// The point of `D`.
    pub point: Vec<T>,
    /// The inlier and outlier it is the difference of.
    pub tag: Tag,
}

impl<T> AsRef<[T]> for Vertex<T> {
    fn as_ref(&self) -> &[T] {
        &self.point
    }
}

/// The simplex, owned by the caller and reused between runs (warm start).
#[derive(Clone, Debug)]
pub(crate) struct Simplex<T> {
    /// The vertices, affinely independent.
    vertices: Vec<Vertex<T>>,
    /// Barycentric weights, positive, summing to one.
    weights: Vec<T>,
    /// Scratch space of the minor cycle, kept so that `f64` runs do not allocate.
    work: Work<T>,
    /// Buffers of dropped vertices and points, handed out again by [`Simplex::buffer`].
    spare: Vec<Vec<T>>,
}

/// The minor cycle's scratch: flat row-major matrices, reused between calls.
#[derive(Clone, Debug)]
pub(crate) struct Work<T> {
    /// The edges `e_i = w_i − w_0`, `(k−1) × n`.
    edges: Vec<T>,
    /// The augmented system `[EᵀE | −Eᵀw_0]`, `(k−1) × k`.
    system: Vec<T>,
    /// Its solution `t`.
    t: Vec<T>,
    /// The affine weights `μ`.
    pub mu: Vec<T>,
    /// The `f64` edges' products, kept while the vertices they come from stay.
    gram: Grams,
}

impl<T> Default for Work<T> {
    fn default() -> Self {
        Work {
            edges: Vec::new(),
            system: Vec::new(),
            t: Vec::new(),
            mu: Vec::new(),
            gram: Grams::default(),
        }
    }
}

/// The affine system of step 1 is singular: the vertices are (numerically) affinely dependent.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Degenerate;

impl<T: Scalar> Default for Simplex<T> {
    fn default() -> Self {
        Simplex {
            vertices: Vec::new(),
            weights: Vec::new(),
            work: Work::default(),
            spare: Vec::new(),
        }
    }
}

impl<T: Scalar> Simplex<T> {
    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// True when there is no vertex.
    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty()
    }

    /// The vertices.
    pub fn vertices(&self) -> &[Vertex<T>] {
        &self.vertices
    }

    /// Where the vertices came from, in order.
    pub fn tags(&self) -> Vec<Tag> {
        self.vertices.iter().map(|v| v.tag).collect()
    }

    /// The vertices' tags and their barycentric weights (positive, summing to one).
    pub fn into_tags_and_weights(self) -> (Vec<Tag>, Vec<T>) {
        (
            self.vertices.into_iter().map(|v| v.tag).collect(),
            self.weights,
        )
    }

    /// A simplex of `vertices` with equal weights, not reduced (the caller runs
    /// [`Simplex::closest_point_to_origin`]).
    pub fn uniform(vertices: Vec<Vertex<T>>) -> Simplex<T> {
        let k = vertices.len();
        let w = T::one() / T::from_i64(k as i64);
        Simplex {
            weights: vec![w; k],
            vertices,
            work: Work::default(),
            spare: Vec::new(),
        }
    }

    /// Rebuilds every vertex's point from its tag (the same points in other coordinates),
    /// in its own buffer, keeping the weights.
    pub fn rebuild(&mut self, mut point: impl FnMut(&Tag, &mut Vec<T>)) {
        self.work.gram.invalidate();
        for v in self.vertices.iter_mut() {
            point(&v.tag, &mut v.point);
        }
    }

    /// Removes vertex `i` and spreads the weight equally over the others (a correction of
    /// rounding, outside Algorithm 1: the caller reduces again).
    pub fn drop_vertex(&mut self, i: usize) {
        self.work.gram.forget(i);
        let v = self.vertices.remove(i);
        self.recycle(v.point);
        self.weights.remove(i);
        let k = self.vertices.len();
        if k > 0 {
            self.weights = vec![T::one() / T::from_i64(k as i64); k];
        }
    }

    /// Removes every vertex.
    pub fn clear(&mut self) {
        self.work.gram.invalidate();
        while let Some(v) = self.vertices.pop() {
            self.recycle(v.point);
        }
        self.weights.clear();
    }

    /// True if a vertex has this tag.
    pub fn contains(&self, tag: &Tag) -> bool {
        self.vertices.iter().any(|v| v.tag == *tag)
    }

    /// True if a vertex is the point `p` (whatever its tag).
    pub fn contains_point(&self, p: &[T]) -> bool {
        self.vertices.iter().any(|v| v.point == p)
    }

    /// The current point `x = Σ λ_i w_i` (the closest point once reduced). Empty simplex: `None`.
    pub fn point(&mut self, dim: usize) -> Option<Vec<T>> {
        if self.vertices.is_empty() {
            return None;
        }
        let mut x = self.buffer();
        T::combination_into(&self.weights, &self.vertices, dim, &mut x);
        Some(x)
    }

    /// A buffer for a point: one a dropped vertex or point left, else a new one.
    pub fn buffer(&mut self) -> Vec<T> {
        self.spare.pop().unwrap_or_default()
    }

    /// Keeps `v`'s buffer for [`Simplex::buffer`] (a few: a simplex has at most `n + 1`
    /// vertices).
    pub fn recycle(&mut self, v: Vec<T>) {
        if self.spare.len() < 16 {
            self.spare.push(v);
        }
    }

    /// addVertex: adds a support point with weight zero (the caller then runs
    /// [`Simplex::closest_point_to_origin`]).
    pub fn add_vertex(&mut self, v: Vertex<T>) {
        self.vertices.push(v);
        self.weights.push(T::zero());
    }

    /// Starts the simplex afresh from one vertex.
    pub fn reset_to(&mut self, v: Vertex<T>) {
        self.clear();
        self.vertices.push(v);
        self.weights.push(T::one());
    }

    /// closestPointToOrigin, by Wolfe's minor cycle: moves the weights to the closest point
    /// of the simplex to the origin, calling [`Simplex::remove_vertices`] on the vertices
    /// whose weight vanished on the way.
    ///
    /// `eps` is the relative tolerance of `f64` runs (ignored by exact numbers).
    pub fn closest_point_to_origin(&mut self, eps: f64) -> Result<(), Degenerate> {
        let tiny = T::tolerance(&T::one(), eps);
        // Each pass removes at least one vertex, so at most len() passes.
        for _ in 0..=self.vertices.len() {
            if !T::affine_min_norm_into(&self.vertices, eps, &mut self.work) {
                return Err(Degenerate);
            }
            let mu = &mut self.work.mu;
            if mu.iter().all(|m| *m > tiny) {
                std::mem::swap(&mut self.weights, mu);
                return Ok(());
            }
            // Walk from λ towards μ until a weight reaches zero.
            let mut theta = T::one();
            let mut leaving = None;
            for (i, (l, m)) in self.weights.iter().zip(mu.iter()).enumerate() {
                if *m <= tiny {
                    let denom = l.clone() - m.clone();
                    let t = if denom > T::zero() {
                        l.clone() / denom
                    } else {
                        T::zero()
                    };
                    if leaving.is_none() || t < theta {
                        theta = t;
                        leaving = Some(i);
                    }
                }
            }
            let keep = T::one() - theta.clone();
            for (l, m) in self.weights.iter_mut().zip(mu.iter()) {
                *l = keep.clone() * l.clone() + theta.clone() * m.clone();
            }
            if let Some(i) = leaving {
                self.weights[i] = T::zero();
            }
            self.remove_vertices(&tiny)?;
        }
        Err(Degenerate)
    }

    /// removeVertices: drops the vertices whose weight is at most `tiny` (zero for exact
    /// numbers) and renormalizes the others' weights; `Degenerate` if none is left.
    pub fn remove_vertices(&mut self, tiny: &T) -> Result<(), Degenerate> {
        let mut i = 0;
        while i < self.weights.len() {
            if self.weights[i] <= *tiny {
                self.weights.remove(i);
                self.work.gram.forget(i);
                let v = self.vertices.remove(i);
                self.recycle(v.point);
            } else {
                i += 1;
            }
        }
        if self.vertices.is_empty() {
            return Err(Degenerate);
        }
        // Renormalize (exact numbers already sum to one; floats drift).
        let sum = self.weights.iter().fold(T::zero(), |s, l| s + l.clone());
        for l in self.weights.iter_mut() {
            *l = l.clone() / sum.clone();
        }
        Ok(())
    }
}

/// The weights `μ` (summing to one) of the point of the affine hull of `vertices` nearest to
/// the origin, into `work.mu`, by Gaussian elimination in `T` (the `f64` method); false if
/// the vertices are (numerically) affinely dependent.
///
/// Reduced form, better conditioned than the bordered Gram system: with the edges
/// `e_i = w_i − w_0`, minimize `‖w_0 + Σ t_i e_i‖²`, i.e. `(EᵀE) t = −Eᵀ w_0`, and
/// `μ_0 = 1 − Σ t_i`, `μ_i = t_i`.
pub(crate) fn affine_min_norm_by_elimination<T: Scalar>(
    vertices: &[Vertex<T>],
    eps: f64,
    work: &mut Work<T>,
) -> bool {
    let k = vertices.len();
    work.mu.clear();
    if k == 0 {
        return false;
    }
    if k == 1 {
        work.mu.push(T::one());
        return true;
    }
    let w0 = &vertices[0].point;
    let n = w0.len();
    work.edges.clear();
    for v in &vertices[1..] {
        work.edges
            .extend(v.point.iter().zip(w0).map(|(a, b)| a.clone() - b.clone()));
    }
    let m = k - 1;
    let dot = T::dot;
    let edges = &work.edges;
    let edge = |i: usize| &edges[i * n..(i + 1) * n];
    // Augmented matrix [EᵀE | −Eᵀw0], m × (m+1), row-major.
    // (EᵀE is symmetric: each product once.)
    work.system.clear();
    work.system.resize(m * (m + 1), T::zero());
    for i in 0..m {
        for j in i..m {
            let g = dot(edge(i), edge(j));
            if j != i {
                work.system[j * (m + 1) + i] = g.clone();
            }
            work.system[i * (m + 1) + j] = g;
        }
        work.system[i * (m + 1) + m] = -dot(edge(i), w0);
    }
    weights_of_system(work, m, eps)
}

/// The weights `μ` into `work.mu` from the augmented system `[EᵀE | −Eᵀw₀]` of `m` edges in
/// `work.system`: eliminated with pivots relative to the largest diagonal entry, then
/// `μ_0 = 1 − Σ t_i`, `μ_i = t_i`; false when a pivot is too small or a weight not finite.
fn weights_of_system<T: Scalar>(work: &mut Work<T>, m: usize, eps: f64) -> bool {
    let scale = (0..m).fold(T::zero(), |s, i| {
        let d = &work.system[i * (m + 1) + i];
        if *d > s {
            d.clone()
        } else {
            s
        }
    });
    let pivot_tol = T::tolerance(&scale, eps);
    if !solve_in_place(&mut work.system, m, &pivot_tol, &mut work.t) {
        return false;
    }
    let sum_t = work.t.iter().fold(T::zero(), |s, x| s + x.clone());
    work.mu.push(T::one() - sum_t);
    work.mu.extend(work.t.iter().cloned());
    work.mu.iter().all(|x| x.is_finite())
}

/// [`affine_min_norm_by_elimination`] in `f64` on the stack, for the built-in models'
/// dimensions (at most 9, the cubic's, with one vertex more): the same operations in the
/// same order (the same [`Scalar::dot`], the same pivots), so the same weights to the bit;
/// its `Vec` indexing was most of the minor cycle's time. Larger simplices go to `on_heap`,
/// the general one with its products kept.
pub(crate) fn affine_min_norm_f64(
    vertices: &[Vertex<f64>],
    eps: f64,
    work: &mut Work<f64>,
) -> bool {
    let k = vertices.len();
    let n = vertices.first().map_or(0, |v| v.point.len());
    let m = k.saturating_sub(1);
    // (Arrays no larger than needed: zeroing them was a fifth of the work in 5-D.)
    match (m, n) {
        (0, _) => affine_min_norm_by_elimination(vertices, eps, work),
        (..=3, ..=3) => on_stack::<3, 4>(vertices, eps, work),
        (..=5, ..=5) => on_stack::<5, 6>(vertices, eps, work),
        (..=GRAM, ..=GRAM) => on_stack::<GRAM, { GRAM + 1 }>(vertices, eps, work),
        _ => on_heap(vertices, eps, work),
    }
}

/// [`affine_min_norm_f64`] with at most `C` edges and coordinates (`W = C + 1`).
fn on_stack<const C: usize, const W: usize>(
    vertices: &[Vertex<f64>],
    eps: f64,
    work: &mut Work<f64>,
) -> bool {
    // (Cleared first, as the general one does, whatever the answer.)
    work.mu.clear();
    let w0 = &vertices[0].point[..];
    let (n, m) = (w0.len(), vertices.len() - 1);
    debug_assert!(vertices.iter().all(|v| v.point.len() == n));
    // The products of the edges not yet held (see `Gram`), each once.
    let gram = &mut *work.gram.fixed;
    if gram.n != n || gram.valid > m {
        gram.valid = 0;
        gram.n = n;
    }
    for j in gram.valid..m {
        for ((ec, a), b) in gram.edges[j].iter_mut().zip(&vertices[j + 1].point).zip(w0) {
            *ec = a - b;
        }
        for i in 0..=j {
            let g = <f64 as Scalar>::dot(&gram.edges[i][..n], &gram.edges[j][..n]);
            gram.g[i][j] = g;
            gram.g[j][i] = g;
        }
        gram.w[j] = <f64 as Scalar>::dot(&gram.edges[j][..n], w0);
    }
    gram.valid = m;
    // The augmented system [EᵀE | −Eᵀw0].
    let mut a = [[0.0f64; W]; C];
    for i in 0..m {
        a[i][..m].copy_from_slice(&gram.g[i][..m]);
        a[i][m] = -gram.w[i];
    }
    let scale = (0..m).fold(0.0f64, |s, i| if a[i][i] > s { a[i][i] } else { s });
    let pivot_tol = <f64 as Scalar>::tolerance(&scale, eps);
    // Gaussian elimination with partial pivoting, as `solve_in_place`.
    for col in 0..m {
        let mut best = col;
        for r in col + 1..m {
            if a[r][col].abs() > a[best][col].abs() {
                best = r;
            }
        }
        if a[best][col].abs() <= pivot_tol || a[best][col] == 0.0 {
            return false;
        }
        a.swap(col, best);
        let pivot = a[col];
        for row in a[col + 1..m].iter_mut() {
            if row[col] == 0.0 {
                continue;
            }
            let f = row[col] / pivot[col];
            for (e, v) in row[col..=m].iter_mut().zip(&pivot[col..=m]) {
                *e -= f * v;
            }
        }
    }
    let mut t = [0.0f64; C];
    for r in (0..m).rev() {
        let mut s = a[r][m];
        for c in r + 1..m {
            s -= a[r][c] * t[c];
        }
        t[r] = s / a[r][r];
    }
    let sum_t = t[..m].iter().fold(0.0, |s, x| s + x);
    work.mu.push(1.0 - sum_t);
    work.mu.extend_from_slice(&t[..m]);
    work.mu.iter().all(|x| x.is_finite())
}

/// [`affine_min_norm_f64`] beyond the stack's sizes: [`affine_min_norm_by_elimination`] with
/// the edges' products kept between calls ([`super::gram::HeapGram`]), the same numbers to
/// the bit.
fn on_heap(vertices: &[Vertex<f64>], eps: f64, work: &mut Work<f64>) -> bool {
    let heap = &mut work.gram.heap;
    if !heap.update(vertices, <f64 as Scalar>::dot) {
        return affine_min_norm_by_elimination(vertices, eps, work);
    }
    work.mu.clear();
    let m = vertices.len() - 1;
    // The augmented system [EᵀE | −Eᵀw0], m × (m+1), row-major.
    let system = &mut work.system;
    system.clear();
    system.resize(m * (m + 1), 0.0);
    for (i, row) in system.chunks_exact_mut(m + 1).enumerate() {
        for (j, e) in row[..m].iter_mut().enumerate() {
            *e = heap.product(i, j);
        }
        row[m] = -heap.with_first(i);
    }
    weights_of_system(work, m, eps)
}

/// The weights of [`affine_min_norm_by_elimination`] in exact arithmetic, without a single
/// rational reduction in the elimination: the vertices are brought to integers (multiplied
/// by the lcm of their denominators, which leaves `μ` unchanged), the reduced system `(EᵀE) t = −Eᵀw₀` is solved
/// by fraction-free (Bareiss) elimination in big integers, and only the `k` weights
/// `μ = (d − Σy, y₁, …)/d` with `y = d·t`, `d = det(EᵀE)`, are reduced at the end.
///
/// Rational elimination reduced every intermediate by a gcd, which was most of the time of
/// the exact fallback.
pub(crate) fn affine_min_norm_weights_exact(
    vertices: &[Vertex<BigRational>],
) -> Option<Vec<BigRational>> {
    let k = vertices.len();
    if k == 0 {
        return None;
    }
    if k == 1 {
        return Some(vec![<BigRational as One>::one()]);
    }
    let mut l = BigInt::one();
    for v in vertices {
        for c in &v.point {
            if !c.denom().is_one() {
                l = l.lcm(c.denom());
            }
        }
    }
    let points: Vec<Vec<BigInt>> = vertices
        .iter()
        .map(|v| {
            v.point
                .iter()
                .map(|c| {
                    if l.is_one() {
                        c.numer().clone()
                    } else {
                        c.numer() * (&l / c.denom())
                    }
                })
                .collect()
        })
        .collect();
    let w0 = &points[0];
    let edges: Vec<Vec<BigInt>> = points[1..]
        .iter()
        .map(|p| p.iter().zip(w0).map(|(a, b)| a - b).collect())
        .collect();
    let dot = |a: &[BigInt], b: &[BigInt]| -> BigInt {
        a.iter().zip(b).fold(BigInt::zero(), |s, (x, y)| s + x * y)
    };
    let m = k - 1;
    let mut a: Vec<Vec<BigInt>> = (0..m)
        .map(|i| {
            let mut row: Vec<BigInt> = (0..m).map(|j| dot(&edges[i], &edges[j])).collect();
            row.push(-dot(&edges[i], w0));
            row
        })
        .collect();
    let (y, d) = bareiss::solve(&mut a, m)?;
    let sum_y = y.iter().fold(BigInt::zero(), |s, v| s + v);
    let mut mu = Vec::with_capacity(k);
    mu.push(BigRational::new(&d - sum_y, d.clone()));
    mu.extend(y.into_iter().map(|v| BigRational::new(v, d.clone())));
    Some(mu)
}

/// Gaussian elimination with partial pivoting on the row-major augmented `m × (m+1)`
/// matrix `a`; the solution goes to `x`. False when a pivot is not larger than `pivot_tol`
/// (singular).
fn solve_in_place<T: Scalar>(a: &mut [T], m: usize, pivot_tol: &T, x: &mut Vec<T>) -> bool {
    let w = m + 1;
    let a = &mut a[..m * w];
    for col in 0..m {
        let mut best = col;
        for r in col + 1..m {
            if a[r * w + col].abs() > a[best * w + col].abs() {
                best = r;
            }
        }
        if a[best * w + col].abs() <= *pivot_tol || a[best * w + col] == T::zero() {
            return false;
        }
        if best != col {
            let (top, rest) = a.split_at_mut(best * w);
            top[col * w..(col + 1) * w].swap_with_slice(&mut rest[..w]);
        }
        // The rows below the pivot's, each minus its multiple of the pivot's (by row
        // slices: the same operations in the same order, without an index per entry).
        let (top, below) = a.split_at_mut((col + 1) * w);
        let pivot = &top[col * w + col..];
        for row in below.chunks_exact_mut(w) {
            let row = &mut row[col..];
            if row[0] == T::zero() {
                continue;
            }
            let f = row[0].clone() / pivot[0].clone();
            for (e, v) in row.iter_mut().zip(pivot) {
                *e = e.clone() - f.clone() * v.clone();
            }
        }
    }
    x.clear();
    x.resize(m, T::zero());
    for r in (0..m).rev() {
        let row = &a[r * w..(r + 1) * w];
        let mut s = row[m].clone();
        for (e, xc) in row[r + 1..m].iter().zip(&x[r + 1..]) {
            s = s - e.clone() * xc.clone();
        }
        x[r] = s / row[r].clone();
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::recognize::support::Tag;

    fn simplex_of(points: &[Vec<f64>]) -> Simplex<f64> {
        Simplex::uniform(
            points
                .iter()
                .enumerate()
                .map(|(i, p)| Vertex {
                    point: p.clone(),
                    tag: Tag::explicit(i),
                })
                .collect(),
        )
    }

    fn norm2(x: &[f64]) -> f64 {
        x.iter().map(|v| v * v).sum()
    }

    fn assert_close(got: f64, want: f64, tol: f64, what: &str) {
        assert!(
            (got - want).abs() <= tol,
            "{what}: got {got}, want {want} (tolerance {tol})"
        );
    }

    #[test]
    fn segment_and_triangle() {
        // Segment from (1,-1) to (1,1): closest point (1,0).
        let mut s = simplex_of(&[vec![1.0, -1.0], vec![1.0, 1.0]]);
        s.closest_point_to_origin(1e-12).unwrap();
        let x = s.point(2).unwrap();
        assert_close(x[0], 1.0, 1e-12, "x");
        assert_close(x[1], 0.0, 1e-12, "y");
        // Segment whose closest point is an end: the other vertex is removed.
        let mut s = simplex_of(&[vec![1.0, 1.0], vec![2.0, 3.0]]);
        s.closest_point_to_origin(1e-12).unwrap();
        assert_eq!(s.len(), 1);
        // Triangle around the origin: closest point is the origin itself.
        let mut s = simplex_of(&[vec![1.0, 0.0], vec![-1.0, 1.0], vec![-1.0, -1.0]]);
        s.closest_point_to_origin(1e-12).unwrap();
        assert!(norm2(&s.point(2).unwrap()) < 1e-24);
        assert_eq!(s.len(), 3);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(500))]
        /// The fraction-free weights equal those of rational elimination, exactly, for
        /// integer and fractional vertices, independent or not, up to 7 vertices in 6-D.
        #[test]
        fn fraction_free_weights_equal_rational_elimination(
            raw in proptest::collection::vec(proptest::collection::vec(-(1i64 << 40)..(1i64 << 40), 6), 1..=7),
            small in proptest::prelude::any::<bool>(),
            denom in 1i64..5,
        ) {
            use num_rational::BigRational;
            let mut s: Simplex<BigRational> = Simplex::default();
            for (i, p) in raw.iter().enumerate() {
                s.add_vertex(Vertex {
                    point: p
                        .iter()
                        .map(|&v| {
                            let v = if small { v % 3 } else { v };
                            BigRational::new(v.into(), (denom + i as i64 % 2).into())
                        })
                        .collect(),
                    tag: Tag::explicit(i),
                });
            }
            let got = affine_min_norm_weights_exact(&s.vertices);
            let mut work = Work::default();
            let want = affine_min_norm_by_elimination(&s.vertices, 0.0, &mut work).then_some(work.mu);
            proptest::prop_assert_eq!(got, want);
        }

        /// The minor cycle with the products kept from call to call (see `super::gram`)
        /// gives the weights and vertices of one that recomputes them all, to the bit,
        /// through vertices added, removed by the cycle, dropped, and rebuilt: on the stack
        /// up to 10 coordinates, on the heap beyond.
        #[test]
        fn kept_products_give_the_same_cycles(
            dim in 2usize..=14,
            ops in proptest::collection::vec((0u8..6, proptest::collection::vec(-1e3f64..1e3, 14)), 1..40),
        ) {
            let bits = |s: &Simplex<f64>| -> (Vec<u64>, Vec<Tag>) {
                (s.weights.iter().map(|w| w.to_bits()).collect(), s.tags())
            };
            let mut s: Simplex<f64> = Simplex::default();
            for (i, (op, p)) in ops.iter().enumerate() {
                let v = Vertex { point: p[..dim].to_vec(), tag: Tag::explicit(i) };
                match op {
                    _ if s.is_empty() => s.reset_to(v),
                    0..=2 if s.len() <= dim => s.add_vertex(v),
                    3 if s.len() > 1 => s.drop_vertex(i % s.len()),
                    4 => s.rebuild(|_, point| point.iter_mut().for_each(|c| *c = 0.5 * *c + 1.0)),
                    _ => {}
                }
                let mut fresh = s.clone();
                fresh.work.gram.invalidate();
                let (want, got) = (fresh.closest_point_to_origin(1e-12), s.closest_point_to_origin(1e-12));
                proptest::prop_assert_eq!(want.is_ok(), got.is_ok());
                if got.is_err() {
                    s.clear();
                    continue;
                }
                proptest::prop_assert_eq!(bits(&fresh), bits(&s));
            }
        }

        /// The stack and heap versions give the general one's weights to the bit (or fail
        /// with it), in the dimensions the stack unrolls and beyond (up to poly:6's 27
        /// coordinates), independent vertices or not, up to more vertices than the heap's
        /// buffers hold (which go to the general one).
        #[test]
        fn stack_weights_are_the_general_ones(
            dim in 1usize..=27,
            raw in proptest::collection::vec(proptest::collection::vec(-1e6f64..1e6, 27), 1..=30),
            repeat in proptest::prelude::any::<bool>(),
            eps in proptest::sample::select(vec![0.0, 1e-12, 1e-3]),
        ) {
            let mut vertices: Vec<Vertex<f64>> = raw
                .iter()
                .enumerate()
                .map(|(i, p)| Vertex { point: p[..dim].to_vec(), tag: Tag::explicit(i) })
                .collect();
            if repeat && vertices.len() > 2 {
                // Affinely dependent: a vertex between two others.
                let mid: Vec<f64> = vertices[0].point.iter().zip(&vertices[1].point).map(|(a, b)| 0.5 * (a + b)).collect();
                vertices[2].point = mid;
            }
            let (mut w1, mut w2) = (Work::default(), Work::default());
            let got = affine_min_norm_f64(&vertices, eps, &mut w1).then(|| w1.mu.iter().map(|v| v.to_bits()).collect::<Vec<_>>());
            let want = affine_min_norm_by_elimination(&vertices, eps, &mut w2).then(|| w2.mu.iter().map(|v| v.to_bits()).collect::<Vec<_>>());
            proptest::prop_assert_eq!(got, want);
        }
    }

    #[test]
    fn exact_numbers() {
        use num_rational::BigRational;
        let r = |v: i64| BigRational::from_i64(v);
        let mut s: Simplex<BigRational> = Simplex::default();
        for (i, p) in [[3, 1], [1, 3], [5, 5]].iter().enumerate() {
            s.add_vertex(Vertex {
                point: vec![r(p[0]), r(p[1])],
                tag: Tag::explicit(i),
            });
        }
        s.weights = vec![BigRational::from_i64(1) / r(3); 3];
        s.closest_point_to_origin(0.0).unwrap();
        // Closest point of the triangle is (2, 2), the middle of the first edge.
        assert_eq!(s.point(2).unwrap(), vec![r(2), r(2)]);
        assert_eq!(s.len(), 2);
    }
}
