//! The products of the minor cycle's edges, kept between its calls while the vertices they
//! come from stay.
//!
//! With the edges `e_i = w_i − w_0` of a simplex, the minor cycle solves
//! `(EᵀE) t = −Eᵀ w_0` ([`super::simplex::affine_min_norm_by_elimination`]). Most of its calls
//! follow one vertex added or removed, so the products `e_i · e_j` and `e_i · w_0` of the
//! vertices that stayed are kept: a vertex added later gets its products then, a vertex
//! removed takes its row and column away, and `w_0` removed (or the points rebuilt) empties
//! them. The same products of the same numbers in the same order, so the same bits.

/// Most edges and coordinates [`Gram`] holds on the stack: the built-in models' (the cubic's 9
/// numbers, 10 vertices), as [`super::simplex::affine_min_norm_f64`].
pub(super) const GRAM: usize = 10;

/// The kept products of simplices of at most [`GRAM`] edges and coordinates, in arrays:
/// recomputing every product was a sixth of the minor cycle's instructions (digits).
#[derive(Clone, Debug, Default)]
pub(super) struct Gram {
    /// How many edges (vertices after `w_0`) have their products here.
    pub(super) valid: usize,
    /// The coordinates of the points.
    pub(super) n: usize,
    /// The edges `e_j`, row by row.
    pub(super) edges: [[f64; GRAM]; GRAM],
    /// `e_i · e_j`.
    pub(super) g: [[f64; GRAM]; GRAM],
    /// `e_j · w_0`.
    pub(super) w: [f64; GRAM],
}

impl Gram {
    /// Vertex `i` of the simplex is removed.
    fn forget(&mut self, i: usize) {
        if i == 0 {
            self.valid = 0;
        } else if i <= self.valid {
            let k = i - 1;
            self.edges.copy_within(k + 1..self.valid, k);
            self.g.copy_within(k + 1..self.valid, k);
            for row in &mut self.g[..self.valid - 1] {
                row.copy_within(k + 1..self.valid, k);
            }
            self.w.copy_within(k + 1..self.valid, k);
            self.valid -= 1;
        }
    }
}

/// The kept products of larger simplices (the polynomial models of degree 4 to 6: up to 27
/// coordinates and 28 vertices), on the heap. Recomputing `EᵀE` took `m²n` products a call,
/// more than the elimination's `m³/3`: with them recomputed, the minor cycle was 40% of
/// `--model poly:6`'s time on 400² noise.
#[derive(Clone, Debug, Default)]
pub(super) struct HeapGram {
    /// How many edges have their products here.
    valid: usize,
    /// The coordinates of the points.
    n: usize,
    /// The edges, [`HeapGram::most`] rows of `n`.
    edges: Vec<f64>,
    /// `e_i · e_j`, `most × most`, row-major.
    g: Vec<f64>,
    /// `e_j · w_0`.
    w: Vec<f64>,
}

impl HeapGram {
    /// Most edges the buffers hold: `n + 1`, a full simplex's vertices.
    fn most(&self) -> usize {
        self.n + 1
    }

    /// Vertex `i` of the simplex is removed.
    fn forget(&mut self, i: usize) {
        if i == 0 {
            self.valid = 0;
        } else if i <= self.valid {
            let (k, v, n, s) = (i - 1, self.valid, self.n, self.most());
            self.edges.copy_within((k + 1) * n..v * n, k * n);
            self.g.copy_within((k + 1) * s..v * s, k * s);
            for r in 0..v - 1 {
                self.g.copy_within(r * s + k + 1..r * s + v, r * s + k);
            }
            self.w.copy_within(k + 1..v, k);
            self.valid -= 1;
        }
    }

    /// Brings the products up to the `m = vertices.len() − 1` edges of `vertices` (the first
    /// `valid` are kept, the others computed with `dot`); false (and nothing kept) when the
    /// simplex has more edges than its points have coordinates plus one, or points of
    /// different lengths.
    pub(super) fn update(
        &mut self,
        vertices: &[super::simplex::Vertex<f64>],
        dot: impl Fn(&[f64], &[f64]) -> f64,
    ) -> bool {
        let Some(first) = vertices.first() else {
            return false;
        };
        let (w0, m) = (&first.point[..], vertices.len() - 1);
        let n = w0.len();
        // (Sized on first use, and afresh for points of another length.)
        if n != self.n || self.w.is_empty() {
            self.n = n;
            let most = self.most();
            self.edges.clear();
            self.edges.resize(most * n, 0.0);
            self.g.clear();
            self.g.resize(most * most, 0.0);
            self.w.clear();
            self.w.resize(most, 0.0);
            self.valid = 0;
        }
        let s = self.most();
        if m > s {
            self.valid = 0;
            return false;
        }
        if self.valid > m {
            self.valid = 0;
        }
        for j in self.valid..m {
            let point = &vertices[j + 1].point;
            if point.len() != n {
                self.valid = 0;
                return false;
            }
            for ((e, a), b) in self.edges[j * n..(j + 1) * n].iter_mut().zip(point).zip(w0) {
                *e = a - b;
            }
            let ej = &self.edges[j * n..(j + 1) * n];
            for i in 0..=j {
                let g = dot(&self.edges[i * n..(i + 1) * n], ej);
                self.g[i * s + j] = g;
                self.g[j * s + i] = g;
            }
            self.w[j] = dot(ej, w0);
        }
        self.valid = m;
        true
    }

    /// `e_i · e_j` (after [`HeapGram::update`]).
    pub(super) fn product(&self, i: usize, j: usize) -> f64 {
        self.g[i * self.most() + j]
    }

    /// `e_i · w_0` (after [`HeapGram::update`]).
    pub(super) fn with_first(&self, i: usize) -> f64 {
        self.w[i]
    }
}

/// Both kept products of a simplex: the arrays' for small simplices, the heap's for large
/// ones. Each is told of every vertex removed and of every rebuild.
#[derive(Clone, Debug, Default)]
pub(super) struct Grams {
    /// Simplices of at most [`GRAM`] edges and coordinates.
    pub(super) fixed: Box<Gram>,
    /// Larger ones.
    pub(super) heap: HeapGram,
}

impl Grams {
    /// Vertex `i` of the simplex is removed.
    pub(super) fn forget(&mut self, i: usize) {
        self.fixed.forget(i);
        // (The heap's are empty for the built-in models.)
        if self.heap.valid > 0 {
            self.heap.forget(i);
        }
    }

    /// The points were rebuilt, or every vertex removed: nothing kept is valid.
    pub(super) fn invalidate(&mut self) {
        self.fixed.valid = 0;
        self.heap.valid = 0;
    }
}
