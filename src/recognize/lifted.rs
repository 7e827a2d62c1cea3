//! A set of lifted points stored contiguously, in exact integers and in `f64`.

/// Points of `Zᵈ` (relative to the recognizer's local origin) with their liftings
/// `F(p) ∈ Zⁿ`, row by row, plus an `f64` copy of the liftings for the support loop.
#[derive(Clone, Debug, Default)]
pub(crate) struct LiftedSet {
    point_dim: usize,
    dim: usize,
    points: Vec<i64>,
    lifted: Vec<i64>,
    float: Vec<f64>,
}

impl LiftedSet {
    /// An empty set of points of dimension `point_dim` lifted to dimension `dim`.
    pub fn new(point_dim: usize, dim: usize) -> LiftedSet {
        LiftedSet {
            point_dim,
            dim,
            ..LiftedSet::default()
        }
    }

    /// An empty set with room for `count` points (no reallocation while they are pushed).
    pub fn with_capacity(point_dim: usize, dim: usize, count: usize) -> LiftedSet {
        LiftedSet {
            point_dim,
            dim,
            points: Vec::with_capacity(count * point_dim),
            lifted: Vec::with_capacity(count * dim),
            float: Vec::with_capacity(count * dim),
        }
    }

    /// Number of points.
    #[inline]
    pub fn len(&self) -> usize {
        self.points.len() / self.point_dim.max(1)
    }

    /// Dimension of the liftings.
    #[inline]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// True when empty.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Removes every point, keeping the allocations.
    pub fn clear(&mut self) {
        self.points.clear();
        self.lifted.clear();
        self.float.clear();
    }

    /// Appends a point and its lifting.
    pub fn push(&mut self, point: &[i64], lifted: &[i64]) {
        debug_assert_eq!(point.len(), self.point_dim);
        debug_assert_eq!(lifted.len(), self.dim);
        // The planar models' sizes copied as arrays: slices of unknown length are copied
        // by calls to `memcpy`, which cost more than the copies themselves.
        match (point, lifted) {
            (&[x, y], &[a, b]) => self.push_sized([x, y], [a, b]),
            (&[x, y], &[a, b, c]) => self.push_sized([x, y], [a, b, c]),
            (&[x, y], &[a, b, c, d, e]) => self.push_sized([x, y], [a, b, c, d, e]),
            (&[x, y], &[a, b, c, d, e, f, g, h, i]) => {
                self.push_sized([x, y], [a, b, c, d, e, f, g, h, i]);
            }
            _ => {
                self.points.extend_from_slice(point);
                self.lifted.extend_from_slice(lifted);
                self.float.extend(lifted.iter().map(|&v| v as f64));
            }
        }
    }

    /// [`LiftedSet::push`] of a point of `P` coordinates lifted to `N`.
    #[inline]
    fn push_sized<const P: usize, const N: usize>(&mut self, point: [i64; P], lifted: [i64; N]) {
        self.points.extend_from_slice(&point);
        self.lifted.extend_from_slice(&lifted);
        self.float.extend_from_slice(&lifted.map(|v| v as f64));
    }

    /// The index of a point equal to `point`, if any.
    pub fn find(&self, point: &[i64]) -> Option<usize> {
        self.points
            .chunks_exact(self.point_dim)
            .position(|p| p == point)
    }

    /// Removes point `i`, moving the last point into its place.
    pub fn swap_remove(&mut self, i: usize) {
        let (pd, n) = (self.point_dim, self.dim);
        let last = self.len() - 1;
        if i != last {
            self.points.copy_within(last * pd..(last + 1) * pd, i * pd);
            self.lifted.copy_within(last * n..(last + 1) * n, i * n);
            self.float.copy_within(last * n..(last + 1) * n, i * n);
        }
        self.points.truncate(last * pd);
        self.lifted.truncate(last * n);
        self.float.truncate(last * n);
    }

    /// The point `i` (relative coordinates).
    #[inline]
    pub fn point(&self, i: usize) -> &[i64] {
        &self.points[i * self.point_dim..(i + 1) * self.point_dim]
    }

    /// The lifting `F(p_i)`.
    #[inline]
    pub fn lifted(&self, i: usize) -> &[i64] {
        &self.lifted[i * self.dim..(i + 1) * self.dim]
    }

    /// All liftings as `f64`, row after row.
    #[inline]
    pub fn float_rows(&self) -> std::slice::ChunksExact<'_, f64> {
        self.float.chunks_exact(self.dim.max(1))
    }

    /// All liftings as `f64`, one slice (rows of [`LiftedSet::dim`] numbers).
    #[inline]
    pub fn float_values(&self) -> &[f64] {
        &self.float
    }

    /// All exact liftings, row after row.
    #[inline]
    pub fn lifted_rows(&self) -> std::slice::ChunksExact<'_, i64> {
        self.lifted.chunks_exact(self.dim.max(1))
    }
}
